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
A camera's segmentation and recognition against a composed scene (docs/sensors.md).

The scene: a car at the origin with a camera 1.5 m ahead of base_link, 1.3 m up, looking along
+x; in front of it a strip of road with a lane marking, a car, a pedestrian, a traffic light
pole and, at the end, a wall. Each body is where the projection of the camera's intrinsics puts
it, so the label of the pixel at its projected centre is known.
"""

import copy
import math
import os
from pathlib import Path
import subprocess
import sys

from conftest import peer_env
import numpy as np
import pytest

import vehicle_msgs_py
from vehicle_sim.config import load_car, read_yaml, world_from_data, world_path
from vehicle_sim.core.sensors.labels import LABEL_IDS, labels_markdown
from vehicle_sim.core.sensors.params import sensor_from_dict
from vehicle_sim.core.sensors.sets import merge_sensors
from vehicle_sim.core.specs.errors import InvalidParameterError
from vehicle_sim.physics import World
from vehicle_sim.physics.body_labels import instance_uuid
from vehicle_sim.physics.scene import build_scene, mount_suite
from vehicle_sim.physics.sensors import SensorSuite
from vehicle_sim.physics.simulated_car import SimulatedCar
from vehicle_sim.ros.traffic_messages import predicted_objects_builder

CAMERA = {'name': 'camera', 'pose': {'x': 1.5, 'z': 1.3}, 'width': 320, 'height': 240,
          'fov': 1.2, 'far': 200.0, 'segmentation': True, 'recognition': True}
# name: (label, obstacle entry); an object label gets an instance id, stuff (road, marking,
# wall) none
SCENE = {
    'road': ('road', {'shape': 'box', 'size': [39.0, 7.0, 0.02], 'position': [24.5, 0.0, 0.01]}),
    'marking': ('lane_marking', {'shape': 'box', 'size': [39.0, 0.3, 0.01],
                                 'position': [24.5, -1.5, 0.025]}),
    'car_ahead': ('car', {'shape': 'box', 'size': [4.0, 1.8, 1.5],
                          'position': [16.0, 1.5, 0.9]}),
    'walker': ('pedestrian', {'shape': 'cylinder', 'radius': 0.3, 'height': 1.8,
                              'position': [12.0, -2.8, 0.9]}),
    'signal': ('traffic_light', {'shape': 'box', 'size': [0.3, 0.3, 4.0],
                                 'position': [25.0, -4.5, 2.0]}),
    'wall': ('wall', {'shape': 'box', 'size': [1.0, 40.0, 8.0], 'position': [45.0, 0.0, 4.0]}),
}
OBJECTS = ('car_ahead', 'walker', 'signal')


class Scene:
    """A world with the car, its camera and the given labelled boxes."""

    def __init__(self, bodies, camera=None):
        data = {'vehicles': [{'name': 'ego'}],
                'obstacles': [dict(entry, name=name) for name, (_, entry) in bodies.items()]}
        spec = world_from_data(data, 'test')
        self.world = World()
        self.body_ids = {}
        for obstacle in spec.obstacles:
            body = self.body_ids[obstacle.name] = self.world.add_obstacle(obstacle)
            label = bodies[obstacle.name][0]
            stuff = label in ('road', 'lane_marking', 'wall')
            self.world.labels.set(body, label,
                                  0 if stuff else self.world.labels.instance(obstacle.name))
        params = load_car('Car')
        self.car = SimulatedCar(self.world, params, (0.0, 0.0, 0.0), name='ego')
        specs = merge_sensors(params.sensor_set, [dict(CAMERA, **(camera or {}))], 'test')
        self.suite = SensorSuite(self.world, self.car.body, specs)
        self.spec = self.suite.specs['camera']
        self.world.step()

    def sample(self):
        return self.suite.sample('camera')

    def project(self, point):
        """Return the pixel (u, v) of a world point (the camera's pinhole model)."""
        position, rotation, _ = self.suite.sensors['camera'].mount.world_frame()
        x, y, z = rotation.T @ (np.asarray(point, dtype=float) - position)
        fx, fy, cx, cy = self.spec.intrinsics
        return cx - fx * y / x, cy - fy * z / x

    def instance(self, name):
        return self.world.labels.instance(name)

    def close(self):
        self.world.close()


@pytest.fixture
def scene():
    made = []

    def make(*args, **kwargs):
        made.append(Scene(*args, **kwargs))
        return made[-1]
    yield make
    for one in made:
        one.close()


def _centre(entry):
    return entry['position']


def test_each_class_of_the_label_table_is_where_the_scene_puts_it(scene):
    view = scene(SCENE)
    reading = view.sample()
    assert reading.semantic.shape == reading.instance.shape == (240, 320)
    assert reading.semantic.dtype == np.uint8 and reading.instance.dtype == np.uint16
    points = {name: _centre(entry) for name, (_, entry) in SCENE.items()}
    points['road'] = (10.0, 1.0, 0.02)          # the road between the marking and the car
    points['marking'] = (10.0, -1.5, 0.03)
    points['wall'] = (44.5, 0.0, 6.0)           # above the car ahead
    for name, point in points.items():
        u, v = view.project(point)
        label = SCENE[name][0]
        assert reading.semantic[round(v), round(u)] == LABEL_IDS[label], name
        expected = view.instance(name) if name in OBJECTS else 0
        assert reading.instance[round(v), round(u)] == expected, name
    # the sky above the wall is nothing, the ground beside the road is ground
    assert reading.semantic[0, 160] == LABEL_IDS['none'] and reading.instance[0, 160] == 0
    u, v = view.project((12.0, 5.0, 0.0))
    assert reading.semantic[round(v), round(u)] == LABEL_IDS['ground']


def test_the_cameras_own_car_is_ego_and_no_object(scene):
    # mounted 1 m up over the front axle, the camera sees its own front wheels left and right
    reading = scene(SCENE, {'pose': {'x': 1.5, 'z': 1.0}}).sample()
    ego = reading.semantic == LABEL_IDS['ego']
    assert ego[180, 70] and ego[180, 240] and not ego[180, 160]
    assert (reading.instance[ego] == 0).all()
    assert all(o.model != 'ego' for o in reading.objects)


def test_recognition_finds_the_visible_objects_with_their_pose_size_and_image_box(scene):
    view = scene(SCENE)
    reading = view.sample()
    found = {o.id: o for o in reading.objects}
    assert sorted(found) == sorted(view.instance(name) for name in OBJECTS)
    car = found[view.instance('car_ahead')]
    assert (car.model, car.label) == ('car', LABEL_IDS['car'])
    # its box centre in the camera frame (x forward, y left, z up): the camera is 1.5 m ahead
    # of base_link and 1.3 m above it
    position, rotation, _ = view.suite.sensors['camera'].mount.world_frame()
    expected = rotation.T @ (np.array([16.0, 1.5, 0.9]) - position)
    assert car.position_m == pytest.approx(tuple(expected), abs=1e-6)
    assert car.dimensions_m == pytest.approx((4.0, 1.8, 1.5))
    assert car.size_m == pytest.approx((1.8, 1.5), abs=0.02)      # across the view, upwards
    assert car.colour == pytest.approx((0.0, 0.0, 142 / 255))
    # the image box: the mask's pixels of that id, and where the near face's corners project
    rows, cols = np.nonzero(reading.instance == car.id)
    assert car.box_px == (cols.min(), rows.min(), cols.max(), rows.max())
    assert car.pixels == rows.size
    # unhidden, a box's image is the hull of its projected corners (to the rasteriser's
    # coverage of the edge pixels)
    corners = np.array([view.project((x, y, z)) for x in (14.0, 18.0) for y in (0.6, 2.4)
                        for z in (0.15, 1.65)])
    assert car.box_px == pytest.approx((*corners.min(axis=0), *corners.max(axis=0)), abs=1.5)
    assert car.size_on_image == (car.box_px[2] - car.box_px[0] + 1,
                                 car.box_px[3] - car.box_px[1] + 1)
    walker = found[view.instance('walker')]
    assert walker.model == 'pedestrian' and walker.dimensions_m == pytest.approx((0.6, 0.6, 1.8))


def test_a_box_half_hidden_behind_another_gets_the_image_box_of_its_visible_part(scene):
    # the front box covers the left half of the back one (y from 0 to 2 of the back one's
    # -2..2): the back box's image box starts where the front one's right edge is
    bodies = {'front': ('car', {'shape': 'box', 'size': [1.0, 3.0, 3.0],
                                'position': [10.0, 1.5, 1.5]}),
              'back': ('car', {'shape': 'box', 'size': [1.0, 4.0, 2.0],
                               'position': [20.0, 0.0, 1.0]})}
    view = scene(bodies)
    reading = view.sample()
    back = next(o for o in reading.objects if o.id == view.instance('back'))
    front_right, _ = view.project((9.5, 0.0, 1.5))       # the front box's right edge
    back_right, back_bottom = view.project((19.5, -2.0, 0.0))
    back_left, back_top = view.project((19.5, 2.0, 2.0))  # hidden: the full box's left edge
    u_min, v_min, u_max, v_max = back.box_px
    front_cols = np.nonzero(reading.instance == view.instance('front'))[1]
    assert u_min == front_cols.max() + 1                   # the first column the front leaves
    assert u_min == pytest.approx(front_right, abs=2.0)
    assert u_min > back_left + 20                          # not the whole box
    assert (u_max, v_min) == pytest.approx((back_right, back_top), abs=1.0)
    # the bottom edge hides under the camera's own car or reaches the ground line
    assert v_max <= back_bottom + 1.0
    hidden = reading.instance[round(back_top) + 2:round(back_bottom) - 2,
                              round(back_left) + 2:round(front_right) - 2]
    assert (hidden == view.instance('front')).all()
    assert back.pixels == np.count_nonzero(reading.instance == back.id)


def test_recognition_keeps_its_classes_range_pixels_and_the_biggest_objects(scene):
    only_people = scene(SCENE, {'recognition_classes': ['pedestrian']}).sample()
    assert [o.model for o in only_people.objects] == ['pedestrian']
    near = scene(SCENE, {'recognition_max_range': 16.0}).sample()
    # from the camera, the walker's centre is 11.0 m away, the car's 14.6 m, the signal's 24.0 m
    assert sorted(o.model for o in near.objects) == ['car', 'pedestrian']
    everything = scene(SCENE).sample()
    pixels = {o.model: o.pixels for o in everything.objects}
    biggest = scene(SCENE, {'recognition_max_objects': 1}).sample()
    assert [o.model for o in biggest.objects] == [max(pixels, key=pixels.get)]
    few = min(pixels.values())
    fewest = scene(SCENE, {'recognition_min_pixels': few + 1}).sample()
    assert len(fewest.objects) == 2
    assert scene(SCENE, {'recognition_max_objects': 0}).sample().objects == ()


def test_a_colour_only_camera_has_no_segmentation_and_segmentation_alone_no_objects(scene):
    plain = scene(SCENE, {'segmentation': False, 'recognition': False}).sample()
    assert plain.semantic is None and plain.instance is None and plain.objects is None
    images = scene(SCENE, {'recognition': False}).sample()
    assert images.semantic is not None and images.objects is None
    objects = scene(SCENE, {'segmentation': False}).sample()
    assert len(objects.objects) == 3


@pytest.mark.parametrize('key, value, fragment', [
    ('recognition_classes', ['car', 'tree'], "field 'recognition_classes' = ['car', 'tree']: "
                                             "a class: 'tree' is not a label"),
    ('recognition_classes', [], "field 'recognition_classes' = []"),
    ('recognition_max_objects', -2, "field 'recognition_max_objects' = -2: must be >= -1"),
    ('recognition_min_pixels', 0, "field 'recognition_min_pixels' = 0: must be >= 1"),
    ('recognition_max_range', 0.0, "field 'recognition_max_range' = 0.0: must be > 0"),
    ('segmentation', 'yes', "field 'segmentation' = 'yes'"),
])
def test_bad_recognition_keys_are_refused_naming_the_field(key, value, fragment):
    with pytest.raises(InvalidParameterError, match='w.yaml: cam: ' + _escaped(fragment)):
        sensor_from_dict({'type': 'camera', 'name': 'c', key: value}, 'w.yaml: cam')


def test_the_installed_command_refuses_an_unknown_class_at_start_naming_file_and_field(
        tmp_path):
    path = tmp_path / 'bad_classes.yaml'
    path.write_text('vehicles: [{name: Car, sensors: [{type: camera, name: cam, recognition: '
                    'true, recognition_classes: [car, tree]}]}]\n')
    command = os.path.join(os.path.dirname(sys.executable), 'vehicle-sim')
    done = subprocess.run([command, 'run', '--no-status', '--duration', '0', '--', '--ros-args',
                           '-r', '__ns:=/bad_classes', '-p', f'world:={path}'], env=peer_env(),
                          capture_output=True, text=True, timeout=120.0)
    assert done.returncode != 0
    assert (f"{path}: vehicles[0].sensors[0]: field 'recognition_classes' = ['car', 'tree']: "
            "a class: 'tree' is not a label") in done.stderr


def _escaped(text):
    return ''.join('\\' + c if c in '[]().*+?' else c for c in text)


def test_the_recognition_topics_follow_the_camera_topic():
    spec = sensor_from_dict({'type': 'camera', 'name': 'front', 'topic': 'front_cam',
                             'segmentation': True, 'recognition': True}, 'w.yaml')
    assert spec.topics == ('front_cam/image_raw', 'front_cam/camera_info',
                           'front_cam/semantic/image_raw', 'front_cam/instance/image_raw',
                           'front_cam/detections', 'front_cam/labels')
    assert math.isclose(spec.recognition_max_range_m, 100.0)


def test_the_sensors_doc_shows_the_label_table():
    text = (Path(__file__).resolve().parent.parent / 'docs' / 'sensors.md').read_text(
        encoding='utf-8')
    assert labels_markdown() in text


# ------------------------------------------------------------------- a world's own labelling

HIGHWAY = read_yaml(world_path('highway'))
MIDDLE = 100002             # the ego's lane: y = -5.625 m, along +x; lanes 3.75 m wide
LANE_WIDTH_M = 3.75


def _highway_scene(x=20.0):
    data = copy.deepcopy(HIGHWAY)
    camera = dict(CAMERA, type='camera', width=160, height=120)
    data['vehicles'][0].update(model='Car', sensors=[camera],
                               pose={'x': x, 'y': -5.625, 'yaw': 0.0})
    data['traffic'] = {'update_period': 0.01, 'placed': [
        {'model': 'ToyotaPrius', 'lanelet': MIDDLE, 's': 40.0, 'speed': 0.0,
         'route': [100102]}]}
    return build_scene(world_from_data(data, 'highway_test.yaml'), mount=mount_suite)


def _ground_point(sensor, spec, u, v):
    # where the ray through pixel (u, v) meets the plane z = 0
    position, rotation, _ = sensor.mount.world_frame()
    fx, fy, cx, cy = spec.intrinsics
    ray = rotation @ np.array([1.0, -(u - cx) / fx, -(v - cy) / fy])
    return position - ray * position[2] / ray[2]


def test_a_highway_reads_road_markings_and_a_traffic_car_with_its_predicted_objects_id():
    scene = _highway_scene()
    try:
        traffic = scene.parts['traffic']
        traffic.manager.stop(0)
        for _ in range(20):
            scene.world.step()
        suite = scene.vehicles['Car'].sensors
        sensor, spec = suite.sensors['camera'], suite.specs['camera']
        reading = suite.sample('camera')
        semantic = reading.semantic
        # the traffic car, recognised under the id its PredictedObjects entry carries
        (car,) = reading.objects
        (traffic_car,) = traffic.objects()
        assert car.model == 'car' and car.id == traffic_car.instance_id > 0
        message = predicted_objects_builder(vehicle_msgs_py.message_type, 'map')(
            None, traffic.objects())
        (predicted,) = message.objects
        assert bytes(predicted.object_id.uuid) == instance_uuid(car.id)
        u, v = car.position_on_image
        assert reading.instance[v, u] == car.id and semantic[v, u] == LABEL_IDS['car']
        # below the car, the ego's lane is road; every marking pixel lies on a lane boundary
        # (y a multiple of the lane width), on the ground
        assert semantic[v + 8, u] == LABEL_IDS['road']
        rows, cols = np.nonzero(semantic == LABEL_IDS['lane_marking'])
        assert rows.size > 20
        for row, col in zip(rows, cols):
            _, y, _ = _ground_point(sensor, spec, col, row)
            assert abs(y / LANE_WIDTH_M - round(y / LANE_WIDTH_M)) * LANE_WIDTH_M < 0.35, y
    finally:
        scene.world.close()
