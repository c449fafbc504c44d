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
The interface definitions shipped with vehicle_sim, as ``.msg`` / ``.srv`` text files.

Every definition lives once, under ``definitions/<package>/<msg|srv>/<Name>.<msg|srv>``:

* ``vehicle_msgs``: our own Webots-shaped types (docs/ros_interface.md); exported as an ament
package.
* ``autoware_control_msgs``, ``autoware_auto_control_msgs``, ``autoware_vehicle_msgs``,
  ``autoware_perception_msgs`` (traffic's PredictedObjects, the signals' TrafficLightGroupArray),
  ``ackermann_msgs``, ``vision_msgs`` (a camera's detections and label table): copies of the
  real packages' definitions (autoware_msgs 1.9.0, ackermann_msgs 2.0, vision_msgs 4.1.1), so
  the embedded transport can speak them without ROS installed.
* ``radar_msgs`` (the radar's RadarTracks and RadarScan): copies of ros-perception/radar_msgs
  0.2.2.
* ``rcl_interfaces`` / ``std_srvs`` services, which rosbags' Jazzy type store lacks.

This module only finds and splits the files; ``vehicle_msgs_py.types`` turns them into types.
"""

from dataclasses import dataclass
from pathlib import Path

DEFINITIONS_DIR = Path(__file__).resolve().parent / 'definitions'

# A line holding only '---' separates a service's request from its response (rosidl).
SERVICE_SEPARATOR = '---'


@dataclass(frozen=True)
class Definition:
    """One interface file: ``ros_type`` is ``pkg/msg/Name`` or ``pkg/srv/Name``."""

    package: str
    kind: str
    name: str
    path: Path

    @property
    def ros_type(self):
        return f'{self.package}/{self.kind}/{self.name}'

    def text(self):
        return self.path.read_text(encoding='utf-8')


def definitions(package=None):
    """
    List the shipped interface definitions, sorted by ROS type name.

    :param package: only this ROS package (e.g. ``'vehicle_msgs'``); ``None`` for all.
    :return: tuple of :class:`Definition`.
    """
    found = []
    for path in DEFINITIONS_DIR.glob('*/*/*'):
        kind = path.parent.name
        if kind not in ('msg', 'srv') or path.suffix != '.' + kind:
            continue
        pkg = path.parent.parent.name
        if package is None or pkg == package:
            found.append(Definition(pkg, kind, path.stem, path))
    return tuple(sorted(found, key=lambda d: d.ros_type))


def split_service(text):
    """
    Split a ``.srv`` text into its request and response parts.

    :param text: the service definition.
    :return: ``(request_text, response_text)``.
    :raises ValueError: when there is not exactly one ``---`` separator line.
    """
    lines = text.splitlines()
    cuts = [i for i, line in enumerate(lines) if line.strip() == SERVICE_SEPARATOR]
    if len(cuts) != 1:
        raise ValueError(f'a .srv needs exactly one {SERVICE_SEPARATOR!r} line, found {len(cuts)}')
    cut = cuts[0]
    return '\n'.join(lines[:cut]) + '\n', '\n'.join(lines[cut + 1:]) + '\n'
