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
A labelled lidar (``labels: true``): each point's label, instance id and intensity.

The intensity is the label's reflectivity (core/sensors/labels.py) times |cos| of the angle
between the ray and the surface normal: a flat panel turned by a known angle gives it ray by
ray; another car, a pedestrian, the ground and an occupancy map's walls read their labels and
instance ids from ``World.labels``; the PointCloud2 carries them as fields intensity, label and
instance, the LaserScan its intensities.
"""

import math

import numpy as np
import pytest

from vehicle_msgs_py import message_type, to_rosbags, typestore
from vehicle_sim.config import load_car, load_world, world_from_data
from vehicle_sim.core.map.grid_rays import GridRays
from vehicle_sim.core.sensors.labels import LABEL_IDS, LABELS
from vehicle_sim.core.sensors.params import sensor_as_dict
from vehicle_sim.core.sensors.sets import merge_sensors
from vehicle_sim.core.world.params import obstacle_from_dict
from vehicle_sim.physics import World
from vehicle_sim.physics.scene import build_scene, mount_suite
from vehicle_sim.physics.sensors import SensorSuite
from vehicle_sim.physics.simulated_car import SimulatedCar
from vehicle_sim.ros.messages import laser_scan_builder, point_cloud2_builder

PANEL_YAW = 0.5
LIDAR_Z = 1.5


def reflectivity(name):
    return LABELS[LABEL_IDS[name]].reflectivity


def mounted(world, sensors, name='ego', position=(0.0, 0.0, 0.0)):
    params = load_car('Car')
    car = SimulatedCar(world, params, position, name=name)
    specs = merge_sensors(params.sensor_set, sensors, 'test')
    return car, SensorSuite(world, car.body, specs, load_world('obstacle_course').origin)


@pytest.fixture
def world():
    made = World()
    yield made
    made.close()


def test_a_panel_at_a_known_angle_gives_reflectivity_times_the_cosine_per_ray(world):
    world.add_obstacle(obstacle_from_dict(
        {'name': 'panel', 'shape': 'box', 'size': [0.2, 20.0, 3.0], 'position': [8.0, 0.0, 1.5],
         'yaw': PANEL_YAW}, 'w.yaml'))
    _, suite = mounted(world, [{'name': 'lidar', 'type': 'lidar', 'fov': 0.6,
                                'horizontal_resolution': 31, 'labels': True,
                                'pose': {'x': 1.0, 'z': LIDAR_Z}}])
    scan = suite.sample('lidar')
    angles = scan.angle_min_rad + scan.angle_increment_rad * np.arange(31)
    assert np.all(np.isfinite(scan.scan))
    # the panel's face normal points along yaw + pi: the angle of incidence is a - yaw
    expected = reflectivity('obstacle') * np.abs(np.cos(angles - PANEL_YAW))
    assert scan.intensities.dtype == np.float32 and scan.intensities.shape == (1, 31)
    assert scan.intensities[0] == pytest.approx(expected, rel=1e-4)
    assert scan.intensities[0, 15] == pytest.approx(0.3 * math.cos(0.5), rel=1e-4)
    assert set(scan.labels[0].tolist()) == {LABEL_IDS['obstacle']}
    assert set(scan.instances[0].tolist()) == {world.labels.instance('panel')}


def test_a_plain_lidar_has_no_labels(world):
    _, suite = mounted(world, [{'name': 'lidar', 'type': 'lidar', 'fov': 0.6,
                                'horizontal_resolution': 31, 'pose': {'x': 1.0, 'z': LIDAR_Z}}])
    scan = suite.sample('lidar')
    assert scan.labels is None and scan.instances is None and scan.intensities is None


def test_a_car_a_pedestrian_and_the_ground_read_their_labels_and_instances(world):
    world.add_obstacle(obstacle_from_dict(
        {'name': 'walker', 'shape': 'cylinder', 'radius': 0.3, 'height': 1.8,
         'position': [8.0, 4.0, 0.9]}, 'w.yaml'), placed=True,
        label=('pedestrian', world.labels.instance('sumo person p0')))
    mounted(world, [], name='other', position=(12.0, -4.0, 0.0))
    _, suite = mounted(world, [{'name': 'lidar', 'type': 'lidar', 'fov': 6.28,
                                'horizontal_resolution': 720, 'layers': 16,
                                'vertical_fov': 0.5, 'labels': True,
                                'pose': {'x': 1.0, 'z': LIDAR_Z}}])
    for _ in range(50):
        world.step()
    cloud = suite.sample('lidar')
    labels, instances = cloud.labels, cloud.instances
    finite = np.isfinite(cloud.ranges_m)
    found = {(LABELS[label].name, int(instance))
             for label, instance in zip(labels[finite], instances[finite])}
    assert found == {('ground', 0), ('car', world.labels.instance('other')),
                     ('pedestrian', world.labels.instance('sumo person p0'))}
    assert np.all(labels[~finite] == 0) and np.all(instances[~finite] == 0)
    # not its own car ('ego'): the rays pass its body
    assert world.labels.instance('ego') not in instances
    # the ground: reflectivity times the sine of the ray's depression (flat ground)
    ground = (labels == LABEL_IDS['ground']) & finite
    directions = cloud.directions[ground]
    assert cloud.intensities[ground] == pytest.approx(
        reflectivity('ground') * np.abs(directions[:, 2]), abs=2e-3)
    points = cloud.points()[labels == LABEL_IDS['pedestrian']]
    assert np.hypot(points[:, 0] - 7.0, points[:, 1] - 4.0).max() < 0.35   # the lidar at x 1


def test_an_occupancy_maps_walls_read_wall_with_the_cells_face_normal(tmp_path):
    spec = load_world('race_track')
    lidar = dict(sensor_as_dict(spec.vehicles[0].sensors[0]), labels=True)
    spec = world_from_data({'vehicles': [{'name': 'Car', 'model': 'CitroenCZero',
                                          'sensors': [lidar]}],
                            'map': {'type': 'occupancy_grid',
                                    'file': str(load_world_map('race_track')),
                                    'wall_height': 1.0}}, str(tmp_path / 'w.yaml'))
    scene = build_scene(spec, mount=mount_suite)
    try:
        scan = scene.vehicles['Car'].sensors.sample('lidar')
    finally:
        scene.world.close()
    finite = np.isfinite(scan.scan)
    assert finite.sum() > 500
    assert set(scan.labels[0][finite].tolist()) == {LABEL_IDS['wall']}
    assert np.all(scan.instances == 0)
    intensity = scan.intensities[0][finite]
    assert 0.0 < intensity.min() and intensity.max() <= reflectivity('wall') + 1e-6


def load_world_map(name):
    from vehicle_sim.config import world_path
    return (world_path(name).parent / '..' / 'maps' / f'{name}.yaml').resolve()


def test_grid_normals_face_against_the_ray_on_the_face_it_met():
    walls = np.zeros((10, 10), dtype=bool)
    walls[:, 6] = True                          # a wall along y at x = 6 .. 7 cells
    rays = GridRays(walls, 0.5, (0.0, 0.0, 0.0), 1.0)
    origin = np.array([1.0, 2.5, 0.5])
    angles = np.array([-0.6, 0.0, 0.4])
    ends = origin + 10.0 * np.column_stack([np.cos(angles), np.sin(angles), 0.0 * angles])
    fractions = rays.cast(origin, ends)
    assert np.all(fractions < 1.0)
    normals = rays.normals(origin, ends, fractions)
    assert normals == pytest.approx(np.array([[-1.0, 0.0, 0.0]] * 3))
    # from above onto the walls' top
    down = rays.normals(np.array([3.25, 2.5, 3.0]), np.array([[3.25, 2.5, -1.0]]),
                        rays.cast(np.array([3.25, 2.5, 3.0]), np.array([[3.25, 2.5, -1.0]])))
    assert down.tolist() == [[0.0, 0.0, 1.0]]
    # a turned grid: its x axis along the frame's y (the wall at y 3 .. 3.5 m, x -5 .. 0 m)
    turned = GridRays(walls, 0.5, (0.0, 0.0, math.pi / 2), 1.0)
    origin = np.array([-2.5, 0.5, 0.5])
    ends = np.array([[-2.5, 10.0, 0.5]])
    fraction = turned.cast(origin, ends)
    assert fraction[0] * 9.5 == pytest.approx(2.5)
    assert turned.normals(origin, ends, fraction) == pytest.approx(np.array([[0.0, -1.0, 0.0]]))


def _labelled_reading(layers):
    from vehicle_sim.core.sensors.readings import LidarReading
    from vehicle_sim.physics.sensors.lidar import ray_directions
    directions = ray_directions([-0.1, 0.0, 0.1], [0.0] if layers == 1 else [0.1, -0.1])
    ranges = np.full((layers, 3), 5.0, dtype=np.float32)
    ranges[0, 0] = np.inf
    labels = np.full((layers, 3), LABEL_IDS['car'], dtype=np.uint8)
    labels[0, 0] = 0
    instances = np.full((layers, 3), 300, dtype=np.uint16)
    instances[0, 0] = 0
    intensities = np.full((layers, 3), 0.25, dtype=np.float32)
    intensities[0, 0] = 0.0
    return LidarReading('lidar', 1.0, -0.1, 0.1, 0.1, 0.1, 30.0, 0.1,
                        (0.0,) if layers == 1 else (0.1, -0.1), ranges, directions,
                        labels=labels, instances=instances, intensities=intensities)


def test_the_labelled_cloud_has_intensity_label_and_instance_fields():
    stamp = message_type('builtin_interfaces/msg/Time')(sec=1)
    reading = _labelled_reading(2)
    message = point_cloud2_builder(message_type, 'lidar')(stamp, reading)
    field = message_type('sensor_msgs/msg/PointField')
    assert [(f.name, f.offset, f.datatype, f.count) for f in message.fields] == [
        ('x', 0, field.FLOAT32, 1), ('y', 4, field.FLOAT32, 1), ('z', 8, field.FLOAT32, 1),
        ('intensity', 12, field.FLOAT32, 1), ('label', 16, field.UINT16, 1),
        ('instance', 18, field.UINT16, 1)]
    assert (message.point_step, message.row_step, message.height, message.width) == \
        (20, 60, 2, 3)
    data = bytes(message.data)
    assert bytes(typestore().serialize_cdr(to_rosbags(message), 'sensor_msgs/msg/PointCloud2')) \
        == message.serialize()
    points = np.frombuffer(data, dtype=np.dtype([('x', '<f4'), ('y', '<f4'), ('z', '<f4'),
                                                 ('intensity', '<f4'), ('label', '<u2'),
                                                 ('instance', '<u2')])).reshape(2, 3)
    assert np.isnan(points['x'][0, 0]) and points['label'][0, 0] == 0
    assert points['x'][1, 1] == pytest.approx(5.0 * math.cos(0.1), rel=1e-6)
    assert points['intensity'][1].tolist() == [0.25] * 3
    assert points['label'][1].tolist() == [LABEL_IDS['car']] * 3
    assert points['instance'][1].tolist() == [300] * 3
    scan = laser_scan_builder(message_type, 'lidar')(stamp, _labelled_reading(1))
    assert list(scan.intensities) == [0.0, 0.25, 0.25]


def test_docs_sensors_hold_the_label_table_and_the_lidar_key():
    from pathlib import Path

    from vehicle_sim.core.sensors.labels import labels_markdown
    text = (Path(__file__).resolve().parent.parent / 'docs' / 'sensors.md').read_text('utf-8')
    assert labels_markdown() in text
    assert 'intensity = reflectivity(label) × |cos θ|' in text
