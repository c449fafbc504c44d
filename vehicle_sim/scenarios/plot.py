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

matplotlib is an optional dependency (``pip install vehicle_sim[plot]``): :func:`require`
tells early, with the install hint, when it is missing.
"""

import math


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


def plot_result(result, out_path):
    """
    Draw every vehicle's path, the obstacles, goal regions and reference paths to ``out_path``.

    :param result: ScenarioResult.
    :return: out_path.
    """
    require()
    from matplotlib import patches
    from matplotlib import pyplot as plt

    spec = result.spec
    fig, ax = plt.subplots(figsize=(10, 7))
    for obstacle in spec.world.obstacles:
        x, y, _ = obstacle.position_m
        colour = obstacle.color_rgba[:3]
        if obstacle.shape == 'box':
            sx, sy = obstacle.size_m[0], obstacle.size_m[1]
            box = patches.Rectangle((x - sx / 2, y - sy / 2), sx, sy,
                                    angle=math.degrees(obstacle.yaw_rad), rotation_point='center',
                                    color=colour, alpha=0.6)
            ax.add_patch(box)
        else:
            ax.add_patch(patches.Circle((x, y), obstacle.size_m[0] / 2, color=colour, alpha=0.6))
        ax.annotate(obstacle.name, (x, y), fontsize=8, ha='center')
    for criterion in spec.criteria:
        values = criterion.values
        if criterion.kind == 'reach_goal':
            gx, gy = values['goal']
            ax.add_patch(patches.Circle((gx, gy), values['radius_m'], fill=False,
                                        linestyle='--', color='tab:green'))
            ax.annotate(criterion.name, (gx, gy), fontsize=8, color='tab:green', ha='center')
        elif criterion.kind == 'stay_on_path':
            xs = [p[0] for p in values['path']]
            ys = [p[1] for p in values['path']]
            ax.plot(xs, ys, ':', color='black', label=f'{criterion.name} path '
                                                      f'(± {values["max_distance_m"]:g} m)')
    actors = {actor.vehicle for actor in spec.actors}
    for name, track in result.tracks.items():
        style = '-' if name == spec.vehicle else '--'
        role = ('under test' if name == spec.vehicle else
                'actor' if name in actors else 'parked')
        ax.plot(track.x_m, track.y_m, style, linewidth=2 if name == spec.vehicle else 1,
                label=f'{name} ({role})')
        ax.plot(track.x_m[:1], track.y_m[:1], 'o', color='grey')     # start
        ax.plot(track.x_m[-1:], track.y_m[-1:], 'x', color='black')   # end
    verdict = 'PASS' if result.passed else 'FAIL'
    ax.set_title(f'{spec.name}: {verdict} (seed {result.seed}, {result.sim_time_s:g} s)')
    ax.set_xlabel('x [m]')
    ax.set_ylabel('y [m]')
    ax.set_aspect('equal', adjustable='datalim')
    ax.grid(True, alpha=0.3)
    ax.legend(fontsize=8, loc='best')
    fig.tight_layout()
    fig.savefig(out_path, dpi=100)
    plt.close(fig)
    return out_path
