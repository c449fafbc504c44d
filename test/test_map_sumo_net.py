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
A SUMO network as a lane map (``map: {type: sumo, net: ...}``, vehicle_sim/maps/sumo_net.py).

The network is netgenerate's signalised grid (test/sumo_helpers.py); what the lane graph says
is compared with what sumolib reads from the same file.
"""

import gzip
import math

import numpy as np
import pytest
import yaml

pytest.importorskip('sumolib', reason="sumolib is not installed (pip install "
                                      "'vehicle_sim[sumo]')")

from sumo_helpers import grid_net, run_tool  # noqa: E402
import sumolib  # noqa: E402  (after the skip)

from vehicle_sim.config import load_world  # noqa: E402
from vehicle_sim.core.map.lane_graph import distances_to_polyline  # noqa: E402
from vehicle_sim.core.map.signal_programs import ProgramController, SUMO_STATES  # noqa: E402
from vehicle_sim.core.specs.errors import InvalidParameterError  # noqa: E402
from vehicle_sim.maps.lane_maps import with_lanes  # noqa: E402
from vehicle_sim.maps.sumo_net import lane_ids, load_sumo_net, SumoNetWarning  # noqa: E402


@pytest.fixture(scope='module')
def net_path(tmp_path_factory):
    return grid_net(tmp_path_factory.mktemp('grid'))


@pytest.fixture(scope='module')
def loaded(net_path):
    graph, _ = load_sumo_net(net_path)
    net = sumolib.net.readNet(net_path, withInternal=True, withPedestrianConnections=True,
                              withPrograms=True)
    return graph, net


def _vehicle_lanes(net):
    return [lane for edge in net.getEdges(withInternal=True)
            if edge.getFunction() in ('', 'normal', 'internal')
            for lane in edge.getLanes() if lane.allows('passenger')]


def _world(tmp_path, net_path, **more):
    world = tmp_path / 'sumo_world.yaml'
    data = {'vehicles': [{'name': 'Car', 'model': 'ToyotaPrius',
                          'pose': more.pop('pose', {'lanelet': 1, 's': 0.0})}],
            'map': {'type': 'sumo', 'net': str(net_path)}}
    data.update(more)
    world.write_text(yaml.safe_dump(data), encoding='utf-8')
    return world


# ----------------------------------------------------------------------------------- the lanes

def test_the_lanes_are_sumolibs_passenger_lanes_with_their_shapes_and_lengths(loaded):
    graph, net = loaded
    expected = _vehicle_lanes(net)
    assert sorted(lane.name for lane in graph.lanes.values()) == sorted(
        lane.getID() for lane in expected)
    ids = lane_ids(net)
    for lane in expected:
        ours = graph.lanes[ids[lane.getID()]]
        assert ours.name == lane.getID()
        assert ours.length_m == pytest.approx(lane.getLength(), abs=0.1)
        assert ours.widths[0] == pytest.approx(lane.getWidth())
        assert ours.speed_limit_mps == pytest.approx(lane.getSpeed())
        assert ours.centerline[0] == pytest.approx(lane.getShape()[0])
        assert ours.centerline[-1] == pytest.approx(lane.getShape()[-1])
        assert ours.subtype == 'road'


def test_successors_go_through_the_internal_lanes_as_sumolibs_connections(loaded):
    graph, net = loaded
    ids = lane_ids(net)
    through = 0
    for lane in _vehicle_lanes(net):
        want, straight = [], []
        for connection in lane.getOutgoing():
            via = connection.getViaLaneID()
            want.append(via or connection.getToLane().getID())
            if connection.getDirection() == 's':
                straight.append(want[-1])
        ours = [graph.lanes[i].name for i in graph.lanes[ids[lane.getID()]].successors]
        assert sorted(ours) == sorted(set(want))
        assert ours[:len(straight)] == straight        # straight on first
        through += sum(name.startswith(':') for name in want)
    assert through > 50                 # the approach lanes lead into their junction's lanes
    # an approach lane of the signalised junction B1 leads to the lanes beyond it through one
    # internal lane (straight on) or two (a left turn waits in the junction's middle)
    reached, front = set(), {ids['A1B1_1'], ids['A1B1_2']}
    for _ in range(3):
        front = {j for i in front for j in graph.lanes[i].successors}
        reached |= {graph.lanes[i].name for i in front}
    assert {'B1C1_1', 'B1B2_2'} <= reached


def test_lanes_of_one_edge_are_neighbours_dashed_between_curbstone_beside_the_sidewalk(loaded):
    graph, net = loaded
    ids = lane_ids(net)
    right, left = graph.lanes[ids['A0A1_1']], graph.lanes[ids['A0A1_2']]
    assert (right.left_lane, right.left_change) == (left.id, True)
    assert (left.right_lane, left.right_change) == (right.id, True)
    assert right.left is left.right and right.left.line_type == 'dashed'
    assert right.right.line_type == 'curbstone'          # the sidewalk A0A1_0 on its right
    assert left.left.line_type == 'solid'                # the opposite direction beyond
    assert right.right_lane is None                      # a sidewalk is not a lane
    inner = graph.lanes[ids[':B1_0_0']]
    assert inner.left.line_type == inner.right.line_type == 'virtual'


def test_lane_names_give_their_ids_and_a_point_on_a_lane_is_located_on_it(loaded):
    graph, net = loaded
    ids = lane_ids(net)
    lane = graph.lane_named('A0A1_1')
    assert lane.id == ids['A0A1_1']
    x, y, yaw = graph.pose_at(lane.id, 30.0)
    found = graph.locate(x, y, yaw)
    assert (found.lane_id, found.s_m) == (lane.id, pytest.approx(30.0))
    with pytest.raises(InvalidParameterError, match=r"lane named 'nowhere_0' is not in the map"):
        graph.lane_named('nowhere_0')


# ------------------------------------------------------------------------- signals and rules

def test_a_group_per_tls_link_index_with_its_stop_line_at_the_internal_lanes_start(loaded):
    graph, net = loaded
    ids = lane_ids(net)
    rules = graph.rules
    expected = {}
    for lane in _vehicle_lanes(net):
        for connection in lane.getOutgoing():
            if connection.getTLSID():
                expected.setdefault(f'{connection.getTLSID()}:{connection.getTLLinkIndex()}',
                                    set()).add(ids[connection.getViaLaneID()])
    assert {group.name: set(group.lanes) for group in rules.groups} == expected
    lines = {line.id: line for line in rules.stop_lines}
    for group in rules.groups:
        for line_id in group.stop_lines:
            line = lines[line_id]
            assert line.kind == 'traffic_light' and line.group_id == group.id
            assert line.s_m == 0.0 and line.lane_id in group.lanes
        assert [bulb.color for bulb in group.bulbs] == ['red', 'yellow', 'green']
        assert all(bulb.z_m > 4.0 for bulb in group.bulbs)


def test_the_programs_are_the_nets_tl_logics_with_links_to_the_groups(loaded):
    graph, net = loaded
    rules = graph.rules
    by_name = {group.name: group.id for group in rules.groups}
    programs = {program.tls_id: program for program in rules.programs}
    assert set(programs) == {tls.getID() for tls in net.getTrafficLights()}
    for tls in net.getTrafficLights():
        logic = list(tls.getPrograms().values())[-1]
        program = programs[tls.getID()]
        assert program.phases == tuple((float(p.duration), p.state) for p in logic.getPhases())
        assert program.offset_s == float(logic.getOffset())
        for index, group_id in enumerate(program.links):
            assert group_id == by_name.get(f'{tls.getID()}:{index}')
    assert any(group_id is None for p in rules.programs for group_id in p.links)  # crossings


def test_the_controller_shows_the_programs_state_at_given_times(loaded):
    graph, _ = loaded
    controller = ProgramController(graph)
    program = graph.rules.programs[0]
    start = 0.0
    for duration, state in program.phases:
        for t in (start + 0.01, start + duration / 2, start + duration - 0.01):
            controller.update(t)
            for index, group_id in enumerate(program.links):
                if group_id is not None:
                    assert controller.state(group_id) == SUMO_STATES[state[index]], (t, index)
        start += duration
    controller.update(start + 0.01)                                 # the next cycle
    assert controller.states()[program.links[0]] == SUMO_STATES[program.phases[0][1][0]]


def test_the_programs_states_are_sumos_own_for_an_offset_program(tmp_path, net_path):
    # the net's first program shifted by 10 s; SUMO (its sumo binary, through TraCI) runs it
    import os

    import sumo
    import traci
    text = open(net_path, encoding='utf-8').read()
    first = text.index('<tlLogic ')
    shifted = text[:first] + text[first:].replace('offset="0"', 'offset="10"', 1)
    net = tmp_path / 'offset.net.xml'
    net.write_text(shifted, encoding='utf-8')
    graph, _ = load_sumo_net(str(net))
    program = graph.rules.programs[0]
    assert program.offset_s == 10.0
    controller = ProgramController(graph)
    binary = os.path.join(sumo.SUMO_HOME, 'bin', 'sumo')
    traci.start([binary, '-n', str(net), '--no-step-log', '--step-length', '1'],
                label='programs', stdout=open(os.devnull, 'w'))
    try:
        connection = traci.getConnection('programs')
        for second in range(0, 200):
            # SUMO switches at the start of the step from a switch time t on, and TraCI at
            # time t reads the state before that step: the state of the second before
            theirs = connection.trafficlight.getRedYellowGreenState(program.tls_id)
            assert program.state_at(second - 0.5) == theirs, second
            controller.update(second - 0.5)
            for index, group_id in enumerate(program.links):
                if group_id is not None:
                    assert controller.state(group_id) == SUMO_STATES[theirs[index]]
            connection.simulationStep()
    finally:
        traci.switch('programs')
        traci.close()


def test_an_engine_drives_the_states_and_a_forced_state_still_wins(loaded):
    graph, _ = loaded
    controller = ProgramController(graph)
    program = graph.rules.programs[0]
    first, second = program.links[0], program.links[1]
    controller.drive({first: 'yellow'})
    controller.update(1000.0)                      # the programs no longer advance
    assert controller.state(first) == 'yellow' and controller.driven
    controller.force(first, 'red')
    controller.drive({first: 'green', second: 'green'})
    assert (controller.state(first), controller.state(second)) == ('red', 'green')
    controller.release()
    assert controller.state(first) == 'green'
    with pytest.raises(InvalidParameterError, match="signal state 'blue'"):
        controller.drive({first: 'blue'})
    assert controller.state(first) == 'green'
    controller.stop_driving()
    assert controller.state(first) == SUMO_STATES[program.state_at(1000.0)[0]]


def test_walkways_crosswalks_and_junctions_are_areas(loaded):
    graph, net = loaded
    kinds = {}
    for area in graph.rules.areas:
        kinds.setdefault(area.kind, []).append(area)
    crossings = [e for e in net.getEdges(withInternal=True) if e.getFunction() == 'crossing']
    walking = [e for e in net.getEdges(withInternal=True) if e.getFunction() == 'walkingarea']
    sidewalks = [lane for e in net.getEdges(withInternal=False) for lane in e.getLanes()
                 if lane.getPermissions() == {'pedestrian'}]
    assert len(kinds['crosswalk']) == len(crossings) > 0
    assert len(kinds['walkway']) == len(walking) + len(sidewalks)
    assert len(kinds['junction']) == len(net.getNodes())
    for crosswalk in kinds['crosswalk']:      # the road lanes it crosses
        assert any(not graph.lanes[i].name.startswith(':') for i in crosswalk.lanes)


# ---------------------------------------------------------------------------------- the world

def test_a_sumo_world_runs_its_programs_without_sumo(tmp_path, net_path):
    from vehicle_sim.physics.scene import build_scene
    scene = build_scene(load_world(str(_world(tmp_path, net_path,
                                              pose={'lanelet': 1, 's': 0.0})), 'ToyotaPrius'))
    try:
        controller = scene.parts['signals'].controller
        assert isinstance(controller, ProgramController)
        program = scene.lanes.rules.programs[0]
        for _ in range(500):
            scene.world.step()
        assert controller.time_s == pytest.approx(5.0)
        state = program.state_at(5.0)
        assert controller.state(program.links[0]) == SUMO_STATES[state[0]]
        assert scene.parts['map'].spec.type == 'sumo'
    finally:
        scene.world.close()


def test_a_signals_key_beside_a_maps_programs_is_refused_naming_it(tmp_path, net_path):
    from vehicle_sim.physics.scene import build_scene
    world = _world(tmp_path, net_path, signals={'green': 10.0})
    with pytest.raises(InvalidParameterError, match=r'sumo_world.yaml: signals: the lane map '
                                                    r'.* has signal programs of its own'):
        build_scene(load_world(str(world), 'ToyotaPrius'))


def test_a_vehicle_is_placed_by_sumo_lane_name(tmp_path, net_path, loaded):
    graph, _ = loaded
    world = _world(tmp_path, net_path, pose={'lane': 'A0A1_2', 's': 25.0, 'offset': 0.5})
    spec = with_lanes(load_world(str(world), 'ToyotaPrius'))
    car = spec.vehicles[0]
    x, y, yaw = graph.pose_at(graph.lane_named('A0A1_2').id, 25.0, 0.5)
    assert (car.x_m, car.y_m, car.yaw_rad) == (pytest.approx(x), pytest.approx(y),
                                               pytest.approx(yaw))
    world = _world(tmp_path, net_path, pose={'lane': 'A0A1_9', 's': 5.0})
    with pytest.raises(InvalidParameterError, match=r"vehicles\[0\].pose: lane named "
                                                    r"'A0A1_9' is not in the map"):
        with_lanes(load_world(str(world), 'ToyotaPrius'))


# ------------------------------------------------------------------------------- bad networks

def test_a_missing_net_is_refused_naming_the_world_file_and_key(tmp_path):
    world = _world(tmp_path, tmp_path / 'absent.net.xml')
    with pytest.raises(InvalidParameterError, match=r'sumo_world.yaml: map.net: .*absent.net.xml: '
                                                    r'no such file'):
        with_lanes(load_world(str(world), 'ToyotaPrius'))


@pytest.mark.parametrize('text', ['', '<net><edge id="e" from="a" to="b">',
                                  'not xml at all', '<net version="1.20"></net>'])
def test_a_corrupt_net_is_refused_naming_the_file(tmp_path, text):
    net = tmp_path / 'corrupt.net.xml'
    net.write_text(text, encoding='utf-8')
    with pytest.raises(InvalidParameterError, match=r'map.net: .*corrupt.net.xml: '):
        with_lanes(load_world(str(_world(tmp_path, net)), 'ToyotaPrius'))


def test_lanes_no_road_vehicle_uses_are_skipped_with_one_warning(tmp_path, net_path):
    text = open(net_path, encoding='utf-8').read()
    # the rightmost road lane of one edge becomes a rail
    edited = text.replace('<lane id="A0A1_1" index="1" disallow="pedestrian" ',
                          '<lane id="A0A1_1" index="1" allow="rail" ', 1)
    assert edited != text
    net = tmp_path / 'rail.net.xml'
    net.write_text(edited, encoding='utf-8')
    with pytest.warns(SumoNetWarning, match=r'1 lane\(s\) skipped, it allows no road '
                                            r'vehicle: A0A1_1'):
        graph, _ = load_sumo_net(str(net))
    assert 'A0A1_1' not in {lane.name for lane in graph.lanes.values()}
    assert math.isfinite(graph.lane_named('A0A1_2').length_m)


def test_right_of_way_is_sumos_major_and_minor_links_at_unsignalled_junctions(loaded):
    graph, net = loaded
    ids = lane_ids(net)
    rules = {}
    for rule in graph.rules.right_of_way:
        rules[graph.lanes[rule.priority_lanes[0]].name.split('_')[0][1:]] = rule
    expected = {}
    for lane in _vehicle_lanes(net):
        for connection in lane.getOutgoing():
            if not lane.getID().startswith(':') and not connection.getTLSID():
                node = lane.getEdge().getToNode().getID()
                state = connection.getState()
                side = 'priority' if state == 'M' else 'yield' if state in 'ms' else None
                if side:
                    expected.setdefault(node, {'priority': set(), 'yield': set()})[side].add(
                        ids[connection.getViaLaneID()])
    expected = {node: sides for node, sides in expected.items() if all(sides.values())}
    assert expected and set(rules) == set(expected)
    for node, rule in rules.items():
        assert set(rule.priority_lanes) == expected[node]['priority']
        assert set(rule.yield_lanes) == expected[node]['yield']


def test_an_all_way_stop_has_a_stop_line_on_every_link_and_no_priority(tmp_path):
    net = str(tmp_path / 'stop.net.xml')
    run_tool('netgenerate', '--grid', '--grid.number', '3', '--default-junction-type',
             'allway_stop', '-o', net)
    graph, sumo = load_sumo_net(net)
    assert not graph.rules.groups and not graph.rules.programs
    assert not graph.rules.right_of_way
    ids = lane_ids(sumo)
    links = {ids[c.getViaLaneID()] for lane in _vehicle_lanes(sumo)
             if not lane.getID().startswith(':') for c in lane.getOutgoing()}
    lines = graph.rules.stop_lines
    assert {line.lane_id for line in lines} == links
    assert {line.kind for line in lines} == {'stop_sign'} and {line.s_m for line in lines} == {0.0}


# -------------------------------------------------------------------------------------- docs

def test_docs_maps_embeds_the_key_tables_and_the_netconvert_options():
    from pathlib import Path

    from vehicle_sim.core.map.kinds import NETCONVERT_MAP_SPECS, SUMO_MAP_SPECS
    from vehicle_sim.core.map.sumo_net_params import NETCONVERT_ALWAYS, OPENDRIVE_INPUT, OSM_INPUT
    from vehicle_sim.core.specs.param_spec import parameter_table_markdown
    text = (Path(__file__).resolve().parents[1] / 'docs' / 'maps.md').read_text('utf-8')
    assert parameter_table_markdown(SUMO_MAP_SPECS, 'key') in text
    assert parameter_table_markdown(NETCONVERT_MAP_SPECS, 'key') in text
    for option, defaults in (OPENDRIVE_INPUT, OSM_INPUT):
        assert f"| `{option}` | `{' '.join(defaults)}`" in text
    assert ' '.join(NETCONVERT_ALWAYS) in text


def test_docs_signals_lists_every_sumo_state():
    from pathlib import Path
    text = (Path(__file__).resolve().parents[1] / 'docs' / 'signals.md').read_text('utf-8')
    rows = [line for line in text.splitlines() if line.startswith('| `')]
    for character, state in SUMO_STATES.items():
        assert any(f'`{character}`' in row.split('|')[1] and row.rstrip(' |').endswith(state)
                   for row in rows), character


@pytest.mark.parametrize('vclass, subtypes', [
    ('passenger', {'A0A1_1': 'bicycle_lane', 'A0A1_2': 'road', 'A0A1_3': 'road'}),
    ('bicycle', {'A0A1_1': 'road', 'A0A1_2': 'restricted_lane', 'A0A1_3': 'restricted_lane'}),
])
def test_a_bicycle_lane_is_a_lane_of_its_subtype_unless_it_is_the_vclasss(tmp_path, vclass,
                                                                         subtypes):
    net = grid_net(tmp_path, 'bike.net.xml', '--bikelanes.guess')
    graph, _ = load_sumo_net(net, vclass)
    lanes = {name: graph.lane_named(name) for name in subtypes}
    assert {name: lane.subtype for name, lane in lanes.items()} == subtypes
    bike, right, left = lanes['A0A1_1'], lanes['A0A1_2'], lanes['A0A1_3']
    assert bike.right.line_type == 'curbstone'            # the sidewalk beyond
    assert bike.left is right.right and bike.left.line_type == 'solid'
    assert (right.right_lane, right.right_change) == (bike.id, False)
    assert right.left.line_type == 'dashed' and (right.left_lane, right.left_change) == (
        left.id, True)


def test_the_vclass_key_is_checked_and_passed_to_the_reader(tmp_path):
    net = grid_net(tmp_path, 'bike.net.xml', '--bikelanes.guess')
    world = tmp_path / 'bike_world.yaml'
    data = {'vehicles': [{'name': 'Car', 'model': 'ToyotaPrius',
                          'pose': {'lane': 'A0A1_1', 's': 5.0}}],
            'map': {'type': 'sumo', 'net': net, 'vclass': 'bicycle'}}
    world.write_text(yaml.safe_dump(data), encoding='utf-8')
    graph = with_lanes(load_world(str(world), 'ToyotaPrius')).lanes
    assert graph.lane_named('A0A1_1').subtype == 'road'
    data['map']['vclass'] = 'hovercraft'
    world.write_text(yaml.safe_dump(data), encoding='utf-8')
    with pytest.raises(InvalidParameterError, match=r"bike_world.yaml: map: field 'vclass' = "
                                                    r"'hovercraft': .*passenger"):
        load_world(str(world), 'ToyotaPrius')


def test_in_a_left_hand_network_the_next_lane_of_an_edge_is_on_the_right(tmp_path):
    net = grid_net(tmp_path, 'left.net.xml', '--lefthand')
    graph, _ = load_sumo_net(net)
    outer, inner = graph.lane_named('A0A1_1'), graph.lane_named('A0A1_2')
    assert (outer.right_lane, outer.right_change) == (inner.id, True)
    assert (inner.left_lane, inner.left_change) == (outer.id, True)
    assert outer.right is inner.left and outer.right.line_type == 'dashed'
    assert outer.left.line_type == 'curbstone'           # the sidewalk on the left
    x, y, yaw = graph.pose_at(outer.id, 10.0, 0.5 * outer.widths[0] - 0.01)   # its left edge
    assert distances_to_polyline(np.array([[x, y]]), outer.left.points)[0] < 0.02
    # and a gzipped network reads as it is
    with open(net, 'rb') as plain, gzip.open(tmp_path / 'left.net.xml.gz', 'wb') as packed:
        packed.write(plain.read())
    again, _ = load_sumo_net(str(tmp_path / 'left.net.xml.gz'))
    assert again.lane_named('A0A1_1').right_lane == inner.id
