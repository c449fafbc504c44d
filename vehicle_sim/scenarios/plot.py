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
Trajectory plot of a scenario run (PNG, matplotlib with the Agg backend).

What it draws, each artist with a ``gid`` (``kind:name``) so that tests find it:

- ``track:<vehicle>``: every vehicle's path (start o, end x), the traffic vehicles' too
  (dotted, while they drove);
- ``outline:<vehicle>``: its footprint rectangle every :func:`outline_interval_s` seconds where
  it moved, and ``outline-end:<vehicle>`` at the end (traffic vehicles: a criterion's, or all
  of them when there are at most :data:`TRAFFIC_OUTLINED`);
- ``lane:<lane id>``: a lane's surface, and ``lane-line:<boundary id>`` its boundaries (solid,
  dashed as their line type; unmarked ones not drawn);
- ``walls:map``: an occupancy map's walls (one collection of rectangles);
- ``obstacle:<name>``: each obstacle's footprint (at its initial pose);
- ``collision:<vehicle>``: the contact points of its collisions (the first
  :data:`ANNOTATED_COLLISIONS` named, with their time);
- ``band:<criterion>``: a stay_on_path criterion's path ± its limit, shaded;
- ``goal:<criterion>``: a reach_goal criterion's circle;
- ``clearance:<criterion>``: a clearance criterion's closest approach, vehicle to obstacle
  (``clearance-other:<criterion>``: the closest approach to each other obstacle);
- ``gap:<criterion>``: a min_gap criterion's smallest gap, the vehicle's front to the traffic
  vehicle's rear;
- ``moment:<criterion>``: a ring at a criterion's key moment (the smallest gap or clearance, the
  first collision), at the vehicle's point of it, and ``moment-outline:<criterion>:<vehicle>``
  the outlines of the vehicle and the others involved at that time.

The view holds the vehicles' paths, the obstacles, the criteria's shapes and the traffic
vehicles a criterion names; lanes and walls are drawn where they fall in it. The axes are equal
unless that would squeeze the view's short side below 15 % of the plot (a long straight
road): then the short side is stretched to fill it, its axis label says by how much, and a
second panel (``gid`` ``zoom``) shows the key moment (the first failed criterion's, else the
first) with equal axes.

matplotlib is an optional dependency (``pip install vehicle_sim[plot]``): :func:`require`
tells early, with the install hint, when it is missing.
"""

import bisect
import math

import numpy as np

from vehicle_sim.core.geometry.angles import wrap_angle_rad
from vehicle_sim.core.geometry.footprint import band_polygon, obstacle_footprint
from vehicle_sim.core.map.lane_graph import SOLID_TYPES, UNMARKED_TYPES

# outlines at most every this many of these seconds: about ten per run
_NICE_INTERVALS_S = (0.5, 1.0, 2.0, 5.0, 10.0, 20.0, 30.0, 60.0, 120.0, 300.0, 600.0)
_MOVED_M, _TURNED_RAD = 0.05, 0.02     # an outline where the vehicle has not moved is left out
_EPS_S = 1e-9
# an end outline says since when the vehicle stands there when that is longer than this (a
# traffic vehicle's pose changes only at the traffic's updates, every 0.1 s by default)
_STILL_S = 0.5
ANNOTATED_COLLISIONS = 1        # a vehicle's first collisions named at their mark
TRAFFIC_OUTLINED = 4            # at most this many traffic vehicles: every one's outlines
MARGIN_M, MARGIN_FRACTION = 2.0, 0.08   # the view's margin: the larger of these (each axis)
STRETCH_BELOW = 0.15            # equal axes unless the short side would fill less of the plot
ZOOM_HALF_M = 15.0              # the key moment's panel: at least this either side of it
ROAD_COLOUR, LINE_COLOUR, WALL_COLOUR = '0.9', '0.45', (0.55, 0.55, 0.6)
BARRIER_TYPES = ('curbstone', 'road_border', 'wall')


class PlotUnavailable(RuntimeError):
    """matplotlib is not installed."""


def require():
    """
    Import matplotlib (Agg backend) or explain how to get it.

    :raises PlotUnavailable: with the install hint.
    """
    try:
        import matplotlib
    except ImportError:
        raise PlotUnavailable("--plot needs matplotlib: pip install 'vehicle_sim[plot]' "
                              '(or pip install matplotlib)') from None
    matplotlib.use('Agg')
    return matplotlib


def outline_interval_s(duration_s):
    """Return the time between two drawn outlines: the first of 0.5, 1, 2, 5, ... s, <= 10."""
    for interval in _NICE_INTERVALS_S:
        if duration_s / interval <= 10.0 + _EPS_S:
            return interval
    return _NICE_INTERVALS_S[-1]


def outline_indices(track, interval_s):
    """
    Return the samples of a track whose outline is drawn, the last one (the end) included.

    One sample every ``interval_s`` (the first at or after each multiple), left out where the
    vehicle is within 5 cm and 0.02 rad of the outline drawn before it or of the end.
    """
    times = track.time_s
    last = len(times) - 1
    chosen = []
    due = times[0]
    for index, time_s in enumerate(times[:-1]):
        if time_s < due - _EPS_S:
            continue
        due += interval_s * math.floor((time_s - due + _EPS_S) / interval_s + 1.0)
        if (not chosen or _moved(track, chosen[-1], index)) and _moved(track, index, last):
            chosen.append(index)
    return chosen + [last]


def settled_index(track):
    """Return the first sample from which the vehicle stays within 5 cm and 0.02 rad of its end."""
    last = len(track.time_s) - 1
    index = last
    while index > 0 and not _moved(track, index - 1, last):
        index -= 1
    return index


def _moved(track, a, b):
    return (math.hypot(track.x_m[b] - track.x_m[a], track.y_m[b] - track.y_m[a]) > _MOVED_M
            or abs(wrap_angle_rad(track.yaw_rad[b] - track.yaw_rad[a]))
            > _TURNED_RAD)


def _obstacles(ax, spec, patches):
    for obstacle in spec.world.obstacles:
        footprint = obstacle_footprint(obstacle)
        style = dict(facecolor=obstacle.color_rgba[:3], edgecolor='black', alpha=0.7,
                     gid=f'obstacle:{obstacle.name}')
        if footprint.is_circle:
            ax.add_patch(patches.Circle(footprint.center_m, footprint.radius_m, **style))
        else:
            ax.add_patch(patches.Polygon(footprint.vertices, closed=True, **style))
        top = (footprint.center_m[1] + footprint.radius_m if footprint.is_circle
               else max(y for _, y in footprint.vertices))
        ax.annotate(obstacle.name, (obstacle.position_m[0], top), xytext=(0, 3),
                    textcoords='offset points', fontsize=9, ha='center', va='bottom')


def _criteria(ax, result, patches):
    by_name = {c.name: c for c in result.criteria}
    for criterion in result.spec.criteria:
        values = criterion.values
        if criterion.kind == 'reach_goal':
            ax.add_patch(patches.Circle(values['goal'], values['radius_m'], fill=False,
                                        linestyle='--', linewidth=1.5, color='tab:green',
                                        gid=f'goal:{criterion.name}',
                                        label=f'{criterion.name} (r = {values["radius_m"]:g} m)'))
        elif criterion.kind == 'stay_on_path':
            limit = values['max_distance_m']
            ax.add_patch(patches.Polygon(band_polygon(values['path'], limit), closed=True,
                                         facecolor='tab:cyan', edgecolor='none', alpha=0.25,
                                         gid=f'band:{criterion.name}',
                                         label=f'{criterion.name}: path ± {limit:g} m'))
            xs, ys = zip(*values['path'])
            ax.plot(xs, ys, ':', color='tab:blue', linewidth=1)
        elif criterion.kind == 'clearance':
            _clearance(ax, criterion, by_name[criterion.name])


def _clearance(ax, criterion, measured):
    # one segment per obstacle, vehicle to obstacle; the nearest (the value) in red
    # (a collision's contact point, twice: the ring of its key moment marks it)
    points = measured.points_m
    for index in range(0, len(points) - 1, 2):
        (x0, y0), (x1, y1) = points[index], points[index + 1]
        if (x0, y0) == (x1, y1):
            continue
        distance = math.hypot(x1 - x0, y1 - y0)
        nearest = index == 0 and abs(distance - measured.value) < 1e-9
        ax.plot([x0, x1], [y0, y1], '-' if nearest else '--',
                color='tab:red' if nearest else 'dimgrey', linewidth=1.5, marker='.',
                gid=f'clearance:{criterion.name}' if nearest else
                f'clearance-other:{criterion.name}',
                label=(f'{criterion.name}: closest {distance:.2f} m (bound '
                       f'{criterion.values["min_m"]:g} m)' if nearest else '_'))
        ax.annotate(f'{distance:.2f} m', ((x0 + x1) / 2, (y0 + y1) / 2), xytext=(4, 4),
                    textcoords='offset points', fontsize=8,
                    color='tab:red' if nearest else 'dimgrey')


def _involved(result):
    """Return the names of the vehicles a criterion names (min_gap's, what was hit)."""
    names = {name for c in result.criteria for name in c.others}
    names.update(e.other for events in result.collisions.values() for e in events)
    return names


def _view(result):
    """Return (x0, x1, y0, y1) [m]: what the plot shows, margins included."""
    xs, ys = [], []

    def track_extent(track):
        reach = 0.0 if track.outline is None else max(
            abs(track.outline.x_min_m), abs(track.outline.x_max_m),
            abs(track.outline.y_min_m), abs(track.outline.y_max_m))
        xs.extend((min(track.x_m) - reach, max(track.x_m) + reach))
        ys.extend((min(track.y_m) - reach, max(track.y_m) + reach))

    for track in result.tracks.values():
        track_extent(track)
    involved = _involved(result)
    for name, track in result.traffic_tracks.items():
        if name in involved:
            track_extent(track)
    for obstacle in result.spec.world.obstacles:
        footprint = obstacle_footprint(obstacle)
        if footprint.is_circle:
            (cx, cy), r = footprint.center_m, footprint.radius_m
            xs.extend((cx - r, cx + r))
            ys.extend((cy - r, cy + r))
        else:
            xs.extend(x for x, _ in footprint.vertices)
            ys.extend(y for _, y in footprint.vertices)
    for criterion in result.spec.criteria:
        values = criterion.values
        if criterion.kind == 'reach_goal':
            (gx, gy), r = values['goal'], values['radius_m']
            xs.extend((gx - r, gx + r))
            ys.extend((gy - r, gy + r))
        elif criterion.kind == 'stay_on_path':
            xs.extend(x for x, _ in values['path'])
            ys.extend(y for _, y in values['path'])
    for measured in result.criteria:
        xs.extend(x for x, _ in measured.points_m)
        ys.extend(y for _, y in measured.points_m)
    x0, x1, y0, y1 = min(xs), max(xs), min(ys), max(ys)
    pad_x = max(MARGIN_M, MARGIN_FRACTION * (x1 - x0))
    pad_y = max(MARGIN_M, MARGIN_FRACTION * (y1 - y0))
    return x0 - pad_x, x1 + pad_x, y0 - pad_y, y1 + pad_y


def _meets(view, points):
    """Whether a polyline's (or polygon's) box along the axes meets the view's."""
    points = np.asarray(points, dtype=float)
    x0, x1, y0, y1 = view
    return (points[:, 0].min() <= x1 and points[:, 0].max() >= x0
            and points[:, 1].min() <= y1 and points[:, 1].max() >= y0)


def _lanes(ax, lanes, view, patches):
    if lanes is None:
        return
    for lane in lanes.lanes.values():
        outline = np.vstack((lane.left.points, lane.right.points[::-1]))
        if _meets(view, outline):
            ax.add_patch(patches.Polygon(outline, closed=True, facecolor=ROAD_COLOUR,
                                         edgecolor='none', zorder=0, gid=f'lane:{lane.id}'))
    labelled = set()
    for boundary in lanes.boundaries():
        kind = boundary.line_type
        if kind in UNMARKED_TYPES or not _meets(view, boundary.points):
            continue
        barrier = kind in BARRIER_TYPES
        style = '-' if kind in SOLID_TYPES else '--'
        what = 'road edge' if barrier else 'solid line' if style == '-' else 'dashed line'
        ax.plot(boundary.points[:, 0], boundary.points[:, 1], style, zorder=1,
                color='0.2' if barrier else LINE_COLOUR, linewidth=1.5 if barrier else 0.8,
                gid=f'lane-line:{boundary.id}',
                label='_' if what in labelled else f'lane {what}s')
        labelled.add(what)


def _walls(ax, walls, view):
    if not walls:
        return
    from matplotlib.collections import PolyCollection
    shown = [footprint.vertices for footprint in walls if _meets(view, footprint.vertices)]
    if shown:
        ax.add_collection(PolyCollection(shown, facecolors=[WALL_COLOUR], edgecolors='none',
                                         zorder=1, gid=f'walls:{walls[0].name}',
                                         label=f'{walls[0].name} walls'))


def _at(track, time_s):
    """Return the index of a track's sample at ``time_s`` (the last one at or before it)."""
    return max(0, bisect.bisect_right(track.time_s, time_s + _EPS_S) - 1)


def _track(ax, name, track, style, role, patches, interval_s, outlines, collisions):
    (line,) = ax.plot(track.x_m, track.y_m, style['line'], linewidth=style['width'],
                      gid=f'track:{name}', label=f'{name} ({role})' if role else '_')
    colour = line.get_color()
    ax.plot(track.x_m[:1], track.y_m[:1], 'o', color=colour)      # start
    ax.plot(track.x_m[-1:], track.y_m[-1:], 'x', color=colour)    # end
    if outlines and track.outline is not None:
        indices = outline_indices(track, interval_s)
        for count, index in enumerate(indices):
            end = count == len(indices) - 1
            corners = track.outline.corners(track.x_m[index], track.y_m[index],
                                            track.yaw_rad[index])
            label = ('_' if count or not style['outline_label']
                     else f'{name} outline every {interval_s:g} s')
            ax.add_patch(patches.Polygon(
                corners, closed=True, fill=end, facecolor=colour, alpha=0.35 if end else 0.8,
                edgecolor=colour, linewidth=1.5 if end else 0.8,
                gid=f'outline-end:{name}' if end else f'outline:{name}', label=label))
            # its time (at the end: since when it stands there), at its front edge
            front = ((corners[1][0] + corners[2][0]) / 2, (corners[1][1] + corners[2][1]) / 2)
            since = track.time_s[settled_index(track)] if end else track.time_s[index]
            when = (f'{since:g}–{track.time_s[index]:g} s'
                    if since < track.time_s[index] - _STILL_S else f'{track.time_s[index]:g} s')
            yaw = track.yaw_rad[index]       # 6 points inside, clear of collision marks
            ax.annotate(when, front, xytext=(-6 * math.cos(yaw), -6 * math.sin(yaw)),
                        textcoords='offset points', fontsize=7, color=colour,
                        rotation=90 + math.degrees(yaw), rotation_mode='anchor',
                        ha='center', va='bottom')
    events = [e for e in collisions if e.position_m is not None]
    if events:
        ax.plot([e.position_m[0] for e in events], [e.position_m[1] for e in events], 'X',
                color='red', markersize=10, markeredgecolor='black',
                gid=f'collision:{name}', label=f'{name} collisions ({len(events)})')
        for event in events[:ANNOTATED_COLLISIONS]:
            ax.annotate(f'{event.other} at {event.time_s:.2f} s', event.position_m[:2],
                        xytext=(6, -14), textcoords='offset points', fontsize=8,
                        color='red')


def _vehicles(ax, result, patches, interval_s):
    spec = result.spec
    actors = {actor.vehicle for actor in spec.actors}
    for name, track in result.tracks.items():
        under_test = name == spec.vehicle
        role = 'under test' if under_test else 'actor' if name in actors else 'parked'
        style = {'line': '-' if under_test else '--', 'width': 2 if under_test else 1,
                 'outline_label': under_test}
        _track(ax, name, track, style, role, patches, interval_s, True,
               result.collisions.get(name, ()))
    involved = _involved(result)
    every = len(result.traffic_tracks) <= TRAFFIC_OUTLINED
    style = {'line': ':', 'width': 1.5, 'outline_label': False}
    for name, track in result.traffic_tracks.items():
        shown = every or name in involved
        _track(ax, name, track, style, 'traffic' if shown else '', patches, interval_s, shown,
               ())


def _moments(ax, result, patches):
    tracks = dict(result.traffic_tracks, **result.tracks)
    for criterion, measured in zip(result.spec.criteria, result.criteria):
        if measured.at_s is None:
            continue
        colour = 'tab:green' if measured.passed else 'red'
        touched = len(measured.points_m) == 2 and measured.points_m[0] == measured.points_m[1]
        if measured.kind == 'no_collision':
            what = f'first collision at {measured.at_s:.2f} s'
        elif touched:
            what = f'touched at {measured.at_s:.2f} s'
        elif measured.kind == 'clearance':         # its segment's label gives the value
            what = f'closest at {measured.at_s:.2f} s'
        else:
            what = f'{measured.value:.4g} {measured.unit} at {measured.at_s:.2f} s'
        if measured.kind == 'min_gap' and len(measured.points_m) == 2 and not touched:
            (x0, y0), (x1, y1) = measured.points_m
            ax.plot([x0, x1], [y0, y1], '-', color=colour, linewidth=2.5,
                    gid=f'gap:{criterion.name}', label='_')
            ax.annotate(f'{measured.value:.2f} m', ((x0 + x1) / 2, (y0 + y1) / 2),
                        xytext=(0, 14), textcoords='offset points', fontsize=8, color=colour,
                        ha='center', va='bottom')
        for name in (criterion.vehicle,) + tuple(measured.others):
            track = tracks.get(name)
            if track is None or track.outline is None:
                continue
            index = _at(track, measured.at_s)
            ax.add_patch(patches.Polygon(
                track.outline.corners(track.x_m[index], track.y_m[index],
                                      track.yaw_rad[index]),
                closed=True, fill=False, edgecolor=colour, linewidth=1.5, zorder=4,
                gid=f'moment-outline:{criterion.name}:{name}', label='_'))
        if measured.points_m:
            x, y = measured.points_m[0]
            ax.plot([x], [y], 'o', markersize=18, markerfacecolor='none',
                    markeredgecolor=colour, markeredgewidth=2, zorder=5,
                    gid=f'moment:{criterion.name}', label=f'{criterion.name}: {what}')


def _axes(fig, ax, view):
    """Set the view: equal axes, or the short side stretched (said in its label; True)."""
    x0, x1, y0, y1 = view
    fig.tight_layout()
    box = ax.get_position()
    width_in, height_in = fig.get_size_inches()
    box_w, box_h = box.width * width_in, box.height * height_in
    # how much of the plot's short side the data's short side fills with equal axes
    scale = min(box_w / (x1 - x0), box_h / (y1 - y0))
    fill_x, fill_y = scale * (x1 - x0) / box_w, scale * (y1 - y0) / box_h
    if min(fill_x, fill_y) >= STRETCH_BELOW:
        # equal axes: the view widened on its short side to the plot's shape
        grow_x, grow_y = (x1 - x0) * (1.0 / fill_x - 1.0), (y1 - y0) * (1.0 / fill_y - 1.0)
        ax.set_xlim(x0 - grow_x / 2, x1 + grow_x / 2)
        ax.set_ylim(y0 - grow_y / 2, y1 + grow_y / 2)
        ax.set_aspect('equal', adjustable='box')
        return False
    ax.set_xlim(x0, x1)
    ax.set_ylim(y0, y1)
    ax.set_aspect('auto')
    if fill_y < fill_x:
        ax.set_ylabel(f'y [m] (stretched {1.0 / fill_y:.0f}× against x)')
    else:
        ax.set_xlabel(f'x [m] (stretched {1.0 / fill_x:.0f}× against y)')
    fig.tight_layout()
    return True


def _key_moment(result):
    """Return (criterion spec, its result) of the first failed key moment, else the first."""
    moments = [(c, m) for c, m in zip(result.spec.criteria, result.criteria)
               if m.at_s is not None and m.points_m]
    failed = [(c, m) for c, m in moments if not m.passed]
    return (failed or moments or [None])[0]


def _moment_window(result, criterion, measured):
    """Return (x0, x1, y0, y1) [m] around a key moment: its points and vehicles, and a margin."""
    points = list(measured.points_m)
    tracks = dict(result.traffic_tracks, **result.tracks)
    for name in (criterion.vehicle,) + tuple(measured.others):
        track = tracks.get(name)
        if track is not None and track.outline is not None:
            index = _at(track, measured.at_s)
            points.extend(track.outline.corners(track.x_m[index], track.y_m[index],
                                                track.yaw_rad[index]))
    xs, ys = [x for x, _ in points], [y for _, y in points]
    cx, cy = (min(xs) + max(xs)) / 2, (min(ys) + max(ys)) / 2
    half_x = max(ZOOM_HALF_M, (max(xs) - min(xs)) / 2 + MARGIN_M)
    half_y = max(ZOOM_HALF_M, (max(ys) - min(ys)) / 2 + MARGIN_M)
    return cx - half_x, cx + half_x, cy - half_y, cy + half_y


def _zoom(fig, ax, result, moment, patches, interval_s):
    """Add a panel below: the key moment with equal axes (the main view is stretched)."""
    criterion, measured = moment
    window = _moment_window(result, criterion, measured)
    fig.set_size_inches(12, 11)
    grid = fig.add_gridspec(2, 1, height_ratios=(3, 2))
    ax.set_subplotspec(grid[0])
    zoom = fig.add_subplot(grid[1])
    zoom.set_gid('zoom')
    _draw(zoom, result, window, patches, interval_s)
    zoom.set_title(f'{criterion.name} at {measured.at_s:.2f} s, equal axes', fontsize=10)
    zoom.set_xlabel('x [m]')
    zoom.set_ylabel('y [m]')
    zoom.grid(True, alpha=0.3)
    return zoom, window


def _around(view):
    """Return a square about the view, twice its long side: what equal axes may show of it."""
    x0, x1, y0, y1 = view
    half = max(x1 - x0, y1 - y0)
    cx, cy = (x0 + x1) / 2, (y0 + y1) / 2
    return cx - half, cx + half, cy - half, cy + half


def _draw(ax, result, view, patches, interval_s):
    # the lanes and walls about the view: the axes may widen it to the plot's shape
    _lanes(ax, result.lanes, _around(view), patches)
    _walls(ax, result.walls, _around(view))
    _obstacles(ax, result.spec, patches)
    _criteria(ax, result, patches)
    _vehicles(ax, result, patches, interval_s)
    _moments(ax, result, patches)


def build_figure(result, outline_every_s=None):
    """
    Return the figure of a run (the caller closes it: ``matplotlib.pyplot.close(fig)``).

    :param result: ScenarioResult.
    :param outline_every_s: time between outlines [s]; None = :func:`outline_interval_s`.
    """
    require()
    from matplotlib import patches
    from matplotlib import pyplot as plt

    spec = result.spec
    interval_s = outline_every_s or outline_interval_s(result.sim_time_s)
    view = _view(result)
    fig, ax = plt.subplots(figsize=(12, 7))
    _draw(ax, result, view, patches, interval_s)
    verdict = 'PASS' if result.passed else 'FAIL'
    failed = ', '.join(c.name for c in result.failures)
    ax.set_title(f'{spec.name}: {verdict}{" (" + failed + ")" if failed else ""} — seed '
                 f'{result.seed}, {result.sim_time_s:g} s')
    ax.set_xlabel('x [m]')
    ax.set_ylabel('y [m]')
    ax.grid(True, alpha=0.3)
    ax.legend(fontsize=9, loc='upper left', bbox_to_anchor=(1.01, 1.0), borderaxespad=0.0)
    moment = _key_moment(result)
    if _axes(fig, ax, view) and moment is not None:
        zoom, window = _zoom(fig, ax, result, moment, patches, interval_s)
        _axes(fig, ax, view)
        _axes(fig, zoom, window)
    return fig


def plot_result(result, out_path):
    """
    Draw a run (:func:`build_figure`) to the PNG ``out_path``.

    :param result: ScenarioResult.
    :return: out_path.
    """
    from matplotlib import pyplot as plt
    fig = build_figure(result)
    try:
        fig.savefig(out_path, dpi=110)
    finally:
        plt.close(fig)
    return out_path
