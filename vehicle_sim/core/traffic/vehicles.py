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


"""The state of a traffic vehicle and what traffic knows of our vehicles (plain classes)."""


class OurVehicle:
    """
    One of our vehicles as traffic sees it: its footprint centre, heading, speed and size.

    :param name: its name (for the collision reports).
    :param x_m: footprint centre x [m].
    :param y_m: footprint centre y [m].
    :param yaw_rad: heading [rad].
    :param speed_mps: speed along its heading [m/s].
    :param length_m: footprint length [m].
    :param width_m: footprint width [m].
    """

    __slots__ = ('name', 'x_m', 'y_m', 'yaw_rad', 'speed_mps', 'length_m', 'width_m')

    def __init__(self, name, x_m, y_m, yaw_rad, speed_mps, length_m, width_m):
        self.name, self.x_m, self.y_m, self.yaw_rad = name, x_m, y_m, yaw_rad
        self.speed_mps, self.length_m, self.width_m = speed_mps, length_m, width_m


class TrafficVehicle:
    """The state of one traffic vehicle (mutable; the manager owns it)."""

    __slots__ = ('index', 'name', 'model', 'length_m', 'width_m', 'factor', 'lane', 's_m',
                 'speed_mps', 'acc_mps2', 'offset_m', 'from_lane', 'from_s_m', 'change_s',
                 'change_from_m', 'next_lane', 'prev_lane', 'route', 'keep_lane', 'scripted',
                 'active', 'stopped')

    def __init__(self, index, model, length_m, width_m, factor, lane, s_m, route):
        self.index = index
        self.name = f'traffic_{index}'
        self.model, self.length_m, self.width_m, self.factor = model, length_m, width_m, factor
        self.lane, self.s_m, self.speed_mps, self.acc_mps2 = lane, s_m, 0.0, 0.0
        self.offset_m = 0.0          # lateral offset from the lane's centreline (+ = left)
        self.from_lane = None        # the lane being left during a change
        self.from_s_m = 0.0
        self.change_s = 0.0          # time since the change began [s]
        self.change_from_m = 0.0     # the offset the change began at
        self.next_lane = None
        self.prev_lane = None        # the lane it came from (its rear may still be there)
        self.route = list(route)
        self.keep_lane = bool(route)  # a routed vehicle drives its route: no lane changes
        self.scripted = None          # (side 'left' | 'right', from time [s]): a scripted change
        self.active = True           # False: left the map at a dead end, waiting to re-enter
        self.stopped = False         # collided: stands still

    @property
    def changing(self):
        return self.from_lane is not None
