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

- ``track:<vehicle>``: every vehicle's path (start o, end x);
- ``outline:<vehicle>``: its footprint rectangle every :func:`outline_interval_s` seconds where
  it moved, and ``outline-end:<vehicle>`` at the end;
- ``obstacle:<name>``: each obstacle's footprint (at its initial pose);
- ``collision:<vehicle>``: the contact points of its collisions;
- ``band:<criterion>``: a stay_on_path criterion's path ± its limit, shaded;
- ``goal:<criterion>``: a reach_goal criterion's circle;
- ``clearance:<criterion>``: a clearance criterion's closest approach, vehicle to obstacle
  (``clearance-other:<criterion>``: the closest approach to each other obstacle).

matplotlib is an optional dependency (``pip install vehicle_sim[plot]``): :func:`require`
tells early, with the install hint, when it is missing.
"""

import math

from vehicle_sim.core.geometry.footprint import band_polygon, obstacle_footprint

# outlines at most every this many of these seconds: about ten per run
_NICE_INTERVALS_S = (0.5, 1.0, 2.0, 5.0, 10.0, 20.0, 30.0, 60.0, 120.0, 300.0, 600.0)
_MOVED_M, _TURNED_RAD = 0.05, 0.02     # an outline where the vehicle has not moved is left out
_EPS_S = 1e-9


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
            or abs(math.remainder(track.yaw_rad[b] - track.yaw_rad[a], 2.0 * math.pi))
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
    points = measured.points_m
    for index in range(0, len(points) - 1, 2):
        (x0, y0), (x1, y1) = points[index], points[index + 1]
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


def _vehicles(ax, result, patches, interval_s):
    spec = result.spec
    actors = {actor.vehicle for actor in spec.actors}
    for name, track in result.tracks.items():
        under_test = name == spec.vehicle
        role = 'under test' if under_test else 'actor' if name in actors else 'parked'
        (line,) = ax.plot(track.x_m, track.y_m, '-' if under_test else '--',
                          linewidth=2 if under_test else 1, gid=f'track:{name}',
                          label=f'{name} ({role})')
        colour = line.get_color()
        ax.plot(track.x_m[:1], track.y_m[:1], 'o', color=colour)      # start
        ax.plot(track.x_m[-1:], track.y_m[-1:], 'x', color=colour)    # end
        if track.outline is not None:
            indices = outline_indices(track, interval_s)
            for count, index in enumerate(indices):
                end = count == len(indices) - 1
                corners = track.outline.corners(track.x_m[index], track.y_m[index],
                                                track.yaw_rad[index])
                label = ('_' if count or not under_test
                         else f'{name} outline every {interval_s:g} s')
                ax.add_patch(patches.Polygon(
                    corners, closed=True, fill=end, facecolor=colour, alpha=0.35 if end else 0.8,
                    edgecolor=colour, linewidth=1.5 if end else 0.8,
                    gid=f'outline-end:{name}' if end else f'outline:{name}', label=label))
                # its time (at the end: since when it stands there), at its front edge
                front = ((corners[1][0] + corners[2][0]) / 2, (corners[1][1] + corners[2][1]) / 2)
                since = track.time_s[settled_index(track)] if end else track.time_s[index]
                when = (f'{since:g}–{track.time_s[index]:g} s' if since < track.time_s[index]
                        else f'{track.time_s[index]:g} s')
                yaw = track.yaw_rad[index]       # 6 points inside, clear of collision marks
                ax.annotate(when, front, xytext=(-6 * math.cos(yaw), -6 * math.sin(yaw)),
                            textcoords='offset points', fontsize=7, color=colour,
                            rotation=90 + math.degrees(yaw), rotation_mode='anchor',
                            ha='center', va='bottom')
        events = [e for e in result.collisions.get(name, ()) if e.position_m is not None]
        if events:
            ax.plot([e.position_m[0] for e in events], [e.position_m[1] for e in events], 'X',
                    color='red', markersize=10, markeredgecolor='black',
                    gid=f'collision:{name}', label=f'{name} collisions ({len(events)})')
            for event in events:
                ax.annotate(f'{event.other} at {event.time_s:.2f} s', event.position_m[:2],
                            xytext=(6, -14), textcoords='offset points', fontsize=8,
                            color='red')


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
    fig, ax = plt.subplots(figsize=(12, 7))
    _obstacles(ax, spec, patches)
    _criteria(ax, result, patches)
    _vehicles(ax, result, patches, interval_s)
    verdict = 'PASS' if result.passed else 'FAIL'
    failed = ', '.join(c.name for c in result.failures)
    ax.set_title(f'{spec.name}: {verdict}{" (" + failed + ")" if failed else ""} — seed '
                 f'{result.seed}, {result.sim_time_s:g} s')
    ax.set_xlabel('x [m]')
    ax.set_ylabel('y [m]')
    ax.set_aspect('equal', adjustable='datalim')
    ax.autoscale_view()
    ax.grid(True, alpha=0.3)
    ax.legend(fontsize=9, loc='upper left', bbox_to_anchor=(1.01, 1.0), borderaxespad=0.0)
    fig.tight_layout()
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
