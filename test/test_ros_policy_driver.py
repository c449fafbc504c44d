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
A policy drives the automobile node over the wire (ros/policy_node.py, ``vehicle-sim policy``).

The automobile node (synchronous, the highway with traffic) and the policy driver run on the
embedded DDS transport in this process, in lockstep as the scenario runner drives them: one
basic step, then wait for the driver's ``policy/action`` answer. A scripted policy (any object
with ``predict``) stands in for a trained one: at each of its ticks it computes the Gym
environment's observation parts on the node's own world at that state and records both, so the
observation built from the topics is compared with the environment's at the same state.
"""

from pathlib import Path

from automobile_helpers import wait_for
import numpy as np
import pytest

from vehicle_sim.core.learning.objects_table import ObjectsTableSpec
from vehicle_sim.core.specs.errors import InvalidParameterError
from vehicle_sim.core.specs.units import mps_to_kmh
from vehicle_sim.gym.lanes import LanePart
from vehicle_sim.gym.objects import ObjectsPart
from vehicle_sim.gym.observations import OdometryPart
from vehicle_sim.ros.automobile_node import AutomobileNode
from vehicle_sim.ros.policy_node import check_period
from vehicle_sim.tools.policy_command import make_driver
from vehicle_sim.tools.policy_loader import DriveSetup

WAIT_S = 60.0
PARKED_CAR_AHEAD = str(Path(__file__).resolve().parent / 'data' / 'parked_car_ahead.yaml')
KEYS = ('lane', 'objects', 'twist')
STEER_MAX_RAD, SPEED_MAX_MPS = 0.5, 35.0
# float32 observations of float64 values: a few float32 ulps of their magnitudes
TOLERANCE = {'lane': 1e-4, 'twist': 1e-4, 'objects': 1e-5}


def setup_of(period_s=0.1, keys=KEYS, control='speed_steering'):
    """Return a (braking_)speed_steering policy's DriveSetup (bounds as the environment's)."""
    return DriveSetup(keys, ObjectsTableSpec(), control,
                      (-STEER_MAX_RAD, -5.0), (STEER_MAX_RAD, SPEED_MAX_MPS), (-1.0, 1.0),
                      period_s)


class Scripted:
    """A policy of fixed actions that records, at each call, its observation and the env's."""

    def __init__(self, action, env_view=None):
        self.action = np.asarray(action, dtype=np.float32)
        self.env_view = env_view
        self.seen = []

    def predict(self, obs, deterministic=True):
        assert deterministic
        self.seen.append((obs, None if self.env_view is None else self.env_view()))
        return self.action, None


class Lockstep:
    """The automobile node and the policy driver, stepped as the scenario runner does."""

    def __init__(self, world='highway_traffic', namespace='', timeout_s=WAIT_S):
        self.auto = AutomobileNode(transport='dds', parameter_overrides={
            'world': world, 'synchronous': True, 'time_step_ms': 10})
        self.namespace = namespace
        self.timeout_s = timeout_s
        self.driver = None

    def start(self, policy, setup):
        """Build the driver (it asks the node for its step: the node is spun meanwhile)."""
        import threading
        made = {}

        def build():
            try:
                made['driver'] = make_driver(policy, setup, self.namespace, self.timeout_s,
                                             transport='dds')
            except BaseException as error:   # noqa: BLE001 - handed to the test thread
                made['error'] = error
        thread = threading.Thread(target=build)
        thread.start()
        while thread.is_alive():
            self.auto.node.spin_once(0.01)
        thread.join()
        if 'error' in made:
            raise made['error']
        self.driver = made['driver']
        assert wait_for(lambda: self.driver._clock.get_publisher_count() > 0, WAIT_S,
                        self.driver.node)
        return self.driver

    def spin_once(self, timeout_s):
        self.auto.node.spin_once(0.0)
        self.driver.node.spin_once(timeout_s)

    def step(self):
        """Step to the driver's next answer time (its grid); wait for the answer or an error."""
        before = self.driver.answers
        for _ in range(self.driver.answer_steps):
            self.auto.step_once()
            self.auto.node.spin_once(0.0)
        assert wait_for(lambda: self.driver.answers > before or self.driver.error, WAIT_S,
                        self), 'no policy/action answer'
        assert self.driver.error is None, self.driver.error

    def car(self):
        return self.auto.scene.vehicles['Car']

    def close(self):
        if self.driver is not None:
            self.driver.destroy()
        self.auto.close()


@pytest.fixture
def lockstep():
    made = []

    def make(**kwargs):
        made.append(Lockstep(**kwargs))
        return made[-1]
    yield make
    for item in made:
        item.close()


def env_view_of(bed):
    """Return the Gym environment's observation on the node's world, as a function."""
    car = bed.car()
    parts = [OdometryPart(car.body), LanePart(bed.auto._vehicles[0].lanes),
             ObjectsPart(bed.auto.scene, car.body, ObjectsTableSpec())]

    def view():
        out = {}
        for part in parts:
            part.read(out)
        return out
    return view


def test_the_observation_from_the_topics_is_the_environments_at_the_same_state(lockstep):
    bed = lockstep()
    policy = Scripted((0.0, 0.6), env_view_of(bed))
    bed.start(policy, setup_of(period_s=0.1))
    for _ in range(15):
        bed.step()
    # ticks: on the objects' grid (10 Hz), the first when they are first published (0.1 s)
    assert len(policy.seen) == 15
    worst = {key: 0.0 for key in KEYS}
    present = 0
    for wire, env in policy.seen:
        assert set(wire) == set(KEYS)
        for key in KEYS:
            assert wire[key].dtype == np.float32 and wire[key].shape == env[key].shape
            worst[key] = max(worst[key], float(np.max(np.abs(wire[key] - env[key]))))
        present = max(present, int(wire['objects'][:, 0].sum()))
    print(f'largest |wire - env| per key: {worst}')
    assert all(worst[key] <= TOLERANCE[key] for key in KEYS), worst
    assert present >= 1             # the traffic around the ego was in the table
    assert policy.seen[-1][0]['twist'][0] > 1.0     # the car drove


def test_the_commands_arrive_in_the_units_of_the_setters(lockstep):
    bed = lockstep()
    action = (0.5, 0.2)            # in [-1, 1]: steering 3/4 of the way left, speed 0.6
    driver = bed.start(Scripted(action), setup_of(period_s=0.1))
    bed.step()
    assert driver.ticks == 1
    steer_rad = -STEER_MAX_RAD + (action[0] + 1.0) / 2.0 * 2.0 * STEER_MAX_RAD
    speed_mps = -5.0 + (action[1] + 1.0) / 2.0 * (SPEED_MAX_MPS + 5.0)
    logic = bed.car().car.logic
    # Webots setters: steering + right (the action's + left flips), cruising speed in km/h
    assert logic.commanded_steering_angle_rad == pytest.approx(-steer_rad, abs=1e-6)
    assert logic.target_cruising_speed_kmh == pytest.approx(mps_to_kmh(speed_mps), abs=1e-4)
    # the answer: the physical action in force
    assert tuple(driver.action) == pytest.approx((steer_rad, speed_mps), abs=1e-6)


class Slowing:
    """A policy that speeds up to 8 m/s, then always asks for 3 m/s less than the car's speed."""

    def __init__(self):
        self.seen = []
        self.slowing = False

    def predict(self, obs, deterministic=True):
        forward = float(obs['twist'][0])
        self.seen.append(forward)
        self.slowing = self.slowing or forward >= 8.0
        target = forward - 3.0 if self.slowing else 10.0
        # the physical speed in the box (-5 .. SPEED_MAX_MPS) rescaled to [-1, 1]
        speed = 2.0 * (target + 5.0) / (SPEED_MAX_MPS + 5.0) - 1.0
        return np.array((0.0, speed), np.float32), None


def test_braking_speed_steering_brakes_over_the_wire_for_a_speed_well_below_the_cars(lockstep):
    from vehicle_sim.core.car.drivetrain import ControlMode
    bed = lockstep()
    policy = Slowing()
    driver = bed.start(policy, setup_of(period_s=0.1, control='braking_speed_steering'))
    logic = bed.car().car.logic
    bed.step()
    while policy.seen[-1] < 8.0:    # cruising up to 10 m/s: cruise control, no brake
        assert logic.control_mode == ControlMode.SPEED and logic.brake_intensity == 0.0
        assert logic.target_cruising_speed_kmh == pytest.approx(36.0, abs=1e-3)
        assert len(policy.seen) < 100, 'the car did not reach 8 m/s in 10 s'
        bed.step()
    # the tick that read 8 m/s or more asked for 3 m/s less: throttle 0, brake 3/5
    assert driver.ticks == len(policy.seen)
    assert logic.control_mode == ControlMode.TORQUE and logic.throttle == 0.0
    assert logic.brake_intensity == pytest.approx(0.6, abs=1e-4)
    assert logic.target_cruising_speed_kmh == pytest.approx(36.0, abs=1e-3)    # untouched
    assert tuple(driver.action) == pytest.approx((0.0, policy.seen[-1] - 3.0), abs=1e-4)
    for _ in range(5):
        bed.step()
    assert policy.seen[-1] < policy.seen[-6] - 1.5     # 0.5 s of braking: faster than 2.6 m/s^2


def test_lane_speed_steers_over_the_wire_by_the_cars_lane_state_topic(lockstep):
    from vehicle_sim.core.car.lane_keeping import lane_keeping_steering
    bed = lockstep()
    lanes = bed.auto._vehicles[0].lanes
    body = bed.car().body

    def state():       # the node's world at the tick: what core's law reads in process
        return (lanes.state.offset_m, lanes.state.heading_error_rad, body.body_twist()[0][0])
    # 1 m left of the lane's centre at 10 m/s; the policy reads only the twist, so the lane
    # state is the driver's for the law alone
    offset_asked, speed_asked = 1.0, 10.0
    action = (offset_asked / 4.0, 2.0 * speed_asked / SPEED_MAX_MPS - 1.0)
    policy = Scripted(action, state)
    setup = DriveSetup(('twist',), ObjectsTableSpec(), 'lane_speed', (-4.0, 0.0),
                       (4.0, SPEED_MAX_MPS), (-1.0, 1.0), 0.1, (-0.02, 0.02))
    driver = bed.start(policy, setup)
    assert '/lane_state' in [sub.topic_name for sub in driver._subs]
    logic = bed.car().car.logic
    steered = []
    for _ in range(80):             # 8 s
        bed.step()
        offset, heading_error, forward = policy.seen[-1][1]
        law = lane_keeping_steering(offset_asked, offset, heading_error, forward, -0.02, 0.02)
        # Webots' setter: + right
        assert logic.commanded_steering_angle_rad == pytest.approx(-law, abs=1e-6)
        steered.append(law)
    assert tuple(driver.action) == pytest.approx((offset_asked, speed_asked), abs=1e-5)
    # it steered left, then settled near the offset asked
    assert max(steered) > 0.005
    assert lanes.state.offset_m == pytest.approx(offset_asked, abs=0.1)


def test_guarded_speed_steering_caps_the_speed_over_the_wire_as_in_process(lockstep):
    # the guard reads the objects table the driver builds from the objects topic and the lane
    # state topic, though the policy reads only the twist: each tick's setters are core's for
    # the environment's table and lane state at that tick. A policy asking for 35 m/s straight
    # ahead toward a parked car 200 m down the lane (test/data/parked_car_ahead.yaml) is
    # stopped short of it.
    from vehicle_sim.core.car.drivetrain import ControlMode
    from vehicle_sim.core.learning import actions
    from vehicle_sim.core.learning.headway_guard import guard_speed
    bed = lockstep(world=PARKED_CAR_AHEAD)
    lanes = bed.auto._vehicles[0].lanes
    body = bed.car().body
    spec = ObjectsTableSpec()
    objects = ObjectsPart(bed.auto.scene, body, spec)

    def state():
        out = {}
        objects.read(out)
        forward = body.body_twist()[0][0]
        offset, heading = lanes.state.offset_m, lanes.state.heading_error_rad
        return forward, offset, heading, guard_speed(out['objects'], spec.range_m,
                                                     spec.speed_scale_mps, forward, offset,
                                                     heading)
    speed_asked = SPEED_MAX_MPS
    policy = Scripted((0.0, 1.0), state)
    setup = DriveSetup(('twist',), spec, 'guarded_speed_steering', (-STEER_MAX_RAD, 0.0),
                       (STEER_MAX_RAD, SPEED_MAX_MPS), (-1.0, 1.0), 0.1)
    driver = bed.start(policy, setup)
    topics = [sub.topic_name for sub in driver._subs]
    assert '/lane_state' in topics and '/perception/object_recognition/objects' in topics
    logic = bed.car().car.logic
    capped = braked = 0
    for _ in range(250):            # 25 s
        bed.step()
        forward, offset, heading, guard = policy.seen[-1][1]
        expected = dict(actions.LAYOUTS['guarded_speed_steering'].values(
            (0.0, speed_asked), actions.Reading(forward, offset, heading, None, guard)))
        if expected.get(actions.SET_BRAKE, 0.0) > 0.0:
            braked += 1
            assert logic.control_mode == ControlMode.TORQUE and logic.throttle == 0.0
            assert logic.brake_intensity == pytest.approx(expected[actions.SET_BRAKE], abs=1e-3)
        else:
            assert logic.brake_intensity == 0.0
            assert logic.target_cruising_speed_kmh == pytest.approx(
                expected[actions.SET_CRUISING_SPEED], abs=1e-2)
        capped += guard < speed_asked
    print(f'guard below the {speed_asked} m/s asked at {capped} of 250 ticks, braking at '
          f'{braked}; the car at {body.pose()[0]:.2f} m')
    # the guard capped the speed and braked; the car stands short of the parked car (its
    # centre at x = 220 m, the Prius's bumper 3.7 m ahead of base_link, half the box 2.25 m)
    assert capped > 50 and braked > 5
    assert abs(policy.seen[-1][1][0]) < 0.05
    assert 220.0 - 2.25 - 3.7 - 0.5 > body.pose()[0] > 220.0 - 9.0 - 0.5
    assert tuple(driver.action) == pytest.approx((0.0, speed_asked), abs=1e-5)


def test_a_policy_faster_than_the_simulation_is_refused(lockstep):
    bed = lockstep()
    with pytest.raises(InvalidParameterError, match=r'policy period 5 ms \(200 Hz\) is shorter '
                                                    r"than the simulation's basic step 10 ms"):
        bed.start(Scripted((0.0, 0.0)), setup_of(period_s=0.005))
    with pytest.raises(InvalidParameterError, match='policy period 15 ms is not a whole number '
                                                    "of the simulation's basic steps of 10 ms"):
        bed.start(Scripted((0.0, 0.0)), setup_of(period_s=0.015))
    assert check_period(1.0, 10) == 100


def test_topics_that_do_not_arrive_end_the_driver_naming_them(lockstep):
    # the highway without traffic: no objects are published
    bed = lockstep(world='highway', timeout_s=2.0)
    driver = bed.start(Scripted((0.0, 0.0)), setup_of())
    for _ in range(10):         # the first answer is due at 0.1 s: no objects then
        bed.auto.step_once()
    assert wait_for(lambda: driver.error, WAIT_S, bed)
    assert driver.answers == 0
    assert driver.error == ('at /clock 0.100 s: waited 2 s for '
                            '/perception/object_recognition/objects stamped 0.100 s (none '
                            'received)')
    assert driver.ticks == 0 and bed.car().car.logic.target_cruising_speed_kmh == 0.0


def test_a_node_running_ahead_of_the_policy_is_driven_from_its_newest_messages(lockstep):
    # A node running in real time does not wait for the policy: by the time the policy reads
    # a tick's /clock, the node's odometry, lane state and objects are stamped later. The
    # driver reads those instead of waiting for the tick's own until its timeout.
    bed = lockstep(timeout_s=3.0)
    policy = Scripted((0.0, 0.5))
    driver = bed.start(policy, setup_of(period_s=0.2))
    for _ in range(6):
        for _ in range(5 * driver.answer_steps):     # half a second on, no answer awaited
            bed.auto.step_once()
            bed.auto.node.spin_once(0.0)
        before = driver.ticks
        assert wait_for(lambda: driver.ticks > before or driver.error, WAIT_S, bed)
        assert driver.error is None, driver.error
    assert driver.ticks >= 6 and len(policy.seen) >= 6
    speed_kmh = mps_to_kmh(-5.0 + 0.75 * (SPEED_MAX_MPS + 5.0))   # 0.5 of [-1, 1] in the box
    assert bed.car().car.logic.target_cruising_speed_kmh == pytest.approx(speed_kmh)


def test_a_car_that_is_not_there_is_named(lockstep):
    bed = lockstep(namespace='nope', timeout_s=1.0)
    with pytest.raises(InvalidParameterError, match=r'no automobile node serves '
                                                    r'/nope/automobile/set_steering_angle, '
                                                    r'/nope/automobile/set_cruising_speed'):
        bed.start(Scripted((0.0, 0.0)), setup_of())


def test_the_docs_show_the_drivers_topics():
    from pathlib import Path

    from vehicle_sim.ros.policy_interfaces import policy_table_markdown
    docs = Path(__file__).resolve().parent.parent / 'docs'
    assert policy_table_markdown() in (docs / 'ros_interface.md').read_text(encoding='utf-8')
    learning = (docs / 'learning.md').read_text(encoding='utf-8')
    assert '## The policy drives the ROS node' in learning


def test_the_action_writer_undoes_rescale_action_and_checks_the_box():
    import gymnasium
    from gymnasium.wrappers.utils import rescale_box

    from vehicle_sim.ros.policy_actions import ActionWriter
    low, high = np.array((-0.5, -5.0), np.float32), np.array((0.5, 35.0), np.float32)
    _, _, physical = rescale_box(gymnasium.spaces.Box(low, high), np.float32(-1.0),
                                 np.float32(1.0))
    writer = ActionWriter('speed_steering', low, high)
    for action in ((-1.0, -1.0), (1.0, 1.0), (0.3, -0.7), (-0.25, 0.5)):
        action = np.array(action, np.float32)
        assert np.array_equal(writer.physical(action), physical(action).astype(np.float64))
    steer, speed = writer.physical(np.array((0.3, -0.7), np.float32))
    assert writer.commands(np.array((0.3, -0.7), np.float32)) == [
        ('automobile/set_steering_angle', pytest.approx(-steer)),
        ('automobile/set_cruising_speed', pytest.approx(speed * 3.6))]
    with pytest.raises(ValueError, match=r'action\[0\] \(steering_angle\) = 0.75 rad: outside '
                                         r'\[-0.5, 0.5\]'):
        writer.physical(np.array((1.5, 0.0), np.float32))
    with pytest.raises(InvalidParameterError, match="control 'twist': the automobile node is "
                                                    'driven by speed_steering, '
                                                    'braking_speed_steering, '
                                                    'guarded_speed_steering, '
                                                    'lane_speed, throttle_steering'):
        ActionWriter('twist', low, high)


def test_the_braking_writer_brakes_or_cruises_by_the_cars_forward_speed():
    from vehicle_sim.ros.policy_actions import ActionWriter
    low, high = np.array((-0.5, -5.0), np.float32), np.array((0.5, 35.0), np.float32)
    writer = ActionWriter('braking_speed_steering', low, high)
    assert writer.services == ('automobile/set_steering_angle', 'automobile/set_cruising_speed',
                               'automobile/set_throttle', 'automobile/set_brake_intensity')
    action = np.array((0.2, 0.0), np.float32)           # 0.1 rad left, 15 m/s
    steer, speed = writer.physical(action)
    assert speed == pytest.approx(15.0)
    # the car at 17 m/s: 2 m/s too fast -> throttle 0, brake 2/5
    assert writer.commands(action, 17.0) == [
        ('automobile/set_steering_angle', pytest.approx(-steer)),
        ('automobile/set_throttle', 0.0), ('automobile/set_brake_intensity', pytest.approx(0.4))]
    # 10 m/s too fast: full brake; 0.5 m/s too fast or slower: the cruise control
    assert writer.commands(action, 25.0)[2] == ('automobile/set_brake_intensity', 1.0)
    for forward in (15.5, 15.0, 3.0, 0.0):
        assert writer.commands(action, forward) == [
            ('automobile/set_steering_angle', pytest.approx(-steer)),
            ('automobile/set_brake_intensity', 0.0),
            ('automobile/set_cruising_speed', pytest.approx(15.0 * 3.6))]
    with pytest.raises(ValueError, match=r'action\[1\] \(speed\) = 55.0 m/s: outside '
                                         r'\[-5, 35\]'):
        writer.commands(np.array((0.0, 2.0), np.float32), 10.0)
