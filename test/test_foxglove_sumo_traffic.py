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
The live view's scene of SUMO's traffic: a vehicle a box, a pedestrian an upright cylinder.

On the signalised SUMO city of test/test_physics_sumo_city.py after 30 s: every SUMO body on the
map is an entity ``traffic/sumo_<k>`` where the physics has it; a SUMO vehicle a cube of its
type's length, width and height (less the clearance under it), a person a cylinder of its
width across and its height, as its body in the physics (what the cameras and lidars see); a
body parked (its vehicle arrived) leaves the view.
"""

import pybullet
import pytest

pytest.importorskip('libsumo', reason="needs the 'sumo' extra")

from test_physics_sumo_city import city_net, DEMAND, EGO_LANE, EGO_S  # noqa: E402

from vehicle_sim.config import world_from_data  # noqa: E402
from vehicle_sim.foxglove.scene_stream import SceneStream  # noqa: E402
from vehicle_sim.physics.scene import build_scene  # noqa: E402


def test_sumo_vehicles_are_cubes_and_pedestrians_cylinders_as_their_bodies(tmp_path):
    data = {'vehicles': [{'name': 'ego', 'model': 'Car', 'pose': {'lane': EGO_LANE, 's': EGO_S}}],
            'map': {'type': 'sumo', 'net': city_net(tmp_path)},
            'traffic': {'engine': 'sumo', 'demand': DEMAND, 'seed': 1}}
    scene = build_scene(world_from_data(data, 'city.yaml', base_dir=str(tmp_path)))
    try:
        bodies, world, stream = scene.parts['traffic'], scene.world, SceneStream()
        api, cid = bodies.session.api, world.client_id
        for _ in range(3000):
            world.step()
        entities = {e.id: e for e in stream.frame(scene, full=False).entities
                    if e.id.startswith('traffic/')}
        names = {o.name for o in bodies.objects()}
        assert sorted(entities) == sorted(f'traffic/{name}' for name in names)
        kinds = []
        for name in names:
            primitive, = entities[f'traffic/{name}'].primitives
            body_id, sumo_id = bodies.body_of(name), bodies.sumo_id(name)
            (position, orientation), *_ = world.body_state(body_id)
            assert primitive.position_m == pytest.approx(position)
            assert primitive.orientation == pytest.approx(orientation)
            visual, = pybullet.getVisualShapeData(body_id, physicsClientId=cid)
            person = sumo_id in api.person.getIDList()
            kind = (api.person if person else api.vehicle).getTypeID(sumo_id)
            length, width = api.vehicletype.getLength(kind), api.vehicletype.getWidth(kind)
            height = api.vehicletype.getHeight(kind)
            if person:
                assert primitive.kind == 'cylinder' and visual[2] == pybullet.GEOM_CYLINDER
                assert primitive.size_m == pytest.approx((width, width, height))
                assert visual[3][:2] == pytest.approx((height, 0.5 * width))  # length, radius
            else:
                assert primitive.kind == 'cube' and visual[2] == pybullet.GEOM_BOX
                assert primitive.size_m[:2] == pytest.approx((length, width))
                assert primitive.size_m == pytest.approx(visual[3])
            kinds.append(primitive.kind)
        assert kinds.count('cylinder') >= 3 and kinds.count('cube') >= 3
        # bodies parked (their vehicles arrived, no new one of their size yet) leave the view
        before = set(names)
        for _ in range(60):
            for _ in range(100):
                world.step()
            frame = stream.frame(scene, full=False)
            now = {o.name for o in bodies.objects()}
            assert set(frame.deleted_ids) == {f'traffic/{name}' for name in before - now}
            if before - now:
                break
            before = now
        assert before - now
    finally:
        scene.world.close()
