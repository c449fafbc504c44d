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
A Webots-style highway controller that overtakes slower cars (distance sensors only).

Behaves as Webots' highway_overtake sample controller does: the distance sensor ahead sets the
speed (slower the closer the car ahead), and once a car ahead is within OVERTAKE_RATIO of its
range the controller looks at a neighbouring lane (left first): its three front sensors on that
side, the side sensor and the rear sensor must all read free, and there must be a lane there.
It then moves over with the steering and, once the car it passed is behind it and its home lane
is free again (or that lane has been free for COME_BACK_AFTER_S), comes back. The sensors are
Webots' highway car's (``distance sensor front``, ``... front left 0..2``, ``... front right
0..2``, ``... left``, ``... right``, ``... rear left``, ``... rear right``), returning metres
(no lookup table).

Webots' sample keeps its lane with a PID on the GPS's lateral coordinate of a straight road;
this one keeps its lane on any road with ``Driver.getLaneState()`` (our addition: the lateral
offset from the lane's centreline and the heading error), so in Webots replace the lane state by
the GPS and the lane positions of the world. On vehicle_sim::

    vehicle-sim scenario scenarios/highway_overtake.yaml

runs it on the highway with slower traffic cars ahead (docs/traffic.md).
"""

import math

from vehicle_sim.webots import Driver

MAX_SPEED_KMH = 100.0
LANES = 3                    # lanes of the carriageway: 0 = the right lane
HOME_LANE = 1                # the lane it starts in and comes back to
OVERTAKE_RATIO = 0.8         # a car ahead within this share of the front range: overtake
FREE_RATIO = 0.95            # a sensor reading above this share of its range: free
LANE_CHANGE_SPEED_MPS = 1.2  # lateral speed of the moving lane target
STEER_GAIN = 0.6             # Stanley gain: lateral error [m] -> lateral speed [m/s]
MAX_STEERING_RAD = 0.08
BRAKE_ABOVE_KMH = 5.0        # brake when this much faster than wanted
CUT_IN_M = 4.0               # a front corner sensor closer than this: a car cuts in, slow down
COME_BACK_AFTER_S = 6.0      # back to the home lane once its side was free this long [s]

SIDES = ('left', 'right')

driver = Driver()
time_step = int(driver.getBasicTimeStep())
sensors = {}
for name in ('front', 'left', 'right', 'rear left', 'rear right') + tuple(
        f'front {side} {i}' for side in SIDES for i in range(3)):
    sensors[name] = driver.getDevice('distance sensor ' + name)
    sensors[name].enable(5 * time_step)


def free(name):
    """Return True when the sensor sees nothing within FREE_RATIO of its range."""
    value = sensors[name].getValue()
    return math.isnan(value) or value > FREE_RATIO * sensors[name].getMaxValue()


def side_free(side):
    """Return True when the neighbouring lane on ``side`` is free: ahead, beside and behind."""
    names = [f'front {side} {i}' for i in range(3)] + [side, f'rear {side}']
    return all(free(name) for name in names)


lane = HOME_LANE             # the lane the car is on (counted as it crosses lane lines)
target_lane = HOME_LANE      # the lane it wants to be on
target_offset = 0.0          # the moving lateral target from the current lane's centre [m]
last = None                  # the lane state of the step before
passing = False              # off the home lane: a car seen beside on the home side
free_since = None            # off the home lane: since when the home side is free [s]
step = 0
while driver.step() != -1:
    step += 1
    state = driver.getLaneState()
    if state is None or not state.on_lane:
        driver.setCruisingSpeed(0.0)
        driver.setBrakeIntensity(1.0)
        continue
    if last is not None and state.lane_id != last.lane_id:
        jump = state.offset_m - last.offset_m
        if abs(jump) > 0.5 * state.width_m:      # a lane line crossed (not a segment's end)
            moved = -1 if jump > 0 else 1            # offsets are + left: -width = moved left
            lane += moved
            target_offset -= moved * state.width_m
    last = state

    # speed: slower the closer the car ahead (as Webots' sample)
    front = sensors['front'].getValue()
    front_range = sensors['front'].getMaxValue()
    if math.isnan(front):
        front = front_range
    speed = MAX_SPEED_KMH * min(1.0, front / front_range)
    if min(sensors[f'front {side} 2'].getValue() for side in SIDES) < CUT_IN_M:
        speed = min(speed, 0.5 * MAX_SPEED_KMH)       # a car cutting in at a front corner

    # overtake: a car ahead and a free lane beside (left first)
    home_side = None if lane == HOME_LANE else ('right' if lane > HOME_LANE else 'left')
    if target_lane == lane and front < OVERTAKE_RATIO * front_range:
        if lane < LANES - 1 and side_free('left'):
            target_lane, passing, free_since = lane + 1, False, None
        elif lane > 0 and side_free('right'):
            target_lane, passing, free_since = lane - 1, False, None
    # come back once the car passed (seen beside, on the home side) is behind and that side is
    # free, or once that side has been free for COME_BACK_AFTER_S (the slow car went elsewhere)
    elif target_lane == lane and home_side is not None:
        if not free(home_side):
            passing = True
        if not side_free(home_side):
            free_since = None
        elif free_since is None:
            free_since = driver.getTime()
        if free_since is not None and (
                passing or driver.getTime() - free_since >= COME_BACK_AFTER_S):
            target_lane = lane - 1 if home_side == 'right' else lane + 1
            passing, free_since = False, None

    # the lane target moves over at LANE_CHANGE_SPEED_MPS; steer to it (Stanley's law)
    wanted = (target_lane - lane) * state.width_m
    dt = time_step / 1000.0
    target_offset += max(-LANE_CHANGE_SPEED_MPS * dt,
                         min(LANE_CHANGE_SPEED_MPS * dt, wanted - target_offset))
    now = max(driver.getCurrentSpeed() / 3.6, 1.0)
    error = state.offset_m - target_offset                  # + = left of the target
    steering = state.heading_error_rad + math.atan2(STEER_GAIN * error, now)
    driver.setSteeringAngle(max(-MAX_STEERING_RAD, min(MAX_STEERING_RAD, steering)))

    excess = driver.getCurrentSpeed() - speed
    if excess > BRAKE_ABOVE_KMH:    # the cruise control slows too gently: brake
        driver.setCruisingSpeed(0.0)
        driver.setBrakeIntensity(min(1.0, excess / 30.0))
    else:
        driver.setBrakeIntensity(0.0)
        driver.setCruisingSpeed(speed)
    if step % 100 == 0:
        print(f't={driver.getTime():5.2f} s  speed={driver.getCurrentSpeed():6.2f} km/h  '
              f'front={front:6.2f} m  lane={lane} target={target_lane} '
              f'offset={state.offset_m:+.2f} m')
