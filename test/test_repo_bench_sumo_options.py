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
benchmarks/bench_sumo.py compares like with like: SUMO alone and the engine get the same options.

The co-simulation's cost is its time over SUMO alone's plus the empty world's; SUMO's options
(its warnings on or off: each warning written to the terminal and the error log) move SUMO's
step, so both sides must run SUMO with the same ones.
"""

from pathlib import Path

import pytest
from script_helpers import load_script

from vehicle_sim.physics.sumo_traffic import sumo_arguments

pytest.importorskip('sumolib', reason='the SUMO benchmark needs the sumo extra')


@pytest.fixture(scope='module')
def bench():
    return load_script('benchmarks/bench_sumo.py')


def _options(args, skip=('-n', '-r', '--seed', '--step-length', '--begin')):
    """Return sumo's options in ``args`` other than the network, routes, seed and times."""
    found, index = [], 0
    while index < len(args):
        if args[index] in skip:
            index += 2
            continue
        found.append(args[index])
        index += 1
    return found


def test_sumo_alone_and_the_co_simulation_run_sumo_with_the_same_options(bench, tmp_path):
    routes = (tmp_path / 'v.rou.xml', tmp_path / 'p.rou.xml')
    for path in routes:
        path.write_text('<routes/>\n')
    alone = bench.alone_arguments(*routes, seed=3)
    spec = bench._ego_world(tmp_path, routes, seed=3)
    engine = sumo_arguments(spec.traffic, str(bench.CITY), 3,
                            [str(path) for path in routes])
    # the session adds its error log and no step log (physics/sumo_session.py); alone has
    # no error log (nothing to read it) and no step log
    assert _options(alone) == ['--no-step-log', 'true', *bench.SUMO_OPTIONS]
    assert _options(engine) == list(bench.SUMO_OPTIONS)
    assert '--no-warnings' in bench.SUMO_OPTIONS
    assert alone[alone.index('-r') + 1] == engine[engine.index('-r') + 1] == ','.join(
        str(path) for path in routes)
    assert Path(alone[alone.index('-n') + 1]) == bench.CITY
