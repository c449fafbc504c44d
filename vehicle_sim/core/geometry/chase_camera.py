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
Chase camera math: where a viewer's camera sits behind and above a vehicle.

Pure functions of the vehicle pose; ``vehicle_sim.physics.gui`` hands the result to PyBullet's
window (``resetDebugVisualizerCamera``). The camera is described as PyBullet describes its debug
camera: a target point, a distance from it, a yaw and a pitch in degrees. In PyBullet's
convention (z up) the camera looks along the horizontal direction at angle ``yaw + 90°`` from the
world x axis, tilted down by ``-pitch``; so a camera looking along a heading ψ has
``yaw = degrees(ψ) - 90``, and its eye is ``target - distance * forward``.
"""

from dataclasses import dataclass, replace
import math
from typing import Tuple

from vehicle_sim.core.geometry.angles import wrap_angle_rad
from vehicle_sim.core.specs.errors import InvalidParameterError

Vector = Tuple[float, float, float]

# Zoom factor of one key press (closer: divide, farther: multiply).
ZOOM_STEP = 1.25
MIN_DISTANCE_M = 1.0
MAX_DISTANCE_M = 200.0


@dataclass(frozen=True)
class ChaseSettings:
    """
    How the chase camera follows a vehicle.

    :param distance_m: from the target point to the eye [m].
    :param pitch_deg: PyBullet pitch [deg]: negative looks down (-90 = straight down).
    :param target_height_m: target point above the vehicle's reference point [m].
    :param heading_lag_s: time constant of the camera yaw following the heading [s]; 0 = the
        camera turns with the vehicle at once (a small lag steadies the view in a spin).
    """

    distance_m: float = 8.0
    pitch_deg: float = -20.0
    target_height_m: float = 1.0
    heading_lag_s: float = 0.25

    def __post_init__(self):
        checks = (
            ('distance_m', self.distance_m, MIN_DISTANCE_M <= self.distance_m <= MAX_DISTANCE_M,
             f'[{MIN_DISTANCE_M:g}, {MAX_DISTANCE_M:g}]'),
            ('pitch_deg', self.pitch_deg, -90.0 <= self.pitch_deg <= 0.0, '[-90, 0]'),
            ('target_height_m', self.target_height_m, math.isfinite(self.target_height_m),
             'a finite value'),
            ('heading_lag_s', self.heading_lag_s, 0.0 <= self.heading_lag_s <= 10.0,
             '[0, 10]'),
        )
        for name, value, ok, valid in checks:
            if not ok:   # NaN fails every comparison
                raise InvalidParameterError(f'chase camera {name} = {value!r}: must be in {valid}')

    def zoomed(self, steps: int) -> 'ChaseSettings':
        """
        Return the settings with the distance scaled by ZOOM_STEP**steps, kept in range.

        :param steps: positive = farther, negative = closer.
        """
        distance = self.distance_m * ZOOM_STEP ** steps
        return replace(self, distance_m=min(MAX_DISTANCE_M, max(MIN_DISTANCE_M, distance)))


@dataclass(frozen=True)
class ChaseView:
    """A camera in PyBullet's debug-camera terms."""

    distance_m: float
    yaw_deg: float
    pitch_deg: float
    target_m: Vector


def follow_heading(camera_rad: float, heading_rad: float, dt_s: float, lag_s: float) -> float:
    """
    Move the camera heading towards the vehicle heading by one first-order lag step.

    camera' = camera + wrap(heading - camera) * (1 - exp(-dt / lag)); lag 0 gives the heading.
    The shorter way round is taken, so a heading crossing ±pi does not spin the camera.

    :return: the new camera heading [rad], wrapped to (-pi, pi] (:func:`wrap_angle_rad`).
    """
    if lag_s <= 0.0:
        return wrap_angle_rad(heading_rad)
    gain = 1.0 - math.exp(-dt_s / lag_s)
    return wrap_angle_rad(camera_rad + wrap_angle_rad(heading_rad - camera_rad) * gain)


def bullet_yaw_deg(heading_rad: float) -> float:
    """Return PyBullet's camera yaw [deg] of a camera looking along ``heading_rad`` (REP 103)."""
    return math.degrees(wrap_angle_rad(heading_rad - math.pi / 2.0))


def chase_view(position_m: Vector, heading_rad: float, settings: ChaseSettings) -> ChaseView:
    """
    Return the view behind and above a vehicle, looking along its heading.

    :param position_m: the vehicle's reference point (x, y, z) in the world [m].
    :param heading_rad: the direction the camera looks along (the vehicle's yaw, or its
        lagged value from :func:`follow_heading`) [rad].
    """
    x, y, z = position_m
    return ChaseView(settings.distance_m, bullet_yaw_deg(heading_rad), settings.pitch_deg,
                     (float(x), float(y), float(z) + settings.target_height_m))


def camera_forward(view: ChaseView) -> Vector:
    """Return the unit vector the camera looks along (PyBullet's convention, z up)."""
    yaw = math.radians(view.yaw_deg) + math.pi / 2.0
    pitch = math.radians(view.pitch_deg)
    return (math.cos(pitch) * math.cos(yaw), math.cos(pitch) * math.sin(yaw), math.sin(pitch))


def eye_position(view: ChaseView) -> Vector:
    """Return where the camera is: target - distance * forward [m]."""
    forward = camera_forward(view)
    return tuple(t - view.distance_m * f for t, f in zip(view.target_m, forward))
