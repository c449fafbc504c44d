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
The traffic and signal topics of a node (docs/traffic.md): rows of :mod:`.endpoints`.

The objects' rows are global and published at their own rate on simulated time,
:data:`AT_OBJECTS_RATE` (:func:`objects_rate_hz`: 10 Hz by default, as Autoware's perception),
not each publish period. Wiring context ``w``: ``frame`` (the frame of both,
``map_interfaces.fixed_frame``: ``map`` with a lanelet2 map, as Autoware expects, else
``world``; a frame the node's tree has), ``colours`` (the bodies' colours); call context
``ctx``: ``stamp`` and ``objects`` (core TrafficObjects; None = nothing to publish) and
``obstacles`` (core ObstacleObjects, in PredictedObjects only).

The signals' row (:data:`TRAFFIC_SIGNALS`, a world whose lane map has traffic light groups:
:func:`signal_topics`) is published at the same rate and, besides, at the step any group
changes state (:data:`AT_SIGNALS`), so a planner never waits a period for a change; it is
transient-local, so a node that starts late gets the current states at once. Call context:
``stamp`` and ``groups`` (``traffic_messages.signal_groups_reader``'s). The lamps' markers for
RViz (:data:`TRAFFIC_LIGHT_MARKERS`) go with it, published only at the step a group changes
state (:data:`AT_SIGNAL_CHANGES`, the first step too), transient-local: wiring context ``frame``
and ``lanes`` (the LaneGraph: where the bulbs are), call context ``stamp`` and ``states``.
"""

from vehicle_sim.core.traffic.params import OBJECTS_RATE
from vehicle_sim.ros.endpoints import converter, Topic, topic_table_markdown
from vehicle_sim.ros.lane_messages import traffic_light_markers_builder
from vehicle_sim.ros.traffic_cdr import (
    predicted_objects_serializer,
    traffic_markers_serializer,
    traffic_signals_serializer,
)
from vehicle_sim.ros.traffic_messages import (
    MARKER_ARRAY,
    PREDICTED_OBJECTS,
    predicted_objects_builder,
    TRAFFIC_LIGHT_GROUP_ARRAY,
    traffic_markers_builder,
    traffic_signals_builder,
)
from vehicle_sim.transport.qos import QosProfile, TRANSIENT_LOCAL

# Autoware's dummy perception publisher: reliable, volatile, depth 1.
QOS_OBJECTS = QosProfile(depth=1)
# The signals: reliable, transient local (a late subscriber gets the states now; Autoware's
# planners' volatile depth-1 readers match it, as they match scenario_simulator_v2's
# transient-local publisher of this topic), depth 1 (only the latest states matter).
QOS_SIGNALS = QosProfile(depth=1, durability=TRANSIENT_LOCAL)

# Cadence of the rows: the objects' own rate (the node's objects_rate parameter, or the world's
# traffic: objects_rate), at the first basic step at or after each k / rate.
AT_OBJECTS_RATE = f'objects_rate ({OBJECTS_RATE.default:g} Hz by default)'
# The signals' cadence: the objects' rate, and the step at which any group changes state.
AT_SIGNALS = f'{AT_OBJECTS_RATE} and at the step a group changes state'
# The lamps' cadence: the first step, then the step at which any group changes state.
AT_SIGNAL_CHANGES = 'the first step, then at the step a group changes state'


def _objects(ctx):
    return None if ctx.objects is None else (ctx.stamp, ctx.objects)


def _objects_and_obstacles(ctx):
    return None if ctx.objects is None else (ctx.stamp, ctx.objects, ctx.obstacles)


PREDICTED_OBJECTS_TOPIC = Topic(
    '/perception/object_recognition/objects', PREDICTED_OBJECTS, QOS_OBJECTS, AT_OBJECTS_RATE,
    converter(predicted_objects_builder, _objects_and_obstacles, lambda w: (w.frame,),
              predicted_objects_serializer),
    unit='m, rad, m/s',
    doc='ground truth of every traffic body (its class: CAR, TRUCK, BUS, TRAILER, MOTORCYCLE, '
        'BICYCLE or PEDESTRIAN; a box, a pedestrian a CYLINDER; pose, twist, a path along its '
        'lane at constant speed) and obstacle (class UNKNOWN, at rest); frame map (a lanelet2 '
        'map) or world')
TRAFFIC_MARKERS = Topic(
    '/sim/traffic/markers', MARKER_ARRAY, QOS_OBJECTS, AT_OBJECTS_RATE,
    converter(traffic_markers_builder, _objects, lambda w: (w.frame, w.colours),
              traffic_markers_serializer),
    unit='m, rad', doc='one CUBE per traffic body, a CYLINDER per pedestrian (namespace '
                       'traffic, id its index); frame map (a lanelet2 map) or world')

TRAFFIC_TOPICS = (PREDICTED_OBJECTS_TOPIC, TRAFFIC_MARKERS)

TRAFFIC_SIGNALS = Topic(
    '/perception/traffic_light_recognition/traffic_signals', TRAFFIC_LIGHT_GROUP_ARRAY,
    QOS_SIGNALS, AT_SIGNALS,
    converter(traffic_signals_builder, lambda ctx: (ctx.stamp, ctx.groups),
              serializer=traffic_signals_serializer),
    doc="ground truth of every traffic light group of the lane map, as Autoware's planners "
        "read it: traffic_light_group_id the map's (a lanelet2 traffic_light regulatory "
        "element's id); per group one element (color RED / AMBER / GREEN, status SOLID_ON, "
        "confidence 1) per shape of its bulbs of the lit colour (CIRCLE without bulbs); a dark "
        "group ('off'): color and shape UNKNOWN, SOLID_OFF")
TRAFFIC_LIGHT_MARKERS = Topic(
    '/sim/traffic_lights/markers', MARKER_ARRAY, QOS_SIGNALS, AT_SIGNAL_CHANGES,
    converter(traffic_light_markers_builder, lambda ctx: (ctx.stamp, ctx.states),
              lambda w: (w.frame, w.lanes)),
    unit='m', doc='the bulbs of the traffic lights for RViz in the states of their groups: one '
                  'SPHERE_LIST (namespace traffic_light_bulbs), lit in the colour or dark grey '
                  'as the camera sees them (the housings and poles are in /map/lanes); frame '
                  'map (a lanelet2 map) or world')
SIGNAL_TOPICS = (TRAFFIC_SIGNALS, TRAFFIC_LIGHT_MARKERS)


def object_topics(has_traffic: bool, has_obstacles: bool):
    """Return the rows of a world: both with traffic, the objects alone with obstacles only."""
    if has_traffic:
        return TRAFFIC_TOPICS
    return (PREDICTED_OBJECTS_TOPIC,) if has_obstacles else ()


def signal_topics(controller) -> tuple:
    """Return the signals' rows of a world: its SignalController's groups, if any, else ()."""
    return SIGNAL_TOPICS if controller is not None and controller.rules.groups else ()


def objects_rate_hz(parameter_hz: float, traffic) -> float:
    """
    Return the rate of the object rows [Hz]: the world's ``traffic: objects_rate``, or the node's.

    :param parameter_hz: the node's ``objects_rate`` parameter.
    :param traffic: the world's core TrafficSpec, or None (a world with obstacles only).
    """
    world_hz = getattr(traffic, 'objects_rate_hz', None)
    return parameter_hz if world_hz is None else world_hz


def traffic_topic_table_markdown():
    """Return the docs table of the traffic topics (the signals' too)."""
    return topic_table_markdown(TRAFFIC_TOPICS + SIGNAL_TOPICS)
