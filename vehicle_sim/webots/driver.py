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
Webots-compatible ``Driver`` and ``Car`` classes on top of the strict core.

A Webots Python controller runs unchanged apart from its import::

    from vehicle_sim.webots import Driver   # Webots: from vehicle import Driver

Odd input follows the facade column of the odd-input table (docs/deviations.md): Webots semantics,
each case
reported with a ``WebotsWarning``: NaN/inf ignored, throttle/brake/steering/gear clamped, a
cruising speed beyond the top speed stored as given (the wheel motors saturate),
undefined enums and indicator periods below 1 ms ignored, wheel index outside 0..3 returns 0,
rpm and gear read in SPEED mode return 0. A value of the wrong type (a string for a
number, a float for a gear) raises TypeError, as Webots' own wrapper fails on it.

Sensor devices: ``getDevice(name)`` returns the Webots device (Lidar, Camera, GPS,
InertialUnit, Gyro, Accelerometer, DistanceSensor; webots/devices.py) of a mounted sensor,
looked up by its device name. Sensors are mounted by a world file (``world_file=`` or
``VEHICLE_SIM_WORLD``; the Driver drives its first vehicle) or by ``sensors=`` (names of the
car preset's sensors, which carry the Webots car PROTOs' device names).

Lanes: in a world with a lane map (a lanelet2 map, a SUMO network or ``roads:``; docs/maps.md),
``driver.getLaneState()`` returns the car's lane state now (a core LaneState: lane id, s,
offset, heading error, width, speed limit, the next stop line ahead and its signal's state), an
addition of ours (Webots has no lane map, and no device for a traffic light's state: its
GenericTrafficLight is a robot of its own, seen by a car only through its camera; here the
lane state carries the state, and the camera sees the lamps; docs/maps.md).
"""

from dataclasses import replace
import math
import numbers
import os
import weakref

from vehicle_sim.config import load_car, load_world
from vehicle_sim.core.car.drivetrain import ControlMode
from vehicle_sim.core.geometry.angles import yaw_from_quaternion
from vehicle_sim.core.geometry.geodesy import GeodeticOrigin
from vehicle_sim.core.map.lane_state import LaneTracker
from vehicle_sim.core.sensors.sets import enable_sensors
from vehicle_sim.core.specs.param_spec import check_value
from vehicle_sim.core.specs.simulation import TIME_STEP_MS
from vehicle_sim.core.world.params import VehicleSpec, WorldSpec
from vehicle_sim.maps.lane_maps import with_lanes
from vehicle_sim.physics.scene import build_scene, mount_suite
from vehicle_sim.physics.sensors import SensorSuite
from vehicle_sim.webots.api_table import (
    CAR_API,
    CAR_WHEEL_API,
    DEVICE_API,
    DRIVER_API,
    UNSUPPORTED_ROBOT_API,
)
from vehicle_sim.webots.devices import devices_of
from vehicle_sim.webots.host import current_host
from vehicle_sim.webots.webots_warning import warn, WebotsWarning  # noqa: F401 (exported)


def _warn(message):
    warn(message, stacklevel=3)


def _is_number(value):
    return isinstance(value, numbers.Real) and not isinstance(value, bool)


def _is_integer(value):
    return isinstance(value, numbers.Integral) and not isinstance(value, bool)


# Webots' deprecated Robot.get<Device>(name) -> the device class it returns.
_ROBOT_GETTERS = {row.robot_getter: row.device_class for row in DEVICE_API}


def _coerce(row, value):
    """
    Apply the facade's odd-input policy to a setter argument.

    :return: the value to hand to the core, or None when the call is to be ignored.
    :raises TypeError: for a value of the wrong type.
    """
    name = row.setter
    if row.kind == 'bool':
        if isinstance(value, bool) or (_is_integer(value) and value in (0, 1)):
            return bool(value)
        raise TypeError(f'{name}() expects a bool, got {value!r}')
    if row.kind in ('int', 'enum'):
        if isinstance(value, float) and not math.isfinite(value):
            _warn(f'{name}() called with an invalid argument ({value}); ignored')
            return None
        if not _is_integer(value):
            raise TypeError(f'{name}() expects an int, got {value!r}')
        value = int(value)
        if row.kind == 'enum':
            if value not in row.enum_values:
                _warn(f'{name}({value}): undefined value, valid: '
                      f'{", ".join(map(str, row.enum_values))}; ignored')
                return None
            return value
    elif not _is_number(value):
        raise TypeError(f'{name}() expects a number, got {value!r}')
    else:
        value = float(value)
        if not math.isfinite(value):
            _warn(f'{name}() called with an invalid argument ({value}); ignored')
            return None
    return value


class _WorldSync:
    """
    Tick bookkeeping for Drivers sharing one World.

    A ``step()`` call from a Driver that has seen the latest tick advances the world; a call
    from a Driver behind it (another Driver already advanced this tick) only catches up. So a
    loop ``a.step(); b.step()`` advances time once per iteration, and a loop over one Driver
    alone still advances it on every call.
    """

    _by_world = weakref.WeakKeyDictionary()

    def __init__(self):
        self.tick = 0
        self.seen = weakref.WeakKeyDictionary()

    @classmethod
    def of(cls, world):
        sync = cls._by_world.get(world)
        if sync is None:
            sync = cls._by_world[world] = cls()
        return sync

    def join(self, driver):
        self.seen[driver] = self.tick

    def request_step(self, step, driver):
        if self.seen.get(driver, self.tick) >= self.tick:
            step()
            self.tick += 1
        self.seen[driver] = self.tick


class Driver:
    """
    The Webots driver library (``wbu_driver_*``) on a simulated car.

    :param car: preset name, YAML path or CarParams; default: ``VEHICLE_SIM_CAR`` or 'Car'.
    :param world: a World to share with other vehicles; a new one (owned) when None.
    :param position: (x [m], y [m], yaw [rad]) of the car on the ground.
    :param gui: open PyBullet's GUI (owned world only).
    :param time_step_ms: basic time step of an owned world [ms]: an integer in 1 .. 1000
        (the ``time_step_ms`` row of core/specs/simulation.py); None = its default, 10 ms.
    :param duration_s: ``step()`` returns -1 once the simulation time reaches this [s];
        default: ``VEHICLE_SIM_DURATION`` or never.
    :param name: robot name of the car.
    :param world_file: a world (config/worlds name or .yaml path) to build the owned world from:
        its obstacles and vehicles, this Driver driving the first one (its model, pose and
        sensors); default: ``VEHICLE_SIM_WORLD`` (ignored when ``world`` is given). The other
        vehicles stand held where the file puts them.
    :param sensors: names of the car preset's sensors to mount (or 'all'), in addition to those
        the world file mounts; their Webots devices are then available (``getDevice``).

    Inside a controller host (``vehicle_sim.webots.host.hosting``, as the scenario runner runs
    controllers) the Driver binds to the host's car and world instead, as a Webots controller
    binds to its robot; the world arguments are then ignored.
    """

    INDICATOR_OFF = 0
    INDICATOR_RIGHT = 1
    INDICATOR_LEFT = 2
    SPEED = int(ControlMode.SPEED)
    TORQUE = int(ControlMode.TORQUE)
    DOWN = 0
    SLOW = 1
    NORMAL = 2
    FAST = 3

    _API = DRIVER_API
    _host = None

    def __init__(self, car=None, world=None, position=None, gui=False,
                 time_step_ms=None, duration_s=None, name=None, world_file=None, sensors=None):
        self._last_note = None     # the last setter note shown (see _make_setter)
        host = current_host()
        if host is not None:
            self._bind(host, sensors)
            return
        car = car if car is not None else os.environ.get('VEHICLE_SIM_CAR', 'Car')
        if world is None and world_file is None:
            world_file = os.environ.get('VEHICLE_SIM_WORLD') or None
        spec = load_world(world_file, car) if world is None and world_file else None
        if spec is not None:
            spec = with_lanes(spec)     # vehicles placed by lane get their pose here
        vehicle = spec.vehicles[0] if spec is not None else None
        params = load_car(vehicle.model if vehicle is not None else car)
        if position is None:
            position = ((vehicle.x_m, vehicle.y_m, vehicle.yaw_rad) if vehicle is not None
                        else (0.0, 0.0, 0.0))
        if duration_s is None and os.environ.get('VEHICLE_SIM_DURATION'):
            duration_s = float(os.environ['VEHICLE_SIM_DURATION'])
        specs = vehicle.sensors if vehicle is not None else params.sensor_set
        if sensors is not None:
            specs = enable_sensors(specs, sensors, 'Driver(sensors=...)')
        self._owns_world = world is None
        if time_step_ms is not None:
            check_value(TIME_STEP_MS, time_step_ms, 'Driver', key_word='argument')
        if world is not None and time_step_ms is not None and \
                abs(time_step_ms / 1000.0 - world.time_step_s) > 1e-12:
            raise ValueError(f"time_step_ms={time_step_ms} differs from the shared world's "
                             f'{world.time_step_s * 1000.0:g} ms')
        # This Driver's car: the world file's first vehicle (its name, pose and sensors as
        # given here), added after the others, which stand held where the file puts them.
        name = name or (vehicle.name if vehicle is not None else params.model)
        x_m, y_m, yaw_rad = position
        driven = VehicleSpec(name, '', params.model, x_m, y_m, yaw_rad, specs,
                             vehicle_model=getattr(vehicle, 'vehicle_model', None))
        spec = (replace(spec, vehicles=spec.vehicles[1:] + (driven,)) if spec is not None
                else WorldSpec(GeodeticOrigin(), (driven,), ()))
        scene = build_scene(
            spec, world, time_step_s=(time_step_ms or TIME_STEP_MS.default) / 1000.0,
            gui=gui, params={name: params},
            mount=lambda built, scene: mount_suite(built, scene) if built.name == name else None)
        self.world = world = scene.world
        self._others = [scene.vehicles[other.name].car for other in spec.vehicles[:-1]]
        self.simulated_car = scene.vehicles[name].car
        self.logic = self.simulated_car.logic
        self.sensors = scene.vehicles[name].sensors
        self._lanes = None if scene.lanes is None else LaneTracker(
            scene.lanes, getattr(scene.parts.get('signals'), 'controller', None))
        self._devices = devices_of(self.sensors)
        self._duration_s = duration_s
        self._sync = _WorldSync.of(world)
        self._sync.join(self)

    def _bind(self, host, sensors):
        # A hosted Driver: the host's world and car (see vehicle_sim.webots.host).
        self._host = host
        self._owns_world = False
        self.world = world = host.world
        self._others = []
        self.simulated_car = host.car
        self.logic = host.car.logic
        specs = host.sensors
        if sensors is not None:
            specs = enable_sensors(specs, sensors, 'Driver(sensors=...)')
        self.sensors = SensorSuite(world, host.car.body, specs, host.origin)
        lanes = getattr(host, 'lanes', None)
        self._lanes = None if lanes is None else LaneTracker(lanes, host.signals)
        self._devices = devices_of(self.sensors)
        self._duration_s = host.duration_s
        self._sync = _WorldSync.of(world)
        self._sync.join(self)
        host.drivers.append(self)

    # ---------------------------------------------------------------- Robot API subset
    def step(self, duration_ms=None):
        """
        Run the driver logic and advance the simulation by one basic time step (or ``ms``).

        :param duration_ms: a multiple of the basic time step [ms]; one basic step when None.
        :return: 0, or -1 once the simulation has ended (closed, or ``duration_s`` reached).
        """
        count = 1
        if duration_ms is not None:
            basic_ms = self.getBasicTimeStep()
            if not _is_number(duration_ms) or duration_ms < 0:
                raise ValueError(f'step({duration_ms!r}): the duration must be a number >= 0 ms')
            count = duration_ms / basic_ms
            if abs(count - round(count)) > 1e-9:
                raise ValueError(f'step({duration_ms!r}): the duration must be a multiple of '
                                 f'the basic time step ({basic_ms:g} ms)')
            count = max(1, int(round(count)))
        world = self.world
        if world.closed or self._ended():
            return self._host.after_end() if self._host is not None else -1
        request_step = self._sync.request_step
        step = self._host.step if self._host is not None and self._host.step else world.step
        for _ in range(count):
            request_step(step, self)
        return -1 if self._ended() else 0

    def _ended(self):
        duration_s = self._duration_s
        return duration_s is not None and self.world.time_s >= duration_s - 1e-9

    def getBasicTimeStep(self):
        """Return the basic time step [ms] (a float, as in Webots)."""
        return self.world.time_step_s * 1000.0

    def getTime(self):
        """Return the simulation time [s]."""
        return self.world.time_s

    @property
    def basic_time_step(self):
        return self.getBasicTimeStep()

    @property
    def time(self):
        return self.getTime()

    def close(self):
        """Leave the simulation; an owned world is closed, a shared one loses this car."""
        self.sensors.close()
        if self._owns_world:
            self.world.close()
        elif not self.world.closed and self._host is None:
            self.world.remove(self.simulated_car)
        self._sync.seen.pop(self, None)

    def __enter__(self):
        return self

    def __exit__(self, *exc):
        self.close()
        return False

    def __getattr__(self, name):
        if name in UNSUPPORTED_ROBOT_API:
            def unsupported(*args, **kwargs):
                raise NotImplementedError(
                    f'{name}() is not available: vehicle_sim simulates only the sensor '
                    'devices of mounted sensors. Supported: the driver and car library '
                    'functions (see vehicle_sim.webots.api_table), step(), getBasicTimeStep(), '
                    'getTime(), getDevice().')
            return unsupported
        getter = _ROBOT_GETTERS.get(name)
        if getter is not None:
            def deprecated(device_name):
                _warn(f'Deprecated {name}() use getDevice() instead.')
                device = self.getDevice(device_name)
                if type(device).__name__ != getter:
                    raise TypeError(f'{name}({device_name!r}): the device is a '
                                    f'{type(device).__name__}, not a {getter}')
                return device
            return deprecated
        raise AttributeError(f'{type(self).__name__!r} object has no attribute {name!r}')

    # ---------------------------------------------------------------- devices
    def getDevice(self, name):
        """
        Return the Webots device of a mounted sensor by its device name.

        :raises NotImplementedError: for a name that no mounted sensor carries (the message
            lists the mounted devices and how to mount more).
        """
        device = self._devices.get(name)
        if device is None:
            mounted_names = ', '.join(repr(n) for n in self._devices) or 'none'
            unmounted = [spec.name for spec in self.logic.params.sensor_set
                         if name in spec.device_names]
            hint = (f" (the preset's sensor {unmounted[0]!r} carries it: mount it with "
                    f"Driver(sensors=[{unmounted[0]!r}]) or a world file's sensors)"
                    if unmounted else '')
            raise NotImplementedError(
                f'getDevice({name!r}): no such device on this car{hint}. Mounted devices: '
                f'{mounted_names}. vehicle_sim simulates the devices of mounted sensors '
                '(lidar, camera, GPS, inertial unit, gyro, accelerometer, distance sensors); '
                'the driver and car library functions need no devices.')
        return device

    def getNumberOfDevices(self):
        """Return the number of devices (those of the mounted sensors)."""
        return len(self._devices)

    def getDeviceByIndex(self, index):
        """Return the device at an index (0 .. getNumberOfDevices() - 1), None outside."""
        if not _is_integer(index):
            raise TypeError(f'getDeviceByIndex() expects an int, got {index!r}')
        devices = list(self._devices.values())
        if not 0 <= index < len(devices):
            _warn(f'getDeviceByIndex({index}): index outside 0..{len(devices) - 1}')
            return None
        return devices[index]

    # ---------------------------------------------------------------- lanes (our addition)
    def getLaneState(self):
        """
        Return the car's lane state now, or None in a world without a lane map.

        A core LaneState (core/map/lane_state.py) of base_link's ground-truth pose:
        ``on_lane``, ``lane_id``, ``s_m``, ``offset_m`` (+ left), ``heading_error_rad``,
        ``width_m``, ``speed_limit_mps`` (off every lane: ``on_lane`` False, the rest 0), and
        the next stop line ahead: ``stop_line_ahead``, ``stop_line_id``, ``stop_line_kind``,
        ``stop_line_distance_m``, ``traffic_light_group_id``, ``signal_state`` (the world's
        signal controller's state of its group: 'red', 'yellow', 'green', 'off'; docs/lanes.md).
        The values ``<ns>/lane_state`` carries on ROS (docs/maps.md).
        """
        if self._lanes is None:
            return None
        x, y, _, qx, qy, qz, qw = self.simulated_car.body.pose()
        return self._lanes.update(x, y, yaw_from_quaternion(qx, qy, qz, qw))

    # ---------------------------------------------------------------- special getters
    def getControlMode(self):
        """SPEED, TORQUE, or None before the first command (Webots Python returns None)."""
        mode = int(self.logic.control_mode)
        return None if mode == int(ControlMode.UNDEFINED) else mode


def _make_setter(row):
    core_setter = row.core_setter

    def setter(self, value):
        value = _coerce(row, value)
        if value is None:
            return
        if row.limits is not None:
            low, high = row.limits(self.logic)
            if not low <= value <= high:
                valid = f'outside the valid range ({low:g} .. {high:g})'
                if row.out_of_range == 'ignore':
                    _warn(f'{row.setter}({value!r}): {valid}; ignored')
                    return
                if row.out_of_range == 'store':
                    _warn(f'{row.setter}({value!r}): {valid}; stored as given, the motors '
                          f'saturate at {min(max(value, low), high):g}')
                else:
                    clamped = min(max(value, low), high)
                    _warn(f'{row.setter}({value!r}): {valid}; used {clamped:g} instead')
                    value = type(value)(clamped)
        note = getattr(self.logic, core_setter)(value)
        # Taken, but without effect now (a brake while cruise control holds a speed): said once
        # until the situation changes, not at every step of a controller that keeps braking.
        if note is not None and note != self._last_note:
            _warn(f'{row.setter}({value!r}): {note}')
        self._last_note = note

    setter.__name__ = row.setter
    setter.__doc__ = f'Webots {row.setter}(){": " + row.doc if row.doc else ""}' + (
        f' [{row.unit}]' if row.unit else '') + '.'
    return setter


def _make_getter(row):
    core_getter = row.core_getter

    def getter(self):
        if row.speed_mode_zero and self.logic.control_mode == ControlMode.SPEED:
            _warn(f'no engine model when cruise control is enabled, {row.getter}() is '
                  'therefore not allowed; returns 0')
            return 0
        value = getattr(self.logic, core_getter)
        if row.kind == 'bool':
            return bool(value)
        if row.kind in ('int', 'enum'):
            return int(value)
        return float(value)

    getter.__name__ = row.getter
    getter.__doc__ = f'Webots {row.getter}(){": " + row.doc if row.doc else ""}' + (
        f' [{row.unit}]' if row.unit else '') + '.'
    return getter


def _make_deprecated(name, target):
    def alias(self, *args):
        _warn(f'Deprecated {name}() use {target}() instead.')
        return getattr(self, target)(*args)

    alias.__name__ = name
    alias.__doc__ = f'Deprecated alias of {target}().'
    return alias


def _make_wheel_getter(name, core_method):
    def getter(self, index):
        if not _is_integer(index):
            raise TypeError(f'{name}() expects a wheel index (int), got {index!r}')
        if not 0 <= index <= 3:
            _warn(f'{name}({index}): maximum wheel index is 3; returns 0')
            return 0.0
        return float(getattr(self.logic, core_method)(int(index)))

    getter.__name__ = name
    getter.__doc__ = f'Webots {name}(index): index 0..3 (WHEEL_FRONT_RIGHT ... WHEEL_REAR_LEFT).'
    return getter


def _install(cls, rows):
    for row in rows:
        setter = getter = None
        if row.setter:
            setter = _make_setter(row)
            setattr(cls, row.setter, setter)
        if row.getter and not hasattr(cls, row.getter):
            getter = _make_getter(row)
            setattr(cls, row.getter, getter)
        elif row.getter:
            getter = getattr(cls, row.getter)
        if row.aliases:
            setter_alias, getter_alias = row.aliases
            setattr(cls, setter_alias, _make_deprecated(setter_alias, row.setter))
            setattr(cls, getter_alias, _make_deprecated(getter_alias, row.getter))
        if row.prop and getter is not None:
            setattr(cls, row.prop, property(getter, setter, doc=getter.__doc__))


_install(Driver, DRIVER_API)


class Car(Driver):
    """The Webots car library (``wbu_car_*``) in addition to the driver library."""

    TRACTION = 0
    PROPULSION = 1
    FOUR_BY_FOUR = 2
    COMBUSTION_ENGINE = 0
    ELECTRIC_ENGINE = 1
    PARALLEL_HYBRID_ENGINE = 2
    POWER_SPLIT_HYBRID_ENGINE = 3
    WHEEL_FRONT_RIGHT = 0
    WHEEL_FRONT_LEFT = 1
    WHEEL_REAR_RIGHT = 2
    WHEEL_REAR_LEFT = 3
    WHEEL_NB = 4

    _API = DRIVER_API + CAR_API


_install(Car, CAR_API)
for _name, _method in CAR_WHEEL_API:
    setattr(Car, _name, _make_wheel_getter(_name, _method))
