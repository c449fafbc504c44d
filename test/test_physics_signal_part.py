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


"""The world's signals at run time: the 'signals' scene part and the ``signals:`` world key."""

import os
import shutil
import subprocess
import sys

from conftest import peer_env
import pytest
import yaml

from vehicle_sim.config import load_world
from vehicle_sim.core.specs.errors import InvalidParameterError
from vehicle_sim.physics.scene import build_scene

EAST, WEST, NORTH, SOUTH = 4000100101, 4000100151, 4000200101, 4000200151
EAST_RING = 4000100101      # city_block_signals: eastbound on the ring, green first
# Generous bound for one refused run (interpreter start and imports, on a loaded machine).
RUN_TIMEOUT_S = 120.0


def four_way(signals=None, lights=True):
    """Return a world mapping: two roads crossing at (0, 0), signalised, and one car."""
    def road(name, start, yaw):
        return {'name': name, 'start': {'x': start[0], 'y': start[1], 'yaw': yaw},
                'segments': [{'type': 'straight', 'length': 44},
                             {'type': 'intersection', 'length': 12, 'signals': lights},
                             {'type': 'straight', 'length': 44}]}
    world = {'vehicles': [{'name': 'Car', 'model': 'ToyotaPrius',
                           'pose': {'x': -40.0, 'y': -1.75, 'yaw': 0.0}}],
             'roads': [road('ew', (-50, 0), 0.0), road('ns', (0, -50), 1.5707963267948966)]}
    if signals is not None:
        world['signals'] = signals
    return world


def write(tmp_path, data, name='w.yaml'):
    path = tmp_path / name
    path.write_text(yaml.safe_dump(data))
    return path


def test_the_world_has_one_controller_advanced_to_its_time_and_reset_with_it(tmp_path):
    spec = load_world(str(write(tmp_path, four_way({'green': 1.0, 'yellow': 0.5,
                                                    'all_red': 0.5}))))
    scene = build_scene(spec)
    try:
        part = scene.parts['signals']
        controller = part.controller
        assert controller.plan.green_s == 1.0
        assert controller.state(EAST) == 'green'            # phase 0 from the start
        # four phases of 2 s: east green [0, 1), yellow [1, 1.5), red after; west from 2 s
        seen = {}
        for _ in range(300):                                # 3 s of 10 ms steps
            now = scene.world.step()
            seen[round(now, 2)] = (controller.state(EAST), controller.state(WEST))
        assert controller.time_s == pytest.approx(scene.world.time_s)
        assert seen[0.99] == ('green', 'red') and seen[1.0] == ('yellow', 'red')
        assert seen[1.5] == ('red', 'red') and seen[2.0] == ('red', 'green')
        controller.force(EAST, 'green')
        scene.world.step()
        assert controller.state(EAST) == 'green'            # forced: held over the steps
        message = part.reset()
        assert message == 'signals: their 4 groups back at the plan start'
        assert controller.state(EAST) == 'green' and controller.state(WEST) == 'red'
        for _ in range(100):
            scene.world.step()
        assert controller.time_s == pytest.approx(1.0) and controller.state(EAST) == 'yellow'
    finally:
        scene.world.close()


def test_phases_from_the_world_file_and_no_part_without_lights(tmp_path):
    spec = load_world(str(write(tmp_path, four_way({'phases': [[EAST], [WEST], [NORTH],
                                                               [SOUTH]]}))))
    scene = build_scene(spec)
    try:
        assert scene.parts['signals'].controller.phases == (((EAST,), (WEST,), (NORTH,),
                                                             (SOUTH,)),)
    finally:
        scene.world.close()
    plain = build_scene(load_world(str(write(tmp_path, four_way(lights=False), 'p.yaml'))))
    try:
        assert 'signals' not in plain.parts and 'roads' in plain.parts
    finally:
        plain.world.close()


def test_the_shipped_city_block_signals_world_has_lights_at_every_intersection():
    spec = load_world('city_block_signals')
    assert spec.signals.green_s == 20.0 and spec.traffic.vehicles == 40
    scene = build_scene(spec)
    try:
        rules = scene.lanes.rules
        assert len(rules.groups) == 20 and len(rules.stop_lines) == 20
        controller = scene.parts['signals'].controller
        assert [len(phases) for phases in controller.phases] == [4] * 5
        assert sorted(controller.states().values()) == ['green'] * 5 + ['red'] * 15
    finally:
        scene.world.close()


@pytest.mark.parametrize('signals, fragment', [
    ({'phases': [[EAST, NORTH], [WEST], [SOUTH]]},
     f"signals: field 'phases': signal plan: groups {EAST} and {NORTH} are green together "
     'but their lanes conflict'),
    ({'phases': [[EAST], [WEST], [NORTH], [SOUTH], [123]]},
     "signals: field 'phases': traffic light group 123 is not in the map"),
    ({'phases': [[EAST], [WEST], [NORTH]]},
     f"signals: field 'phases': group(s) [{SOUTH}] of the map are in no phase"),
])
def test_a_bad_plan_is_refused_by_the_command_naming_the_file_and_field(tmp_path, signals,
                                                                        fragment):
    path = write(tmp_path, four_way(signals))
    found = shutil.which('vehicle-sim', path=os.path.dirname(sys.executable))
    command = [found] if found else [sys.executable, '-m', 'vehicle_sim']
    done = subprocess.run([*command, 'run', '--no-status', '--duration', '0.1', '--world',
                           str(path)], env=peer_env(), capture_output=True, text=True,
                          timeout=RUN_TIMEOUT_S)
    lines = [line for line in done.stderr.splitlines() if not line.startswith('[INFO]')]
    assert done.returncode == 2, done.stderr[-2000:]
    assert lines == [f'vehicle-sim run: {path}: {lines[0].split(f"{path}: ", 1)[1]}']
    assert fragment in lines[0], lines[0]


@pytest.mark.parametrize('signals, fragment', [
    ({'phases': [[EAST], [EAST, WEST]]}, f"field 'phases' = [[{EAST}], [{EAST}, {WEST}]]: "
     f'group(s) [{EAST}] in more than one phase'),
    ({'phases': [['east']]}, "field 'phases' = [['east']]: phase 0 = ['east'] must be a "
     'non-empty list of traffic light group ids'),
    ({'green': 0.0}, "field 'green' = 0.0: must be > 0"),
    ({'plan': 'actuated'}, "field 'plan' = 'actuated'"),
    ({'cycle': 90}, "unknown field 'cycle'"),
])
def test_a_bad_signals_key_is_refused_at_load_naming_the_field(tmp_path, signals, fragment):
    path = write(tmp_path, four_way(signals))
    with pytest.raises(InvalidParameterError) as error:
        load_world(str(path))
    assert str(error.value).startswith(f'{path}: signals: ')
    assert fragment in str(error.value)


def test_a_signals_key_without_lights_in_the_map_is_refused(tmp_path):
    spec = load_world(str(write(tmp_path, four_way({'green': 10.0}, lights=False))))
    with pytest.raises(InvalidParameterError, match=r'w.yaml: signals: the lane map has no '
                       'traffic light groups'):
        build_scene(spec)


def test_the_docs_show_the_signals_table():
    from pathlib import Path

    from vehicle_sim.core.map.signal_params import signals_markdown
    text = (Path(__file__).resolve().parents[1] / 'docs' / 'signals.md').read_text()
    assert signals_markdown() in text


def test_the_automobile_nodes_sim_reset_starts_the_signals_again():
    from vehicle_sim.ros.automobile_node import AutomobileNode
    node = AutomobileNode(['x', '--ros-args', '-r', '__ns:=/signals_reset_test'],
                          transport='dds', parameter_overrides={
                              'synchronous': True, 'world': 'city_block_signals'})
    try:
        controller = node.scene.parts['signals'].controller
        node.step(100)
        controller.force(EAST_RING, 'red')
        node.step(1)
        assert controller.time_s == pytest.approx(1.01) and controller.state(EAST_RING) == 'red'
        message = node.reset()
        assert 'signals: their 20 groups back at the plan start' in message
        assert controller.time_s == 0.0 and controller.state(EAST_RING) == 'green'
    finally:
        node.close()


def two_crossings(signals):
    """Return a world mapping: an east-west road crossed by two roads, at x = 0 and x = 100."""
    def road(name, start, yaw, crossings):
        segments = [{'type': 'straight', 'length': 44}]
        for _ in range(crossings):
            segments += [{'type': 'intersection', 'length': 12, 'signals': True},
                         {'type': 'straight', 'length': 88 if crossings > 1 else 44}]
        return {'name': name, 'start': {'x': start[0], 'y': start[1], 'yaw': yaw},
                'segments': segments}
    north = 1.5707963267948966
    return {'vehicles': [{'name': 'Car', 'model': 'ToyotaPrius',
                          'pose': {'x': -40.0, 'y': -1.75, 'yaw': 0.0}}],
            'roads': [road('ew', (-50, 0), 0.0, 2), road('ns1', (0, -50), north, 1),
                      road('ns2', (100, -50), north, 1)],
            'signals': signals}


def _eastbound_group_at(rules, x_m):
    """Return the id of the group whose stop line lies on the eastbound lane before x_m."""
    for line in rules.stop_lines:
        mid_x, mid_y = line.points.mean(axis=0)
        if line.group_id is not None and abs(mid_x - (x_m - 6.0)) < 1.0 and mid_y < 0.0:
            return line.group_id
    raise AssertionError(f'no eastbound stop line before x = {x_m}')


def test_an_intersection_runs_its_own_times_and_offset(tmp_path):
    times = {'green': 2.0, 'yellow': 1.0, 'all_red': 1.0}
    plain = load_world(str(write(tmp_path, two_crossings(times), 'plain.yaml')))
    scene = build_scene(plain)
    try:
        rules = scene.lanes.rules
        first, second = _eastbound_group_at(rules, 0.0), _eastbound_group_at(rules, 100.0)
    finally:
        scene.world.close()
    wave = dict(times, intersections=[{'group': second, 'offset': 1.5, 'green': 3.0}])
    scene = build_scene(load_world(str(write(tmp_path, two_crossings(wave), 'wave.yaml'))))
    try:
        controller = scene.parts['signals'].controller
        seen = {}
        for _ in range(4500):                   # 45 s: two cycles of 16 s and of 20 s
            now = round(scene.world.step(), 2)
            seen[now] = (controller.state(first), controller.state(second))
        for group, green_s, phase_s, offset_s in ((first, 2.0, 4.0, 0.0),
                                                  (second, 3.0, 5.0, 1.5)):
            index, count, _ = controller._slot[group]
            column = 0 if group == first else 1
            greens, since = [], None           # complete green intervals (start, end)
            for now in sorted(seen):
                lit = seen[now][column] == 'green'
                if lit and since is None:
                    since = now
                elif not lit and since is not None:
                    greens.append((since, now))
                    since = None
            greens = [g for g in greens if g[0] > 0.01]         # the first may start at 0
            cycle = count * phase_s
            assert len(greens) >= 2, greens
            for begin, end in greens:
                assert end - begin == pytest.approx(green_s, abs=0.011), greens
                assert (begin - offset_s - index * phase_s) % cycle == pytest.approx(
                    0.0, abs=0.011) or (begin - offset_s - index * phase_s) % cycle == \
                    pytest.approx(cycle, abs=0.011), (group, greens)
    finally:
        scene.world.close()


@pytest.mark.parametrize('entries, fragment', [
    ([{'group': 123}], "field 'intersections': traffic light group 123 is not in the map"),
    ([{'group': 'east'}], "intersections[0]: field 'group' = 'east': must be an integer"),
    ([{'group': 1, 'green': 0.0}], "intersections[0]: field 'green' = 0.0: must be > 0"),
    ([{'group': 1, 'hue': 3}], "intersections[0]: unknown field 'hue'"),
    ({'group': 1}, "field 'intersections' = {'group': 1}: must be a list"),
])
def test_bad_intersection_plans_are_refused_naming_the_field(tmp_path, entries, fragment):
    world = two_crossings({'intersections': entries})
    with pytest.raises(InvalidParameterError) as error:
        build_scene(load_world(str(write(tmp_path, world))))
    assert fragment in str(error.value), str(error.value)
    assert 'w.yaml: signals' in str(error.value), str(error.value)


def test_two_plans_for_one_intersection_are_refused(tmp_path):
    scene = build_scene(load_world(str(write(tmp_path, two_crossings({}), 'plain.yaml'))))
    try:
        rules = scene.lanes.rules
        first = _eastbound_group_at(rules, 0.0)
        phases = scene.parts['signals'].controller.phases
        crossing = next(i for i in phases if any(first in phase for phase in i))
        other = next(g for phase in crossing for g in phase if g != first)
    finally:
        scene.world.close()
    world = two_crossings({'intersections': [{'group': first}, {'group': other, 'offset': 1}]})
    with pytest.raises(InvalidParameterError, match=rf'groups {first} and {other} are of one '
                       'intersection: give its plan once'):
        build_scene(load_world(str(write(tmp_path, world))))
