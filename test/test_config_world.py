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
World files and sensor configuration: the issue's world parses; bad entries are refused.

Every refusal must name the file and the field (and change nothing: parsing is pure).
"""

import math
from pathlib import Path
import re

import pytest
import yaml

from vehicle_sim.config import load_car, load_robot, load_world, parse_world, world_from_data
from vehicle_sim.core.car.params import car_params_from_dict, DEFAULT_CAR
from vehicle_sim.core.diffdrive.params import DEFAULT_ROBOT
from vehicle_sim.core.geometry.frames import Pose
from vehicle_sim.core.sensors.camera_spec import CameraSpec
from vehicle_sim.core.sensors.lidar_spec import LidarSpec
from vehicle_sim.core.sensors.params import sensor_from_dict, SENSOR_TYPES, sensors_markdown
from vehicle_sim.core.sensors.sets import enable_sensors, merge_sensors, mounted, static_transforms
from vehicle_sim.core.specs.errors import InvalidParameterError
from vehicle_sim.core.specs.param_spec import parameter_table_markdown
from vehicle_sim.core.world.params import obstacles_markdown, ORIGIN_SPECS, VEHICLE_SPECS
from vehicle_sim.physics import diff_robot
from vehicle_sim.ros import sim_params

# The exact form of issue 8 ("Sensors and a world to drive in").
ISSUE_WORLD = """
origin: {latitude: 48.0, longitude: 11.0, altitude: 500.0}
vehicles:
  - name: Car
    namespace: ''
    pose: {x: 0.0, y: 0.0, yaw: 0.0}
    sensors:
      - {type: lidar, name: lidar, pose: {x: 1.0, y: 0.0, z: 1.5}, fov: 3.14159, horizontal_resolution: 181,
         min_range: 0.1, max_range: 50.0, rate_hz: 10.0}
      - {type: imu, name: imu, pose: {x: 0.0, y: 0.0, z: 0.5}, rate_hz: 100.0}
      - {type: gnss, name: gnss, pose: {x: 0.0, y: 0.0, z: 1.5}, rate_hz: 10.0}
      - {type: camera, name: camera, pose: {x: 1.5, y: 0.0, z: 1.3}, width: 160, height: 120, fov: 1.0, rate_hz: 5.0}
obstacles:
  - {name: wall, shape: box, size: [1.0, 6.0, 2.0], position: [20.0, 0.0, 1.0], yaw: 0.0}
  - {name: pole, shape: cylinder, radius: 0.2, height: 2.0, position: [10.0, 5.0, 1.0]}
"""  # noqa: E501 (the issue's lines, verbatim)


def _world(text=ISSUE_WORLD):
    return world_from_data(yaml.safe_load(text), 'w.yaml', 'Car')


def test_issue_world_parses_with_origin_sensors_and_obstacles():
    world = _world()
    assert (world.origin.latitude_deg, world.origin.longitude_deg,
            world.origin.altitude_m) == (48.0, 11.0, 500.0)
    car, = world.vehicles
    sensors = {s.name: s for s in mounted(car.sensors)}
    assert set(sensors) == {'lidar', 'imu', 'gnss', 'camera'}
    lidar = sensors['lidar']
    assert isinstance(lidar, LidarSpec)
    assert (lidar.pose, lidar.fov_rad, lidar.horizontal_resolution, lidar.min_range_m,
            lidar.max_range_m, lidar.rate_hz) == (Pose(1.0, 0.0, 1.5), 3.14159, 181, 0.1, 50.0,
                                                  10.0)
    # an odd count has a ray at 0 rad: angle_min + 90 increments = 0
    assert lidar.angle_min_rad + 90 * lidar.angle_increment_rad == pytest.approx(0.0, abs=1e-15)
    camera = sensors['camera']
    assert (camera.width, camera.height, camera.fov_rad, camera.rate_hz) == (160, 120, 1.0, 5.0)
    wall, pole = world.obstacles
    assert (wall.name, wall.shape, wall.size_m, wall.position_m, wall.static) == (
        'wall', 'box', (1.0, 6.0, 2.0), (20.0, 0.0, 1.0), True)
    assert (pole.shape, pole.radius_m, pole.height_m, pole.size_m) == (
        'cylinder', 0.2, 2.0, (0.4, 0.4, 2.0))


def test_shipped_obstacle_course_is_the_issue_world():
    shipped = load_world('obstacle_course')
    issue = _world()
    assert (shipped.origin, shipped.vehicles, shipped.obstacles) == (
        issue.origin, issue.vehicles, issue.obstacles)


def test_world_sensors_keep_the_preset_device_names():
    # the world changes the preset's sensors of the same name, so Webots names stay
    car, = _world().vehicles
    devices = {s.name: s.device_names for s in car.sensors}
    assert devices == {'lidar': ('Sick LMS 291',), 'camera': ('camera',), 'gnss': ('gps',),
                       'imu': ('inertial unit', 'gyro', 'accelerometer')}


def test_default_topics_of_the_issue_world():
    car, = _world().vehicles
    topics = sorted(t for s in mounted(car.sensors) for t in s.topics)
    assert topics == ['camera/camera_info', 'camera/image_raw', 'gnss/fix', 'imu', 'scan']


def test_car_and_robot_presets_have_default_sensors_all_off():
    for params in (DEFAULT_CAR, load_car('ToyotaPrius')):
        sensors = params.sensor_set
        assert [s.name for s in sensors] == ['lidar', 'camera', 'gnss', 'imu']
        assert not mounted(sensors)
    robot = load_robot('caster_robot').sensor_set
    assert [(s.name, s.sensor_type) for s in robot] == [('lidar', 'lidar'), ('imu', 'imu')]
    assert not mounted(robot)


def test_default_car_lidar_sits_on_the_front_face_of_the_body():
    lidar = DEFAULT_CAR.sensor_set[0]
    # Car: box centre x 2.0, length 5.0 -> front face x = 4.5; base_link is the rear tyre
    # radius (0.4 m) below the Webots vehicle frame: box centre z 0.5 -> 0.9 m
    assert (lidar.pose.x_m, lidar.pose.z_m) == pytest.approx((4.5, 0.9))


def test_robot_default_lidar_scans_360_degrees_one_degree_apart():
    lidar = DEFAULT_ROBOT.sensor_set[0]
    assert lidar.angle_increment_rad == pytest.approx(math.radians(1.0))
    assert lidar.fov_rad + lidar.angle_increment_rad == pytest.approx(2.0 * math.pi)


def test_world_without_sensors_mounts_nothing():
    car, = _world('vehicles: [{name: Car}]').vehicles
    assert car.sensors == DEFAULT_CAR.sensor_set and not mounted(car.sensors)


def test_world_entry_naming_a_preset_sensor_mounts_it():
    car, = _world('vehicles: [{name: Car, sensors: [{name: gnss}]}]').vehicles
    assert [s.name for s in mounted(car.sensors)] == ['gnss']


def test_world_entry_may_keep_a_preset_sensor_unmounted():
    car, = _world('vehicles: [{sensors: [{name: gnss, enabled: false, rate_hz: 1.0}]}]').vehicles
    gnss = [s for s in car.sensors if s.name == 'gnss'][0]
    assert not gnss.enabled and gnss.rate_hz == 1.0


def test_enable_sensors_by_name_mounts_preset_sensors():
    sensors = enable_sensors(DEFAULT_CAR.sensor_set, ['lidar', 'imu'], 'param sensors')
    assert [s.name for s in mounted(sensors)] == ['lidar', 'imu']
    assert len(mounted(enable_sensors(DEFAULT_CAR.sensor_set, 'all', 'x'))) == 4
    with pytest.raises(InvalidParameterError, match="'radar'.*lidar, camera, gnss, imu"):
        enable_sensors(DEFAULT_CAR.sensor_set, ['radar'], 'param sensors')


def test_car_preset_may_define_its_own_sensors():
    params = car_params_from_dict(
        {'sensors': [{'type': 'distance', 'name': 'front', 'device': 'distance sensor front',
                      'lookup_table': [[0, 0, 0], [20, 20, 0]]}]}, 'cars/X.yaml')
    front, = params.sensor_set
    assert (front.enabled, front.max_range_m, front.device) == (False, 20.0, 'distance sensor '
                                                                             'front')


def test_static_transforms_of_mounted_sensors_include_the_camera_optical_frame():
    car, = _world().vehicles
    transforms = {(t.parent, t.child): t for t in static_transforms(car.sensors, 'car1/')}
    assert set(transforms) == {('car1/base_link', 'car1/lidar'), ('car1/base_link', 'car1/imu'),
                               ('car1/base_link', 'car1/gnss'), ('car1/base_link', 'car1/camera'),
                               ('car1/camera', 'car1/camera_optical')}
    assert transforms[('car1/base_link', 'car1/lidar')].xyz == (1.0, 0.0, 1.5)
    assert transforms[('car1/camera', 'car1/camera_optical')].quaternion == pytest.approx(
        (-0.5, 0.5, -0.5, 0.5))


def test_parse_world_and_vehicle_spec_still_import_from_sim_params():
    vehicles = sim_params.parse_world(yaml.safe_load(ISSUE_WORLD), 'w.yaml', 'Car')
    assert vehicles == parse_world(yaml.safe_load(ISSUE_WORLD), 'w.yaml', 'Car')
    assert sim_params.VehicleSpec('Car', '', 'Car').sensors == ()


def test_load_robot_is_the_config_loader_also_from_physics():
    assert diff_robot.load_robot is load_robot


def _sensor(**changes):
    entry = {'type': 'lidar', 'name': 'front', 'pose': {'x': 1.0}}
    entry.update(changes)
    return 'vehicles: [{name: Car, sensors: [' + yaml.safe_dump(entry, default_flow_style=True
                                                                ).strip() + ']}]'


@pytest.mark.parametrize('text, fragment', [
    (_sensor(max_range=-1.0), "sensors[0]: field 'max_range' = -1.0: must be > 0"),
    (_sensor(min_range=-0.5), "field 'min_range' = -0.5: must be >= 0"),
    (_sensor(min_range=60.0, max_range=50.0), "field 'min_range' = 60.0: must be < max_range"),
    (_sensor(horizontal_resolution=0), "field 'horizontal_resolution' = 0: must be in 2 .. 4096"),
    (_sensor(horizontal_resolution=10.5), "field 'horizontal_resolution' = 10.5: must be an "
                                          'integer'),
    (_sensor(layers=4), "field 'vertical_fov' = 0.0: must be > 0 with 4 layers"),
    (_sensor(type='sonar'), "field 'type' = 'sonar': unknown sensor type; valid: lidar, imu"),
    (_sensor(fov=float('nan')), "field 'fov' = nan: must be finite"),
    (_sensor(fov=7.0), "field 'fov' = 7.0: must be > 0 and <= 6.28319"),
    (_sensor(rate_hz=0.0), "field 'rate_hz' = 0.0: must be > 0"),
    (_sensor(colour='red'), "unknown field 'colour'"),
    (_sensor(name='front lidar'), "field 'name' = 'front lidar': must be a ROS name"),
    (_sensor(name='2d_lidar'), "field 'name' = '2d_lidar': must be a ROS name"),
    (_sensor(pose={'x': 1.0, 'q': 2.0}), "field 'pose'.*unknown key"),
    (_sensor(pose={'z': float('inf')}), "field 'pose.z' = inf: must be a finite number"),
    (_sensor(topic='bad topic'), "field 'topic' = 'bad topic': must be a ROS topic name"),
    (_sensor(topic='odom'), "topic 'odom' is one of the vehicle's own topics"),
    (_sensor(seed=-1), "field 'seed' = -1: must be >= 0"),
    (_sensor(type='camera', width=0), "field 'width' = 0: must be in 1 .. 3840"),
    (_sensor(type='camera', fov=3.2), "field 'fov' = 3.2: must be > 0 and < 3.14159"),
    (_sensor(type='distance', aperture=-0.1), "field 'aperture' = -0.1: must be >= 0"),
    (_sensor(type='distance', rays=0), "field 'rays' = 0: must be in 1 .. 1024"),
    (_sensor(type='distance', lookup_table=[[0.2, 1, 0], [0.1, 2, 0]]),
     "field 'lookup_table'.*strictly increasing"),
    (_sensor(type='distance', lookup_table=[[0, 1]]), "field 'lookup_table'"),
    (_sensor(type='imu', angular_velocity_noise=-1.0),
     "field 'angular_velocity_noise' = -1.0: must be >= 0"),
    ('vehicles: [{sensors: [{type: lidar}]}]', "sensors[0]: field 'name' is required"),
    ('vehicles: [{sensors: [{name: x1}]}]', "sensors[0]: field 'type' is required"),
    ('vehicles: [{sensors: [{name: lidar, type: imu}]}]', "field 'type' = 'imu': the preset "
                                                         "sensor 'lidar' is a lidar"),
    ('vehicles: [{sensors: {type: imu}}]', 'vehicles[0].sensors: must be a list'),
])
def test_bad_sensor_is_refused_naming_file_and_field(text, fragment):
    with pytest.raises(InvalidParameterError, match='w.yaml') as info:
        _world(text)
    assert fragment in str(info.value) or re.search(fragment, str(info.value)), str(info.value)


def test_two_sensors_on_one_topic_are_refused():
    text = ('vehicles: [{sensors: [{type: lidar, name: front}, {type: lidar, name: rear, '
            'pose: {yaw: 3.14}}]}]')
    with pytest.raises(InvalidParameterError, match="w.yaml.*'front' and 'rear' have the same "
                                                    "topic 'scan'"):
        _world(text)
    text = text.replace('yaw: 3.14}', 'yaw: 3.14}, topic: rear_scan')
    assert len(mounted(_world(text).vehicles[0].sensors)) == 2


def test_two_sensors_with_one_device_name_are_refused():
    text = ('vehicles: [{sensors: [{type: gnss, name: a, device: gps, topic: a}, '
            '{type: gnss, name: b, device: gps, topic: b}]}]')
    with pytest.raises(InvalidParameterError, match="same device name 'gps'"):
        _world(text)


def test_two_sensors_with_one_name_are_refused():
    with pytest.raises(InvalidParameterError, match="two sensors are named 'x'"):
        merge_sensors((), [{'type': 'imu', 'name': 'x'}, {'type': 'gnss', 'name': 'x'}], 'w.yaml')


def _obstacle(**changes):
    entry = {'name': 'box1', 'shape': 'box', 'size': [1.0, 1.0, 1.0], 'position': [5, 0, 0.5]}
    entry.update(changes)
    return 'vehicles: [{name: Car}]\nobstacles: [' + yaml.safe_dump(
        entry, default_flow_style=True).strip() + ']'


@pytest.mark.parametrize('text, fragment', [
    (_obstacle(shape='cone'), "obstacles[0]: field 'shape' = 'cone': unknown shape; valid: box, "
                              'cylinder, sphere'),
    (_obstacle(size=[1.0, float('nan'), 1.0]), "field 'size'"),
    (_obstacle(size=[1.0, 0.0, 1.0]), "field 'size' = [1.0, 0.0, 1.0]: every entry must be > 0"),
    (_obstacle(size=[1.0, 1.0]), "field 'size'"),
    (_obstacle(mass=-1.0), "field 'mass' = -1.0: must be >= 0"),
    (_obstacle(color=[1.0, 0.0, 0.0]), "field 'color'"),
    (_obstacle(color=[2.0, 0.0, 0.0, 1.0]), "field 'color'.*in \\[0, 1\\]"),
    (_obstacle(radius=1.0), "unknown field 'radius'"),
    (_obstacle(shape='cylinder', size=None, radius=0.2), "field 'size'"),
    (_obstacle(name='the wall'), "field 'name' = 'the wall': must be a ROS name"),
    (_obstacle(position=None), "field 'position'"),
    (_obstacle(name='Car'), 'obstacle and vehicle share a name'),
    ('vehicles: [{name: Car}]\nobstacles: {name: a}', 'obstacles: must be a list'),
    ('vehicles: [{name: Car}]\norigin: {latitude: 91.0}', "origin: field 'latitude' = 91.0"),
    ('vehicles: [{name: Car}]\norigin: {lat: 1.0}', "unknown field 'lat'"),
    ('vehicles: [{name: Car}]\nobstacle: []', "unknown key(s) ['obstacle']"),
    ('vehicles: [{name: Car, pose: {z: 1.0}}]', "vehicles[0]: field 'pose'"),
])
def test_bad_obstacle_or_world_key_is_refused_naming_file_and_field(text, fragment):
    with pytest.raises(InvalidParameterError, match='w.yaml') as info:
        _world(text)
    assert fragment in str(info.value) or re.search(fragment, str(info.value)), str(info.value)


def test_two_obstacles_with_one_name_are_refused():
    text = ('vehicles: [{name: Car}]\nobstacles: [{name: a, shape: sphere, radius: 1, '
            'position: [0, 5, 1]}, {name: a, shape: sphere, radius: 1, position: [0, 9, 1]}]')
    with pytest.raises(InvalidParameterError, match="two obstacles are named 'a'"):
        _world(text)


def test_obstacle_defaults_static_and_a_colour_per_shape():
    text = ('vehicles: [{name: Car}]\nobstacles: [{name: a, shape: sphere, radius: 0.5, '
            'position: [0, 5, 1]}]')
    ball, = _world(text).obstacles
    assert ball.static and ball.size_m == (1.0, 1.0, 1.0) and len(ball.color_rgba) == 4


def test_every_sensor_type_has_a_table_and_a_spec_class():
    for name, row in SENSOR_TYPES.items():
        spec = sensor_from_dict({'type': name, 'name': 'x'}, 'test')
        assert isinstance(spec, row.spec_class) and spec.sensor_type == name
        assert spec.enabled and spec.device == 'x' and spec.topics
    assert isinstance(sensor_from_dict({'type': 'camera', 'name': 'c'}, 't'), CameraSpec)


def test_sensors_doc_contains_the_generated_key_tables():
    text = (Path(__file__).resolve().parent.parent / 'docs' / 'sensors.md').read_text(
        encoding='utf-8')
    assert sensors_markdown() in text
    assert obstacles_markdown() in text
    assert parameter_table_markdown(ORIGIN_SPECS, 'key') in text
    assert parameter_table_markdown(VEHICLE_SPECS, 'key') in text
    assert ISSUE_WORLD.strip().split('obstacles:')[0].strip() in text


@pytest.mark.parametrize('entry, fragment', [
    ('{type: lidar, name: lidar, max_range: -1.0}', "field 'max_range' = -1.0"),
    ('{type: sonar, name: s}', "field 'type' = 'sonar'"),
])
def test_automobile_node_refuses_a_bad_sensor_at_start_naming_file_and_field(
        tmp_path, entry, fragment):
    from vehicle_sim.ros.automobile_node import AutomobileNode
    path = tmp_path / 'bad_world.yaml'
    path.write_text(f'vehicles: [{{name: Car, sensors: [{entry}]}}]\n')
    with pytest.raises(InvalidParameterError) as info:
        AutomobileNode(['x', '--ros-args', '-r', '__ns:=/bad_sensor', '-p', f'world:={path}'],
                       transport='dds')
    assert str(path) in str(info.value) and fragment in str(info.value)


def test_automobile_node_refuses_a_bad_obstacle_at_start_naming_file_and_field(tmp_path):
    from vehicle_sim.ros.automobile_node import AutomobileNode
    path = tmp_path / 'bad_world.yaml'
    path.write_text('vehicles: [{name: Car}]\nobstacles: [{name: a, shape: box, '
                    'size: [1, .nan, 1], position: [5, 0, 0.5]}]\n')
    with pytest.raises(InvalidParameterError) as info:
        AutomobileNode(['x', '--ros-args', '-r', '__ns:=/bad_obstacle', '-p',
                        f'world:={path}'], transport='dds')
    assert str(path) in str(info.value) and "obstacles[0]: field 'size'" in str(info.value)
