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
End-to-end scenario: a scripted Autoware command stream, its bicycle reference, and the runner.

The stream (a function of simulated time) is straight -> constant-curvature arc (left) ->
S-curve -> silence (no commands: the watchdogs act) -> stop (v = 0 commands) -> end. It drives

- the caster robot and the skid-steer robot through the ``ackermann_to_differential`` bridge
  (:class:`~vehicle_sim.ros.bridge_node.AckermannToDifferentialNode`), both robot nodes
  (:class:`~vehicle_sim.ros.diff_robot_node.DiffRobotNode`) sharing ONE World;
- a car through the ``autoware_automobile`` node (its own World, stepped in lockstep).

Everything runs in-process on simulated time: messages are built with the nodes' own types and
handed to the nodes' in-process API with the sim time as receipt time (the node-to-node links
are direct calls), so a run is deterministic. The reference is the kinematic bicycle
(ẋ = v cos ψ, ẏ = v sin ψ, ψ̇ = v tan δ / L) integrated from the commands AS APPLIED: for the
robots the bridge's applied (v, ω) after its ramps, wheel-speed limit and watchdog (δ_applied =
atan(ω L / v)); for the car the cruising speed the node set on the car, ramped at the car's
acceleration (time0To100), and after the watchdog's safety stop (throttle released, full brake)
the speed falling at the car's full-brake deceleration, with the commanded steering.
docs/end_to_end.md has the figures.
"""

from dataclasses import dataclass, field
import math
from typing import Callable, List, Optional, Sequence, Tuple

from vehicle_sim.core.car.drivetrain import ControlMode
from vehicle_sim.core.car.speed_braking import cruise_ramp_mps2, full_brake_deceleration_mps2
from vehicle_sim.core.diffdrive.kinematics import integrate_pose
from vehicle_sim.core.diffdrive.speed_limiter import SpeedLimiter
from vehicle_sim.core.geometry.angles import wrap_angle_rad, yaw_from_quaternion
from vehicle_sim.core.specs.simulation import TIME_STEP_MS
from vehicle_sim.core.specs.units import kmh_to_mps

DT_S = TIME_STEP_MS.default / 1000.0   # basic time step [s]: the nodes' default
COMMAND_PERIOD_S = 0.020     # Autoware control command period [s] (50 Hz)
BRIDGE_CONTROL_RATE_HZ = 50.0
COMMAND_TIMEOUT_S = 0.5
# Scenario speeds and steering: modest, within every limit.
ROBOT_SPEED_MPS, ROBOT_STEER_RAD = 0.8, 0.35
CAR_SPEED_MPS, CAR_STEER_RAD = 4.0, 0.2
ROBOTS = ('caster_robot', 'skid_steer_robot')
DEFAULT_CAR = 'ToyotaPrius'
# Lateral spacing of the robots in their shared world [m] (they must not meet).
ROBOT_SPACING_M = 20.0


@dataclass(frozen=True)
class Segment:
    """
    One part of the stream.

    :param name: label.
    :param duration_s: length [s].
    :param command: ``command(t_local_s) -> (speed [m/s], steering tire angle [rad, + left])``,
        or None for silence (no command is sent).
    """

    name: str
    duration_s: float
    command: Optional[Callable[[float], Tuple[float, float]]]


@dataclass(frozen=True)
class CommandStream:
    """A sequence of segments; ``command_at(t)`` gives the command due at sim time t."""

    segments: Tuple[Segment, ...]

    @property
    def duration_s(self):
        return sum(s.duration_s for s in self.segments)

    def segment_at(self, time_s):
        """Return (segment, start time [s]) at ``time_s``; None after the end."""
        start = 0.0
        for segment in self.segments:
            if time_s < start + segment.duration_s - 1e-9:
                return segment, start
            start += segment.duration_s
        return None

    def command_at(self, time_s):
        """Return (speed [m/s], steering [rad]) due at ``time_s``, or None (silence / end)."""
        found = self.segment_at(time_s)
        if found is None or found[0].command is None:
            return None
        segment, start = found
        return segment.command(time_s - start)

    def bounds(self, name):
        """Return (start, end) [s] of the first segment called ``name``."""
        start = 0.0
        for segment in self.segments:
            if segment.name == name:
                return start, start + segment.duration_s
            start += segment.duration_s
        raise KeyError(name)


def autoware_stream(speed_mps, steer_rad, straight_s=3.0, arc_s=4.0, s_curve_s=6.0,
                    silence_s=1.0, stop_s=2.0):
    """
    Build the scenario: straight, left arc, S-curve, silence, stop.

    :param speed_mps: cruise speed [m/s].
    :param steer_rad: arc steering tire angle [rad] (+ left); the S-curve peaks at 0.8 of it.
    :return: CommandStream.
    """
    amplitude = 0.8 * steer_rad

    def s_curve(t_s):
        return speed_mps, amplitude * math.sin(2.0 * math.pi * t_s / s_curve_s)

    return CommandStream((
        Segment('straight', straight_s, lambda t: (speed_mps, 0.0)),
        Segment('arc', arc_s, lambda t: (speed_mps, steer_rad)),
        Segment('s_curve', s_curve_s, s_curve),
        Segment('silence', silence_s, None),
        Segment('stop', stop_s, lambda t: (0.0, 0.0)),
    ))


def constant_stream(speed_mps, steer_rad, duration_s):
    """Return a stream holding one command for ``duration_s`` (saturation checks)."""
    return CommandStream((Segment('constant', duration_s, lambda t: (speed_mps, steer_rad)),))


def bicycle_reference(applied, wheel_base_m, dt_s, start=(0.0, 0.0, 0.0)):
    """
    Integrate the kinematic bicycle over the applied commands.

    ẋ = v cos ψ, ẏ = v sin ψ, ψ̇ = v tan δ / L; each (v, δ) is held for one ``dt_s`` and
    integrated exactly (circular arc, ``integrate_pose``).

    :param applied: sequence of (v [m/s], δ [rad, + left]) per step, as applied.
    :param wheel_base_m: L [m].
    :param dt_s: step [s].
    :param start: initial (x [m], y [m], ψ [rad]).
    :return: list of (x, y, ψ), one more than ``applied`` (the start first).
    """
    pose = tuple(start)
    poses = [pose]
    for speed_mps, steer_rad in applied:
        pose = integrate_pose(*pose, speed_mps, speed_mps * math.tan(steer_rad) / wheel_base_m,
                              dt_s)
        poses.append(tuple(pose))
    return poses


@dataclass
class EndToEndTrack:
    """What one vehicle did: times, ground truth, reference, wheel speeds, applied commands."""

    name: str
    wheel_base_m: float
    time_s: List[float] = field(default_factory=list)
    pose: List[Tuple[float, float, float]] = field(default_factory=list)      # ground truth
    reference: List[Tuple[float, float, float]] = field(default_factory=list)
    applied: List[Tuple[float, float]] = field(default_factory=list)         # (v, δ) per step
    wheel_time_s: List[float] = field(default_factory=list)
    wheel_speeds: List[Tuple[float, ...]] = field(default_factory=list)
    wheel_labels: Tuple[str, ...] = ()
    wheel_unit: str = 'm/s'
    commanded_yaw_rate: List[float] = field(default_factory=list)
    measured_yaw_rate: List[float] = field(default_factory=list)
    last_command_s: Optional[float] = None
    command_times_s: List[float] = field(default_factory=list)
    zero_after_silence_s: Optional[float] = None
    silence_start_s: Optional[float] = None

    def distance_m(self):
        """Arc length of the reference path up to each sample [m]."""
        out, total = [0.0], 0.0
        for (x0, y0, _), (x1, y1, _) in zip(self.reference, self.reference[1:]):
            total += math.hypot(x1 - x0, y1 - y0)
            out.append(total)
        return out

    def errors_m(self):
        """|p_gt(t) − p_ref(t)| at each sample [m]."""
        return [math.hypot(a[0] - b[0], a[1] - b[1]) for a, b in zip(self.pose, self.reference)]

    def error_ratio(self, fraction, floor_m):
        """
        Return max over t of |p_gt(t) − p_ref(t)| / max(fraction · distance(t), floor_m).

        <= 1 means the path stayed within ``fraction`` of the distance travelled (with an
        absolute floor for t near 0).
        """
        return max(e / max(fraction * d, floor_m)
                   for e, d in zip(self.errors_m(), self.distance_m()))

    def max_error_fraction(self, min_distance_m):
        """Return max |p_gt − p_ref| / distance(t) over the samples with distance >= min."""
        return max((e / d for e, d in zip(self.errors_m(), self.distance_m())
                    if d >= min_distance_m), default=0.0)

    def end_error_m(self):
        return self.errors_m()[-1]

    def watchdog_delay_s(self):
        """Return (zero command time − last command before the silence) [s], or None."""
        if self.silence_start_s is None or self.zero_after_silence_s is None:
            return None
        last = max(t for t in self.command_times_s if t < self.silence_start_s)
        return self.zero_after_silence_s - last

    def yaw_efficiency(self, start_s, end_s):
        """Measured heading change / commanded (reference) heading change over [start, end]."""
        i0 = min(range(len(self.time_s)), key=lambda i: abs(self.time_s[i] - start_s))
        i1 = min(range(len(self.time_s)), key=lambda i: abs(self.time_s[i] - end_s))
        measured = _unwrap([p[2] for p in self.pose[i0:i1 + 1]])
        reference = _unwrap([p[2] for p in self.reference[i0:i1 + 1]])
        return (measured[-1] - measured[0]) / (reference[-1] - reference[0])


def _unwrap(angles):
    out = [angles[0]]
    for angle in angles[1:]:
        delta = wrap_angle_rad(angle - out[-1])
        out.append(out[-1] + delta)
    return out


def _due(time_s, period_s):
    return abs(time_s / period_s - round(time_s / period_s)) < 1e-6


def _control_msg(node, msg_type, speed_mps, steer_rad):
    msg = node.msg(msg_type)()
    msg.longitudinal.velocity = speed_mps
    msg.lateral.steering_tire_angle = steer_rad
    return msg


@dataclass
class _RobotRig:
    robot: object
    bridge: object
    track: EndToEndTrack
    last_tick_s: Optional[float] = None


def run_robots(stream, robots=ROBOTS, bridge_overrides=None, transport='dds',
               record_every=5):
    """
    Drive robots through bridges with a stream, all robots in ONE shared World.

    :param stream: CommandStream.
    :param robots: robot presets (config/robots); each gets its own bridge with wheel_base =
        wheel_tread = the preset's tread, wheel_radius from the preset.
    :param bridge_overrides: extra bridge parameters for every bridge.
    :param transport: transport of the nodes (they are driven in-process, never spun).
    :param record_every: record wheel speeds every n steps.
    :return: {preset: EndToEndTrack}.
    """
    from vehicle_sim.core.geometry.geodesy import GeodeticOrigin
    from vehicle_sim.core.world.params import WorldSpec
    from vehicle_sim.physics.scene import build_scene
    from vehicle_sim.ros import autoware_interfaces as awi
    from vehicle_sim.ros.bridge_node import AckermannToDifferentialNode
    from vehicle_sim.ros.diff_robot_node import DiffRobotNode

    # An empty world the robot nodes fill (each through the scene builder).
    world = build_scene(WorldSpec(GeodeticOrigin(), (), ()), time_step_s=DT_S).world
    rigs = []
    try:
        for index, preset in enumerate(robots):
            y_m = -ROBOT_SPACING_M * index
            robot = DiffRobotNode([], world=world, transport=transport,
                                  parameter_overrides={'robot': preset, 'y': y_m,
                                                       'synchronous': True},
                                  node_name=preset)
            params = robot.params
            overrides = {'wheel_base': params.wheel_tread_m, 'wheel_tread': params.wheel_tread_m,
                         'wheel_radius': params.wheel_radius_m,
                         'command_timeout_s': COMMAND_TIMEOUT_S,
                         'control_rate_hz': BRIDGE_CONTROL_RATE_HZ, 'use_sim_time': True,
                         'publish_wheel_velocities': False}
            overrides.update(bridge_overrides or {})
            bridge = AckermannToDifferentialNode([], transport=transport,
                                                 parameter_overrides=overrides,
                                                 node_name=f'bridge_{preset}_e2e')
            track = EndToEndTrack(preset, params.wheel_tread_m,
                                  wheel_labels=('left', 'right'), wheel_unit='m/s')
            track.silence_start_s = _bounds_or_none(stream, 'silence')
            rigs.append(_RobotRig(robot, bridge, track))
        for rig in rigs:
            _record_pose(rig.track, world.time_s, rig.robot.robot.pose())
        steps = int(round(stream.duration_s / DT_S))
        for step in range(steps):
            now_s = world.time_s
            command = stream.command_at(now_s) if _due(now_s, COMMAND_PERIOD_S) else None
            for rig in rigs:
                _robot_control(rig, command, now_s, awi.CONTROL)
            world.step()
            for rig in rigs:
                robot = rig.robot.robot
                track = rig.track
                _record_pose(track, world.time_s, robot.pose())
                linear, angular = robot.body_twist()
                track.measured_yaw_rate.append(angular[2])
                if step % record_every == 0:
                    reading = robot.read()
                    radius = rig.robot.params.wheel_radius_m
                    track.wheel_time_s.append(world.time_s)
                    track.wheel_speeds.append((reading.left_radps * radius,
                                               reading.right_radps * radius))
        for rig in rigs:
            track = rig.track
            start = track.pose[0]
            track.reference = bicycle_reference(track.applied, track.wheel_base_m, DT_S, start)
        return {rig.track.name: rig.track for rig in rigs}
    finally:
        for rig in rigs:
            rig.bridge.destroy()
            rig.robot.destroy()
        world.close()


def _bounds_or_none(stream, name):
    try:
        return stream.bounds(name)[0]
    except KeyError:
        return None


def _record_pose(track, time_s, pose):
    track.time_s.append(time_s)
    track.pose.append((pose[0], pose[1], yaw_from_quaternion(*pose[3:7])))


def _robot_control(rig, command, now_s, msg_type):
    """One control step of a bridge at ``now_s``: the command (if due), then its tick."""
    bridge = rig.bridge
    track = rig.track
    out = None
    if command is not None:
        out = bridge.handle_command(_control_msg(bridge.node, msg_type, *command), now_s=now_s)
        track.last_command_s = now_s
        track.command_times_s.append(now_s)
    period_s = 1.0 / BRIDGE_CONTROL_RATE_HZ
    if rig.last_tick_s is None or now_s - rig.last_tick_s >= period_s - 1e-9:
        rig.last_tick_s = now_s
        ticked = bridge.tick(now_s)
        out = ticked if ticked is not None else out
    if out is not None:
        radius = rig.robot.params.wheel_radius_m
        # the link bridge -> robot: /vehicle/differential_command [m/s] -> the robot's wheels
        rig.robot.robot.set_wheel_velocities(out.left_mps / radius, out.right_mps / radius)
        if (track.silence_start_s is not None and track.zero_after_silence_s is None
                and now_s >= track.silence_start_s and out.left_mps == 0.0
                and out.right_mps == 0.0):
            track.zero_after_silence_s = now_s
    # in force for the coming step: the bridge's applied (v, ω) (a brake resets it to 0)
    speed, yaw_rate = bridge.controller.kinematics.applied_twist
    steer = math.atan(yaw_rate * track.wheel_base_m / speed) if abs(speed) > 1e-9 else 0.0
    track.applied.append((speed, steer))
    track.commanded_yaw_rate.append(yaw_rate)


def run_car(stream, car_model=DEFAULT_CAR, transport='dds', record_every=5):
    """
    Drive a car through the autoware_automobile node with a stream (synchronous, in-process).

    :param stream: CommandStream.
    :param car_model: car preset (config/cars).
    :return: EndToEndTrack (wheel speeds: the four wheels [rad/s], FR FL RR RL).
    """
    from vehicle_sim.ros import autoware_interfaces as awi
    from vehicle_sim.ros.autoware_automobile_node import AutowareAutomobileNode

    node = AutowareAutomobileNode([], transport=transport, parameter_overrides={
        'car_model': car_model, 'synchronous': True, 'publish_period_ms': 100,
        'initial_y': ROBOT_SPACING_M, 'command_timeout_s': COMMAND_TIMEOUT_S})
    try:
        car = node.car
        logic = car.logic
        params = car.params
        track = EndToEndTrack(car_model, params.wheelbase_m,
                              wheel_labels=('front right', 'front left', 'rear right',
                                            'rear left'),
                              wheel_unit='rad/s')
        track.silence_start_s = _bounds_or_none(stream, 'silence')
        # the car's cruise ramp: Car.proto's acceleration (100 km/h)/time0To100, up and down
        accel = cruise_ramp_mps2(params)
        ramp = SpeedLimiter(accel, accel, 'car speed')
        full_brake = full_brake_deceleration_mps2(params)
        speed = 0.0
        automobile = node.automobile
        _record_pose(track, automobile.world.time_s, car.body.pose())
        steps = int(round(stream.duration_s / DT_S))
        for step in range(steps):
            now_s = automobile.world.time_s
            command = stream.command_at(now_s) if _due(now_s, COMMAND_PERIOD_S) else None
            if command is not None:
                node.handle_command(_control_msg(node.node, awi.CONTROL, *command), now_s=now_s)
                track.last_command_s = now_s
                track.command_times_s.append(now_s)
            automobile.step_once()
            # as applied: the cruising speed the node set, ramped like the car's wheel motors;
            # the commanded steering (the steering motors reach it within a few steps)
            if logic.control_mode == ControlMode.TORQUE and logic.throttle == 0.0:
                # the watchdog's safety stop: the brakes, at their deceleration
                slower = abs(speed) - logic.brake_intensity * full_brake * DT_S
                speed = math.copysign(max(slower, 0.0), speed)
            else:
                speed = ramp.limit(kmh_to_mps(logic.effective_cruising_speed_kmh), speed, DT_S)
            steer = -logic.commanded_steering_angle_rad   # Webots + right -> + left
            track.applied.append((speed, steer))
            _record_pose(track, automobile.world.time_s, car.body.pose())
            track.measured_yaw_rate.append(car.body.yaw_rate_radps())
            track.commanded_yaw_rate.append(speed * math.tan(steer) / params.wheelbase_m)
            if (track.silence_start_s is not None and track.zero_after_silence_s is None
                    and now_s >= track.silence_start_s and node.state.timed_out):
                track.zero_after_silence_s = now_s
            if step % record_every == 0:
                track.wheel_time_s.append(automobile.world.time_s)
                track.wheel_speeds.append(tuple(logic.wheel_speed_radps(i) for i in range(4)))
        track.reference = bicycle_reference(track.applied, track.wheel_base_m, DT_S,
                                            track.pose[0])
        return track
    finally:
        node.close()


@dataclass
class EndToEndResult:
    """The tracks of one end-to-end run and the stream that drove them."""

    robot_stream: CommandStream
    car_stream: CommandStream
    robots: dict
    car: Optional[EndToEndTrack]


def run_scenario(car_model=DEFAULT_CAR, robots=ROBOTS, scale=1.0, transport='dds'):
    """
    Run the whole scenario: the robots through bridges, the car through autoware_automobile.

    :param car_model: car preset, or None to skip the car.
    :param robots: robot presets.
    :param scale: multiplies every segment duration (0.5 = the short variant).
    :return: EndToEndResult.
    """
    def stream(speed, steer):
        return autoware_stream(speed, steer, straight_s=3.0 * scale, arc_s=4.0 * scale,
                               s_curve_s=6.0 * scale, silence_s=1.0, stop_s=2.0 * scale)

    robot_stream = stream(ROBOT_SPEED_MPS, ROBOT_STEER_RAD)
    car_stream = stream(CAR_SPEED_MPS, CAR_STEER_RAD)
    tracks = run_robots(robot_stream, robots, transport=transport) if robots else {}
    car = run_car(car_stream, car_model, transport=transport) if car_model else None
    return EndToEndResult(robot_stream, car_stream, tracks, car)


def summary(result: EndToEndResult) -> Sequence[str]:
    """Return printable lines: path errors per vehicle, skid-steer yaw efficiency."""
    lines = []
    arc = result.robot_stream.bounds('arc')
    for name, track in result.robots.items():
        distance = track.distance_m()[-1]
        lines.append(
            f'{name}: travelled {distance:.2f} m, max error '
            f'{max(track.errors_m()):.3f} m, max error / distance '
            f'{track.max_error_fraction(1.0):.2%} (after 1 m), end error '
            f'{track.end_error_m():.3f} m, yaw efficiency on the arc '
            f'{track.yaw_efficiency(*arc):.3f}')
    car = result.car
    if car is not None:
        distance = car.distance_m()[-1]
        lines.append(f'{car.name}: travelled {distance:.2f} m, end error '
                     f'{car.end_error_m():.3f} m ({car.end_error_m() / distance:.2%} of the '
                     f'distance), max error {max(car.errors_m()):.3f} m')
    return lines
