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
Scripted actors: vehicles that follow waypoints at given speeds, with pure pursuit.

A car actor drives through its own CarLogic, as any car: the cruising speed (SPEED mode) and the
steering angle, the one from pure pursuit (Coulter 1992: δ = atan(2 L sin α / L_d), α the angle
of the aim point seen from the rear axle, L_d its distance), limited to the car's steering range
by the follower (the follower's choice, not an input clamp). A robot actor gets the same
curvature κ = 2 sin α / L_d as wheel speeds v ∓ κ v t / 2. After the last waypoint (unless it
loops) the vehicle stops: core/car/speed_braking.py's full_stop (full brake, the throttle
released: the Prius slows at about 5 m/s^2) for a car, zero wheel speeds for a robot.

With ``speed_control: idm`` (the default; :class:`IdmSpeed`) the waypoint's speed is the
desired speed of the improved Intelligent Driver Model (IIDM, core/traffic/idm.py's
iidm_acceleration) behind the nearest vehicle ahead within the actor's width (traffic vehicles
and the scenario's other vehicles): the actor slows down and stops behind it as traffic does;
IIDM asks at most the comfortable deceleration b to slow down to a lower waypoint speed (IDM
would ask a slam on the brakes there). While IIDM asks no more deceleration than the car's
cruise control gives, its ramp (100 km/h) / time0To100 (2.6 m/s^2 for the Prius), the cruise
control takes IIDM's speed IDM_HORIZON_S ahead (and approaches it at up to its ramp); beyond,
the car brakes as a driver presses the brake pedal: the throttle released (cruise control off)
and the brake at deceleration / full-brake deceleration (core/car/speed_braking.py's
brake_for_deceleration; the Prius at full brake: 4.8 m/s^2). ``speed_control: waypoints``
drives the waypoints' speeds whatever is ahead.

:func:`make_actors` tells the world's traffic where each actor will drive (its path from where it
stands through its waypoints): the SUMO engine gives the actor's vehicle in SUMO the route of the
edges the path passes (docs/sumo_engine.md), so that SUMO's drivers know where it will turn.
"""

import math

from vehicle_sim.core.car.speed_braking import (
    brake_for_deceleration,
    cruise_ramp_mps2,
    full_brake_deceleration_mps2,
    full_stop,
)
from vehicle_sim.core.geometry.angles import yaw_from_quaternion
from vehicle_sim.core.specs.units import mps_to_kmh, ros_steering_to_webots
from vehicle_sim.core.traffic.idm import IdmParams, iidm_acceleration

# The aim point moves on once the vehicle is this close to it (its look-ahead), and the last
# waypoint counts as reached within ARRIVE_M or one wheelbase (a robot: its tread), the smaller.
ARRIVE_M = 1.0
LOOKAHEAD_TIME_S = 1.0
# IDM speed control: the speed asked for is the speed IIDM reaches after this time [s] (a car
# brakes instead where IIDM asks more deceleration than its cruise control gives).
IDM_HORIZON_S = 0.5
LEADER_RANGE_M = 250.0


class IdmSpeed:
    """
    The improved Intelligent Driver Model's speed for an actor behind whatever drives ahead.

    :param outline: the actor's footprint (core Outline) in its base_link frame.
    :param others: ``others()`` -> [(name, x, y, yaw, length, width, speed)] of the vehicles
        around (box centres, speed along their heading), the actor's own left out.
    :param params: IdmParams (the traffic's, or the defaults).
    """

    def __init__(self, outline, others, params=None):
        self.outline = outline
        self.others = others
        self.params = params or IdmParams()

    def leader(self, x_m, y_m, yaw_rad):
        """Return (bumper gap [m], speed [m/s]) of the nearest vehicle ahead, or None."""
        c, s = math.cos(yaw_rad), math.sin(yaw_rad)
        outline = self.outline
        best = None
        for _, x, y, yaw, length, width, speed in self.others():
            dx, dy = x - x_m, y - y_m
            ahead, side = c * dx + s * dy, -s * dx + c * dy
            if ahead <= 0.0 or ahead > LEADER_RANGE_M:
                continue
            turn = yaw - yaw_rad
            across = 0.5 * (abs(math.sin(turn)) * length + abs(math.cos(turn)) * width)
            if side - across >= outline.y_max_m or side + across <= outline.y_min_m:
                continue
            along = 0.5 * (abs(math.cos(turn)) * length + abs(math.sin(turn)) * width)
            gap = ahead - along - outline.x_max_m
            if best is None or gap < best[0]:
                best = (gap, speed * math.cos(turn))
        return best

    def acceleration(self, x_m, y_m, yaw_rad, speed_mps, desired_mps):
        """Return IIDM's acceleration [m/s^2] toward ``desired_mps`` (>= 0) behind the leader."""
        found = self.leader(x_m, y_m, yaw_rad)
        speed = max(speed_mps, 0.0)
        desired = max(desired_mps, 0.0)
        if found is None:
            return iidm_acceleration(speed, desired, None, 0.0, self.params)
        gap, leader_speed = found
        return iidm_acceleration(speed, desired, gap, speed - leader_speed, self.params)

    @staticmethod
    def speed_after(speed_mps, acceleration_mps2, desired_mps):
        """Return the speed [m/s] to ask for: after IDM_HORIZON_S, within 0 .. desired."""
        speed = max(speed_mps, 0.0) + acceleration_mps2 * IDM_HORIZON_S
        return min(max(speed, 0.0), max(desired_mps, 0.0))

    def speed(self, x_m, y_m, yaw_rad, speed_mps, desired_mps):
        """Return the speed [m/s] to ask for: IIDM's after IDM_HORIZON_S, within 0 .. desired."""
        return self.speed_after(speed_mps, self.acceleration(x_m, y_m, yaw_rad, speed_mps,
                                                              desired_mps), desired_mps)


class WaypointFollower:
    """
    Pure pursuit over a waypoint list (ROS-free, PyBullet-free).

    :param spec: the ActorSpec (waypoints, look-ahead, loop).
    :param wheelbase_m: L for the steering angle [m].
    """

    def __init__(self, spec, wheelbase_m):
        self.spec = spec
        self.wheelbase_m = float(wheelbase_m)
        self.index = 0
        self.done = False

    def lookahead_m(self, speed_mps):
        """Return the look-ahead distance [m] at a speed."""
        if self.spec.lookahead_m > 0.0:
            return self.spec.lookahead_m
        return max(2.0 * self.wheelbase_m, abs(speed_mps) * LOOKAHEAD_TIME_S)

    def command(self, x_m, y_m, yaw_rad):
        """
        Return (speed [m/s], curvature [1/m], + = left) towards the current aim point, or None.

        :param x_m: rear-axle (base_link) x in the world [m].
        :param y_m: its y [m].
        :param yaw_rad: heading [rad].
        :return: None once the last waypoint is reached (and it does not loop).
        """
        points = self.spec.waypoints
        if self.done:
            return None
        while True:
            target = points[self.index]
            distance = math.hypot(target.x_m - x_m, target.y_m - y_m)
            last = self.index == len(points) - 1 and not self.spec.loop
            reach = (min(ARRIVE_M, self.wheelbase_m) if last
                     else self.lookahead_m(target.speed_mps))
            if distance > reach:
                break
            if last:
                self.done = True
                return None
            self.index = (self.index + 1) % len(points)
            if self.index == 0 and len(points) == 1:
                break
        alpha = math.atan2(target.y_m - y_m, target.x_m - x_m) - yaw_rad
        curvature = 2.0 * math.sin(alpha) / max(distance, 1e-6)
        return target.speed_mps, curvature


class CarActor:
    """
    A car following waypoints through its CarLogic (cruising speed and steering angle).

    :param spec: ActorSpec.
    :param car: SimulatedCar.
    """

    def __init__(self, spec, car, idm=None):
        self.car = car
        self.idm = idm if spec.speed_control == 'idm' else None
        logic = car.logic
        self.follower = WaypointFollower(spec, logic.wheelbase_m)
        self._limits = (logic.min_steering_angle_rad, logic.max_steering_angle_rad)
        self._ramp_mps2 = cruise_ramp_mps2(logic.params)
        self._full_brake_mps2 = full_brake_deceleration_mps2(logic.params)
        logic.set_brake_intensity(0.0)

    def control(self):
        """Set the car's commands for the coming step."""
        logic = self.car.logic
        x, y, _, qx, qy, qz, qw = self.car.body.pose()
        yaw = yaw_from_quaternion(qx, qy, qz, qw)
        command = self.follower.command(x, y, yaw)
        if command is None:
            full_stop(logic)
            return
        speed, curvature = command
        steer = ros_steering_to_webots(math.atan(curvature * self.follower.wheelbase_m))
        low, high = self._limits
        logic.set_steering_angle(min(max(steer, low), high))
        if self.idm is not None:
            now = self.car.body.forward_speed_mps()
            acc = self.idm.acceleration(x, y, yaw, now, speed)
            brake = brake_for_deceleration(-acc, self._ramp_mps2, self._full_brake_mps2)
            if brake > 0.0:     # beyond the cruise control's ramp: the brake pedal instead
                logic.set_throttle(0.0)
                logic.set_brake_intensity(brake)
                return
            speed = self.idm.speed_after(now, acc, speed)
            logic.set_brake_intensity(0.0)
        logic.set_cruising_speed_kmh(mps_to_kmh(speed))


class RobotActor:
    """
    A differential robot following waypoints (wheel speeds from speed and curvature).

    :param spec: ActorSpec.
    :param robot: DiffRobotBody.
    """

    def __init__(self, spec, robot, idm=None):
        self.robot = robot
        self.idm = idm if spec.speed_control == 'idm' else None
        params = robot.params
        self._tread = params.wheel_tread_m
        self._radius = params.wheel_radius_m
        self.follower = WaypointFollower(spec, params.wheel_tread_m)

    def control(self):
        """Set the robot's wheel speeds for the coming step."""
        x, y, _, qx, qy, qz, qw = self.robot.pose()
        yaw = yaw_from_quaternion(qx, qy, qz, qw)
        command = self.follower.command(x, y, yaw)
        if command is None:
            self.robot.set_wheel_velocities(0.0, 0.0)
            return
        speed, curvature = command
        if self.idm is not None:
            speed = self.idm.speed(x, y, yaw, self.robot.forward_speed_mps(), speed)
        half = curvature * speed * self._tread / 2.0
        self.robot.set_wheel_velocities((speed - half) / self._radius,
                                        (speed + half) / self._radius)


def vehicles_around(vehicles, name, traffic=None):
    """
    Return ``others()`` for the IdmSpeed of actor ``name``: the boxes of the vehicles around.

    :param vehicles: {name: VehicleHandle} of the scenario (the actor's own left out).
    :param traffic: the world's traffic (physics TrafficBodies), or None.
    :return: a callable giving [(name, x, y, yaw, length, width, speed)] now (box centres).
    """
    handles = [(other, handle, handle.outline) for other, handle in vehicles.items()
               if other != name]

    def others():
        found = []
        for other, handle, outline in handles:
            x, y, _, qx, qy, qz, qw = handle.body.pose()
            yaw = yaw_from_quaternion(qx, qy, qz, qw)
            cx = 0.5 * (outline.x_min_m + outline.x_max_m)
            cy = 0.5 * (outline.y_min_m + outline.y_max_m)
            c, s = math.cos(yaw), math.sin(yaw)
            found.append((other, x + c * cx - s * cy, y + s * cx + c * cy, yaw,
                          outline.length_m, outline.width_m, handle.body.forward_speed_mps()))
        if traffic is not None:
            found += traffic.agents()
        return found
    return others


def make_actors(specs, vehicles, traffic=None):
    """
    Return the actors of ActorSpecs (:func:`make_actor`), the traffic told where each will drive.

    The world's traffic hears of each actor's path (:func:`actor_path`,
    ``traffic.expect_path``): the SUMO engine gives the actor's vehicle in SUMO the route of
    the edges its waypoints pass, so that SUMO's drivers know where it will turn.
    """
    actors = [make_actor(spec, vehicles, traffic) for spec in specs]
    if traffic is not None:
        for spec in specs:
            traffic.expect_path(spec.vehicle, actor_path(spec, vehicles))
    return actors


def actor_path(spec, vehicles):
    """
    Return the path an actor will drive: [(x, y)] from where its vehicle is, its waypoints on.

    A looping actor's path goes round once, back to its first waypoint.

    :param spec: the ActorSpec.
    :param vehicles: {name: VehicleHandle} of the scenario.
    """
    x, y = vehicles[spec.vehicle].body.pose()[:2]
    points = [(x, y)] + [(p.x_m, p.y_m) for p in spec.waypoints]
    if spec.loop:
        points.append(points[1])
    return points


def make_actor(spec, vehicles, traffic=None):
    """
    Return the CarActor or RobotActor of an ActorSpec, with its IdmSpeed.

    The IdmSpeed is used when the actor's ``speed_control`` is idm (the default).

    :param spec: the ActorSpec.
    :param vehicles: {name: VehicleHandle} of the scenario.
    :param traffic: the world's traffic (physics TrafficBodies), or None: its vehicles count as
        leaders and its IDM parameters are the actor's (the defaults without traffic).
    """
    handle = vehicles[spec.vehicle]
    idm = IdmSpeed(handle.outline, vehicles_around(vehicles, spec.vehicle, traffic),
                   None if traffic is None else traffic.follow_params)
    return (CarActor(spec, handle.car, idm) if handle.is_car
            else RobotActor(spec, handle.body, idm))
