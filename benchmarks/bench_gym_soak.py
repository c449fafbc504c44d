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
Memory of the Gymnasium environment over a long run (docs/gym.md, "Memory over long runs").

A soak: one ``vehicle_sim/Drive-v0`` (``gymnasium.make``) and one ``DriveVectorEnv`` of 4
worlds, each stepped 1,000,000 world steps (the vector env: 250,000 steps of its 4 worlds) on
``highway_traffic`` (the highway with 60 traffic cars), 10 ms steps, action_repeat 1, seeded
random actions, reset at every episode end; episodes are cut at 3 s (``max_episode_s``, 300
steps) so that resets come often (random actions crash the car sooner, also a reset). This
process's RSS (after ``gc.collect()``) is printed after a warm-up (the start), at 20 regular
checkpoints and at the end, with the growth per 1,000 steps: (end - start) / steps, and the
slope of a straight line through the checkpoints of the second half (a structure that grows
with steps or resets keeps its slope; memory that levels off has none). Target: growth
<= 1 KiB per 1,000 steps (10 MB over a 10 M-step training run).

``--lidar`` adds the 1080-ray lidar observation (``lidar: true``; slower: give ``--steps``).
``--diagnose`` prints at each checkpoint what grew since the start: the top tracemalloc lines
(allocations by source line), the object types of ``gc.get_objects()`` whose counts rose, and
each world's PyBullet bodies, constraints and user data (tracemalloc slows the run about 2x).

Run: ``.venv/bin/python benchmarks/bench_gym_soak.py [--quick] [--steps N] [--only single|vector]
[--lidar] [--diagnose]`` (``--quick``: 20,000 steps each).
"""

import argparse
import collections
import gc
import os
import sys
import time
import tracemalloc

from bench_record import rss_mib
import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.dirname(HERE))

WORLD = 'highway_traffic'
STEPS = 1_000_000
QUICK_STEPS = 20_000
WARMUP_STEPS = 5_000          # before the start's RSS: imports, caches, the first episodes
EPISODE_S = 3.0
VECTOR_ENVS = 4
CHECKPOINTS = 20
TARGET_KIB_PER_1000 = 1.0
SEED = 0


class _Single:
    """One Drive-v0 stepped with random actions, reset at each episode end."""

    def __init__(self, options):
        import gymnasium

        import vehicle_sim.gym  # noqa: F401  (registers Drive-v0)
        self.env = gymnasium.make('vehicle_sim/Drive-v0', world=WORLD, **options)
        self.worlds = 1
        self.resets = 0
        self.env.action_space.seed(SEED)
        self.env.reset(seed=SEED)

    def run(self, steps):
        """Step ``steps`` world steps."""
        env = self.env
        sample = env.action_space.sample
        for _ in range(steps):
            _, _, terminated, truncated, _ = env.step(sample())
            if terminated or truncated:
                env.reset()
                self.resets += 1

    def sims(self):
        return [self.env.unwrapped.sim]


class _Vector:
    """A DriveVectorEnv stepped with random actions (next_step autoreset)."""

    def __init__(self, options, num_envs=VECTOR_ENVS):
        from vehicle_sim.gym.vector_env import DriveVectorEnv
        self.env = DriveVectorEnv(num_envs, world=WORLD, **options)
        self.worlds = num_envs
        self.resets = 0
        self.env.action_space.seed(SEED)
        self.env.reset(seed=SEED)

    def run(self, steps):
        """Step ``steps`` world steps (steps / worlds vector steps)."""
        env = self.env
        sample = env.action_space.sample
        for _ in range(steps // self.worlds):
            _, _, terminated, truncated, _ = env.step(sample())
            self.resets += int(np.count_nonzero(terminated | truncated))

    def sims(self):
        return self.env.sims


def _pybullet_counts(sims):
    # (bodies, constraints, user data) summed over the worlds' physics clients
    import pybullet
    bodies = constraints = user_data = 0
    for sim in sims:
        cid = sim.world.client_id
        count = pybullet.getNumBodies(physicsClientId=cid)
        bodies += count
        constraints += pybullet.getNumConstraints(physicsClientId=cid)
        for index in range(count):
            body = pybullet.getBodyUniqueId(index, physicsClientId=cid)
            user_data += pybullet.getNumUserData(body, physicsClientId=cid)
    return bodies, constraints, user_data


def _type_counts():
    return collections.Counter(type(o).__qualname__ for o in gc.get_objects())


class _Diagnosis:
    """What grew since the start: tracemalloc lines, gc object types, PyBullet counts."""

    def __init__(self, runner):
        self.runner = runner
        self.snapshot = tracemalloc.take_snapshot()
        self.types = _type_counts()
        self.bullet = _pybullet_counts(runner.sims())

    def report(self, top=8):
        snapshot = tracemalloc.take_snapshot()
        lines = []
        for stat in snapshot.compare_to(self.snapshot, 'lineno')[:top]:
            if stat.size_diff <= 0:
                break
            frame = stat.traceback[0]
            lines.append(f'      {stat.size_diff / 1024:+9.1f} KiB {stat.count_diff:+7d} blocks  '
                         f'{frame.filename}:{frame.lineno}')
        types = _type_counts()
        grown = [(name, count - self.types.get(name, 0)) for name, count in types.items()
                 if count > self.types.get(name, 0)]
        grown.sort(key=lambda item: -item[1])
        lines.append('      objects: ' + (', '.join(f'{name} {diff:+d}' for name, diff in
                                                   grown[:top]) or 'no type grew'))
        lines.append('      pybullet bodies/constraints/user data: '
                     f'{self.bullet} -> {_pybullet_counts(self.runner.sims())}')
        return '\n'.join(lines)


def _slope_kib_per_1000(points):
    # least-squares slope of RSS [MiB] over steps, in KiB per 1000 steps
    if len(points) < 2:
        return float('nan')
    steps = np.array([p[0] for p in points], dtype=float)
    rss = np.array([p[1] for p in points])
    return float(np.polyfit(steps, rss, 1)[0]) * 1024.0 * 1000.0


def soak(kind, steps, options=None, checkpoints=CHECKPOINTS, warmup=WARMUP_STEPS,
         diagnose=False, out=print):
    """
    Run one soak; print its checkpoints through ``out``; return its figures.

    :param kind: 'single' or 'vector'.
    :return: {'start_mib', 'end_mib', 'kib_per_1000' (end - start over the steps),
        'late_kib_per_1000' (slope of the second half's checkpoints), 'points' [(steps, MiB)],
        'resets', 'steps', 'steps_per_s'}.
    """
    options = dict({'max_episode_s': EPISODE_S}, **(options or {}))
    if diagnose:
        tracemalloc.start()
    runner = (_Single if kind == 'single' else _Vector)(options)
    try:
        runner.run(warmup)
        gc.collect()
        start = rss_mib()
        diagnosis = _Diagnosis(runner) if diagnose else None
        out(f'{kind}: {runner.worlds} world(s), {WORLD}, episodes <= {options["max_episode_s"]:g}'
            f' s; RSS after {warmup} warm-up steps: {start:.1f} MiB', flush=True)
        points = [(0, start)]
        chunk = max(runner.worlds, steps // checkpoints // runner.worlds * runner.worlds)
        done = 0
        resets0 = runner.resets
        began = time.perf_counter()
        while done < steps:
            now = min(chunk, steps - done)
            runner.run(now)
            done += now
            gc.collect()
            points.append((done, rss_mib()))
            rate = done / (time.perf_counter() - began)
            out(f'  {done:>9d} steps  RSS {points[-1][1]:7.1f} MiB  '
                f'({(points[-1][1] - start) * 1024.0:+8.0f} KiB)  '
                f'resets {runner.resets - resets0:>6d}  {rate:5.0f} steps/s', flush=True)
            if diagnosis is not None:
                out(diagnosis.report(), flush=True)
        elapsed = time.perf_counter() - began
    finally:
        runner.env.close()
        if diagnose:
            tracemalloc.stop()
    end = points[-1][1]
    found = {'start_mib': start, 'end_mib': end, 'steps': done, 'points': points,
             'kib_per_1000': (end - start) * 1024.0 * 1000.0 / done,
             'late_kib_per_1000': _slope_kib_per_1000(points[len(points) // 2:]),
             'resets': runner.resets - resets0, 'steps_per_s': done / elapsed}
    out(f'  {kind}: RSS {start:.1f} -> {end:.1f} MiB over {done} steps and {found["resets"]} '
        f'resets: {found["kib_per_1000"]:+.2f} KiB per 1000 steps (second half\'s slope '
        f'{found["late_kib_per_1000"]:+.2f}; target <= {TARGET_KIB_PER_1000:g})', flush=True)
    return found


def figures(quick=False):
    """Return the rows of run_all.py (name, value, relation, target, unit)."""
    steps = QUICK_STEPS if quick else 100_000
    rows = []
    for kind in ('single', 'vector'):
        found = soak(kind, steps, checkpoints=10, out=lambda *a, **k: None)
        what = 'Drive-v0' if kind == 'single' else f'DriveVectorEnv({VECTOR_ENVS})'
        rows.append((f'gym soak, {what} on {WORLD}, {steps} steps with resets: RSS growth per '
                     '1000 steps', found['kib_per_1000'], '<=', TARGET_KIB_PER_1000, 'KiB'))
        rows.append((f'  same, RSS at the start ({found["start_mib"]:.0f} MiB) -> the end',
                     found['end_mib'], None, None, 'MiB'))
    return rows


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.strip().splitlines()[0])
    parser.add_argument('--quick', action='store_true', help=f'{QUICK_STEPS} steps each')
    parser.add_argument('--steps', type=int, default=None,
                        help=f'world steps of each soak (default {STEPS})')
    parser.add_argument('--only', choices=('single', 'vector'), default=None,
                        help='one of the two soaks')
    parser.add_argument('--lidar', action='store_true', help='the 1080-ray lidar observation')
    parser.add_argument('--diagnose', action='store_true',
                        help='what grew at each checkpoint (tracemalloc, gc, PyBullet)')
    options = parser.parse_args(argv)
    steps = options.steps or (QUICK_STEPS if options.quick else STEPS)
    env_options = {'lidar': True} if options.lidar else {}
    results = {}
    for kind in (options.only,) if options.only else ('single', 'vector'):
        results[kind] = soak(kind, steps, env_options, diagnose=options.diagnose)
    print()
    for kind, found in results.items():
        print(f'{kind:<6}: RSS {found["start_mib"]:.1f} MiB at the start, {found["end_mib"]:.1f} '
              f'MiB after {found["steps"]} steps ({found["resets"]} resets, '
              f'{found["steps_per_s"]:.0f} steps/s): {found["kib_per_1000"]:+.2f} KiB per 1000 '
              f'steps, second half {found["late_kib_per_1000"]:+.2f} (target <= '
              f'{TARGET_KIB_PER_1000:g})')
    print(f'load {"/".join(f"{x:.1f}" for x in os.getloadavg())}')


if __name__ == '__main__':
    main()
