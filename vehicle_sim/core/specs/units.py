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
Unit and sign conversions: the one place where units change.

Webots semantics: speed in km/h, steering angle in rad with positive = right.
ROS / REP 103 / Autoware semantics: speed in m/s, steering angle in rad with positive = left.
"""

import math

KMH_PER_MPS = 3.6
RPM_PER_RADPS = 60.0 / (2.0 * math.pi)


def kmh_to_mps(speed_kmh):
    """Convert a speed [km/h] to [m/s]."""
    return speed_kmh / KMH_PER_MPS


def mps_to_kmh(speed_mps):
    """Convert a speed [m/s] to [km/h]."""
    return speed_mps * KMH_PER_MPS


def radps_to_rpm(speed_radps):
    """Convert an angular speed [rad/s] to [rev/min]."""
    return speed_radps * RPM_PER_RADPS


def rpm_to_radps(speed_rpm):
    """Convert an angular speed [rev/min] to [rad/s]."""
    return speed_rpm / RPM_PER_RADPS


def webots_steering_to_ros(angle_rad):
    """Convert a Webots steering angle (+ = right) to the REP 103 / Autoware sign (+ = left)."""
    return -angle_rad


def ros_steering_to_webots(angle_rad):
    """Convert a REP 103 / Autoware steering angle (+ = left) to the Webots sign (+ = right)."""
    return -angle_rad


def seconds_to_stamp(time_s):
    """
    Split a time [s] into the (sec, nanosec) pair of builtin_interfaces/Time.

    :param time_s: time [s], non-negative.
    :return: (sec, nanosec) with 0 <= nanosec < 1e9.
    """
    total_ns = int(round(time_s * 1e9))
    return total_ns // 1_000_000_000, total_ns % 1_000_000_000


def stamp_to_seconds(sec, nanosec):
    """Join a builtin_interfaces/Time (sec, nanosec) pair into seconds."""
    return sec + nanosec * 1e-9
