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
Webots Radar (radar.md): ``getTargets`` and ``getNumberOfTargets`` of the last sample.

:class:`RadarMethods` are the Radar's own methods; webots/devices.py makes the ``Radar`` device
of them and its ``Device`` base (enable, disable, getSamplingPeriod, the last reading), and the
field getters (getMinRange, getMaxRange, getHorizontalFov, getVerticalFov) come from its
DEVICE_API row (webots/api_table.py).
"""


class RadarTarget:
    """
    Webots RadarTarget: distance [m], received_power [dBm], speed [m/s], azimuth [rad].

    Webots' sign: ``azimuth`` > 0 to the right of the radar's axis (WbRadar), ``speed`` > 0
    moving away. Webots' Python class names its power ``receiver_power`` (radar_target.py) where
    its documentation says ``received_power``: both are here.
    """

    def __init__(self, distance, received_power, speed, azimuth):
        self.distance = distance
        self.received_power = received_power
        self.speed = speed
        self.azimuth = azimuth

    @property
    def receiver_power(self):
        return self.received_power

    def __repr__(self):
        return (f'RadarTarget(distance={self.distance}, received_power={self.received_power}, '
                f'speed={self.speed}, azimuth={self.azimuth})')


class RadarMethods:
    """
    Webots Radar's methods over a Device's last reading (``_reading``).

    With the snake_case properties of Webots' Python Radar (radar.py): targets,
    number_of_targets, min_range, max_range, horizontal_fov, vertical_fov.
    """

    def getTargets(self):
        """Return the targets of the last sample, nearest first ([] before the first)."""
        reading = self._reading('getTargets')
        if reading is None:
            return []
        return [RadarTarget(t.distance_m, t.received_power_dbm, t.speed_mps, -t.azimuth_rad)
                for t in reading.targets]

    def getNumberOfTargets(self):
        """Return how many targets the last sample has (0 before the first)."""
        reading = self._reading('getNumberOfTargets')
        return 0 if reading is None else len(reading.targets)

    @property
    def targets(self):
        return self.getTargets()

    @property
    def min_range(self):
        return self.getMinRange()

    @property
    def max_range(self):
        return self.getMaxRange()

    @property
    def horizontal_fov(self):
        return self.getHorizontalFov()

    @property
    def vertical_fov(self):
        return self.getVerticalFov()

    @property
    def number_of_targets(self):
        return self.getNumberOfTargets()
