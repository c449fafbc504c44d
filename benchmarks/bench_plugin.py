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
The pytest plugin's view: one simulated minute stepped one basic step at a time.

A pytest test using the plugin's ``automobile_node`` fixture (default car, 10 ms, synchronous,
every topic each step) calls ``automobile_node.client.step()`` 6000 times, as a test that checks
something after every step would, and reports the wall time per step (issue 10 target:
<= 0.5 ms per step). It runs twice: with the client's default subscriptions (every
Float64Stamped topic and ``/clock``: 19 deliveries per step) and with the subset a
speed-conscious test names, ``vehicle_sim_topics = current_speed`` (``/clock`` and
``current_speed``: 2 deliveries per step). ``python benchmarks/bench_plugin.py [--steps N]``
runs that test in a child pytest (the installed package registers the plugin) and prints both
figures; ``pytest benchmarks/bench_plugin.py -s`` runs it directly (default subscriptions).
"""

import argparse
import json
import os
import subprocess
import sys
import tempfile
import time

from bench_common import process_cpu_s, use_free_domain

REPO_ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
TARGET_MS = 0.5
STEPS = 6000
# Where the test writes its figures when run by main() (JSON).
OUT_ENV = 'VEHICLE_SIM_BENCH_PLUGIN_OUT'
STEPS_ENV = 'VEHICLE_SIM_BENCH_PLUGIN_STEPS'
# The topics a speed-conscious test subscribes to (the client adds /clock).
SUBSET = ('current_speed',)


def test_one_simulated_minute_in_single_steps(automobile_node):
    car = automobile_node.client
    steps = int(os.environ.get(STEPS_ENV, STEPS))
    assert car.call('set_cruising_speed', 30.0).success
    car.step(10)
    start_s = car.sim_time()
    node_cpu0, own_cpu0 = process_cpu_s(automobile_node.process.pid), time.process_time()
    start = time.perf_counter()
    for _ in range(steps):
        car.step()
    wall = time.perf_counter() - start
    node_cpu = process_cpu_s(automobile_node.process.pid) - node_cpu0
    own_cpu = time.process_time() - own_cpu0
    end_s = car.sim_time()
    assert abs(end_s - start_s - steps * car.basic_time_step_ms / 1000.0) < 1e-6
    assert car.latest('current_speed').data > 0.0
    figures = {'steps': steps, 'wall_s': wall, 'ms_per_step': wall / steps * 1e3,
               'node_cpu_ms_per_step': node_cpu / steps * 1e3,
               'client_cpu_ms_per_step': own_cpu / steps * 1e3}
    print(f'\n{steps} single steps through automobile_node.client.step(): {wall:.2f} s, '
          f'{figures["ms_per_step"]:.3f} ms per step (target <= {TARGET_MS} ms); CPU per step: '
          f'node {figures["node_cpu_ms_per_step"]:.3f} ms, '
          f'test {figures["client_cpu_ms_per_step"]:.3f} ms')
    out = os.environ.get(OUT_ENV)
    if out:
        with open(out, 'w', encoding='utf-8') as stream:
            json.dump(figures, stream)


def figures(steps=STEPS, topics=None):
    """
    Run the test in a child pytest; return its figures ({'ms_per_step', ...}).

    :param topics: the client's topics (the ini option ``vehicle_sim_topics``); None: default.
    """
    with tempfile.TemporaryDirectory() as folder:
        out = os.path.join(folder, 'figures.json')
        env = dict(os.environ, **{OUT_ENV: out, STEPS_ENV: str(steps)})
        ini = ['-o', 'vehicle_sim_topics=' + ' '.join(topics)] if topics else []
        result = subprocess.run(
            [sys.executable, '-m', 'pytest', '-p', 'no:cacheprovider', '-q', '-s', *ini,
             os.path.abspath(__file__)],
            cwd=REPO_ROOT, env=env, capture_output=True, text=True, timeout=1200)
        if result.returncode != 0:
            raise RuntimeError('the plugin benchmark failed:\n'
                               f'{result.stdout[-3000:]}{result.stderr[-2000:]}')
        with open(out, encoding='utf-8') as stream:
            return json.load(stream)


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.split('\n\n')[0])
    parser.add_argument('--steps', type=int, default=STEPS)
    options = parser.parse_args(argv)
    use_free_domain()
    for label, topics in (('every Float64Stamped topic', None),
                          (f'topics={SUBSET}', SUBSET)):
        found = figures(options.steps, topics)
        print(f'{found["steps"]} single steps through automobile_node.client.step(), '
              f'{label}: {found["wall_s"]:.2f} s, {found["ms_per_step"]:.3f} ms per step '
              f'(target <= {TARGET_MS} ms); CPU per step: node '
              f'{found["node_cpu_ms_per_step"]:.3f} ms, '
              f'test {found["client_cpu_ms_per_step"]:.3f} ms')
    return 0


if __name__ == '__main__':
    sys.exit(main())
