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
Every kind other than sensor types is registered once per layer, checked across the layers.

Obstacle shapes, map kinds, traffic models, scene parts and sweep backends each have a core
registration and one registry per layer that takes part (the table :data:`REGISTRIES`); each
layer's registry lists exactly the core's names, docs/architecture.md's "Where each kind of
change goes" names exactly those files, and a fake new kind added by registration only works
end to end (as test/test_repo_sensor_registration.py shows for sensor types).
"""

import ast
from dataclasses import replace
from pathlib import Path
import re

from map_helpers import write_map
import pytest
import yaml

from vehicle_sim.config import load_world, world_from_data
from vehicle_sim.core.geometry import footprint
from vehicle_sim.core.map import kinds as map_kinds
from vehicle_sim.core.map.lane_graph import LaneGraph
from vehicle_sim.core.map.road_segments import lane_graph_from_roads
from vehicle_sim.core.specs.errors import InvalidParameterError, InvalidPoseError
from vehicle_sim.core.specs.param_spec import ParamSpec, validate_table
from vehicle_sim.core.traffic import engines as traffic_engines
from vehicle_sim.core.traffic import models as traffic_models
from vehicle_sim.core.traffic.manager import TrafficManager
from vehicle_sim.core.traffic.params import traffic_from_dict, traffic_markdown
from vehicle_sim.core.world import params as world_params
from vehicle_sim.foxglove import scene as foxglove_scene
from vehicle_sim.maps import lane_maps
from vehicle_sim.physics import map_layer, obstacles, traffic_bodies
from vehicle_sim.physics import scene as physics_scene
from vehicle_sim.physics.scene import build_scene, ScenePartRow
from vehicle_sim.ros import map_interfaces, traffic_messages
from vehicle_sim.scenarios.scene import map_walls
from vehicle_sim.sweep import run as sweep_run
from vehicle_sim.sweep.worker import run_case_logged

REPO = Path(__file__).resolve().parent.parent


def _highway_data():
    return yaml.safe_load((REPO / 'config' / 'worlds' / 'highway.yaml').read_text())

CAR = {'name': 'car', 'model': 'Car', 'pose': {'x': 0.0, 'y': 0.0}}
ROOT_KEYS = {'origin', 'vehicles', 'obstacles'}     # the scene builder's own, not parts

# kind -> (the core registration's names, {file: names()} of each layer's registry), the
# files in the order docs/architecture.md lists them.
REGISTRIES = {
    'obstacle shape': (lambda: set(world_params.OBSTACLE_SHAPES), {
        'vehicle_sim/core/world/params.py': lambda: set(world_params.OBSTACLE_SHAPES),
        'vehicle_sim/core/geometry/footprint.py': lambda: set(footprint.OBSTACLE_FOOTPRINTS),
        'vehicle_sim/physics/obstacles.py': lambda: set(obstacles.OBSTACLE_GEOMETRY),
        'vehicle_sim/foxglove/scene.py': lambda: set(foxglove_scene.PRIMITIVE_OF_SHAPE),
        'vehicle_sim/ros/traffic_messages.py':
            lambda: set(traffic_messages.OBJECT_SHAPE_OF_OBSTACLE),
    }),
    'map type': (lambda: set(map_kinds.MAP_KINDS), {
        'vehicle_sim/core/map/kinds.py': lambda: set(map_kinds.MAP_KINDS),
        'vehicle_sim/physics/map_layer.py': lambda: set(map_layer.MAP_BUILDERS),
        'vehicle_sim/ros/map_interfaces.py': lambda: set(map_interfaces.MAP_TOPICS),
    }),
    'lane map type': (lambda: {n for n, k in map_kinds.MAP_KINDS.items() if k.lane_map}, {
        'vehicle_sim/maps/lane_maps.py': lambda: set(lane_maps.LANE_LOADERS),
    }),
    'traffic model': (lambda: set(traffic_models.all_models()), {
        'vehicle_sim/core/traffic/models.py': lambda: set(traffic_models.all_models()),
    }),
    'traffic engine': (lambda: set(traffic_engines.TRAFFIC_ENGINES), {
        'vehicle_sim/core/traffic/engines.py': lambda: set(traffic_engines.TRAFFIC_ENGINES),
        'vehicle_sim/physics/traffic_bodies.py': lambda: set(traffic_bodies.TRAFFIC_BUILDERS),
    }),
    'scene part': (lambda: set(world_params.WORLD_KEYS) - ROOT_KEYS, {
        'vehicle_sim/core/world/params.py': lambda: set(world_params.WORLD_KEYS) - ROOT_KEYS,
        'vehicle_sim/physics/scene.py': lambda: {
            name for name, row in physics_scene.SCENE_PARTS.items() if row.world_key},
    }),
    'sweep backend': (lambda: set(sweep_run.BACKENDS), {
        'vehicle_sim/sweep/run.py': lambda: set(sweep_run.BACKENDS),
    }),
}
# docs/architecture.md's heading of each kind -> the kinds of REGISTRIES whose files it lists.
DOC_SECTIONS = {
    'A new obstacle shape': ('obstacle shape',),
    'A new map type': ('map type',),
    'A new traffic model': ('traffic model',),
    'A new traffic engine': ('traffic engine',),
    'A new scene part': ('scene part',),
    'A new sweep backend': ('sweep backend',),
}


LAYER_CASES = [(kind, path) for kind, (_, layers) in REGISTRIES.items() for path in layers]


@pytest.mark.parametrize('kind, path', LAYER_CASES, ids=[f'{k}:{p}' for k, p in LAYER_CASES])
def test_every_layer_registers_exactly_the_core_names(kind, path):
    core, layers = REGISTRIES[kind]
    assert layers[path]() == core()


def _section(heading):
    text = (REPO / 'docs' / 'architecture.md').read_text(encoding='utf-8')
    start = text.index(f'**{heading}**')
    end = text.find('\n\n**', start + 1)
    return text[start:end if end >= 0 else len(text)]


@pytest.mark.parametrize('heading', sorted(DOC_SECTIONS))
def test_the_architecture_doc_names_exactly_the_registry_files(heading):
    files = [path for kind in DOC_SECTIONS[heading] for path in REGISTRIES[kind][1]]
    section = _section(heading)
    numbered = re.findall(r'^\d+\. `(vehicle_sim/[^`]+\.py)`', section, re.M)
    assert numbered == files
    count = {1: 'one', 2: 'two', 3: 'three', 4: 'four', 5: 'five', 6: 'six'}[len(files)]
    assert f'registered in {count} file' in ' '.join(section.split())


# ------------------------------------------------------------------------------ obstacle shapes

def _pillar_extents(values):
    return (values['side_m'], values['side_m'], values['height_m'])


def test_a_new_obstacle_shape_registered_in_each_layer_works_with_no_other_change(monkeypatch):
    # A square 'pillar' (a side and a height) that reuses the box's parts in every other layer.
    monkeypatch.setitem(world_params.OBSTACLE_SHAPES, 'pillar', world_params.ObstacleShape(
        'pillar', (0.5, 0.5, 0.5, 1.0),
        (ParamSpec('side', 'side_m', 'float', 1.0, 'm', 'side', gt=0.0),
         ParamSpec('height', 'height_m', 'float', 3.0, 'm', 'height', gt=0.0)),
        _pillar_extents))
    monkeypatch.setitem(footprint.OBSTACLE_FOOTPRINTS, 'pillar', footprint.box_footprint)
    monkeypatch.setitem(obstacles.OBSTACLE_GEOMETRY, 'pillar', obstacles.OBSTACLE_GEOMETRY['box'])
    monkeypatch.setitem(foxglove_scene.PRIMITIVE_OF_SHAPE, 'pillar', 'cube')
    monkeypatch.setitem(traffic_messages.OBJECT_SHAPE_OF_OBSTACLE, 'pillar',
                        traffic_messages.BOUNDING_BOX)
    data = {'vehicles': [{'name': 'car', 'model': 'Car', 'pose': {'x': 0.0, 'y': 0.0}}],
            'obstacles': [{'name': 'p', 'shape': 'pillar', 'position': [10.0, 0.0, 1.5],
                           'side': 2.0, 'yaw': 0.0}]}
    spec = world_from_data(data, 'w.yaml')
    pillar, = spec.obstacles
    assert (pillar.shape, pillar.size_m, pillar.color_rgba) == (
        'pillar', (2.0, 2.0, 3.0), (0.5, 0.5, 0.5, 1.0))
    outline = footprint.obstacle_footprint(pillar)
    assert sorted(outline.vertices) == [(9.0, -1.0), (9.0, 1.0), (11.0, -1.0), (11.0, 1.0)]
    scene = build_scene(spec)
    try:
        entity, = [e for e in foxglove_scene.scene_entities(scene, ['obstacles'])]
        primitive, = entity.primitives
        assert (entity.id, primitive.kind, primitive.size_m) == ('obstacle/p', 'cube',
                                                               (2.0, 2.0, 3.0))
        # its physics body is there, as large as its spec: a car refused where it stands
        car = scene.vehicles['car'].body
        with pytest.raises(InvalidPoseError):
            car.teleport((8.0, 0.0, 0.0))
        car.teleport((8.0, 4.0, 0.0))
    finally:
        scene.world.close()
    with pytest.raises(InvalidParameterError,
                       match=r"obstacles\[0\]: field 'side' = -1.0: must be > 0"):
        world_from_data({**data, 'obstacles': [{**data['obstacles'][0], 'side': -1}]}, 'w.yaml')


def test_an_unknown_obstacle_shape_lists_the_registered_ones():
    with pytest.raises(InvalidParameterError,
                       match=r"obstacles\[0\]: field 'shape' = 'capsule': unknown shape; valid: "
                             r'box, cylinder, sphere$'):
        world_from_data({'vehicles': [CAR], 'obstacles': [
            {'name': 'c', 'shape': 'capsule', 'position': [0, 0, 0]}]}, 'w.yaml')


# ------------------------------------------------------------------------------ map kinds

def test_a_new_map_kind_registered_in_each_layer_works_with_no_other_change(
        monkeypatch, tmp_path):
    # A 'floor_plan' kind read as an occupancy grid: one row per layer, nothing else.
    monkeypatch.setitem(map_kinds.MAP_KINDS, 'floor_plan', replace(
        map_kinds.MAP_KINDS['occupancy_grid'], name='floor_plan'))
    monkeypatch.setitem(map_layer.MAP_BUILDERS, 'floor_plan', map_layer.build_occupancy_grid)
    monkeypatch.setitem(map_interfaces.MAP_TOPICS, 'floor_plan', (map_interfaces.MAP,))
    data = {'vehicles': [{'name': 'car', 'model': 'Car', 'pose': {'x': 0.0, 'y': 0.0}}],
            'map': {'type': 'floor_plan', 'file': str(write_map(tmp_path))}}
    spec = world_from_data(data, str(tmp_path / 'w.yaml'))
    assert spec.map.type == 'floor_plan'
    scene = build_scene(spec)
    try:
        built = scene.parts['map']
        assert len(built.rectangles) > 0 and built.body_ids
        walls, = foxglove_scene.scene_entities(scene, ['map'])
        assert walls.id == 'map/walls' and len(walls.primitives) == len(built.rectangles)
        assert len(map_walls(scene)) == len(built.rectangles)
        assert map_interfaces.map_rows(built) == (map_interfaces.MAP,)
        assert map_interfaces.fixed_frame(scene.spec) == 'world'
        assert scene.lanes is None
    finally:
        scene.world.close()


def test_a_lane_map_kind_is_loaded_by_its_lane_loader_and_excludes_roads(monkeypatch):
    # A 'road_table' lane map kind whose loader makes the lanes of the highway's roads.
    roads = load_world('highway').roads
    monkeypatch.setitem(map_kinds.MAP_KINDS, 'road_table', map_kinds.MapKind(
        'road_table', map_kinds.COMMON_MAP_SPECS,
        lambda values, source, base_dir: map_kinds.OccupancyMapSpec(
            values['type'], map_kinds.MapPlacement(), '', source=source),
        lane_map=True))
    monkeypatch.setitem(lane_maps.LANE_LOADERS, 'road_table',
                        lambda spec: lane_graph_from_roads(roads))
    spec = world_from_data({'vehicles': [CAR], 'map': {'type': 'road_table'}}, 'w.yaml')
    loaded = lane_maps.with_lanes(spec)
    assert isinstance(loaded.lanes, LaneGraph) and 100001 in loaded.lanes.lanes
    assert map_interfaces.fixed_frame(spec) == 'map'
    with pytest.raises(InvalidParameterError, match=r'both roads: and a road_table map'):
        world_from_data({'vehicles': [CAR], 'map': {'type': 'road_table'},
                         'roads': _highway_data()['roads']}, 'w.yaml')


# The registrations of map kinds (and lanelet2's own key table): the only modules that write a
# map kind's name; everything else reads the kind's row or the built map.
MAP_KIND_FILES = {'core/map/kinds.py', 'core/map/lanelet2_params.py', 'maps/lane_maps.py',
                  'physics/map_layer.py', 'ros/map_interfaces.py'}
# Map kind names that are other things' words too, and the modules (path prefixes) that write
# them as those: OSM's XML root element (a Lanelet2 .osm file's), the SUMO traffic engine's
# name (core/traffic/engines.py) and SUMO's program.
SHARED_WORDS = {'osm': ('maps/lanelet2_file.py',),
                'sumo': ('core/traffic/', 'physics/sumo', 'physics/traffic', 'maps/sumo')}


def test_map_kind_names_are_written_only_in_the_registrations():
    package = REPO / 'vehicle_sim'
    found = [f'{path.relative_to(package)}:{node.lineno}: {node.value!r}'
             for path in sorted(package.rglob('*.py'))
             if str(path.relative_to(package)) not in MAP_KIND_FILES
             for node in ast.walk(ast.parse(path.read_text(encoding='utf-8')))
             if isinstance(node, ast.Constant) and node.value in map_kinds.MAP_KINDS
             and not str(path.relative_to(package)).startswith(
                 SHARED_WORDS.get(node.value, ('\0',)))]
    assert found == []


def test_an_unknown_map_type_lists_the_registered_ones():
    with pytest.raises(InvalidParameterError,
                       match=r"map: field 'type' = 'tiles': unknown; valid: lanelet2, "
                             r'occupancy_grid, opendrive, osm, sumo$'):
        world_from_data({'vehicles': [CAR], 'map': {'type': 'tiles'}}, 'w.yaml')


# ------------------------------------------------------------------------------ traffic engines

def _still_parse(data, source, check_model, base_dir):
    # The builtin table without the engine key, then the new engine's name on the spec.
    rest = {k: v for k, v in data.items() if k != 'engine'}
    return replace(traffic_from_dict(rest, source, check_model), engine='still')


def _still_build(part, world, spec, parts):
    # The builtin bodies, each vehicle driving at a tenth of its desired speed.
    bodies = traffic_bodies.TrafficPart.build_builtin(part, world, spec, parts)
    for v in bodies.manager.vehicles:
        v.factor = 0.1
    return bodies


def test_a_new_traffic_engine_registered_in_each_layer_works_with_no_other_change(monkeypatch):
    monkeypatch.setitem(traffic_engines.TRAFFIC_ENGINES, 'still', traffic_engines.TrafficEngine(
        'still', _still_parse, traffic_markdown, 'slow vehicles'))
    monkeypatch.setitem(traffic_bodies.TRAFFIC_BUILDERS, 'still', _still_build)
    data = _highway_data()
    data['traffic'] = {'engine': 'still', 'placed': [
        {'model': 'Car', 'lanelet': 100002, 's': 50.0, 'speed': 0.0}]}
    spec = world_from_data(data, 'highway.yaml')
    assert spec.traffic.engine == 'still'
    scene = build_scene(spec)
    try:
        bodies = scene.parts['traffic']
        for _ in range(100):
            scene.world.step()
        (name, x, y, _, length, _, speed), = bodies.agents()
        limit = scene.spec.lanes.lane(100002).speed_limit_mps
        assert name in bodies.moving_names() and 0.5 < speed <= 0.1 * limit and length > 3.0
        obj, = bodies.objects()
        assert (obj.name, obj.object_class) == (name, 'car')
        assert obj.x_m == pytest.approx(x + speed * bodies.since_update_s, abs=1e-6)
    finally:
        scene.world.close()


def test_an_unknown_traffic_engine_lists_the_registered_ones():
    data = _highway_data()
    data['traffic'] = {'engine': 'vissim'}
    with pytest.raises(InvalidParameterError,
                       match=r"highway.yaml: traffic: field 'engine' = 'vissim': unknown "
                             r'traffic engine; valid: builtin, sumo'):
        world_from_data(data, 'highway.yaml')


# ------------------------------------------------------------------------------ traffic models

GAIN_SPECS = (ParamSpec('gain', 'gain_per_s', 'float', 0.5, '1/s', 'speed gain', gt=0.0),)


def _relax(params):
    # a toy car-following model: towards the desired speed at a rate, stopping for any leader
    # nearer than 10 m
    gain = params['gain_per_s']

    def acceleration(speed, desired, gap, leader_speed):
        if gap is not None and gap < 10.0:
            return -9.0
        return gain * (desired - speed)
    return acceleration


RELAX = traffic_models.CarFollowingModel(
    'relax', GAIN_SPECS, lambda data, source: validate_table(GAIN_SPECS, data or {}, source),
    _relax, lambda params, speed: 10.0, lambda params: 2.0, 'a toy model')
NEVER = traffic_models.LaneChangeModel('never', (), lambda data, source: None,
                                       lambda params: lambda accelerations: False, 'no change')

HIGHWAY = lane_graph_from_roads(load_world('highway').roads)
DIMS = {'Car': (4.5, 1.8), 'Truck': (8.0, 2.4)}


@pytest.fixture
def toy_models(monkeypatch):
    monkeypatch.setitem(traffic_models.CAR_FOLLOWING_MODELS, 'relax', RELAX)
    monkeypatch.setitem(traffic_models.LANE_CHANGE_MODELS, 'never', NEVER)


def test_a_new_car_following_model_drives_the_traffic_with_no_other_change(toy_models,
                                                                            monkeypatch):
    spec = traffic_from_dict({'model': {'car_following': 'relax'}, 'relax': {'gain': 0.5},
                              'placed': [{'model': 'Car', 'lanelet': 100002, 's': 10.0,
                                          'speed': 0.0}]}, 'w.yaml: traffic')
    assert (spec.car_following, spec.lane_change) == ('relax', 'mobil')
    assert spec.params_of('relax') == {'gain_per_s': 0.5}
    m = TrafficManager(HIGHWAY, spec, DIMS)
    # looked up once: the registry may lose it, the manager drives on
    monkeypatch.delitem(traffic_models.CAR_FOLLOWING_MODELS, 'relax')
    v, = m.vehicles
    desired = m.desired_speed(v)
    for _ in range(20):
        m.step(0.1)
    # v' = 0.5 (v0 - v), integrated in steps of 0.1 s: v_n = v0 (1 - 0.95^n)
    assert v.speed_mps == pytest.approx(desired * (1.0 - 0.95 ** 20), rel=1e-12)
    assert v.s_m > 10.0


def test_a_new_lane_change_model_decides_the_changes(toy_models):
    def run(lane_change):
        m = TrafficManager(HIGHWAY, traffic_from_dict(
            {'model': {'lane_change': lane_change},
             'placed': [{'model': 'Car', 'lanelet': 100002, 's': 100.0, 'speed': 30.0},
                        {'model': 'Truck', 'lanelet': 100002, 's': 160.0, 'speed': 10.0,
                         'speed_factor': 0.3, 'route': [100102]}]}, 'w.yaml: traffic'), DIMS)
        for _ in range(60):
            m.step(0.05)
        return m.lane_changes
    assert run('mobil') == 1
    assert run('never') == 0


def test_a_new_traffic_model_drives_the_traffic_of_a_built_world(toy_models):
    data = _highway_data()
    data['traffic'] = {'model': {'car_following': 'relax', 'lane_change': 'never'},
                       'placed': [{'model': 'Car', 'lanelet': 100002, 's': 50.0, 'speed': 0.0}]}
    scene = build_scene(world_from_data(data, 'highway.yaml'))
    try:
        manager = scene.parts['traffic'].manager
        for _ in range(100):
            scene.world.step()
        v, = manager.vehicles
        assert v.speed_mps > 1.0 and v.s_m > 50.0 and manager.lane_changes == 0
    finally:
        scene.world.close()


def test_an_unknown_traffic_model_lists_the_registered_ones():
    with pytest.raises(InvalidParameterError,
                       match=r"w.yaml: traffic: model: field 'car_following' = 'gipps': "
                             r'unknown; valid: idm$'):
        traffic_from_dict({'model': {'car_following': 'gipps'}}, 'w.yaml: traffic')
    with pytest.raises(InvalidParameterError, match=r"field 'lane_change' = 'lc2013': "
                                                    r'unknown; valid: mobil$'):
        traffic_from_dict({'model': {'lane_change': 'lc2013'}}, 'w.yaml: traffic')
    with pytest.raises(InvalidParameterError, match=r"traffic: model: traffic models must be a "
                                                    r"mapping, got 'idm'$"):
        traffic_from_dict({'model': 'idm'}, 'w.yaml: traffic')


def test_a_model_s_parameters_are_validated_under_its_name(toy_models):
    with pytest.raises(InvalidParameterError, match=r"traffic: relax: field 'gain' = -1"):
        traffic_from_dict({'model': {'car_following': 'relax'}, 'relax': {'gain': -1}},
                          'w.yaml: traffic')
    assert '#### `relax:` (a toy model)' in traffic_markdown()


# ------------------------------------------------------------------------------ scene parts

class _Signs:
    name = 'signs'

    def __init__(self, log):
        self.log = log

    def build(self, world, spec):
        self.log.append('signs')
        return [o.name for o in spec.obstacles]


def test_a_new_scene_part_is_built_for_the_worlds_that_ask_with_no_other_change(monkeypatch):
    log = []
    monkeypatch.setattr(physics_scene, 'SCENE_PARTS', dict(physics_scene.SCENE_PARTS))
    physics_scene.register_scene_part(ScenePartRow(
        'signs', lambda spec: bool(spec.obstacles), lambda: _Signs(log)))
    scene = build_scene(load_world('obstacle_course'))
    try:
        assert scene.parts['signs'] == [o.name for o in load_world('obstacle_course').obstacles]
        assert log == ['signs']
    finally:
        scene.world.close()
    scene = build_scene(load_world('default'))
    try:
        assert 'signs' not in scene.parts and log == ['signs']
    finally:
        scene.world.close()


def test_scene_parts_build_in_row_order_around_the_given_parts():
    spec = world_from_data({**_highway_data(), 'traffic': {'vehicles': 1}}, 'highway.yaml')

    class Given:
        name = 'given'

    assert [p.name for p in physics_scene.scene_parts(spec, (Given(),))] == [
        'roads', 'given', 'traffic']
    given_traffic = Given()
    given_traffic.name = 'traffic'
    parts = physics_scene.scene_parts(spec, (given_traffic,))
    assert [p.name for p in parts] == ['roads', 'traffic'] and parts[1] is given_traffic


# ------------------------------------------------------------------------------ sweep backends

def _run_inline(todo, workers, timeout_s, address, case_log, finished):
    for work in todo:
        finished(run_case_logged(work, case_log(work)))


def test_a_new_sweep_backend_runs_the_sweep_with_no_other_change(monkeypatch, tmp_path):
    from vehicle_sim.tools.cli import main
    monkeypatch.setitem(sweep_run.BACKENDS, 'inline',
                        sweep_run.Backend('inline', _run_inline, doc='in this process'))
    scenario = str(REPO / 'scenarios' / 'stop_before_obstacle.yaml')
    result = sweep_run.run_sweep(scenario, ['duration=1'], '0:2', str(tmp_path / 'api'),
                                 backend='inline', plot=False)
    assert [r['seed'] for r in result.records] == [0, 1] and result.done == 2
    assert (tmp_path / 'api' / 'results.csv').is_file()
    assert main(['sweep', scenario, '--set', 'duration=1', '--backend', 'inline',
                 '--no-progress', '--out', str(tmp_path / 'cli')]) in (0, 1)
    assert (tmp_path / 'cli' / 'results.csv').read_text().count('\n') == 2


def test_an_unknown_sweep_backend_and_an_address_for_one_that_takes_none_are_refused(tmp_path):
    scenario = str(REPO / 'scenarios' / 'stop_before_obstacle.yaml')
    with pytest.raises(sweep_run.SweepError, match=r"--backend 'slurm': one of local, ray$"):
        sweep_run.run_sweep(scenario, out_dir=str(tmp_path), backend='slurm')
    with pytest.raises(sweep_run.SweepError, match=r'--ray-address needs --backend ray$'):
        sweep_run.run_sweep(scenario, out_dir=str(tmp_path), ray_address='auto')
