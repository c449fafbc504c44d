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
The same traffic per seed in process and over the wire (``vehicle-sim policy evaluate``).

A Gym reset with ``seed`` starts the traffic from the first draw of its generator
(``episode_traffic_seed``); the over-the-wire run writes that seed into its world's
``traffic: seed``, and the automobile node builds its scene from that world file.
"""

from pathlib import Path

import gymnasium
import pytest

from vehicle_sim.config import world_from_data
from vehicle_sim.core.specs.errors import InvalidParameterError
import vehicle_sim.gym  # noqa: F401  (registers the ids)
from vehicle_sim.gym.drive_sim import episode_traffic_seed, TRAFFIC_SEEDS
from vehicle_sim.physics.scene import build_scene
from vehicle_sim.scenarios.schema import load_scenario
from vehicle_sim.tools.policy_command import wire_spec
from vehicle_sim.tools.policy_loader import DriveSetup

SCENARIO = Path(__file__).resolve().parent.parent / 'scenarios' / 'highway_policy.yaml'
SETUP = DriveSetup(('lane', 'twist'), None, 'speed_steering', (-0.5, -5.0), (0.5, 30.0),
                   (-1.0, 1.0), 1.0)


def _places(traffic):
    return sorted((o.name, round(o.x_m, 9), round(o.y_m, 9), round(o.yaw_rad, 9),
                   round(o.speed_mps, 9)) for o in traffic.objects())


@pytest.mark.parametrize('seed', [0, 1234])
def test_the_wire_worlds_traffic_is_the_resets_traffic(seed):
    spec = load_scenario(SCENARIO)
    env = gymnasium.make('vehicle_sim/Drive-v0', scenario=spec)
    try:
        env.reset(seed=seed)
        in_process = _places(env.unwrapped.sim.scene.parts['traffic'])
    finally:
        env.close()
    wired = wire_spec(spec, 'model.zip', seed, SETUP)
    traffic_seed = episode_traffic_seed(seed)
    assert wired.world_data['traffic']['seed'] == traffic_seed > 999999    # a Gym-sized seed
    assert wired.world.traffic.seed == traffic_seed and wired.seed == seed
    # the world as the automobile node reads the file the runner writes
    scene = build_scene(world_from_data(wired.world_data, 'wire world'), time_step_s=0.01)
    try:
        assert _places(scene.parts['traffic']) == in_process
        assert len(in_process) == 60
    finally:
        scene.world.close()


def test_a_world_names_every_traffic_seed_a_reset_can_draw():
    data = {'vehicles': [], 'roads': [{'name': 'r', 'segments': [
        {'type': 'straight', 'length': 100.0}]}], 'traffic': {'vehicles': 1}}
    top = TRAFFIC_SEEDS - 1
    assert world_from_data(dict(data, traffic={'vehicles': 1, 'seed': top}),
                           'w', vehicles_required=False).traffic.seed == top
    with pytest.raises(InvalidParameterError, match='2147483648'):
        world_from_data(dict(data, traffic={'vehicles': 1, 'seed': TRAFFIC_SEEDS}), 'w',
                        vehicles_required=False)


class _Spaces:
    """A model as the checks read it: its two spaces."""

    def __init__(self, observation_space, action_space):
        self.observation_space = observation_space
        self.action_space = action_space


def test_drive_setup_reads_the_cards_environment():
    from vehicle_sim.gym.policy_card import make_env, PolicyCard
    from vehicle_sim.tools.policy_loader import drive_setup
    card = PolicyCard('vehicle_sim/Drive-v0', {'world': 'highway', 'action_repeat': 20,
                                               'objects': {'count': 8}, 'max_speed': 30.0},
                      ('lane', 'objects', 'twist'))
    env = make_env(card)
    model = _Spaces(env.observation_space, env.action_space)
    low, high = env.unwrapped.action_space.low, env.unwrapped.action_space.high
    env.close()
    setup = drive_setup(card, model)
    assert setup.control == 'speed_steering'           # 'auto' for a car
    assert setup.period_s == pytest.approx(0.2) and setup.keys == card.observation_keys
    assert setup.objects_spec.count == 8
    assert setup.low == tuple(low) and setup.high == tuple(high) and setup.high[1] == 30.0
    with pytest.raises(InvalidParameterError, match=r'--rate 0.0: must be a number > 0'):
        drive_setup(card, model, rate_hz=0.0)
    other = make_env(PolicyCard('vehicle_sim/Drive-v0', {'world': 'highway'}, ('lane', 'twist')))
    with pytest.raises(InvalidParameterError, match=r"x.zip: observation space differs: "
                                                    r"'objects': \(8, 7\) in the environment, "
                                                    r'not in the model'):
        drive_setup(card, _Spaces(other.observation_space, env.action_space), source='x.zip')
    other.close()
