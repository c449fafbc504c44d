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
The scenario plot: its elements checked on the figure's artists, and the CLI's PNG.

The runs are made up (a track driven by hand through the shipped scenarios' worlds), so every
drawn element has a closed-form place; one CLI run writes the PNG a user asks for.
"""

import math
from pathlib import Path
import subprocess
import sys

import pytest
import yaml

from vehicle_sim.config import load_car, load_robot
from vehicle_sim.core.geometry.footprint import (
    car_outline,
    distance_to_polyline,
    obstacle_footprint,
    robot_outline,
)
from vehicle_sim.core.world.collision import CollisionEvent
from vehicle_sim.scenarios.criteria import build_criteria, Sample
from vehicle_sim.scenarios.runner import run_scenario, ScenarioResult, Track
from vehicle_sim.scenarios.scene import CriteriaScene
from vehicle_sim.scenarios.schema import load_scenario

pytest.importorskip('matplotlib', reason='the plot needs matplotlib')
from matplotlib import pyplot as plt  # noqa: E402 - after the skip

from vehicle_sim.scenarios.plot import (  # noqa: E402, I100 - needs matplotlib
    build_figure,
    outline_indices,
)

ROOT = Path(__file__).resolve().parent.parent
STOP = ROOT / 'scenarios' / 'stop_before_obstacle.yaml'
BLIND = ROOT / 'scenarios' / 'drive_into_obstacle.yaml'
S_CURVE = ROOT / 'scenarios' / 'bridge_s_curve.yaml'
DT_S = 0.1
# CLI run: interpreter start, a 10 s scenario, the plot
CLI_TIMEOUT_S = 300.0


def _made_up_run(path, poses, outline, collisions=()):
    """Return a ScenarioResult of a track given as (x, y, yaw) every DT_S, judged for real."""
    spec = load_scenario(path)
    criteria = build_criteria(spec.criteria, spec.duration_s)
    scene = CriteriaScene({spec.vehicle: outline},
                          [obstacle_footprint(o) for o in spec.world.obstacles])
    track = Track(outline=outline)
    for index, (x, y, yaw) in enumerate(poses):
        track.time_s.append(round(index * DT_S, 9))
        track.x_m.append(x)
        track.y_m.append(y)
        track.yaw_rad.append(yaw)
    for criterion in criteria:
        criterion.bind(scene)
        for time_s, x, y, yaw in zip(track.time_s, track.x_m, track.y_m, track.yaw_rad):
            criterion.observe(Sample(time_s, x, y, yaw, 1.0))
    return ScenarioResult(spec, 0, [c.result() for c in criteria], track.time_s[-1], 0.0,
                          {spec.vehicle: track}, '', True,
                          collisions={spec.vehicle: list(collisions)})


def _artists(fig, gid):
    ax = fig.axes[0]
    return [a for a in ax.patches + ax.lines if a.get_gid() == gid]


@pytest.fixture
def straight():
    # 1 m/s along x for 10 s, then the bumper (4.5 m ahead) is 19.5 - 14.5 = 5 m from the wall
    poses = [(index * DT_S, 0.0, 0.0) for index in range(101)]
    fig = build_figure(_made_up_run(STOP, poses, car_outline(load_car('Car')), [
        CollisionEvent(3.0, 'wall', 100.0, (19.5, 0.25, 0.5))]))
    yield fig
    plt.close(fig)


def test_plot_draws_an_outline_every_second_and_one_at_the_end(straight):
    outlines = _artists(straight, 'outline:Car')
    assert len(outlines) == 10                               # t = 0, 1, ..., 9 s
    ends = _artists(straight, 'outline-end:Car')
    assert len(ends) == 1
    # the end: base_link at x = 10, the rectangle from 0.5 m behind it to 4.5 m ahead
    assert sorted(map(tuple, ends[0].get_xy()[:4].round(9))) == \
        [(9.5, -1.0), (9.5, 1.0), (14.5, -1.0), (14.5, 1.0)]
    firsts = sorted(min(p.get_xy()[:, 0]) for p in outlines)
    assert firsts == pytest.approx([t - 0.5 for t in range(10)], abs=1e-9)


def test_plot_draws_the_obstacles_as_their_footprints(straight):
    (wall,) = _artists(straight, 'obstacle:wall')
    assert sorted(map(tuple, wall.get_xy()[:4].round(9))) == \
        [(19.5, -3.0), (19.5, 3.0), (20.5, -3.0), (20.5, 3.0)]
    (pole,) = _artists(straight, 'obstacle:pole')
    assert (tuple(pole.center), pole.radius) == ((10.0, 5.0), 0.2)


def test_plot_draws_the_goal_circle_of_reach_goal(straight):
    (goal,) = _artists(straight, 'goal:reach_goal')
    assert (tuple(goal.center), goal.radius) == ((12.0, 0.0), 3.0)


def test_plot_marks_the_collision_points(straight):
    (marks,) = _artists(straight, 'collision:Car')
    assert (list(marks.get_xdata()), list(marks.get_ydata())) == ([19.5], [0.25])
    texts = [t.get_text() for t in straight.axes[0].texts]
    assert 'wall at 3.00 s' in texts


def test_plot_of_the_blind_run_marks_where_the_car_hit_the_wall():
    result = run_scenario(BLIND)
    (event,) = result.collisions['Car']
    # the bumper (y within the car's +-1 m) met the wall's face at x = 19.5, bumper-high
    assert event.other == 'wall'
    assert event.position_m[0] == pytest.approx(19.5, abs=0.01)
    assert abs(event.position_m[1]) < 1.0 and 0.0 < event.position_m[2] < 2.0
    fig = build_figure(result)
    try:
        (marks,) = _artists(fig, 'collision:Car')
        assert (marks.get_xdata()[0], marks.get_ydata()[0]) == event.position_m[:2]
    finally:
        plt.close(fig)


def test_plot_draws_the_closest_approach_of_clearance_with_its_value(straight):
    # the car's side (y = 1) passes the pole (y = 5, r = 0.2): 3.8 m, nearer than the wall (5 m)
    (nearest,) = _artists(straight, 'clearance:clearance')
    assert list(zip(nearest.get_xdata(), nearest.get_ydata())) == \
        [pytest.approx((10.0, 1.0)), pytest.approx((10.0, 4.8))]
    assert nearest.get_label() == 'clearance: closest 3.80 m (bound 2 m)'
    (wall,) = _artists(straight, 'clearance-other:clearance')
    assert list(wall.get_xdata()) == pytest.approx([14.5, 19.5])
    labels = [t.get_text() for t in straight.axes[0].get_legend().get_texts()]
    assert 'Car outline every 1 s' in labels


def test_plot_keeps_equal_axes(straight):
    assert straight.axes[0].get_aspect() == 1.0


def test_plot_draws_one_outline_where_the_vehicle_stood_still_with_since_when():
    # drives 1 m/s for 4 s, then stands until 10 s: outlines at 0..3 s and the end only
    poses = [(min(index * DT_S, 4.0), 0.0, 0.0) for index in range(101)]
    result = _made_up_run(STOP, poses, car_outline(load_car('Car')))
    assert outline_indices(result.tracks['Car'], 1.0) == [0, 10, 20, 30, 100]
    fig = build_figure(result)
    try:
        assert len(_artists(fig, 'outline:Car')) == 4
        assert '4–10 s' in [t.get_text() for t in fig.axes[0].texts]
    finally:
        plt.close(fig)


def test_plot_shades_the_band_of_stay_on_path():
    spec = load_scenario(S_CURVE)
    (criterion,) = [c for c in spec.criteria if c.kind == 'stay_on_path']
    path = criterion.values['path']
    poses = [(x, y, 0.0) for x, y in path]
    fig = build_figure(_made_up_run(S_CURVE, poses, robot_outline(load_robot('caster_robot'))))
    try:
        (band,) = _artists(fig, 'band:stay_on_path')
        vertices = band.get_xy()
        assert len(vertices) > 2 * len(path)
        for x, y in vertices:                     # every vertex 0.15 m from the path
            assert distance_to_polyline(x, y, path) == pytest.approx(0.15, abs=1e-6)
        assert band.get_label() == 'stay_on_path: path ± 0.15 m'
    finally:
        plt.close(fig)


def test_cli_scenario_plot_of_stop_before_obstacle_writes_a_readable_png(tmp_path):
    from matplotlib import image
    out = tmp_path / 'stop.png'
    command = Path(sys.executable).with_name('vehicle-sim')
    run = subprocess.run([str(command), 'scenario', str(STOP), '--plot', str(out),
                          '--no-progress'], capture_output=True, text=True,
                         timeout=CLI_TIMEOUT_S)
    assert run.returncode == 0, run.stdout + run.stderr
    assert 'PASS  clearance: 3.8 m' in run.stdout
    assert f'wrote {out}' in run.stdout
    assert out.read_bytes()[:8] == b'\x89PNG\r\n\x1a\n'
    height, width, _ = image.imread(str(out)).shape
    assert width >= 1000 and height >= 600


CUT_IN = ROOT / 'scenarios' / 'cut_in.yaml'


@pytest.fixture(scope='module')
def cut_in():
    result = run_scenario(CUT_IN)
    fig = build_figure(result)
    yield result, fig
    plt.close(fig)


def test_plot_of_the_cut_in_draws_every_vehicle_s_path_with_its_label(cut_in):
    result, fig = cut_in
    (car,) = _artists(fig, 'track:Car')
    (traffic,) = _artists(fig, 'track:traffic_0')
    assert (car.get_label(), traffic.get_label()) == ('Car (under test)', 'traffic_0 (traffic)')
    track = result.traffic_tracks['traffic_0']
    assert list(traffic.get_xdata()) == track.x_m and list(traffic.get_ydata()) == track.y_m
    # the traffic car drove the fast lane (centre y = -1.875) and changed into the car's lane
    assert track.y_m[0] == pytest.approx(-1.875, abs=0.01)
    assert track.y_m[-1] == pytest.approx(-5.625, abs=0.05)
    assert len(_artists(fig, 'outline:traffic_0')) >= 5


def test_plot_of_the_cut_in_draws_the_lane_lines_as_marked(cut_in):
    _, fig = cut_in
    ax = fig.axes[0]
    lines = [a for a in ax.lines if (a.get_gid() or '').startswith('lane-line:')]
    # the straight's boundaries where it starts (x = 0), 3.75 m apart: the edges, the dashed
    # lines between lanes, the centre line
    starts = {round(float(a.get_ydata()[0]), 3): a.get_linestyle() for a in lines
              if abs(a.get_xdata()[0]) < 1e-6}
    assert starts == {-11.25: '-', -7.5: '--', -3.75: '--', 0.0: '-', 3.75: '--', 7.5: '--',
                      11.25: '-'}
    lanes = [p for p in ax.patches if (p.get_gid() or '').startswith('lane:')]
    assert len(lanes) >= 6


def test_plot_of_the_cut_in_marks_the_smallest_gap(cut_in):
    result, fig = cut_in
    gap = result.criterion('min_gap')
    assert gap.at_s == pytest.approx(17.0) and gap.others == ('traffic_0',)
    (ring,) = _artists(fig, 'moment:min_gap')
    assert (ring.get_xdata()[0], ring.get_ydata()[0]) == gap.points_m[0]
    assert ring.get_label() == f'min_gap: {gap.value:.4g} m at 17.00 s'
    # the ring is at the car's front bumper at 17 s (4.5 m ahead of base_link)
    car = result.tracks['Car']
    index = car.time_s.index(pytest.approx(17.0))
    assert gap.points_m[0][0] == pytest.approx(car.x_m[index] + 4.5, abs=1e-6)
    (segment,) = _artists(fig, 'gap:min_gap')
    (x0, x1), (y0, y1) = segment.get_xdata(), segment.get_ydata()
    assert math.hypot(x1 - x0, y1 - y0) == pytest.approx(gap.value, abs=1e-9)
    names = {a.get_gid() for a in fig.axes[0].patches}
    assert {'moment-outline:min_gap:Car', 'moment-outline:min_gap:traffic_0'} <= names


def test_plot_of_the_long_straight_road_stretches_y_and_zooms_on_the_gap(cut_in):
    result, fig = cut_in
    ax = fig.axes[0]
    (x0, x1), (y0, y1) = ax.get_xlim(), ax.get_ylim()
    assert x1 - x0 > 550.0                  # the whole drive
    assert y1 - y0 < (x1 - x0) / 10.0       # not equal axes: the lane change shows
    assert ax.get_aspect() == 'auto' and 'stretched' in ax.get_ylabel()
    (zoom,) = [a for a in fig.axes if a.get_gid() == 'zoom']
    assert zoom.get_aspect() == 1.0
    (gx0, gy0), (gx1, gy1) = result.criterion('min_gap').points_m
    (zx0, zx1), (zy0, zy1) = zoom.get_xlim(), zoom.get_ylim()
    assert zx0 < min(gx0, gx1) and max(gx0, gx1) < zx1 and zy0 < gy0 < zy1
    assert zx1 - zx0 < 100.0


def test_plot_of_a_collision_with_traffic_marks_the_contact(tmp_path):
    data = yaml.safe_load(CUT_IN.read_text(encoding='utf-8'))
    placed = data['world']['traffic']['placed'][0]
    placed['change_at'], placed['speed_factor'] = 8.0, 0.4     # it swerves into the car
    data['driver']['controller'] = str(ROOT / 'examples' / 'acc_controller.py')
    path = tmp_path / 'cut_in_hit.yaml'
    path.write_text(yaml.safe_dump(data), encoding='utf-8')
    result = run_scenario(path)
    (event,) = result.collisions['Car']
    fig = build_figure(result)
    try:
        for name in ('no_collision', 'min_gap'):
            (ring,) = _artists(fig, f'moment:{name}')
            assert (ring.get_xdata()[0], ring.get_ydata()[0]) == event.position_m[:2]
        assert _artists(fig, 'moment:min_gap')[0].get_label() == 'min_gap: touched at 9.33 s'
        (outline,) = _artists(fig, 'moment-outline:min_gap:traffic_0')
        track = result.traffic_tracks['traffic_0']
        index = max(i for i, t in enumerate(track.time_s) if t <= 9.33 + 1e-9)
        corners = track.outline.corners(track.x_m[index], track.y_m[index],
                                        track.yaw_rad[index])
        assert outline.get_xy()[:4].ravel().tolist() == pytest.approx(
            [v for corner in corners for v in corner])
    finally:
        plt.close(fig)


def test_plot_of_a_map_scenario_draws_its_walls_with_equal_axes(tmp_path):
    # config/worlds/race_track.yaml's occupancy map; the car steers left into its wall
    data = {'name': 'race_track_wall', 'world': 'race_track', 'duration': 4.0,
            'driver': {'commands': [{'t': 0.0, 'cruising_speed': 20.0, 'steering_angle': -0.3}]},
            'criteria': [{'kind': 'clearance', 'min': 0.5}]}
    path = tmp_path / 'race_track_wall.yaml'
    path.write_text(yaml.safe_dump(data), encoding='utf-8')
    result = run_scenario(path)
    fig = build_figure(result)
    try:
        ax = fig.axes[0]
        (walls,) = [c for c in ax.collections if c.get_gid() == 'walls:map']
        drawn = {tuple(map(tuple, p.vertices[:4].round(6))) for p in walls.get_paths()}
        known = {tuple((round(x, 6), round(y, 6)) for x, y in w.vertices) for w in result.walls}
        assert drawn and drawn <= known
        # the wall the car touched is drawn, and the ring marks the contact
        clearance = result.criterion('clearance')
        x, y = clearance.points_m[0]
        touched = [w for w in drawn if min(p[0] for p in w) - 0.2 <= x <= max(p[0] for p in w)
                   + 0.2 and min(p[1] for p in w) - 0.2 <= y <= max(p[1] for p in w) + 0.2]
        assert touched
        (ring,) = _artists(fig, 'moment:clearance')
        assert (ring.get_xdata()[0], ring.get_ydata()[0]) == (x, y)
        assert ax.get_aspect() == 1.0 and [a.get_gid() for a in fig.axes] == [None]
    finally:
        plt.close(fig)
