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
A world's lane map, loaded before its bodies are built: :func:`with_lanes`.

A world has at most one lane map: a ``map:`` of a lane map kind (``MapKind.lane_map``, read by
its row of :data:`LANE_LOADERS`: ``lanelet2`` with the lanelet2 package,
``maps/lanelet2_map.py``; ``sumo``, ``opendrive`` and ``osm`` with sumolib,
``maps/sumo_net.py``, the latter two converted by netconvert first, ``maps/netconvert.py``) or
its ``roads:`` (core/map/road_segments.py). The scene
builder calls :func:`with_lanes` before it builds anything, so that a file that cannot be read
or a vehicle placed off every lane is refused with nothing started, and the vehicles placed by
lane (``pose: {lanelet, s, offset}``) have their x, y, yaw when their bodies are made.
"""

from dataclasses import replace

from vehicle_sim.core.map.kinds import is_lane_map
from vehicle_sim.core.map.lane_placement import place_on_lanes
from vehicle_sim.core.map.road_segments import lane_graph_from_roads


def load_lanelet2_graph(spec):
    """Return the LaneGraph of a WorldSpec's lanelet2 map (``LANE_LOADERS['lanelet2']``)."""
    from vehicle_sim.maps.lanelet2_map import load_lanelet2  # the lanelet2 extra
    world_map = spec.map
    graph, _, _ = load_lanelet2(world_map.file, spec.origin, world_map.projector,
                                world_map.default_speed_limit_mps, f'{world_map.source}.file')
    return graph


def load_sumo_net_graph(spec):
    """Return the LaneGraph of a WorldSpec's SUMO network map (converted first if need be)."""
    from vehicle_sim.maps.netconvert import net_file  # the sumo extra
    from vehicle_sim.maps.sumo_net import load_sumo_net
    world_map = spec.map
    path = net_file(world_map)
    shown = path if world_map.net else \
        f'{world_map.file} (converted by netconvert into {path})'   # the user's file first
    graph, _ = load_sumo_net(path, world_map.vclass, f'{world_map.source}.{world_map.field}',
                             shown)
    return graph


# lane map kind (core/map/kinds.py MAP_KINDS, lane_map=True) -> load(WorldSpec) -> LaneGraph.
LANE_LOADERS = {
    'lanelet2': load_lanelet2_graph,
    'sumo': load_sumo_net_graph,
    'opendrive': load_sumo_net_graph,
    'osm': load_sumo_net_graph,
}


def load_lane_graph(spec):
    """Return the LaneGraph of a WorldSpec's lane map, or None when it has none."""
    if is_lane_map(spec.map):
        return LANE_LOADERS[spec.map.type](spec)
    if spec.roads:
        return lane_graph_from_roads(spec.roads, f"{spec.source or 'world'}: roads")
    return None


def with_lanes(spec):
    """
    Return the WorldSpec with its lane map loaded (``spec.lanes``) and its vehicles placed.

    A spec loaded already, or one without a lane map and without vehicles placed by lane, is
    returned as it is.

    :raises InvalidParameterError: the lane map cannot be read, or a vehicle placed by lane is
        off it (or the world has none), naming the file and the field.
    """
    if spec.lanes is not None:
        return spec
    graph = load_lane_graph(spec)
    placed_by_lane = any(v.lane_pose is not None for v in spec.vehicles)
    if graph is None and not placed_by_lane:
        return spec
    vehicles = place_on_lanes(spec.vehicles, graph, spec.source or 'world')
    return replace(spec, vehicles=vehicles, lanes=graph)
