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
Which ROS 2 distribution's wire conventions this process speaks: ``humble`` or ``jazzy``.

Humble and Jazzy both run rmw_cyclonedds on Cyclone DDS 0.10, but their graph messages differ:
Humble's ``rmw_dds_common/msg/Gid`` is ``char[24]`` (rmw's ``RMW_GID_STORAGE_SIZE`` was 24: the
16-byte GUID followed by 8 zero bytes), Jazzy's ``char[16]``; both use the same DDS type name on
``ros_discovery_info``, so one process can speak only one of them. Among the messages in use,
only ``sensor_msgs/msg/Range`` has another layout (Humble has no ``variance``).

The choice: ``VEHICLE_SIM_ROS_DISTRO=humble|jazzy`` when set (it wins), else ``humble`` when
``ROS_DISTRO=humble`` (Humble's ``setup.bash`` sets it), else ``jazzy``. It is made once per
process, on first use.
"""

import os
import threading
from typing import Mapping, Optional, Tuple

ENV_VAR = 'VEHICLE_SIM_ROS_DISTRO'
HUMBLE = 'humble'
JAZZY = 'jazzy'
DISTROS = (HUMBLE, JAZZY)
DEFAULT = JAZZY

# Bytes of rmw_dds_common/msg/Gid on the wire.
GID_SIZES = {HUMBLE: 24, JAZZY: 16}
# The bytes of a DDS GUID (prefix + entity id): the part of a Gid that identifies the entity.
GUID_SIZE = 16

# Message types whose layout differs from Jazzy's, taken from rosbags' Humble type store.
HUMBLE_LAYOUTS = ('sensor_msgs/msg/Range',)

_lock = threading.Lock()
_selected: Optional[Tuple[str, str]] = None


def choose(environ: Optional[Mapping[str, str]] = None) -> Tuple[str, str]:
    """
    Return ``(distro, why)`` for an environment (default ``os.environ``).

    :raises ValueError: when ``VEHICLE_SIM_ROS_DISTRO`` is set to anything but humble or jazzy.
    """
    environ = os.environ if environ is None else environ
    explicit = environ.get(ENV_VAR, '').strip()
    if explicit:
        if explicit.lower() not in DISTROS:
            raise ValueError(f'{ENV_VAR}={explicit!r}: expected one of {", ".join(DISTROS)}')
        return explicit.lower(), f'{ENV_VAR}={explicit}'
    ros_distro = environ.get('ROS_DISTRO', '').strip()
    if ros_distro.lower() == HUMBLE:
        return HUMBLE, f'ROS_DISTRO={ros_distro}'
    if ros_distro:
        return DEFAULT, f'ROS_DISTRO={ros_distro} (not humble: {DEFAULT})'
    return DEFAULT, f'default ({ENV_VAR} and ROS_DISTRO unset)'


def selected_with_reason() -> Tuple[str, str]:
    """Return this process's ``(distro, why)``: chosen from the environment on the first call."""
    global _selected
    with _lock:
        if _selected is None:
            _selected = choose()
        return _selected


def selected() -> str:
    """Return the distribution this process speaks (``'humble'`` or ``'jazzy'``)."""
    return selected_with_reason()[0]


def gid_size(distro: Optional[str] = None) -> int:
    """Return the size of a Gid for ``distro`` (default: this process's)."""
    return GID_SIZES[distro or selected()]


def title(distro: str) -> str:
    """Return the display name of a distribution: ``'Humble'``."""
    return distro.capitalize()
