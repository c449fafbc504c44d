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
Webots sensor devices: Driver.getDevice returns Webots' device classes with Webots' semantics.

The table DEVICE_API (webots/api_table.py) drives the class and configuration-getter checks.
"""

import math
import os
from pathlib import Path
import subprocess
import sys
import warnings

import numpy as np
import pytest

from vehicle_sim.core.specs.errors import InvalidPoseError
from vehicle_sim.webots import Driver, WebotsWarning
from vehicle_sim.webots.api_table import DEVICE_API
from vehicle_sim.webots.devices import DEVICE_CLASSES

REPO = Path(__file__).resolve().parent.parent
# Devices of the issue world: the Car preset's names ('Sick LMS 291', 'gps', ...)
COURSE_DEVICES = ['Sick LMS 291', 'camera', 'gps', 'inertial unit', 'gyro', 'accelerometer']

WORLD_WITH_EVERY_DEVICE = """
origin: {latitude: 48.0, longitude: 11.0, altitude: 500.0}
vehicles:
  - name: ego
    pose: {x: 0.0, y: 0.0, yaw: 0.0}
    sensors:
      - {name: lidar, pose: {x: 1.0, z: 1.5}, fov: 3.14159, horizontal_resolution: 181,
         max_range: 50.0}
      - {name: camera, pose: {x: 1.5, z: 1.3}, width: 64, height: 48}
      - {name: gnss, pose: {z: 1.5}}
      - {name: imu, pose: {z: 0.5}}
      - {type: distance, name: front, device: distance sensor front, pose: {x: 4.6, z: 0.9},
         lookup_table: [[0.0, 0.0, 0.0], [20.0, 20.0, 0.0]]}
      - {type: range_finder, name: depth_cam, pose: {x: 1.5, z: 1.3}, width: 64, height: 48,
         max_range: 50.0}
      - {type: radar, name: radar, pose: {x: 4.6, z: 1.0}, horizontal_fov: 2.0}
  - name: parked
    namespace: parked
    pose: {x: 10.0, y: -6.0, yaw: 1.0}
obstacles:
  - {name: wall, shape: box, size: [1.0, 6.0, 2.0], position: [20.0, 0.0, 1.0]}
  - {name: pole, shape: cylinder, radius: 0.2, height: 2.0, position: [10.0, 5.0, 1.0]}
"""


@pytest.fixture
def world_file(tmp_path):
    path = tmp_path / 'every_device.yaml'
    path.write_text(WORLD_WITH_EVERY_DEVICE)
    return str(path)


@pytest.fixture
def driver(world_file):
    with Driver(world_file=world_file) as instance:
        yield instance


def _quiet(function, *args):
    with warnings.catch_warnings():
        warnings.simplefilter('ignore', WebotsWarning)
        return function(*args)


# ------------------------------------------------------------------------------- devices

@pytest.mark.parametrize('row', DEVICE_API, ids=lambda row: row.device_class)
def test_get_device_returns_the_webots_class_and_its_configuration(driver, row):
    spec = [s for s in driver.sensors.specs.values() if s.sensor_type == row.sensor_type][0]
    name = getattr(spec, row.name_attr)
    device = driver.getDevice(name)
    assert type(device) is DEVICE_CLASSES[row.device_class]
    assert type(device).__name__ == row.device_class
    assert device.getName() == name and device.getSamplingPeriod() == 0
    for getter, attr, kind in row.spec_getters:
        value = getattr(device, getter)()
        assert value == getattr(spec, attr) and type(value) is kind


def test_devices_are_listed_by_index_in_sensor_order(driver):
    names = [driver.getDeviceByIndex(i).getName() for i in range(driver.getNumberOfDevices())]
    assert names == ['Sick LMS 291', 'camera', 'gps', 'inertial unit', 'gyro', 'accelerometer',
                     'distance sensor front', 'depth_cam', 'radar']
    with pytest.warns(WebotsWarning, match='outside'):
        assert driver.getDeviceByIndex(9) is None


def test_unknown_device_keeps_a_clear_error_listing_the_mounted_ones(driver):
    with pytest.raises(NotImplementedError, match="getDevice\\('display'\\).*'Sick LMS 291'"):
        driver.getDevice('display')


def test_preset_device_not_mounted_says_how_to_mount_it():
    with Driver() as driver:
        with pytest.raises(NotImplementedError, match="Driver\\(sensors=\\['camera'\\]\\)"):
            driver.getDevice('camera')
    with Driver(sensors=['camera', 'gnss']) as driver:
        assert [driver.getDeviceByIndex(i).getName() for i in range(2)] == ['camera', 'gps']


def test_deprecated_robot_getters_return_the_device_with_a_warning(driver):
    with pytest.warns(WebotsWarning, match='Deprecated getGPS'):
        assert driver.getGPS('gps') is driver.getDevice('gps')
    with pytest.raises(TypeError, match='not a Lidar'):
        _quiet(driver.getLidar, 'gps')


# ------------------------------------------------------------------------------- sampling

def test_values_are_nan_until_one_period_after_enable(driver):
    gps = driver.getDevice('gps')
    gps.enable(50)
    assert gps.getSamplingPeriod() == 50
    for _ in range(4):
        driver.step()
        assert all(math.isnan(v) for v in gps.getValues())      # Webots: NaN before a sample
    driver.step()                                                # 50 ms: the first sample
    assert not any(math.isnan(v) for v in gps.getValues())


def test_each_device_of_an_imu_has_its_own_period(driver):
    gyro, unit = driver.getDevice('gyro'), driver.getDevice('inertial unit')
    gyro.enable(10)
    unit.enable(50)
    driver.step()
    assert not math.isnan(gyro.getValues()[0]) and math.isnan(unit.getRollPitchYaw()[0])


def test_disabled_device_warns_and_reads_nan(driver):
    gps = driver.getDevice('gps')
    gps.enable(10)
    driver.step()
    gps.disable()
    assert gps.getSamplingPeriod() == 0
    with pytest.warns(WebotsWarning, match='disabled device'):
        assert all(math.isnan(v) for v in gps.getValues())


def test_enable_zero_disables_negative_warns_and_wrong_type_raises(driver):
    gps = driver.getDevice('gps')
    gps.enable(20)
    with pytest.warns(WebotsWarning, match='negative sampling period'):
        gps.enable(-10)
    assert gps.getSamplingPeriod() == 20
    with pytest.raises(TypeError):
        gps.enable(12.5)
    gps.enable(0)
    assert gps.getSamplingPeriod() == 0


# ------------------------------------------------------------------------------- values

def _settle(driver, devices, period_ms=10, steps=100):
    for device in devices:
        device.enable(period_ms)
    for _ in range(steps):
        driver.step()


def test_lidar_range_image_runs_left_to_right_as_in_webots(driver):
    lidar = driver.getDevice('Sick LMS 291')
    _settle(driver, [lidar], steps=2)
    image = lidar.getRangeImage()
    scan = driver.sensors.latest('Sick LMS 291')
    # Webots: index 0 = leftmost (+fov/2); ROS LaserScan: index 0 = rightmost (-fov/2)
    assert image == pytest.approx(scan.scan[::-1].astype(float).tolist())
    assert image[90] == pytest.approx(18.5, abs=1e-3)              # straight ahead
    pole = int(np.argmin(image[:90]))           # the pole is on the left: the first half
    assert image[pole] == pytest.approx(10.096, abs=0.01)
    assert lidar.getRangeImageArray() == [image]
    assert lidar.getLayerRangeImage(0) == image
    assert lidar.getNumberOfPoints() == 181


def test_lidar_returns_closer_than_min_range_read_inf_as_in_webots(world_file, tmp_path):
    text = Path(world_file).read_text().replace('max_range: 50.0}', 'max_range: 50.0, '
                                                'min_range: 19.0}')
    path = tmp_path / 'close.yaml'
    path.write_text(text)
    with Driver(world_file=str(path)) as driver:
        lidar = driver.getDevice('Sick LMS 291')
        _settle(driver, [lidar], steps=1)
        assert np.isneginf(driver.sensors.latest('Sick LMS 291').scan[90])  # REP 117
        assert lidar.getRangeImage()[90] == math.inf                          # Webots


def test_lidar_point_cloud_is_in_the_lidar_frame(driver):
    lidar = driver.getDevice('Sick LMS 291')
    lidar.enablePointCloud()
    _settle(driver, [lidar], steps=1)
    points = lidar.getPointCloud()
    assert len(points) == 181 and lidar.isPointCloudEnabled()
    ahead = points[90]
    assert (ahead.x, ahead.y, ahead.layer_id) == pytest.approx((18.5, 0.0, 0), abs=1e-3)
    assert points[-1].x == math.inf                     # the rightmost ray misses


def test_gps_values_are_the_antenna_position_in_the_world(driver):
    gps = driver.getDevice('gps')
    _settle(driver, [gps])
    assert gps.getValues() == pytest.approx([0.0, 0.0, 1.5], abs=0.01)
    assert gps.getSpeed() == pytest.approx(0.0, abs=1e-3)
    assert gps.getCoordinateSystem() == gps.LOCAL
    assert gps.convertToDegreesMinutesSeconds(48.125) == '48°7' + "'" + '30.00"'


def test_inertial_unit_gyro_and_accelerometer_at_rest(driver):
    devices = [driver.getDevice(n) for n in ('inertial unit', 'gyro', 'accelerometer')]
    _settle(driver, devices, steps=300)
    unit, gyro, accelerometer = devices
    assert unit.getRollPitchYaw() == pytest.approx([0.0, 0.0, 0.0], abs=1e-4)
    assert unit.getQuaternion() == pytest.approx([0.0, 0.0, 0.0, 1.0], abs=1e-4)
    assert gyro.getValues() == pytest.approx([0.0, 0.0, 0.0], abs=1e-6)
    assert accelerometer.getValues() == pytest.approx([0.0, 0.0, 9.81], abs=1e-3)


def test_distance_sensor_value_and_range_come_from_its_lookup_table(driver):
    front = driver.getDevice('distance sensor front')
    _settle(driver, [front], steps=1)
    # the wall is 19.5 - 4.6 = 14.9 m ahead; table [0 0 0, 20 20 0]: value = distance
    assert front.getValue() == pytest.approx(14.9, abs=1e-3)
    assert (front.getMinValue(), front.getMaxValue()) == (0.0, 20.0)
    assert front.getLookupTable() == [0.0, 0.0, 0.0, 20.0, 20.0, 0.0]
    assert front.getType() == front.SONAR


def test_radar_targets_as_webots_reads_them(driver):
    # Webots' Radar (radar.md): RadarTarget distance, received_power, speed, azimuth; the
    # azimuth > 0 to the right (WbRadar); none before the first sample
    radar = driver.getDevice('radar')
    radar.enable(10)
    assert radar.getTargets() == [] and radar.getNumberOfTargets() == 0
    for _ in range(5):
        driver.step()
    reading = driver.sensors.latest('radar')
    targets = radar.getTargets()
    assert radar.getNumberOfTargets() == len(targets) == len(reading.targets) >= 2
    for target, truth in zip(targets, reading.targets):
        assert target.distance == truth.distance_m
        assert target.received_power == target.receiver_power == truth.received_power_dbm
        assert target.speed == truth.speed_mps
        assert target.azimuth == -truth.azimuth_rad
    # the pole (y = +5) to the left: azimuth < 0; the parked car (y = -6) to the right: > 0;
    # the wall straight ahead: 0
    assert sorted(round(t.azimuth, 6) for t in targets) == [
        pytest.approx(-math.atan2(5.0, 5.4), abs=1e-3), 0.0,
        pytest.approx(math.atan2(4.317, 6.4806), abs=1e-3)]
    assert radar.getHorizontalFov() == 2.0 and radar.getMinRange() == 1.0
    assert radar.getMaxRange() == 50.0 and radar.getVerticalFov() == 0.1


# Webots' radar.md (Python tabs) and its Python controller's radar.py: every method and property
RADAR_METHODS = ('enable', 'disable', 'getSamplingPeriod', 'getMinRange', 'getMaxRange',
                 'getHorizontalFov', 'getVerticalFov', 'getNumberOfTargets', 'getTargets')
RADAR_PROPERTIES = ('min_range', 'max_range', 'horizontal_fov', 'vertical_fov',
                    'number_of_targets', 'targets', 'sampling_period')


def test_radar_has_every_method_and_property_of_webots_radar(driver):
    radar = driver.getDevice('radar')
    spec = driver.sensors.specs['radar']
    for name in RADAR_METHODS:
        assert callable(getattr(radar, name)), name
    assert (radar.min_range, radar.max_range) == (spec.min_range_m, spec.max_range_m)
    assert radar.horizontal_fov == radar.getHorizontalFov() == spec.horizontal_fov_rad
    assert radar.vertical_fov == radar.getVerticalFov() == spec.vertical_fov_rad
    assert radar.sampling_period == radar.getSamplingPeriod() == 0
    radar.enable(20)
    assert radar.getSamplingPeriod() == 20
    for _ in range(4):
        driver.step()
    assert radar.number_of_targets == radar.getNumberOfTargets() == len(radar.targets) == 3
    assert all(hasattr(radar, name) for name in RADAR_PROPERTIES)
    target = radar.getTargets()[0]
    assert [type(getattr(target, name)) for name in (
        'distance', 'received_power', 'receiver_power', 'speed', 'azimuth')] == [float] * 5
    radar.disable()
    assert radar.getSamplingPeriod() == 0
    with pytest.warns(WebotsWarning, match='disabled device'):
        assert radar.getTargets() == []


def test_camera_image_is_bgra_and_the_array_is_x_y_rgb(driver):
    camera = driver.getDevice('camera')
    _settle(driver, [camera], steps=1)
    image = camera.getImage()
    width, height = camera.getWidth(), camera.getHeight()
    assert len(image) == width * height * 4
    rgb = driver.sensors.latest('camera').rgb
    x, y = width // 2, height // 2
    assert [camera.imageGetRed(image, width, x, y), camera.imageGetGreen(image, width, x, y),
            camera.imageGetBlue(image, width, x, y)] == rgb[y, x].tolist()
    assert camera.getImageArray()[x][y] == rgb[y, x].tolist()
    assert camera.imageGetGray(image, width, x, y) == sum(rgb[y, x].tolist()) // 3


# ------------------------------------------------------------------------------- worlds

def test_world_file_from_the_environment_drives_its_first_vehicle(world_file, monkeypatch):
    monkeypatch.setenv('VEHICLE_SIM_WORLD', world_file)
    with Driver() as driver:
        assert driver.simulated_car.body.name == 'ego'
        assert set(driver.world.obstacles) == {'wall', 'pole'}
        names = [b.body.name for b in driver.world.bodies if hasattr(b, 'body')]
        assert names == ['parked', 'ego']
        assert driver.getNumberOfDevices() == 9


def test_shipped_obstacle_course_mounts_the_webots_car_devices(monkeypatch):
    monkeypatch.setenv('VEHICLE_SIM_WORLD', 'obstacle_course')
    with Driver() as driver:
        assert [driver.getDeviceByIndex(i).getName()
                for i in range(driver.getNumberOfDevices())] == COURSE_DEVICES


def test_lidar_example_controller_stops_before_the_wall():
    env = dict(os.environ, VEHICLE_SIM_WORLD='obstacle_course')
    result = subprocess.run([sys.executable, str(REPO / 'examples' / 'lidar_stop_controller.py')],
                            capture_output=True, text=True, env=env, timeout=300)
    assert result.returncode == 0, result.stderr
    last = result.stdout.strip().splitlines()[-1]
    assert 'stopped' in last, result.stdout
    gap_m = float(last.split('m ahead of the lidar, ')[1].split(' m')[0])
    assert 0.5 < gap_m < 5.0          # stopped before the wall, without touching it


def test_radar_example_controller_stops_behind_the_parked_car():
    # examples/radar_controller.py, Webots' style, on config/worlds/radar_stop.yaml: the box's
    # centre 60 m ahead, the radar at the front bumper (4.5 m): it stops short of the box's rear
    env = dict(os.environ, VEHICLE_SIM_WORLD='radar_stop')
    result = subprocess.run([sys.executable, str(REPO / 'examples' / 'radar_controller.py')],
                            capture_output=True, text=True, env=env, timeout=300)
    assert result.returncode == 0, result.stderr
    lines = result.stdout.strip().splitlines()
    assert 'stopped' in lines[-1], result.stdout
    distance_m = float(lines[-1].split('target ')[1].split(' m')[0])
    assert 2.25 + 0.5 < distance_m < 2.25 + 10.0     # the box's rear 0.5 .. 10 m ahead
    # while cruising, the radial speed is the car's speed, closing (< 0)
    cruising = [line for line in lines if 'speed=' in line and 'radial speed' in line]
    for line in cruising:
        speed_kmh = float(line.split('speed=')[1].split(' km/h')[0])
        radial = float(line.split('radial speed')[1].split(' m/s')[0])
        assert radial == pytest.approx(-speed_kmh / 3.6, abs=0.1)
    assert len(cruising) >= 5


def test_radar_camera_example_controller_sees_the_parked_car_with_both_and_stops():
    # examples/radar_camera_controller.py, Webots' style, on config/worlds/radar_camera.yaml:
    # the camera recognises the parked car, the radar target at its bearing measures it
    env = dict(os.environ, VEHICLE_SIM_WORLD='radar_camera')
    result = subprocess.run(
        [sys.executable, str(REPO / 'examples' / 'radar_camera_controller.py')],
        capture_output=True, text=True, env=env, timeout=300)
    assert result.returncode == 0, result.stderr
    lines = result.stdout.strip().splitlines()
    assert 'stopped' in lines[-1], result.stdout
    seen = [line for line in lines if '(car): radar' in line]
    assert len(seen) >= 5, result.stdout
    ids = set()
    for line in seen:
        ids.add(int(line.split(' car ')[1].split(' ')[0]))
        speed_kmh = float(line.split('speed=')[1].split(' km/h')[0])
        radar_m = float(line.split('radar ')[1].split(' m')[0])
        closing = float(line.split('closing at ')[1].split(' m/s')[0])
        camera_m = float(line.split('camera ')[1].split(' m')[0])
        assert closing == pytest.approx(speed_kmh / 3.6, abs=0.1)
        if radar_m < 50.0:      # a car partly within maxRange reads maxRange (Webots clamps)
            assert camera_m == pytest.approx(radar_m, abs=1.0)   # two mounts, the same car
    assert len(ids) == 1 and ids.pop() > 0      # one object, its instance id
    radar_m = float(lines[-1].split('radar ')[1].split(' m')[0])
    assert 2.5 + 0.5 < radar_m < 2.5 + 10.0     # stopped short of the parked car


def test_a_world_whose_vehicle_starts_inside_an_obstacle_is_refused_naming_both(tmp_path):
    # As the node and the scenario runner refuse it: the check is where vehicles join a World.
    path = tmp_path / 'crate.yaml'
    path.write_text('vehicles:\n  - {name: ego}\nobstacles:\n  - {name: crate, shape: box, '
                    'size: [2, 2, 2], position: [1.5, 0, 1]}\n', encoding='utf-8')
    with pytest.raises(InvalidPoseError, match="vehicle 'ego' starts inside obstacle 'crate'"):
        Driver(world_file=str(path))
