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

"""The shipped SUMO city (config/maps/city_sumo.net.xml) is what its script makes, as described."""

from pathlib import Path

import pytest
from script_helpers import load_script

sumolib = pytest.importorskip('sumolib', reason="needs the 'sumo' extra (sumolib)")
pytest.importorskip('sumo', reason="needs the 'sumo' extra (eclipse-sumo: netgenerate)")

REPO = Path(__file__).resolve().parent.parent
MAPS = REPO / 'config' / 'maps'


def _script():
    return load_script(MAPS / 'make_city_sumo.py')


def _without_date(text):
    # netgenerate's header names the time it ran; the rest is the network
    return [line for line in text.splitlines() if not line.startswith('<!-- generated on')]


def test_the_shipped_city_is_what_its_script_makes(tmp_path):
    output = tmp_path / 'city_sumo.net.xml'
    _script().make(output)
    assert (_without_date(output.read_text('utf-8'))
            == _without_date((MAPS / 'city_sumo.net.xml').read_text('utf-8')))


def test_the_city_is_a_signalised_4_by_4_grid_with_sidewalks_and_crossings():
    net = sumolib.net.readNet(str(MAPS / 'city_sumo.net.xml'), withInternal=True,
                              withPedestrianConnections=True, withPrograms=True)
    signals = net.getTrafficLights()
    assert sorted(tls.getID() for tls in signals) == sorted(
        f'{column}{row}' for column in 'ABCD' for row in range(4))
    assert net.getNode('A0').getCoord() == (60.0, 60.0)
    assert net.getNode('D3').getCoord() == (360.0, 360.0)
    edge = net.getEdge('A0B0')
    lanes = edge.getLanes()
    assert [lane.getID() for lane in lanes] == ['A0B0_0', 'A0B0_1', 'A0B0_2']
    assert lanes[0].allows('pedestrian') and not lanes[0].allows('passenger')
    assert [lane.allows('passenger') for lane in lanes[1:]] == [True, True]
    assert lanes[1].getSpeed() == pytest.approx(13.89)
    crossings = [e for e in net.getEdges() if e.getFunction() == 'crossing']
    # a crossing over each of the four arms of each of the 16 signalised junctions
    assert len(crossings) == 64
    programs = {tls.getID(): tls.getPrograms()['0'] for tls in signals}
    # netgenerate's static program: 90 s, green, green for the turns, yellow per axis
    assert {sum(p.duration for p in program.getPhases()) for program in programs.values()} == {90}
