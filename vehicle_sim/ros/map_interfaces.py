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
The topics of a world's map: rows per map kind, and the map -> world transform.

A node whose scene has a map (``scene.parts['map']``, physics/map_layer.py) wires the rows
:func:`map_rows` gives for its kind with :class:`MapOutputs` and publishes them once, latched,
with its other latched rows. An occupancy grid publishes ``/map`` and ``/map_metadata`` as nav2
map_server does (transient-local, reliable, depth 1; frame ``map``); a lane map (a lanelet2
map, a SUMO network, or a world's ``roads:``) publishes ``/map/lanes``
(visualization_msgs/MarkerArray, the same QoS; frame :func:`fixed_frame`). Every map adds the
``map -> world`` transform to ``/tf_static`` (:func:`map_static_transform`): identity unless the
world file's ``world_in_map`` says otherwise.

Wiring context: ``map_frame``, ``lanes_frame``; call context: ``stamp`` (the loading time),
``grid`` (the core OccupancyGrid), ``lanes`` (the core LaneGraph).
"""

import math
from types import SimpleNamespace
from typing import Dict, Tuple

from vehicle_sim.core.geometry.frames import quaternion_from_yaw
from vehicle_sim.core.map.kinds import is_lane_map
from vehicle_sim.ros import messages as m
from vehicle_sim.ros.endpoints import converter, ONCE_LATCHED, Outputs, Topic
from vehicle_sim.ros.lane_cdr import lane_markers_serializer
from vehicle_sim.ros.lane_messages import lane_markers_builder, MARKER_ARRAY
from vehicle_sim.transport.qos import QOS_LATCHED

MAP_FRAME = 'map'
WORLD_FRAME = 'world'

MAP = Topic('/map', m.OCCUPANCY_GRID, QOS_LATCHED, ONCE_LATCHED,
            converter(m.occupancy_grid_builder, lambda ctx: (ctx.stamp, ctx.grid),
                      lambda w: (w.map_frame,)),
            unit='m', doc='the occupancy grid as nav2 map_server publishes it (0 / 100 / -1 in '
                          'trinary mode), frame map')
MAP_METADATA = Topic('/map_metadata', m.MAP_META_DATA, QOS_LATCHED, ONCE_LATCHED,
                     converter(m.map_meta_data_builder, lambda ctx: (ctx.stamp, ctx.grid)),
                     unit='m', doc="the grid's size, resolution and origin")

MAP_LANES = Topic('/map/lanes', MARKER_ARRAY, QOS_LATCHED, ONCE_LATCHED,
                  converter(lane_markers_builder, lambda ctx: (ctx.stamp, ctx.lanes),
                            lambda w: (w.lanes_frame,), serializer=lane_markers_serializer),
                  unit='m', doc='the lane map for RViz: road surface (triangle list), lane '
                                'boundaries by line type, centrelines, and the stop lines, '
                                'crosswalks, areas and traffic light heads and poles of its '
                                'rules; frame map (a map: lane map) or world (roads:)')

# map kind (core/map/kinds.py MAP_KINDS) -> its rows.
MAP_TOPICS: Dict[str, Tuple[Topic, ...]] = {
    'occupancy_grid': (MAP, MAP_METADATA),
    'lanelet2': (MAP_LANES,),
    'sumo': (MAP_LANES,),
    'opendrive': (MAP_LANES,),
    'osm': (MAP_LANES,),
}
# The rows of a world's roads: (a lane map without a map: key).
ROADS_TOPICS: Tuple[Topic, ...] = (MAP_LANES,)


def map_rows(built) -> Tuple[Topic, ...]:
    """Return the rows of a built map (``scene.parts['map']``); () for no map."""
    return () if built is None else MAP_TOPICS[built.spec.type]


def fixed_frame(spec) -> str:
    """
    Return the frame of a world's ground-truth messages: ``map`` (a lane map), else ``world``.

    The one rule for the lane messages (``/map/lanes``, ``lane_state``, ``lane_invasion``) and
    the objects (``/perception/object_recognition/objects``, ``/sim/traffic/markers``): a frame
    the node's tree has. A lanelet2 map's nodes are in the map frame (Autoware's), which is the
    world frame there (core/map/kinds.py refuses a world_in_map other than the identity); roads,
    obstacles and an occupancy grid's world are written in the world frame, and a world without
    ``map:`` has no ``map`` frame (docs/maps.md).
    """
    return MAP_FRAME if is_lane_map(spec.map) else WORLD_FRAME


def map_static_transform(map_spec):
    """Return the ``/tf_static`` entry (parent, child, xyz, q) of ``map -> world``."""
    placement = map_spec.world_in_map
    return (MAP_FRAME, WORLD_FRAME, (placement.x_m, placement.y_m, 0.0),
            quaternion_from_yaw(placement.yaw_rad))


def map_in_world(map_spec):
    """Return the pose (xyz, q) of the map frame in the world frame (/initialpose in 'map')."""
    placement = map_spec.world_in_map
    c, s = math.cos(placement.yaw_rad), math.sin(placement.yaw_rad)
    x, y = -(c * placement.x_m + s * placement.y_m), s * placement.x_m - c * placement.y_m
    return (x, y, 0.0), quaternion_from_yaw(-placement.yaw_rad)


class MapOutputs:
    """
    The publishers of a scene's map rows (none for a scene without a map or roads).

    :param node: a transport NodePort.
    :param built: ``scene.parts.get('map')``.
    :param roads: ``scene.parts.get('roads')`` (a LaneMap of the world's roads:), or None.
    :param frame: the frame of the lane messages (:func:`fixed_frame`).
    """

    def __init__(self, node, built, roads=None, frame=WORLD_FRAME):
        self._built = built
        rows = map_rows(built) + (ROADS_TOPICS if roads is not None else ())
        lanes = getattr(built, 'lanes', None) or getattr(roads, 'lanes', None)
        self._context = SimpleNamespace(map_frame=MAP_FRAME, stamp=None,
                                        grid=getattr(built, 'grid', None), lanes=lanes,
                                        lanes_frame=frame)
        self.outputs = Outputs(node, rows, self._context) if rows else None
        # One line for the node's log: what was loaded ('' without a map).
        loaded = [f'map {built.describe()}'] if built is not None else []
        if roads is not None:
            loaded.append(roads.describe())     # its source names the world file and 'roads'
        self.summary = '' if not loaded else (
            '; '.join(loaded) + '; publishing ' + ', '.join(row.name for row in rows))

    def publish_latched(self, stamp):
        """Publish the map's latched rows with ``stamp`` (the time the map was loaded)."""
        if self.outputs is not None:
            self._context.stamp = stamp
            self.outputs.publish(ONCE_LATCHED, self._context)
