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
Several ego vehicles in one driving world, each stepped by its own action.

:class:`MultiDriveSim` is what the PettingZoo environment (multi.py) needs of the simulator,
without PettingZoo: the world built by the scene builder, one :class:`~vehicle_sim.gym.ego.Ego`
per agent (the single-agent environment's action layout, observation parts, progress, reward
terms and episode ends, not a copy), and the world reset of ``DriveSim`` (drive_sim.py). The
agents are vehicles of the world file (``vehicles:``), its places: ``agents=N`` takes the first
N, a list takes those names; the world's other vehicles stay parked. An agent whose episode
ends (a collision, off the road with ``terminate_off_road``, its goal) leaves: its car is
braked to a stand and stays in the world as an obstacle, the others go on; every agent is
truncated at the episode's time.

With the same seed and the same actions two episodes give bit-identical observations
(test/test_gym_multi.py).
"""

from numbers import Integral

from vehicle_sim.core.learning.reward import total
from vehicle_sim.core.specs.errors import InvalidParameterError
from vehicle_sim.core.specs.simulation import TIME_STEP_MS
from vehicle_sim.gym.drive_sim import _world_spec, DEFAULT_EPISODE_S, reset_world
from vehicle_sim.gym.ego import Ego, mounted_parts
from vehicle_sim.gym.options import validate_options
from vehicle_sim.physics.scene import build_scene

SOURCE = 'vehicle_sim/MultiDrive-v0'
DEFAULT_WORLD = 'crossing4'
# options of one ego that several do not take (the agents are named by ``agents``)
SINGLE_EGO_OPTIONS = ('vehicle', 'robot', 'start')


def agent_names(world_spec, agents, world):
    """
    Return the agents' vehicle names: the first ``agents`` of the world, or those named.

    :param world: the world as an error names it ("the world 'crossing4'").

    :raises InvalidParameterError: for more agents than the world has vehicles, fewer than
        one, an unknown or repeated name.
    """
    places = [v.name for v in world_spec.vehicles]
    listed = ', '.join(places) or 'none'
    if isinstance(agents, Integral) and not isinstance(agents, bool):
        agents = int(agents)
    where = f'{SOURCE}: agents = {agents!r}'
    if isinstance(agents, bool) or not isinstance(agents, (Integral, list, tuple)):
        raise InvalidParameterError(f'{where}: give a number of agents or a list of vehicle '
                                    f'names of {world} ({listed})')
    if isinstance(agents, int):
        if agents < 1:
            raise InvalidParameterError(f'{where}: at least 1 agent')
        if agents > len(places):
            raise InvalidParameterError(
                f'{where}: more agents than {world} has places for: its '
                f'{len(places)} vehicles ({listed}) are the places; add vehicles to it')
        return tuple(places[:agents])
    if not agents:
        raise InvalidParameterError(f'{where}: at least 1 agent')
    unknown = [name for name in agents if name not in places]
    if unknown:
        raise InvalidParameterError(
            f'{where}: {", ".join(repr(n) for n in unknown)}: no such vehicle in {world}; '
            f'its vehicles: {listed}')
    repeated = sorted({name for name in agents if list(agents).count(name) > 1})
    if repeated:
        raise InvalidParameterError(f'{where}: {", ".join(repr(n) for n in repeated)} '
                                    'named more than once')
    return tuple(agents)


class MultiDriveSim:
    """
    One world with several ego vehicles, stepped by a dict of actions (see the module text).

    :param world: a world name (config/worlds), a path to a world .yaml, a world mapping or a
        WorldSpec; None = 'crossing4'.
    :param agents: the number of agents (the world's first vehicles) or their vehicle names.
    :param options: the single-agent environment's options (options.py) but 'vehicle',
        'robot' and 'start'; each agent gets the same.
    :param observation_parts: a function (Ego) -> more observation parts of that agent.
    :raises InvalidParameterError: for a bad option, world or agents; nothing is built.
    """

    def __init__(self, world=None, agents=2, options=None, gui=False,
                 observation_parts=None):
        options = dict(options or {})
        for key in SINGLE_EGO_OPTIONS:
            if key in options:
                raise InvalidParameterError(
                    f'{SOURCE}: option {key!r} = {options[key]!r}: names one ego; several '
                    "agents are the world's vehicles named by 'agents'")
        opts = self.options = validate_options(options, SOURCE)
        world = DEFAULT_WORLD if world is None else world
        world_spec = _world_spec(world, True)
        self.agents = agent_names(world_spec, agents, f'the world {world!r}'
                                  if isinstance(world, str) else 'the world given')
        self.episode_s = opts['max_episode_s'] or DEFAULT_EPISODE_S
        step_ms = opts['time_step_ms'] or TIME_STEP_MS.default
        self._mounted = {}
        self.scene = build_scene(world_spec, time_step_s=step_ms / 1000.0, gui=gui,
                                 mount=self._mount)
        try:
            self.world = self.scene.world
            self.egos = {name: Ego(self.scene, name, opts, self._mounted[name],
                                   () if observation_parts is None else observation_parts(name))
                         for name in self.agents}
            self.live = ()
            self._started = False
            self._step0 = self.world.step_count
        except BaseException:
            self.close()
            raise

    def _mount(self, vehicle, scene):
        # The scene builder's mount step: each agent's observation parts (sensors).
        if vehicle.name not in self.agents:
            return None
        self._mounted[vehicle.name] = mounted_parts(vehicle, scene, self.options, SOURCE)
        return self._mounted[vehicle.name]

    @property
    def elapsed_s(self):
        """Simulated time since the last reset [s]."""
        return (self.world.step_count - self._step0) * self.world.time_step_s

    def reset(self, rng):
        """
        Start an episode with every agent: return ({agent: obs}, {agent: info}).

        :param rng: numpy Generator: the traffic's seed, the start offsets (option start_noise)
            and the sensors' noise seeds are drawn from it, in the agents' order.
        :raises InvalidParameterError: when no start poses of option start_noise fit (no
            agent is then live: ``step`` refuses until a reset succeeds).
        """
        self.live = ()
        self._started = False
        egos = [self.egos[name] for name in self.agents]
        for ego in egos:
            ego.stop()
        reset_world(self.scene, rng, [ego.body for ego in egos], self.options['start_noise'],
                    ', '.join(repr(name) for name in self.agents))
        for ego in egos:
            ego.reseed(rng)
        self._step0 = self.world.step_count
        obs = {ego.name: ego.start() for ego in egos}
        infos = {ego.name: ego.info(0.0, 0.0, dict.fromkeys(ego.terms, 0.0), '', False)
                 for ego in egos}
        self.live = self.agents
        self._started = True
        return obs, infos

    def check(self, actions):
        """
        Return {agent: checked action} of the live agents, or raise naming what is wrong.

        :raises ValueError: for an action of an unknown agent, of one that left, a live agent
            without one, or an action outside its space; nothing is stepped.
        :raises RuntimeError: before the first reset.
        """
        if not self._started:
            raise RuntimeError('step() before reset() (or after a reset that raised): call '
                               'reset() first')
        if not self.live:
            raise RuntimeError('every agent has left the episode: call reset()')
        if not isinstance(actions, dict):
            raise ValueError(f'actions of type {type(actions).__name__}: give a dict '
                             '{agent: action}')
        unknown = [a for a in actions if a not in self.egos]
        if unknown:
            raise ValueError(f'actions for {", ".join(repr(a) for a in unknown)}: no such '
                             f'agent; agents: {", ".join(self.agents)}')
        gone = [a for a in actions if a not in self.live]
        if gone:
            raise ValueError(f'actions for {", ".join(repr(a) for a in gone)}: left the '
                             f'episode; live agents: {", ".join(self.live) or "none"}')
        missing = [a for a in self.live if a not in actions]
        if missing:
            raise ValueError(f'no action for the live agents '
                             f'{", ".join(repr(a) for a in missing)}')
        checked = {}
        for name in self.live:
            try:
                checked[name] = self.egos[name].control.check(actions[name])
            except ValueError as error:
                raise ValueError(f'agent {name!r}: {error}') from None
        return checked

    def step(self, actions):
        """
        Apply each live agent's action for ``action_repeat`` basic steps.

        :return: ({agent: obs}, {agent: reward terms}, {agent: terminated},
            {agent: truncated}, {agent: info}) of the agents live before the step; those
            terminated or truncated have left (``live``) and their cars are braked.
        """
        checked = self.check(actions)
        live = [self.egos[name] for name in self.live]
        for ego in live:
            ego.control.apply(checked[ego.name])
            ego.begin()
        world = self.world
        repeat = self.options['action_repeat']
        for _ in range(repeat):
            world.step()
            for ego in live:
                ego.after_basic_step()
        elapsed_s = self.elapsed_s
        obs, terms, terminated, truncated, infos = {}, {}, {}, {}, {}
        for ego in live:
            name = ego.name
            obs[name], terms[name], terminated[name], truncated[name], facts = \
                ego.outcome(elapsed_s, self.episode_s, repeat)
            infos[name] = ego.info(elapsed_s, *facts)
        for ego in live:
            if terminated[ego.name] or truncated[ego.name]:
                ego.stop()
                ego.control.halt()
        self.live = tuple(n for n in self.live if not (terminated[n] or truncated[n]))
        return obs, terms, terminated, truncated, infos

    @staticmethod
    def reward(terms):
        """Return the default reward of a step's terms (their sum)."""
        return total(terms)

    def close(self):
        """Disconnect the physics client (idempotent)."""
        self.scene.world.close()
