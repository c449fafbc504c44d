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

Both are global and published each publish period. Wiring context ``w``: ``frame`` (the frame of
both, ``map_interfaces.fixed_frame``: ``map`` with a lanelet2 map, as Autoware expects, else
``world``; a frame the node's tree has), ``colours`` (the bodies' colours); call context
``ctx``: ``stamp`` and
``objects`` (core TrafficObjects; None = nothing to publish) and ``obstacles`` (core
ObstacleObjects, in PredictedObjects only).
"""

from vehicle_sim.ros.endpoints import converter, EACH_PUBLISH, Topic, topic_table_markdown
from vehicle_sim.ros.traffic_messages import (
    MARKER_ARRAY,
    PREDICTED_OBJECTS,
    predicted_objects_builder,
    traffic_markers_builder,
)
from vehicle_sim.transport.qos import QosProfile

# Autoware's dummy perception publisher: reliable, volatile, depth 1.
QOS_OBJECTS = QosProfile(depth=1)


def _objects(ctx):
    return None if ctx.objects is None else (ctx.stamp, ctx.objects)


def _objects_and_obstacles(ctx):
    return None if ctx.objects is None else (ctx.stamp, ctx.objects, ctx.obstacles)


PREDICTED_OBJECTS_TOPIC = Topic(
    '/perception/object_recognition/objects', PREDICTED_OBJECTS, QOS_OBJECTS, EACH_PUBLISH,
    converter(predicted_objects_builder, _objects_and_obstacles, lambda w: (w.frame,)),
    unit='m, rad, m/s',
    doc='ground truth of every traffic vehicle (class CAR, box, pose, twist, a path along its '
        'lane at constant speed) and obstacle (class UNKNOWN, at rest); frame map (a lanelet2 '
        'map) or world')
TRAFFIC_MARKERS = Topic(
    '/sim/traffic/markers', MARKER_ARRAY, QOS_OBJECTS, EACH_PUBLISH,
    converter(traffic_markers_builder, _objects, lambda w: (w.frame, w.colours)),
    unit='m, rad', doc='one CUBE per traffic vehicle (namespace traffic, id its index); frame '
                       'map (a lanelet2 map) or world')

TRAFFIC_TOPICS = (PREDICTED_OBJECTS_TOPIC, TRAFFIC_MARKERS)


def object_topics(has_traffic: bool, has_obstacles: bool):
    """Return the rows of a world: both with traffic, the objects alone with obstacles only."""
    if has_traffic:
        return TRAFFIC_TOPICS
    return (PREDICTED_OBJECTS_TOPIC,) if has_obstacles else ()


def traffic_topic_table_markdown():
    """Return the docs table of the traffic topics."""
    return topic_table_markdown(TRAFFIC_TOPICS)
