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
SUMO's signal programs drive the world's signals, and a forced state is SUMO's too.

On the one-lane grid (test/sumo_helpers.py: a traffic light at every junction) with the SUMO
engine: after every SUMO step each group of the lane map shows the state SUMO gives its link
(by traffic light id and link index), through a minute of changes; a group a scenario forces
red is red in SUMO (its link's state character), and SUMO's vehicles stop before it; released,
SUMO runs its program again and the group follows it.
"""

import math

import pytest

pytest.importorskip('traci', reason="needs the 'sumo' extra")

from vehicle_sim.physics import sumo_session  # noqa: E402

if sumo_session.load_libsumo() is None:      # (imported quietly: its pyarrow notice)
    pytest.skip("needs the 'sumo' extra (libsumo)", allow_module_level=True)

from sumo_helpers import one_lane_grid_net, write_routes  # noqa: E402

from vehicle_sim.config import world_from_data  # noqa: E402
from vehicle_sim.core.map.signal_programs import SUMO_STATES  # noqa: E402
from vehicle_sim.physics.scene import build_scene  # noqa: E402

OFF_ROAD = (-30.0, -30.0, 0.0)


@pytest.fixture(scope='module')
def net(tmp_path_factory):
    return one_lane_grid_net(tmp_path_factory.mktemp('sumo_net'))


def _scene(net, folder, vehicles):
    x, y, yaw = OFF_ROAD
    data = {'vehicles': [{'name': 'ego', 'model': 'Car', 'pose': {'x': x, 'y': y, 'yaw': yaw}}],
            'map': {'type': 'sumo', 'net': net},
            'traffic': {'engine': 'sumo', 'routes': write_routes(folder, vehicles)}}
    return build_scene(world_from_data(data, 'w.yaml', base_dir=str(folder)))


def _links(scene):
    return [(program.tls_id, link, group) for program in scene.spec.lanes.rules.programs
            for link, group in enumerate(program.links) if group is not None]


def test_every_group_shows_the_state_sumo_gives_its_link(net, tmp_path):
    scene = _scene(net, tmp_path, [('a', 0, 'A0A1 A1A2')])
    try:
        controller = scene.parts['signals'].controller
        api = scene.parts['traffic'].session.api
        links = _links(scene)
        assert len(links) > 20
        seen = set()
        for _ in range(60):
            for _ in range(100):
                scene.world.step()
            strings = {tls: api.trafficlight.getRedYellowGreenState(tls) for tls, *_ in links}
            states = controller.states()
            for tls, link, group in links:
                assert states[group] == SUMO_STATES[strings[tls][link]], (tls, link, group)
                seen.add((group, states[group]))
        assert {'green', 'yellow', 'red'} <= {state for _, state in seen}
        assert controller.driven
    finally:
        scene.world.close()


def test_a_forced_red_is_red_in_sumo_and_its_traffic_stops(net, tmp_path):
    # a car from A0 north to A1 and on to A2: the group of its link at A1 forced red
    scene = _scene(net, tmp_path, [('a', 0, 'A0A1 A1A2')])
    try:
        controller = scene.parts['signals'].controller
        bodies = scene.parts['traffic']
        api = bodies.session.api
        for _ in range(10):
            scene.world.step()
        tls, link, *_ = api.vehicle.getNextTLS('a')[0]     # its next light and link index
        assert tls == 'A1'
        group = next(g for t, index, g in _links(scene) if (t, index) == (tls, link))
        controller.force(group, 'red')
        for _ in range(120):            # two minutes: SUMO's program would turn it green
            for _ in range(100):
                scene.world.step()
            assert api.trafficlight.getRedYellowGreenState(tls)[link] == 'r'
            assert controller.state(group) == 'red'
        assert api.vehicle.getRoadID('a') == 'A0A1' and api.vehicle.getSpeed('a') < 0.1
        (name, x, y, yaw, length, *_), = bodies.agents()
        assert y + 0.5 * length < 92.8 and math.isclose(yaw, math.pi / 2, abs_tol=1e-6)
        program = next(p for p in scene.spec.lanes.rules.programs if p.tls_id == tls)
        controller.release(group)
        for _ in range(6000):
            scene.world.step()
        assert api.trafficlight.getProgram(tls) == program.program_id
        assert 'a' not in api.vehicle.getIDList() or api.vehicle.getRoadID('a') != 'A0A1'
        state = api.trafficlight.getRedYellowGreenState(tls)
        assert controller.state(group) == SUMO_STATES[state[link]]
    finally:
        scene.world.close()
