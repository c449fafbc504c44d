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
The policy driver node's interface table: what ``vehicle-sim policy run`` reads and writes.

It reads the automobile node's rows (their names and types are those of
:mod:`.automobile_interfaces` and :mod:`.traffic_interfaces`, under the vehicle namespace) and
calls its Webots-level setters (:mod:`.policy_actions`); its one output, ``<ns>/policy/action``,
is the action in force, published at each /clock once that step's commands are served: the
scenario runner's lockstep topic (docs/scenarios.md, ``driver.sync``). docs/ros_interface.md
embeds :func:`policy_table_markdown`.
"""

from vehicle_sim.ros import automobile_interfaces as itf
from vehicle_sim.ros import messages as m
from vehicle_sim.ros.endpoints import (
    CLOCK,
    converter,
    EACH_STEP,
    input_topic,
    TF_STATIC,
    Topic,
    topic_table_markdown,
)
from vehicle_sim.ros.traffic_interfaces import PREDICTED_OBJECTS_TOPIC
from vehicle_sim.transport.qos import QOS_CLOCK, QOS_DEFAULT

POLICY_NODE_NAME = 'policy_driver'


def _same(row, doc, qos=None):
    # An input row reading an output row of another node's table (its name, type and QoS).
    return input_topic(row.name, row.ros_type, None, doc, qos=qos or row.qos, unit=row.unit)


CLOCK_IN = _same(CLOCK, 'simulated time: the policy acts at every multiple of its period '
                        '(action_repeat x time_step), the first time at the first answer time '
                        '(the first objects)', QOS_CLOCK)
ODOM_IN = _same(itf.ODOM, "the ego's odometry: the 'twist' key, and its pose for 'objects'")
LANE_STATE_IN = _same(itf.LANE_STATE, "the ego's lane: the 'lane' key, lane_speed's steering law")
OBJECTS_IN = _same(PREDICTED_OBJECTS_TOPIC,
                   "the 'objects' key (the policy's period a whole number of the objects' "
                   "periods: objects_rate, --objects-rate)")
TF_STATIC_IN = _same(TF_STATIC, "world -> <p>odom: the ego's pose in the objects' frame")
# Call context: ``action`` (the physical action in force; None before the first tick).
ACTION = Topic('policy/action', m.FLOAT64_MULTI_ARRAY, QOS_DEFAULT, EACH_STEP,
               converter(m.float64_multi_array_builder,
                         lambda ctx: ([] if ctx.action is None
                                      else [float(v) for v in ctx.action],)),
               unit='rad, m/s (speed_steering)',
               doc="the action in force, in the environment's units (speed_steering: steering "
                   'angle + left, speed; empty before the first), at each answer time (every '
                   "objects period, else every policy period) once that tick's setters "
                   "answered: the scenario runner's lockstep (sync) topic")
INPUTS = (CLOCK_IN, ODOM_IN, LANE_STATE_IN, OBJECTS_IN, TF_STATIC_IN)
OUTPUTS = (ACTION,)


def policy_table_markdown():
    """Return the policy node's topics as a Markdown table (docs/ros_interface.md)."""
    return topic_table_markdown(
        INPUTS + OUTPUTS, ('type', 'direction', 'QoS', 'unit', 'notes'),
        lambda row: row.name if row.name.startswith('/') else '/<ns>/' + row.name)


def service_type(name):
    """Return the type of an automobile service the policy calls (its table row)."""
    return itf.service(name).srv_type
