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
The radar: its ParamSpec table, its spec and its cross-field check.

Registered as ``radar`` in core/sensors/params.py; keys in docs/sensors.md. Webots' radar
equation and target merging are core/sensors/radar_equation.py's.
"""

from dataclasses import dataclass
import math

from vehicle_sim.core.sensors.sensor_spec import common_specs, SensorSpec, TWO_PI
from vehicle_sim.core.specs.param_spec import fail, ParamSpec

RADAR_SPECS = common_specs('radar', 20.0) + (
    ParamSpec('min_range', 'min_range_m', 'float', 1.0, 'm',
              'nearer targets are not seen (Webots minRange)', ge=0.0),
    ParamSpec('max_range', 'max_range_m', 'float', 50.0, 'm',
              'farther targets are not seen (Webots maxRange)', gt=0.0),
    ParamSpec('horizontal_fov', 'horizontal_fov_rad', 'float', 0.78, 'rad',
              'horizontal field of view of the cone, centred on the x axis', gt=0.0,
              le=TWO_PI),
    ParamSpec('vertical_fov', 'vertical_fov_rad', 'float', 0.1, 'rad',
              'vertical field of view of the cone', gt=0.0, le=math.pi),
    ParamSpec('min_absolute_radial_speed', 'min_absolute_radial_speed_mps', 'float', 0.0,
              'm/s', 'targets slower than this (radially, relative) are not seen', ge=0.0),
    ParamSpec('min_radial_speed', 'min_radial_speed_mps', 'float', 0.0, 'm/s',
              'slowest radial speed seen (both 0: no limits; < 0 = closing)'),
    ParamSpec('max_radial_speed', 'max_radial_speed_mps', 'float', 0.0, 'm/s',
              'fastest radial speed seen (both 0: no limits)'),
    ParamSpec('cell_distance', 'cell_distance_m', 'float', 0.0, 'm',
              'targets closer in range than this merge into one (0: never)', ge=0.0),
    ParamSpec('cell_speed', 'cell_speed_mps', 'float', 0.0, 'm/s',
              'and closer in radial speed than this (0: range alone decides)', ge=0.0),
    ParamSpec('range_noise', 'range_noise_m', 'float', 0.0, 'm',
              'standard deviation of the Gaussian distance noise', ge=0.0),
    ParamSpec('speed_noise', 'speed_noise_mps', 'float', 0.0, 'm/s',
              'standard deviation of the Gaussian radial speed noise', ge=0.0),
    ParamSpec('angular_noise', 'angular_noise_rad', 'float', 0.0, 'rad',
              'standard deviation of the Gaussian azimuth noise', ge=0.0),
    ParamSpec('antenna_gain', 'antenna_gain_dbi', 'float', 20.0, 'dBi',
              'antenna gain (radar equation)'),
    ParamSpec('frequency', 'frequency_ghz', 'float', 24.0, 'GHz',
              'carrier frequency (wavelength of the radar equation)', gt=0.0),
    ParamSpec('transmitted_power', 'transmitted_power_dbm', 'float', 20.0, 'dBm',
              'transmitted power (radar equation)'),
    ParamSpec('min_detectable_signal', 'min_detectable_signal_dbm', 'float', -100.0, 'dBm',
              'targets returning less power are not seen'),
    ParamSpec('occlusion', 'occlusion', 'bool', False,
              doc='a target hidden behind another body (a ray to its centre) is not seen'),
)


@dataclass(frozen=True)
class RadarSpec(SensorSpec):
    """A radar (Webots Radar): targets with distance, received power, radial speed, azimuth."""

    min_range_m: float
    max_range_m: float
    horizontal_fov_rad: float
    vertical_fov_rad: float
    min_absolute_radial_speed_mps: float
    min_radial_speed_mps: float
    max_radial_speed_mps: float
    cell_distance_m: float
    cell_speed_mps: float
    range_noise_m: float
    speed_noise_mps: float
    angular_noise_rad: float
    antenna_gain_dbi: float
    frequency_ghz: float
    transmitted_power_dbm: float
    min_detectable_signal_dbm: float
    occlusion: bool

    def _default_topic(self):
        return self.name

    @property
    def topics(self):
        """``<topic>/tracks`` (radar_msgs/RadarTracks) and ``<topic>/scan`` (RadarScan)."""
        base = self.topic or self._default_topic()
        return (f'{base}/tracks', f'{base}/scan')


def check_radar(source, values):
    """Refuse a radar's values that do not fit together (ranges, radial speed limits)."""
    if values['min_range_m'] >= values['max_range_m']:
        fail(source, 'min_range', values['min_range_m'],
              f'must be < max_range ({values["max_range_m"]:g} m)')
    low, high = values['min_radial_speed_mps'], values['max_radial_speed_mps']
    if (low or high) and low >= high:
        fail(source, 'min_radial_speed', low,
              f'must be < max_radial_speed ({high:g} m/s), or both 0 (no limits)')
