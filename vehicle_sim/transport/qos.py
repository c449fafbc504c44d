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

"""QoS profiles of the port and their presets (rclpy.qos's names; rmw's and rclpy's defaults)."""

from dataclasses import dataclass
from typing import Optional, Union

from vehicle_sim.transport.errors import TransportError

KEEP_LAST = 'keep_last'
KEEP_ALL = 'keep_all'
RELIABLE = 'reliable'
BEST_EFFORT = 'best_effort'
VOLATILE = 'volatile'
TRANSIENT_LOCAL = 'transient_local'


@dataclass(frozen=True)
class QosProfile:
    """
    A ROS QoS profile as a small value type.

    ``lifespan_s``/``deadline_s`` are None for "not specified" (DDS default: infinite).
    ``avoid_ros_namespace_conventions`` drops the ``rt/`` prefix (used for ``ros_discovery_info``).
    """

    depth: int = 10
    history: str = KEEP_LAST
    reliability: str = RELIABLE
    durability: str = VOLATILE
    lifespan_s: Optional[float] = None
    deadline_s: Optional[float] = None
    avoid_ros_namespace_conventions: bool = False

    def __post_init__(self):
        if self.history not in (KEEP_LAST, KEEP_ALL):
            raise TransportError(f'unknown QoS history {self.history!r}')
        if self.reliability not in (RELIABLE, BEST_EFFORT):
            raise TransportError(f'unknown QoS reliability {self.reliability!r}')
        if self.durability not in (VOLATILE, TRANSIENT_LOCAL):
            raise TransportError(f'unknown QoS durability {self.durability!r}')
        if self.history == KEEP_LAST and self.depth < 0:
            raise TransportError(f'QoS depth must be >= 0, got {self.depth}')


QOS_DEFAULT = QosProfile(depth=10)
QOS_SERVICES = QosProfile(depth=10)
QOS_SENSOR_DATA = QosProfile(depth=5, reliability=BEST_EFFORT)
QOS_PARAMETERS = QosProfile(depth=1000)
QOS_PARAMETER_EVENTS = QosProfile(depth=1000)
QOS_SYSTEM_DEFAULT = QosProfile(depth=1)
QOS_ROSOUT = QosProfile(depth=1000, durability=TRANSIENT_LOCAL, lifespan_s=10.0)
QOS_CLOCK = QosProfile(depth=1, reliability=BEST_EFFORT)
QOS_TF = QosProfile(depth=100)
QOS_TF_STATIC = QosProfile(depth=1, durability=TRANSIENT_LOCAL)
QOS_TF_STATIC_LISTENER = QosProfile(depth=100, durability=TRANSIENT_LOCAL)
QOS_LATCHED = QosProfile(depth=1, durability=TRANSIENT_LOCAL)
QOS_DISCOVERY_INFO_WRITER = QosProfile(
    depth=1, durability=TRANSIENT_LOCAL, avoid_ros_namespace_conventions=True)
QOS_DISCOVERY_INFO_READER = QosProfile(
    history=KEEP_ALL, durability=TRANSIENT_LOCAL, avoid_ros_namespace_conventions=True)

QOS_PRESETS = {
    'default': QOS_DEFAULT,
    'services': QOS_SERVICES,
    'sensor_data': QOS_SENSOR_DATA,
    'parameters': QOS_PARAMETERS,
    'parameter_events': QOS_PARAMETER_EVENTS,
    'system_default': QOS_SYSTEM_DEFAULT,
    'rosout': QOS_ROSOUT,
    'clock': QOS_CLOCK,
    'tf': QOS_TF,
    'tf_static': QOS_TF_STATIC,
    'tf_static_listener': QOS_TF_STATIC_LISTENER,
    'latched': QOS_LATCHED,
}


def as_qos(qos: Union[QosProfile, int, str, None]) -> QosProfile:
    """
    Normalise a QoS argument: a profile, a depth (like rclpy's ``10``) or a preset name.

    :raises TransportError: for an unknown preset name.
    """
    if qos is None:
        return QOS_DEFAULT
    if isinstance(qos, QosProfile):
        return qos
    if isinstance(qos, bool):
        raise TransportError(f'invalid QoS {qos!r}')
    if isinstance(qos, int):
        return QosProfile(depth=qos)
    if isinstance(qos, str):
        try:
            return QOS_PRESETS[qos]
        except KeyError:
            raise TransportError(
                f'unknown QoS preset {qos!r}; valid: {", ".join(sorted(QOS_PRESETS))}') from None
    raise TransportError(f'invalid QoS {qos!r}')
