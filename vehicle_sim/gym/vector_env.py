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
Many worlds in one process: N independent DriveSims stepped in one call, a Gymnasium VectorEnv.

Each world has its own PyBullet DIRECT client (PyBullet allows many in one process), its own
bodies and its own seeded generator, so nothing one world does reaches another
(test/test_gym_vector.py crashes world 0 and compares world 1 with a lone run). ``step``
steps every world in turn and stacks the results into preallocated arrays; there is no
inter-process traffic, which is why it beats AsyncVectorEnv on a few cores (docs/gym.md).

Autoreset follows Gymnasium's modes: ``next_step`` (the default, as SyncVectorEnv: a world
that ended is reset by the next ``step``, whose action for it is ignored and whose reward is
0), ``same_step`` (reset at once; the last observation and info are in ``info['final_obs']``,
``info['final_info']``) or ``disabled``.
"""

import numpy as np

from vehicle_sim.gym.drive_sim import DriveSim
from vehicle_sim.gym.require import gymnasium
from vehicle_sim.gym.spaces import action_space, observation_space

AutoresetMode = gymnasium.vector.AutoresetMode
VectorEnv = gymnasium.vector.VectorEnv
batch_space = gymnasium.vector.utils.batch_space

# Gymnasium's values ('NextStep') and the snake-case names ('next_step') of AutoresetMode.
_MODES = {**{mode.value: mode for mode in AutoresetMode},
          **{mode.name.lower(): mode for mode in AutoresetMode}}


def _autoreset_mode(value):
    if isinstance(value, AutoresetMode):
        return value
    if value not in _MODES:
        raise ValueError(f'autoreset_mode = {value!r}: one of ' + ', '.join(_MODES))
    return _MODES[value]


def _stack_infos(infos):
    # Gymnasium's vector info layout: {key: array over worlds, '_key': mask}; dicts nest.
    out = {}
    for key in infos[0]:
        values = [info[key] for info in infos]
        if isinstance(values[0], dict):
            out[key] = _stack_infos(values)
        else:
            out[key] = np.array(values, dtype=object if isinstance(values[0], str) else None)
        out['_' + key] = np.ones(len(infos), dtype=bool)
    return out


class _InfoTable:
    """
    The step infos of every world, as Gymnasium's vector info layout.

    Every world's step info has the same keys (DriveSim), one level of dicts at most. Each step
    gets fresh columns (:meth:`begin`), filled world by world (:meth:`put`) and handed out as
    they are (:meth:`table`): no copy, and nothing the caller keeps is written again. The masks
    are all true and shared (read-only).
    """

    def __init__(self, info, num_envs):
        self.keys = []              # (key, sub key or None)
        self.dtypes = []
        for key, value in info.items():
            for sub, item in (value.items() if isinstance(value, dict) else ((None, value),)):
                self.keys.append((key, sub))
                self.dtypes.append(object if isinstance(item, str) else np.asarray(item).dtype)
        self.num_envs = num_envs
        self.mask = np.ones(num_envs, dtype=bool)
        self.mask.flags.writeable = False
        self.columns = []
        # table()'s layout, the masks filled in: each step copies it and puts in the columns
        self._outer = {}
        self._inner = {}                # key -> its dict's layout
        for key, sub in self.keys:
            self._outer[key] = None
            self._outer['_' + key] = self.mask
            if sub is not None:
                inner = self._inner.setdefault(key, {})
                inner[sub] = None
                inner['_' + sub] = self.mask

    def begin(self):
        """Start a step: fresh columns (every world puts its info before :meth:`table`)."""
        n = self.num_envs
        self.columns = [np.empty(n, dtype=dtype) for dtype in self.dtypes]

    def put(self, index, info):
        """Put world ``index``'s info dict (a reset's)."""
        for (key, sub), column in zip(self.keys, self.columns):
            column[index] = info[key] if sub is None else info[key][sub]

    def put_row(self, index, row):
        """Put world ``index``'s info as its values in ``keys`` order (DriveSim.finish_row)."""
        for column, value in zip(self.columns, row):
            column[index] = value

    def info(self, row):
        """Return the info dict of a row (for a reward_fn and final_info)."""
        out = {}
        for (key, sub), value in zip(self.keys, row):
            if sub is None:
                out[key] = value
            else:
                out.setdefault(key, {})[sub] = value
        return out

    def table(self):
        out = self._outer.copy()
        for key, template in self._inner.items():
            out[key] = template.copy()
        for (key, sub), column in zip(self.keys, self.columns):
            if sub is None:
                out[key] = column
            else:
                out[key][sub] = column
        return out


class DriveVectorEnv(VectorEnv):
    """
    N worlds of ``vehicle_sim/Drive-v0`` in this process.

    :param num_envs: number of worlds, >= 1.
    :param world: as DriveEnv (every world the same).
    :param scenario: as DriveEnv.
    :param render_mode: None or 'rgb_array' (``render()`` returns one picture per world).
    :param autoreset_mode: 'next_step' (default), 'same_step' or 'disabled' (AutoresetMode).
    :param reward_fn: as DriveEnv.
    :param options: the environment's options (gym/options.py).
    """

    metadata = {'render_modes': ['rgb_array'], 'autoreset_mode': AutoresetMode.NEXT_STEP}

    def __init__(self, num_envs=1, world=None, scenario=None, render_mode=None,
                 autoreset_mode=AutoresetMode.NEXT_STEP, reward_fn=None, **options):
        if isinstance(num_envs, bool) or not isinstance(num_envs, int) or num_envs < 1:
            raise ValueError(f'num_envs = {num_envs!r}: must be an integer >= 1')
        if render_mode not in (None, 'rgb_array'):
            raise ValueError(f"render_mode = {render_mode!r}: None or 'rgb_array' (the "
                             "window shows one world: use DriveEnv for 'human')")
        self.autoreset_mode = _autoreset_mode(autoreset_mode)
        self.metadata = dict(self.metadata, autoreset_mode=self.autoreset_mode)
        self.render_mode = render_mode
        self.reward_fn = reward_fn
        self.num_envs = num_envs
        self.sims = []
        try:
            for _ in range(num_envs):
                self.sims.append(DriveSim(world, scenario, options))
        except BaseException:
            self.close()
            raise
        first = self.sims[0]
        self.single_action_space = action_space(first.control)
        self.single_observation_space = observation_space(first.spaces)
        self.action_space = batch_space(self.single_action_space, num_envs)
        self.observation_space = batch_space(self.single_observation_space, num_envs)
        self._actions_shape = self.action_space.shape
        self._backwards = False      # the direction of the next step's first phase
        self._orders = (tuple(range(num_envs)), tuple(reversed(range(num_envs))))
        self._keys = list(first.spaces)
        self._obs = {key: np.zeros((num_envs,) + space.shape, dtype=space.dtype)
                     for key, space in self.single_observation_space.spaces.items()}
        self._rngs = [None] * num_envs
        self._ended = [False] * num_envs       # worlds whose episode ended (autoreset)
        self._images = None
        self._infos = None

    # ---------------------------------------------------------------- seeding
    def _seed(self, index, seed):
        generator, _ = gymnasium.utils.seeding.np_random(seed)
        self._rngs[index] = generator

    def _rng(self, index):
        if self._rngs[index] is None:
            self._seed(index, None)
        return self._rngs[index]

    def _put(self, index, obs):
        for key in self._keys:
            self._obs[key][index] = obs[key]

    def _observations(self):
        return {key: array.copy() for key, array in self._obs.items()}

    # ---------------------------------------------------------------- the API
    def reset(self, *, seed=None, options=None):
        """
        Reset worlds: all, or those of ``options['reset_mask']``.

        :param seed: None, an int (world i gets seed + i) or a list of one per world.
        """
        if seed is None:
            seeds = [None] * self.num_envs
        elif isinstance(seed, int):
            seeds = [seed + i for i in range(self.num_envs)]
        else:
            seeds = list(seed)
            if len(seeds) != self.num_envs:
                raise ValueError(f'{len(seeds)} seeds for {self.num_envs} worlds')
        mask = np.ones(self.num_envs, dtype=bool)
        if options and 'reset_mask' in options:
            mask = np.asarray(options['reset_mask'], dtype=bool)
            if mask.shape != (self.num_envs,):
                raise ValueError(f"options['reset_mask'] of shape {mask.shape}: expected "
                                 f'({self.num_envs},)')
        infos = []
        for i, sim in enumerate(self.sims):
            if not mask[i]:
                continue
            if seeds[i] is not None or self._rngs[i] is None:
                self._seed(i, seeds[i])
            obs, info = sim.reset(self._rngs[i])
            self._put(i, obs)
            self._ended[i] = False
            infos.append(info)
        if self._infos is None and infos:
            self._infos = _InfoTable(infos[0], self.num_envs)
        return self._observations(), _stack_infos(infos) if mask.all() else \
            self._masked(infos, mask)

    def _masked(self, infos, mask):
        stacked = _stack_infos(infos)
        out = {}
        for key, value in stacked.items():
            if key.startswith('_'):
                out[key] = mask.copy()
            elif isinstance(value, dict):
                out[key] = value
            else:
                full = np.zeros(self.num_envs, dtype=value.dtype)
                full[mask] = value
                out[key] = full
        return out

    def step(self, actions):
        """Step every world with its row of ``actions``; return the batched results."""
        actions = np.asarray(actions)
        if actions.shape != self._actions_shape:
            raise ValueError(f'actions of shape {actions.shape}: expected '
                             f'{self._actions_shape} (one row per world)')
        rewards = np.zeros(self.num_envs, dtype=np.float64)
        terminated = np.zeros(self.num_envs, dtype=bool)
        truncated = np.zeros(self.num_envs, dtype=bool)
        table = self._infos
        if table is None:
            raise RuntimeError('step() before reset(): call reset() first')
        table.begin()
        finals = {}
        mode = self.autoreset_mode
        sims, ended = self.sims, self._ended
        any_ended = True in ended
        if mode == AutoresetMode.DISABLED and any_ended:
            i = ended.index(True)
            raise RuntimeError(f'world {i} ended: reset it (reset_mask) before stepping '
                               "it again (autoreset_mode 'disabled')")
        # Every action checked before any world moves (a bad one changes nothing), then the
        # step's phases world after world (DriveSim.apply/advance/finish), each phase walking
        # the worlds the other way round from the one before: the worlds a phase ends with are
        # the ones whose data the processor's cache still holds when the next phase starts.
        order = self._orders[self._backwards]
        self._backwards = not self._backwards      # three phases: the next step turns round
        stepping = [i for i in order if not ended[i]] if any_ended else order
        checked = [sims[i].check(actions[i]) for i in stepping]
        for i, values in zip(stepping, checked):
            sims[i].apply(values)
        for i in reversed(stepping):
            sims[i].advance()
        reward_fn = self.reward_fn
        for i in order:
            sim = sims[i]
            if ended[i]:                  # NEXT_STEP: reset now, the action ignored
                obs, info = sim.reset(self._rng(i))
                ended[i] = False
                table.put(i, info)
            else:
                obs, term, trunc, reward, row = sim.finish_row()
                terminated[i], truncated[i] = term, trunc
                if reward_fn is not None:
                    reward = float(reward_fn(obs, actions[i], table.info(row)))
                rewards[i] = reward
                if (term or trunc) and mode == AutoresetMode.SAME_STEP:
                    finals[i] = (obs, table.info(row))
                    obs, info = sim.reset(self._rng(i))
                    table.put(i, info)
                else:
                    ended[i] = term or trunc
                    table.put_row(i, row)
            self._put(i, obs)
        stacked = table.table()
        if finals:
            mask = np.zeros(self.num_envs, dtype=bool)
            final_obs = np.empty(self.num_envs, dtype=object)
            final_info = np.empty(self.num_envs, dtype=object)
            for i, (obs, info) in finals.items():
                mask[i] = True
                final_obs[i], final_info[i] = obs, info
            stacked.update(final_obs=final_obs, _final_obs=mask, final_info=final_info,
                           _final_info=mask.copy())
        return self._observations(), rewards, terminated, truncated, stacked

    def render(self):
        """'rgb_array': a tuple of one chase-camera picture per world."""
        if self.render_mode != 'rgb_array':
            return None
        if self._images is None:
            from vehicle_sim.physics.chase_image import ChaseImage
            self._images = [ChaseImage(sim.world, sim.ego.body, sim.options['render_width'],
                                       sim.options['render_height']) for sim in self.sims]
        return tuple(image.render() for image in self._images)

    def close_extras(self, **kwargs):
        for sim in self.sims:
            sim.close()
