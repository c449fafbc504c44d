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
The radar against known geometry and motion (Webots' WbRadar rules; docs/sensors.md, "radar").

Targets are car-sized boxes (4.5 x 1.8 x 1.5 m) labelled ``car``, free bodies given a velocity
and read before any step: distance, radial speed and azimuth are then exact (to 1e-9 m, 1e-6
m/s, 1e-9 rad), and the received power follows Webots' radar equation written out here.
"""

import math

import pybullet
import pytest

from vehicle_sim.config import load_car, read_yaml, world_from_data, world_path
from vehicle_sim.core.sensors.labels import LABEL_IDS
from vehicle_sim.core.sensors.params import sensor_from_dict
from vehicle_sim.core.specs.errors import InvalidParameterError
from vehicle_sim.core.world.params import obstacle_from_dict
from vehicle_sim.physics import World
from vehicle_sim.physics.scene import build_scene
from vehicle_sim.physics.sensors import SensorSuite
from vehicle_sim.physics.simulated_car import SimulatedCar
from vehicle_sim.physics.traffic_kinematics import BODY, HEIGHT, LENGTH, VX, VZ, X, Z

CAR_SIZE = (4.5, 1.8, 1.5)
CAR_REFLECTIVITY = 0.5          # core/sensors/labels.py: car
MOUNT_Z_M = 0.75


class RadarScene:
    """Our car with a radar at its front, level with the targets' centres; no gravity."""

    def __init__(self, **radar):
        self.world = World(gravity=0.0)
        self.car = SimulatedCar(self.world, load_car('Car'), (0.0, 0.0, 0.0), name='ego')
        spec = sensor_from_dict(dict({'type': 'radar', 'name': 'radar',
                                      'pose': {'x': 2.0, 'z': MOUNT_Z_M}}, **radar), 'test')
        self.spec = spec
        self.suite = SensorSuite(self.world, self.car.body, [spec])
        self.origin = self.suite.sensors['radar'].mount.world_frame()[0]

    def add_car(self, name, x, y, velocity=(0.0, 0.0, 0.0)):
        """Add a free car-sized box centred level with the radar at (x, y) ahead of it."""
        spec = obstacle_from_dict({'name': name, 'shape': 'box', 'size': list(CAR_SIZE),
                                   'mass': 1000.0,
                                   'position': [x, y, float(self.origin[2])]}, 'test')
        body = self.world.add_obstacle(spec)
        labels = self.world.labels
        labels.set(body, 'car', labels.instance(name))
        pybullet.resetBaseVelocity(body, list(velocity), [0.0, 0.0, 0.0],
                                   physicsClientId=self.world.client_id)
        return body

    def targets(self):
        return self.suite.sample('radar').targets


@pytest.fixture
def scene():
    made = []

    def make(**radar):
        made.append(RadarScene(**radar))
        return made[-1]
    yield make
    for s in made:
        s.world.close()


def webots_power_dbm(distance_m, rcs_m2, gain_dbi=20.0, frequency_ghz=24.0, power_dbm=20.0):
    """Webots' radar equation (radar.md): Pt G^2 lambda^2 sigma / ((4 pi)^3 R^4), in dBm."""
    transmitted_w = 1e-3 * 10.0 ** (power_dbm / 10.0)
    gain = 10.0 ** (gain_dbi / 10.0)
    wavelength = 0.299792458 / frequency_ghz
    received_w = (transmitted_w * gain ** 2 * wavelength ** 2 * rcs_m2
                  / ((4.0 * math.pi) ** 3 * distance_m ** 4))
    return 10.0 * math.log10(received_w / 1e-3)


def test_a_car_ahead_closing_gives_one_target_with_its_distance_and_radial_speed(scene):
    s = scene()
    s.add_car('lead', 30.0, 0.0, velocity=(-10.0, 0.0, 0.0))
    targets = s.targets()
    assert len(targets) == 1
    target, = targets
    distance = 30.0 - float(s.origin[0])
    assert target.distance_m == pytest.approx(distance, abs=1e-9)
    assert target.speed_mps == pytest.approx(-10.0, abs=1e-6)      # closing: < 0 (Webots)
    assert target.azimuth_rad == pytest.approx(0.0, abs=1e-9)
    rcs = CAR_REFLECTIVITY * CAR_SIZE[1] * CAR_SIZE[2]
    assert target.received_power_dbm == pytest.approx(webots_power_dbm(distance, rcs),
                                                      abs=1e-9)
    assert target.label == LABEL_IDS['car']
    assert target.instance_id == s.world.labels.instance('lead')
    assert target.velocity_mps[0] == pytest.approx(-10.0, abs=1e-6)
    assert target.size_m == pytest.approx(CAR_SIZE)


def test_a_target_to_the_left_has_a_positive_azimuth_and_a_receding_one_a_positive_speed(scene):
    s = scene()
    s.add_car('left', 25.0, 5.0, velocity=(3.0, 0.0, 0.0))
    target, = s.targets()
    dx, dy = 25.0 - float(s.origin[0]), 5.0 - float(s.origin[1])
    assert target.azimuth_rad == pytest.approx(math.atan2(dy, dx), abs=1e-9)
    assert target.speed_mps == pytest.approx(3.0 * dx / math.hypot(dx, dy), abs=1e-6)


def test_below_the_minimum_absolute_radial_speed_a_target_is_absent(scene):
    slow = scene(min_absolute_radial_speed=12.0)
    slow.add_car('lead', 30.0, 0.0, velocity=(-10.0, 0.0, 0.0))
    assert slow.targets() == ()
    fast = scene(min_absolute_radial_speed=8.0)
    fast.add_car('lead', 30.0, 0.0, velocity=(-10.0, 0.0, 0.0))
    assert len(fast.targets()) == 1


def test_outside_the_radial_speed_window_a_target_is_absent(scene):
    s = scene(min_radial_speed=-5.0, max_radial_speed=5.0)
    s.add_car('fast', 30.0, 0.0, velocity=(-10.0, 0.0, 0.0))
    s.add_car('slow', 40.0, -1.0, velocity=(-2.0, 0.0, 0.0))
    targets = s.targets()
    assert [t.instance_id for t in targets] == [s.world.labels.instance('slow')]


def test_outside_the_cone_or_the_range_a_target_is_absent(scene):
    s = scene()      # horizontal fov 0.78 rad (+-22 deg), 1 .. 50 m
    s.add_car('beside', 15.0, 15.0)        # 45 deg to the left
    s.add_car('far', 60.0, 0.0)            # beyond 50 m + its half size
    s.add_car('ahead', 20.0, 0.0)
    assert [t.instance_id for t in s.targets()] == [s.world.labels.instance('ahead')]


def test_occlusion_hides_a_car_behind_another(scene):
    seeing = scene(occlusion=False)
    seeing.add_car('near', 15.0, 0.0)
    seeing.add_car('behind', 30.0, 0.0)
    assert len(seeing.targets()) == 2
    hiding = scene(occlusion=True)
    hiding.add_car('near', 15.0, 0.0)
    hiding.add_car('behind', 30.0, 0.0)
    hiding.add_car('aside', 30.0, 8.0)
    names = {hiding.world.labels.instance(n): n for n in ('near', 'behind', 'aside')}
    assert sorted(names[t.instance_id] for t in hiding.targets()) == ['aside', 'near']


def test_targets_within_a_cell_merge_weighted_by_power(scene):
    s = scene(cell_distance=1.0)
    s.add_car('a', 30.0, -1.0, velocity=(-4.0, 0.0, 0.0))
    s.add_car('b', 30.0, 1.0, velocity=(-2.0, 0.0, 0.0))
    s.add_car('c', 40.0, 0.0)
    targets = s.targets()
    assert len(targets) == 2
    merged = targets[0]
    # equal distances and cross-sections: equal powers, the plain means; power doubles (+3 dB)
    alone = scene()
    alone.add_car('a', 30.0, -1.0, velocity=(-4.0, 0.0, 0.0))
    single, = alone.targets()
    assert merged.distance_m == pytest.approx(single.distance_m, abs=1e-9)
    assert merged.azimuth_rad == pytest.approx(0.0, abs=1e-9)
    assert merged.received_power_dbm == pytest.approx(
        single.received_power_dbm + 10.0 * math.log10(2.0), abs=1e-9)
    other = scene()
    other.add_car('b', 30.0, 1.0, velocity=(-2.0, 0.0, 0.0))
    assert merged.speed_mps == pytest.approx(
        (single.speed_mps + other.targets()[0].speed_mps) / 2.0, abs=1e-9)


@pytest.mark.parametrize('field, value, message', [
    ('horizontal_fov', 7.0, "field 'horizontal_fov' = 7.0: must be > 0 and <= 6.28319"),
    ('vertical_fov', 0.0, "field 'vertical_fov' = 0.0: must be > 0"),
    ('min_range', 60.0, "field 'min_range' = 60.0: must be < max_range (50 m)"),
    ('min_radial_speed', 5.0, "field 'min_radial_speed' = 5.0: must be < max_radial_speed"),
    ('frequency', 0.0, "field 'frequency' = 0.0: must be > 0"),
    ('range_noise', -1.0, "field 'range_noise' = -1.0: must be >= 0"),
])
def test_bad_radar_fields_are_refused_naming_the_field(field, value, message):
    with pytest.raises(InvalidParameterError, match=message.replace('(', r'\(').replace(
            ')', r'\)')):
        sensor_from_dict({'type': 'radar', 'name': 'r', field: value}, 'w.yaml: radar')


def test_traffic_targets_are_where_bullet_has_the_boxes_with_their_speed_and_ids():
    # Built-in traffic on the highway: each target is at a traffic box's centre as Bullet has it
    # (between traffic updates), its radial speed the vehicle's speed along its heading, its
    # label car and its instance id the traffic object's (PredictedObjects).
    data = read_yaml(world_path('highway'))
    data['traffic'] = {'vehicles': 30, 'seed': 3}
    scene = build_scene(world_from_data(data, 'highway.yaml'))
    try:
        world = scene.world
        car = scene.vehicles['Car'].car
        spec = sensor_from_dict({'type': 'radar', 'name': 'radar', 'pose': {'x': 2.0, 'z': 0.6},
                                 'horizontal_fov': 6.283, 'vertical_fov': 0.6,
                                 'max_range': 150.0}, 'test')
        radar = SensorSuite(world, car.body, [spec]).sensors['radar']
        for _ in range(23):                 # between two traffic updates (every 10 steps)
            world.step()
        targets = radar.targets()
        assert len(targets) >= 3
        origin, rotation, _ = radar.mount.world_frame()
        world.sync_bodies()
        traffic = scene.parts['traffic']
        boxes = {body: pybullet.getBasePositionAndOrientation(
            body, physicsClientId=world.client_id)[0] for body in traffic.body_ids}
        speeds = {body: v.speed_mps
                  for v, body in zip(traffic.manager.vehicles, traffic.body_ids)}
        own = pybullet.getBaseVelocity(car.body.body_id, physicsClientId=world.client_id)[0]
        instances = {traffic.body_of(o.name): o.instance_id for o in traffic.objects()}
        for target in targets:
            centre = origin + rotation @ target.position_m
            body = min(boxes, key=lambda b: sum((p - c) ** 2 for p, c in zip(boxes[b], centre)))
            assert boxes[body] == pytest.approx(tuple(centre), abs=1e-6)
            _, orientation = pybullet.getBasePositionAndOrientation(
                body, physicsClientId=world.client_id)
            heading = 2.0 * math.atan2(orientation[2], orientation[3])
            speed = speeds[body]
            line = (centre - origin) / target.distance_m
            relative = (speed * math.cos(heading) - own[0], speed * math.sin(heading) - own[1])
            # the radar's own velocity at its mount differs from the body's by w x r (< 1 mm/s)
            assert target.speed_mps == pytest.approx(
                line[0] * relative[0] + line[1] * relative[1], abs=1e-3)
            # what it is: a car, its id the PredictedObjects object's (the instance id)
            assert target.label == LABEL_IDS['car']
            assert target.instance_id == instances[body]
    finally:
        scene.world.close()


def test_sumo_bodies_kinematics_are_where_bullet_has_them(tmp_path):
    # The traffic-body contract's kinematics() of SUMO's bodies (vehicles and persons): each
    # serving body once, at Bullet's pose between SUMO's steps, with its type's size.
    pytest.importorskip('libsumo', reason="needs the 'sumo' extra")
    from test_physics_sumo_city import city_net, DEMAND, EGO_LANE, EGO_S
    data = {'vehicles': [{'name': 'ego', 'model': 'Car', 'pose': {'lane': EGO_LANE, 's': EGO_S}}],
            'map': {'type': 'sumo', 'net': city_net(tmp_path)},
            'traffic': {'engine': 'sumo', 'demand': DEMAND, 'seed': 1}}
    scene = build_scene(world_from_data(data, 'city.yaml', base_dir=str(tmp_path)))
    try:
        bodies, world = scene.parts['traffic'], scene.world
        for _ in range(1503):              # between two SUMO steps (every 10 world steps)
            world.step()
        table, since = bodies.kinematics()
        world.sync_bodies()
        boxes = {body_id: size for _, body_id, size, _, _ in bodies.boxes()}
        assert sorted(table[:, BODY].astype(int).tolist()) == sorted(boxes)
        assert len(boxes) >= 6
        for row in table:
            body_id = int(row[BODY])
            position, _ = pybullet.getBasePositionAndOrientation(
                body_id, physicsClientId=world.client_id)
            assert tuple(row[X:Z + 1] + row[VX:VZ + 1] * since) == pytest.approx(position,
                                                                     abs=1e-6)
            length, width, height = row[LENGTH:HEIGHT + 1]
            size = boxes[body_id]
            assert height == pytest.approx(size[2])
            assert (length, width) == pytest.approx(size[:2]) or width == pytest.approx(size[0])
    finally:
        scene.world.close()
