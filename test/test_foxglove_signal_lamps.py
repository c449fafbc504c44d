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
The traffic lights in the Foxglove scene: ``signals/<group>`` in the colours the physics shows.

The world is lane_helpers.signal_crossing (groups 11 and 12, three bulbs each) with a stand-in
signals part; its entities are sent when a light changes, not at every update.
"""

from dataclasses import replace

from lane_helpers import BULB_Z, LIGHT_XY, signal_crossing, StandInSignals
import pytest

from vehicle_sim.config import world_from_data
from vehicle_sim.core.map.signal_lamps import DARK_LAMP_COLOR, HOUSING_COLOR, LAMP_COLORS
from vehicle_sim.foxglove import scene as fs
from vehicle_sim.foxglove.scene_stream import SceneStream
from vehicle_sim.physics.scene import build_scene
from vehicle_sim.physics.signal_lamps import SignalLampsPart


@pytest.fixture
def scene():
    spec = world_from_data({'vehicles': [{'name': 'car', 'model': 'Car',
                                          'pose': {'x': -10.0, 'y': 0.0}}]}, 'lamps.yaml')
    built = build_scene(replace(spec, lanes=signal_crossing()),
                        parts=(StandInSignals(), SignalLampsPart()))
    yield built
    built.world.close()


def _bulbs(entity):
    """Return {bulb z: RGBA} of a group's entity (its spheres)."""
    return {p.position_m[2]: p.color_rgba for p in entity.primitives if p.kind == 'sphere'}


def test_each_group_is_an_entity_of_housings_and_bulbs_in_its_state_colours(scene):
    scene.parts['signals'].controller.force(11, 'red')
    entities = {e.id: e for e in fs.scene_entities(scene, ['signals'])}
    assert sorted(entities) == ['signals/11', 'signals/12']
    light = entities['signals/11']
    assert [p.kind for p in light.primitives] == ['cube', 'sphere'] * 3
    assert {p.color_rgba for p in light.primitives if p.kind == 'cube'} == {HOUSING_COLOR}
    assert {p.position_m[:2] for p in light.primitives if p.kind == 'sphere'} == {LIGHT_XY}
    assert _bulbs(light) == {BULB_Z['red']: LAMP_COLORS['red'],
                             BULB_Z['yellow']: DARK_LAMP_COLOR,
                             BULB_Z['green']: DARK_LAMP_COLOR}
    assert _bulbs(entities['signals/12'])[BULB_Z['red']] == LAMP_COLORS['red']   # the plan's


def test_a_light_is_sent_when_it_changes_and_in_full_updates_only(scene):
    stream = SceneStream()
    first = stream.frame(scene, full=False)
    assert {'signals/11', 'signals/12'} <= {e.id for e in first.entities}
    assert not {'signals/11', 'signals/12'} & {e.id for e in stream.frame(scene, False).entities}
    scene.parts['signals'].controller.force(11, 'yellow')
    sent = [e for e in stream.frame(scene, full=False).entities if e.id.startswith('signals/')]
    assert [e.id for e in sent] == ['signals/11']
    assert _bulbs(sent[0])[BULB_Z['yellow']] == LAMP_COLORS['yellow']
    assert not [e for e in stream.frame(scene, False).entities if e.id.startswith('signals/')]
    full = stream.frame(scene, full=True)
    assert {'signals/11', 'signals/12'} <= {e.id for e in full.entities}
    assert full.deleted_ids == ()


def test_a_source_cannot_be_static_and_on_change(monkeypatch):
    monkeypatch.setattr(fs, 'ENTITY_SOURCES', dict(fs.ENTITY_SOURCES))
    with pytest.raises(ValueError, match="'x': static or on_change"):
        fs.register_entity_source('x', lambda scene: [], static=True, on_change=True)
    assert 'x' not in fs.ENTITY_SOURCES
