# Copyright 2026 vehicle_sim contributors
#
# Licensed under the Apache License, Version 2.0 (the "License");
# you may not use this file except in compliance with the License.
# You may obtain a copy of the License at
#
#     http://www.apache.org/licenses/LICENSE-2.0
#
# Unless required by applicable law or agreed to in writing, software
# distributed under the License is distributed on an "AS IS" BASIS,
# WITHOUT WARRANTIES OR CONDITIONS OF ANY KIND, either express or implied.
# See the License for the specific language governing permissions and
# limitations under the License.

"""
The radar's arithmetic as Webots' WbRadar does it: the radar equation and merging targets.

Received power (the radar equation, Webots' Radar documentation):
``P_r = P_t G^2 lambda^2 sigma / ((4 pi)^3 R^4)`` with the transmitted power ``P_t``
(``transmitted_power`` dBm -> W: 1e-3 * 10^(dBm / 10)), the antenna gain ``G`` (``antenna_gain``
dBi -> 10^(dBi / 10)), the wavelength ``lambda = 0.299792458 / frequency`` [m, GHz], the
target's radar cross-section ``sigma`` [m^2] and its distance ``R`` [m]; a target returning
less than ``min_detectable_signal`` (dBm -> W) is not seen. Powers stay in W until targets are
merged, then read in dBm (10 log10(P / 1 mW)).

A target's radar cross-section here is its label's reflectivity (core/sensors/labels.py) times
its frontal area, width x height: the label table's reflectivity is per square metre.

Merging (``cell_distance`` > 0): going through the targets in order, a target and every later
one closer in distance than ``cell_distance`` (and, with ``cell_speed`` > 0, closer in radial
speed than ``cell_speed``) become one, whose distance, speed and azimuth are the averages
weighted by received power and whose power is their sum; then again from that target on
(WbRadar::mergeTargets). The merged target keeps the strongest one's identity (label,
instance, position, velocity, size).
"""

import math

SPEED_OF_LIGHT_MGHZ = 0.299792458     # c [m * GHz]: wavelength [m] = this / frequency [GHz]


def dbm_to_w(dbm):
    """Return a power in dBm as W."""
    return 1e-3 * 10.0 ** (dbm / 10.0)


def w_to_dbm(watts):
    """Return a power in W as dBm."""
    return 10.0 * math.log10(watts / 1e-3)


def power_factor_w(spec):
    """Return P_t G^2 lambda^2 / (4 pi)^3 of a RadarSpec [W m^2]: P_r = this sigma / R^4."""
    gain = 10.0 ** (spec.antenna_gain_dbi / 10.0)
    wavelength = SPEED_OF_LIGHT_MGHZ / spec.frequency_ghz
    return dbm_to_w(spec.transmitted_power_dbm) * gain ** 2 * wavelength ** 2 / (
        4.0 * math.pi) ** 3


def merge_targets(targets, cell_distance, cell_speed):
    """
    Merge targets that the radar cannot tell apart (Webots' order and weights).

    :param targets: list of dicts with 'range', 'power' [W], 'speed', 'azimuth' (and
        anything else, kept from the strongest one of a merge), in the radar's order.
    :param cell_distance: [m], > 0.
    :param cell_speed: [m/s]; <= 0: the distance alone decides.
    :return: the merged list (new dicts where merged).
    """
    targets = list(targets)
    start = 0
    while start < len(targets) - 1:
        merged_at = None
        for i in range(start, len(targets) - 1):
            first = targets[i]
            group = [j for j in range(i + 1, len(targets))
                     if abs(first['range'] - targets[j]['range']) < cell_distance
                     and (cell_speed <= 0.0
                          or abs(first['speed'] - targets[j]['speed']) < cell_speed)]
            if group:
                members = [first] + [targets[j] for j in group]
                power = sum(t['power'] for t in members)
                strongest = max(members, key=lambda t: t['power'])
                result = dict(strongest)
                result['power'] = power
                for key in ('range', 'speed', 'azimuth'):
                    result[key] = sum(t[key] * t['power'] for t in members) / power
                targets[i] = result
                for j in reversed(group):
                    del targets[j]
                merged_at = i
                break
        if merged_at is None:
            break
        start = merged_at
    return targets
