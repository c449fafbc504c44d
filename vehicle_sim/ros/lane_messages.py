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
Message builders of the lane topics: ``<ns>/lane_state``, ``<ns>/lane_invasion``, ``/map/lanes``.

And of the traffic lights for RViz (:func:`traffic_light_markers_builder`): the lamps as the
physics draws them (core/map/signal_lamps.py), in the colours of their groups' states.

Same form as ros/messages.py's builders: ``<type>_builder(msg, frame_id)`` resolves the classes
once; the ``build`` it returns makes one message from a stamp and a core value
(core/map/lane_state.LaneState, core/map/lane_invasion.LaneInvasion, a LaneGraph).
"""

from typing import NamedTuple

import numpy as np

from vehicle_sim.core.map.lane_geometry import (
    area_color,
    DASH_M,
    GAP_M,
    PAINT_COLOR,
    polygon_mesh,
    ROAD_AREA_KINDS,
    STOP_LINE_WIDTH_M,
    surface_mesh,
    zebra_stripes,
)
from vehicle_sim.core.map.signal_lamps import (
    box_mesh,
    DARK_LAMP_COLOR,
    HOUSING_COLOR,
    housing_corners,
    lamp_color,
    LAMP_COLORS,
    LAMP_RADIUS_M,
    lamps,
    POLE_COLOR,
    pole_corners,
    poles,
)

HEADER = 'std_msgs/msg/Header'
POINT = 'geometry_msgs/msg/Point'
LANE_STATE = 'vehicle_msgs/msg/LaneState'
LANE_INVASION = 'vehicle_msgs/msg/LaneInvasion'
MARKER = 'visualization_msgs/msg/Marker'
MARKER_ARRAY = 'visualization_msgs/msg/MarkerArray'
COLOR = 'std_msgs/msg/ColorRGBA'

LINE_STRIP, LINE_LIST, SPHERE_LIST, TRIANGLE_LIST = 4, 5, 7, 11   # visualization_msgs/Marker
# marker colours (RGBA) of the line types; virtual and none lines are drawn faint
LINE_COLORS = {
    'solid': (1.0, 1.0, 1.0, 1.0), 'solid_solid': (1.0, 1.0, 1.0, 1.0),
    'dashed': (1.0, 1.0, 1.0, 1.0), 'dashed_dashed': (1.0, 1.0, 1.0, 1.0),
    'dashed_solid': (1.0, 1.0, 1.0, 1.0), 'solid_dashed': (1.0, 1.0, 1.0, 1.0),
    'curbstone': (0.6, 0.6, 0.6, 1.0), 'road_border': (0.6, 0.6, 0.6, 1.0),
    'wall': (0.8, 0.3, 0.2, 1.0), 'virtual': (0.5, 0.5, 0.5, 0.3), 'none': (0.5, 0.5, 0.5, 0.3),
}
CENTRELINE_COLOR = (0.2, 0.6, 1.0, 0.8)
SURFACE_COLOR = (0.25, 0.25, 0.25, 1.0)


def lane_state_builder(msg, frame_id: str):
    """Return ``build(stamp, state)``: vehicle_msgs/LaneState of a core LaneState."""
    header_type, state_type = msg(HEADER), msg(LANE_STATE)

    def build(stamp, state):
        return state_type(header=header_type(stamp=stamp, frame_id=frame_id),
                          on_lane=bool(state.on_lane), lane_id=int(state.lane_id),
                          s=float(state.s_m), offset=float(state.offset_m),
                          heading_error=float(state.heading_error_rad),
                          width=float(state.width_m), speed_limit=float(state.speed_limit_mps),
                          stop_line_ahead=bool(state.stop_line_ahead),
                          stop_line_id=int(state.stop_line_id),
                          stop_line_kind=state.stop_line_kind,
                          stop_line_distance=float(state.stop_line_distance_m),
                          traffic_light_group_id=int(state.traffic_light_group_id),
                          signal_state=state.signal_state)
    return build


def lane_invasion_builder(msg, frame_id: str):
    """Return ``build(stamp, event)``: vehicle_msgs/LaneInvasion of a core LaneInvasion."""
    header_type, invasion_type, point_type = msg(HEADER), msg(LANE_INVASION), msg(POINT)

    def build(stamp, event):
        return invasion_type(header=header_type(stamp=stamp, frame_id=frame_id),
                             boundary_id=int(event.boundary_id), line_type=event.line_type,
                             position=point_type(x=float(event.x_m), y=float(event.y_m), z=0.0))
    return build


class MarkerPart(NamedTuple):
    """
    One marker of ``/map/lanes``, what its message and its bytes are made from.

    :param ns: the marker's namespace; ``marker_id``: its id; ``kind``: its type (LINE_STRIP,
        LINE_LIST or TRIANGLE_LIST).
    :param points: float64 array (N, 3) of its points [m].
    :param rgba: its colour; ``scale``: its scale (x, y, z).
    """

    ns: str
    marker_id: int
    kind: int
    points: np.ndarray
    rgba: tuple
    scale: tuple


def lane_marker_parts(graph):
    """
    Return the markers of a LaneGraph's ``/map/lanes`` as :class:`MarkerPart` rows, in order.

    Namespaces: ``road_surface`` (one triangle list), ``lane_boundaries`` (one marker per
    boundary, its id the boundary's modulo 2^31: a line strip, dashes as a line list, coloured by
    line type), ``centrelines`` (one line strip per lane, in lane order); and from the map's
    rules (``graph.rules``, only those it has): ``stop_lines`` (a white line strip
    ``STOP_LINE_WIDTH_M`` wide per stop line, its id the line's), ``crosswalks`` (a white
    triangle list of its zebra stripes per crosswalk, its id the area's), ``areas`` (a
    triangle list per other area in its kind's colour, core/map/lane_geometry.py's
    ``area_color``, its id the area's) and ``traffic_lights`` (the lamps' housings, id 0, and
    their poles, id 1: triangle lists of the boxes the physics builds; the bulbs change with
    the signals: :func:`traffic_light_markers_builder`). A line's scale is (width, 0, 0), a
    triangle list's (1, 1, 1).
    """
    def line(ns, marker_id, kind, xy, z, rgba, width):
        return MarkerPart(ns, marker_id, kind, _at_height(xy, z), rgba, (width, 0.0, 0.0))

    def mesh(ns, marker_id, points, rgba):
        return MarkerPart(ns, marker_id, TRIANGLE_LIST, points, rgba, (1.0, 1.0, 1.0))

    parts = [mesh('road_surface', 0, _triangles(surface_mesh(graph), 0.0), SURFACE_COLOR)]
    for boundary in graph.boundaries():
        rgba = LINE_COLORS[boundary.line_type]
        if 'dashed' in boundary.line_type:
            xy, kind = _dash_ends(boundary.points), LINE_LIST
        else:
            xy, kind = boundary.points, LINE_STRIP
        parts.append(line('lane_boundaries', boundary.id % 2 ** 31, kind, xy, 0.01, rgba, 0.15))
    for index, lane in enumerate(graph.lanes.values()):
        parts.append(line('centrelines', index, LINE_STRIP, lane.centerline, 0.02,
                          CENTRELINE_COLOR, 0.05))
    rules = graph.rules
    for stop_line in rules.stop_lines:
        parts.append(line('stop_lines', stop_line.id % 2 ** 31, LINE_STRIP, stop_line.points,
                          0.015, PAINT_COLOR, STOP_LINE_WIDTH_M))
    found = lamps(graph)
    for index, (corners, rgba) in enumerate((
            (housing_corners(found), HOUSING_COLOR),
            (pole_corners(poles(graph, found)), POLE_COLOR))):
        if len(corners):
            parts.append(mesh('traffic_lights', index, _triangles(box_mesh(corners)), rgba))
    for area in rules.areas:
        if area.kind in ROAD_AREA_KINDS:        # in the road surface
            continue
        if area.kind == 'crosswalk':
            stripes = [_triangles(polygon_mesh(stripe), 0.012)
                       for stripe in zebra_stripes(area.polygon)]
            points = np.concatenate(stripes) if stripes else np.empty((0, 3))
            ns = 'crosswalks'
        else:
            points, ns = _triangles(polygon_mesh(area.polygon), 0.005), 'areas'
        if len(points):
            parts.append(mesh(ns, area.id % 2 ** 31, points, area_color(area.kind)))
    return parts


def _at_height(xy, z):
    """Return the points (x, y) of ``xy`` at height ``z`` as a float64 array (N, 3)."""
    xy = np.asarray(xy, dtype=float).reshape(-1, 2)
    return np.column_stack((xy, np.full(len(xy), float(z))))


def _triangles(mesh, z=None):
    """Return a mesh's triangles' corners (N, 3): at height ``z`` [m] (flat), or its own."""
    corners = np.asarray(mesh.vertices, dtype=float)[np.asarray(mesh.triangles).reshape(-1)]
    corners = corners.reshape(-1, 3).copy()
    if z is not None:
        corners[:, 2] = z
    return corners


def lane_markers_builder(msg, frame_id: str):
    """
    Return ``build(stamp, graph)``: visualization_msgs/MarkerArray of a LaneGraph (/map/lanes).

    The markers of :func:`lane_marker_parts`, in ``frame_id``; ros/lane_cdr.py's
    ``lane_markers_serializer`` gives the same message's bytes.
    """
    marker_type, array_type = msg(MARKER), msg(MARKER_ARRAY)
    header_type, point_type, color_type = msg(HEADER), msg(POINT), msg(COLOR)

    def marker(stamp, part):
        r, g, b, a = part.rgba
        item = marker_type(header=header_type(stamp=stamp, frame_id=frame_id), ns=part.ns,
                           id=part.marker_id, type=part.kind, action=0,
                           points=[point_type(x=x, y=y, z=z)
                                   for x, y, z in part.points.tolist()],
                           color=color_type(r=r, g=g, b=b, a=a))
        item.pose.orientation.w = 1.0
        item.scale.x, item.scale.y, item.scale.z = part.scale
        return item

    def build(stamp, graph):
        return array_type(markers=[marker(stamp, part) for part in lane_marker_parts(graph)])
    return build


def traffic_light_markers_builder(msg, frame_id: str, graph):
    """
    Return ``build(stamp, states)``: visualization_msgs/MarkerArray of a map's lamps now.

    ``states``: {group id: state} (SignalController.states()). One marker, namespace
    ``traffic_light_bulbs``, id 0: a sphere list, a sphere of the lamp's diameter per bulb, lit
    in its colour or dark grey as :func:`~vehicle_sim.core.map.signal_lamps.lamp_color` says
    (the housings and poles do not change: they are in ``/map/lanes``).
    """
    marker_type, array_type = msg(MARKER), msg(MARKER_ARRAY)
    header_type, point_type, color_type = msg(HEADER), msg(POINT), msg(COLOR)
    found = lamps(graph)
    bulbs = [point_type(x=float(lamp.bulb.x_m), y=float(lamp.bulb.y_m), z=float(lamp.bulb.z_m))
             for lamp in found]
    colors = {rgba: color_type(r=float(rgba[0]), g=float(rgba[1]), b=float(rgba[2]),
                               a=float(rgba[3]))
              for rgba in list(LAMP_COLORS.values()) + [DARK_LAMP_COLOR]}

    def build(stamp, states):
        item = marker_type(header=header_type(stamp=stamp, frame_id=frame_id),
                           ns='traffic_light_bulbs', id=0, type=SPHERE_LIST, action=0,
                           points=bulbs, color=colors[DARK_LAMP_COLOR], colors=[
                               colors[lamp_color(lamp.bulb.color,
                                                 states.get(lamp.group_id, 'off'))]
                               for lamp in found])
        item.pose.orientation.w = 1.0
        item.scale.x = item.scale.y = item.scale.z = 2 * LAMP_RADIUS_M
        return array_type(markers=[item])
    return build


def _dash_ends(points):
    """Return the start and end point of each dash along a polyline (DASH_M on, GAP_M off)."""
    s = np.concatenate(([0.0], np.cumsum(np.hypot(*np.diff(points, axis=0).T))))
    starts = np.arange(0.0, s[-1], DASH_M + GAP_M)
    ends = np.minimum(starts + DASH_M, s[-1])
    at = np.column_stack((starts, ends)).reshape(-1)
    return np.column_stack((np.interp(at, s, points[:, 0]), np.interp(at, s, points[:, 1])))
