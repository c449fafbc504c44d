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
Wall time of a 60-case sweep: serial in this process, local workers (1, 2) and Ray (2 CPUs).

The cases are those of test/test_sweep_run.py (scenarios/stop_before_obstacle.yaml, 3 s each,
four time steps x three speed limits x five seeds). The baseline runs the same 60 scenarios one
after the other in this process with ``run_scenario`` (no sweep machinery); each sweep's
figure is its wall time and the ratio to that baseline, measured in the same run. Ray's figure
includes starting and stopping Ray.

Run: ``.venv/bin/python benchmarks/bench_sweep.py`` (about a minute on a 2-core machine).
"""

import os
import sys
import tempfile
import time

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.dirname(HERE))

SCENARIO = os.path.join(os.path.dirname(HERE), 'scenarios', 'stop_before_obstacle.yaml')
SETS = ['duration=3', 'time_step_ms=8,10,16,20', 'criteria.2.limit=5.5,6,7']
SEEDS = '0:5'


def serial_s():
    """Run the 60 variants one after the other in this process (output discarded)."""
    from vehicle_sim.scenarios.runner import run_scenario
    from vehicle_sim.sweep.run import plan
    planned = plan(SCENARIO, SETS, SEEDS)
    saved = os.dup(1)
    null = os.open(os.devnull, os.O_WRONLY)
    os.dup2(null, 1)
    try:
        start = time.monotonic()
        for case in planned.cases:
            run_scenario(planned.specs[case.case_id], seed=case.seed)
        return time.monotonic() - start
    finally:
        sys.stdout.flush()
        os.dup2(saved, 1)
        os.close(null)
        os.close(saved)


def sweep_s(**options):
    """Run the sweep into a fresh folder; return its wall time."""
    from vehicle_sim.sweep import run_sweep
    with tempfile.TemporaryDirectory() as out:
        start = time.monotonic()
        result = run_sweep(SCENARIO, SETS, SEEDS, out, plot=False, **options)
        elapsed = time.monotonic() - start
    assert result.done == 60 and result.count('error') == 0
    return elapsed


def main():
    print(f'load average {"/".join(f"{x:.1f}" for x in os.getloadavg())}, '
          f'{os.cpu_count()} CPUs')
    base = serial_s()
    print(f'{"60 cases serial in-process (baseline)":45} {base:6.2f} s')
    for label, options in (('local, 1 worker', {'workers': 1}),
                            ('local, 2 workers', {'workers': 2})):
        took = sweep_s(**options)
        print(f'{label:45} {took:6.2f} s  ({took / base:.2f}x baseline)')
    try:
        import ray  # noqa: F401
    except ImportError:
        print("ray: not installed (pip install 'vehicle_sim[ray]')")
    else:
        took = sweep_s(workers=2, backend='ray')
        print(f'{"ray, 2 CPUs (start and stop included)":45} {took:6.2f} s  '
              f'({took / base:.2f}x baseline)')
    print(f'load average {"/".join(f"{x:.1f}" for x in os.getloadavg())}')


if __name__ == '__main__':
    main()
