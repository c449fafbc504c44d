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
Placing a vehicle by lane: ``pose: {lanelet: <id>, s: <m along its centreline>, offset: <m>}``.

Besides x/y/yaw, a vehicle of a world with a lane map may be placed on a lane: at arc length
``s`` along the lane's centreline, ``offset`` to its left (+) or right (-), heading along the
lane. The lane is its id (``lanelet``) or its name (``lane``: a SUMO network's lane id such as
``'E0_0'``, ``LaneGraph.lane_named``), one of the two. A lane that is not in the map, an ``s``
beyond the lane or an offset off it is refused, naming the source and the field.
"""

from dataclasses import replace

from vehicle_sim.core.specs.errors import InvalidParameterError
from vehicle_sim.core.specs.param_spec import ParamSpec, validate_table

LANE_POSE_SPECS = (
    ParamSpec('lanelet', 'lanelet', 'int', None, doc="the lane's id (a lanelet id, or a "
              "road segment lane's id); or give 'lane'", optional=True),
    ParamSpec('lane', 'lane', 'str', None, doc="the lane's name instead of its id (a SUMO "
              "network's lane id, e.g. 'E0_0')", optional=True),
    ParamSpec('s', 's_m', 'float', 0.0, 'm', 'arc length along its centreline', ge=0.0),
    ParamSpec('offset', 'offset_m', 'float', 0.0, 'm', 'lateral offset from the centreline, '
              '+ = left'),
)


def is_lane_pose(data):
    """Return whether a ``pose:`` mapping places by lane (it names a ``lanelet`` or a ``lane``)."""
    return isinstance(data, dict) and ('lanelet' in data or 'lane' in data)


def lane_pose_values(data, source):
    """
    Validate a ``pose: {lanelet | lane, s, offset}`` mapping: (lane id or name, s, offset).

    :raises InvalidParameterError: naming the source and the field; both or neither of
        ``lanelet`` and ``lane``.
    """
    values = validate_table(LANE_POSE_SPECS, data, source, what='a pose on a lane')
    if (values['lanelet'] is None) == (values['lane'] is None):
        raise InvalidParameterError(f"{source}: give the lane by its id ('lanelet') or by its "
                                    "name ('lane'), one of the two")
    lane = values['lanelet'] if values['lane'] is None else values['lane']
    return lane, values['s_m'], values['offset_m']


def pose_on_lane(data, graph, source):
    """
    Return the world pose (x, y, yaw) of a ``pose: {lanelet, s, offset}`` mapping.

    :param data: the mapping.
    :param graph: the world's LaneGraph (None: the world has no lane map, refused).
    :param source: where the pose is written ('w.yaml: vehicles[0].pose').
    :raises InvalidParameterError: naming the source and the field.
    """
    lane, s_m, offset_m = lane_pose_values(data, source)
    what = f'lane {lane!r}' if isinstance(lane, str) else f'lanelet {lane}'
    if graph is None:
        raise InvalidParameterError(f'{source}: placed on {what}, but the world has no lane '
                                    'map (map: of a lane map type, or roads:)')
    try:
        lane_id = graph.lane_named(lane).id if isinstance(lane, str) else lane
        return graph.pose_at(lane_id, s_m, offset_m)
    except InvalidParameterError as error:
        reason, prefix = str(error), graph.source + ': '
        reason = reason[len(prefix):] if reason.startswith(prefix) else reason
        raise InvalidParameterError(f'{source}: {reason}') from None


def place_on_lanes(vehicles, graph, source):
    """
    Return the vehicles with those placed by lane (``lane_pose``) at their lane's pose.

    :param vehicles: VehicleSpecs of a world, in file order (``lane_pose`` None: kept).
    :param graph: the world's LaneGraph, or None.
    :param source: the world file, quoted in errors ('w.yaml: vehicles[0].pose: ...').
    :raises InvalidParameterError: a lane pose off the map, naming the vehicle's ``pose``.
    """
    placed = []
    for index, vehicle in enumerate(vehicles):
        if getattr(vehicle, 'lane_pose', None) is None:
            placed.append(vehicle)
            continue
        lane, s_m, offset_m = vehicle.lane_pose
        key = 'lane' if isinstance(lane, str) else 'lanelet'
        x_m, y_m, yaw_rad = pose_on_lane({key: lane, 's': s_m, 'offset': offset_m},
                                         graph, f'{source}: vehicles[{index}].pose')
        placed.append(replace(vehicle, x_m=x_m, y_m=y_m, yaw_rad=yaw_rad))
    return tuple(placed)
