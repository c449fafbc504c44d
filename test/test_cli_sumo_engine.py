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
``vehicle-sim run`` on a world whose SUMO fails while it runs: SUMO's words, the recording kept.

SUMO reads its routes ahead (``--route-steps 1``: a second ahead); a vehicle of the routes on
an edge the network lacks departs at 6 s, so SUMO fails when it reads it, about 3 s in. The
command ends with status 1 and one line: the world file, the simulated time and SUMO's
message; the recording it was making is a readable MCAP file up to then.
"""

import subprocess
import sys

from conftest import peer_env
import pytest

pytest.importorskip('traci', reason="needs the 'sumo' extra")
mcap_reader = pytest.importorskip('mcap.reader', reason="needs the 'record' extra")

from sumo_helpers import one_lane_grid_net  # noqa: E402

pytestmark = pytest.mark.transport

RUN_TIMEOUT_S = 120.0        # interpreter start, the map, 3 s simulated at 5x


def test_sumo_failing_mid_run_ends_the_command_with_its_words_and_a_readable_recording(
        tmp_path):
    one_lane_grid_net(tmp_path)
    (tmp_path / 'late.rou.xml').write_text(
        '<routes>\n  <vehicle id="a" depart="0"><route edges="A0A1"/></vehicle>\n'
        '  <vehicle id="b" depart="3"><route edges="A0A1"/></vehicle>\n'
        '  <vehicle id="late" depart="6"><route edges="A0A1 NOPE"/></vehicle>\n</routes>\n')
    world = tmp_path / 'late.yaml'
    world.write_text('vehicles:\n  - {name: ego, model: Car, pose: {x: 1.6, y: 30.0, yaw: 1.57}}\n'
                     'map: {type: sumo, net: grid.net.xml}\n'
                     "traffic: {engine: sumo, routes: late.rou.xml, options: ['--route-steps', "
                     "'1']}\n")
    recording = tmp_path / 'run.mcap'
    done = subprocess.run([sys.executable, '-m', 'vehicle_sim', 'run', '--no-status', '--world',
                           str(world), '--real-time-factor', '5', '--duration', '60',
                           '--record', str(recording)],
                          env=peer_env(), capture_output=True, text=True,
                          timeout=RUN_TIMEOUT_S)
    assert done.returncode == 1, done.stderr
    last = done.stderr.strip().splitlines()[-1]
    assert last == (f"vehicle-sim run: {world}: traffic: SUMO at t = 3.100 s: The edge 'NOPE' "
                    "within the route for vehicle 'late' is not known. The route can not be "
                    'build.')
    with open(recording, 'rb') as handle:
        times = [message.log_time for _, _, message in
                 mcap_reader.make_reader(handle).iter_messages(topics=['/clock'])]
    assert len(times) > 100
    assert (max(times) - min(times)) / 1e9 == pytest.approx(3.1, abs=0.2)
