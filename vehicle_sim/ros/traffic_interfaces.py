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
The traffic topics of a node whose world has traffic (docs/traffic.md): rows of :mod:`.endpoints`.

Both are global and published at their own rate on simulated time, :data:`AT_OBJECTS_RATE`
(:func:`objects_rate_hz`: 10 Hz by default, as Autoware's perception), not each publish period.
Wiring context ``w``: ``frame`` (the frame of both, ``map_interfaces.fixed_frame``: ``map`` with
a lanelet2 map, as Autoware expects, else ``world``; a frame the node's tree has), ``colours``
(the bodies' colours); call context ``ctx``: ``stamp`` and ``objects`` (core TrafficObjects;
None = nothing to publish) and ``obstacles`` (core ObstacleObjects, in PredictedObjects only).
"""

from vehicle_sim.core.traffic.params import OBJECTS_RATE
from vehicle_sim.ros.endpoints import converter, Topic, topic_table_markdown
from vehicle_sim.ros.traffic_cdr import predicted_objects_serializer, traffic_markers_serializer
from vehicle_sim.ros.traffic_messages import (
    MARKER_ARRAY,
    PREDICTED_OBJECTS,
    predicted_objects_builder,
    traffic_markers_builder,
)
from vehicle_sim.transport.qos import QosProfile

# Autoware's dummy perception publisher: reliable, volatile, depth 1.
QOS_OBJECTS = QosProfile(depth=1)

# Cadence of the rows: the objects' own rate (the node's objects_rate parameter, or the world's
# traffic: objects_rate), at the first basic step at or after each k / rate.
AT_OBJECTS_RATE = f'objects_rate ({OBJECTS_RATE.default:g} Hz by default)'


def _objects(ctx):
    return None if ctx.objects is None else (ctx.stamp, ctx.objects)


def _objects_and_obstacles(ctx):
    return None if ctx.objects is None else (ctx.stamp, ctx.objects, ctx.obstacles)


PREDICTED_OBJECTS_TOPIC = Topic(
    '/perception/object_recognition/objects', PREDICTED_OBJECTS, QOS_OBJECTS, AT_OBJECTS_RATE,
    converter(predicted_objects_builder, _objects_and_obstacles, lambda w: (w.frame,),
              predicted_objects_serializer),
    unit='m, rad, m/s',
    doc='ground truth of every traffic vehicle (class CAR, box, pose, twist, a path along its '
        'lane at constant speed) and obstacle (class UNKNOWN, at rest); frame map (a lanelet2 '
        'map) or world')
TRAFFIC_MARKERS = Topic(
    '/sim/traffic/markers', MARKER_ARRAY, QOS_OBJECTS, AT_OBJECTS_RATE,
    converter(traffic_markers_builder, _objects, lambda w: (w.frame, w.colours),
              traffic_markers_serializer),
    unit='m, rad', doc='one CUBE per traffic vehicle (namespace traffic, id its index); frame '
                       'map (a lanelet2 map) or world')

TRAFFIC_TOPICS = (PREDICTED_OBJECTS_TOPIC, TRAFFIC_MARKERS)


def object_topics(has_traffic: bool, has_obstacles: bool):
    """Return the rows of a world: both with traffic, the objects alone with obstacles only."""
    if has_traffic:
        return TRAFFIC_TOPICS
    return (PREDICTED_OBJECTS_TOPIC,) if has_obstacles else ()


def objects_rate_hz(parameter_hz: float, traffic) -> float:
    """
    Return the rate of the object rows [Hz]: the world's ``traffic: objects_rate``, or the node's.

    :param parameter_hz: the node's ``objects_rate`` parameter.
    :param traffic: the world's core TrafficSpec, or None (a world with obstacles only).
    """
    world_hz = getattr(traffic, 'objects_rate_hz', None)
    return parameter_hz if world_hz is None else world_hz


def traffic_topic_table_markdown():
    """Return the docs table of the traffic topics."""
    return topic_table_markdown(TRAFFIC_TOPICS)
