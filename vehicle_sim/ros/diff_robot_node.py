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
The simulated differential-drive robot as a ROS 2 node (``/diff_robot``).

Owns a World and one DiffRobotBody (or shares a World built in-process). Its topics and its
service are private names of the node (``~/odom``), so they live under the node's own name;
frames are prefixed with it. Topics, types and QoS: ``ros/robot_interfaces.py``; summary
(``<ns>`` = /diff_robot, ``<p>`` = ``diff_robot/``; ``-r __ns:=/fleet`` gives /fleet/diff_robot
and ``fleet/diff_robot/``):

- in  ``<ns>/differential_command`` vehicle_msgs/DifferentialCommand, tyre speeds [m/s]
- in  ``<ns>/wheel_velocities`` std_msgs/Float64MultiArray, [rad/s] in ``wheel_joints`` order
- in  ``<ns>/cmd_vel`` geometry_msgs/Twist (TwistStamped with ``cmd_vel_stamped``): v [m/s] and
  ω [rad/s] through the differential law, with a watchdog (``cmd_vel_timeout_s``; docs/drive.md)
- out ``<ns>/joint_states``, ``<ns>/odom`` (wheel odometry, ``<p>odom`` -> ``<p>base_link``),
  ``<ns>/ground_truth/odom`` (frame ``world``), ``/tf``, ``/tf_static``, ``/clock``,
  ``<ns>/robot_description``, ``<ns>/collision``, and a topic per mounted sensor (the
  ``sensors`` parameter mounts the preset's lidar and IMU: ``<ns>/scan``, ``<ns>/imu``, frames
  ``<p>lidar``, ``<p>imu``; ``ros/sensor_interfaces.py``)
- service ``<ns>/robot/time_step`` vehicle_msgs/SetInt (synchronous mode; queued requests
  run in chunks from the node's loop, see :mod:`.time_step`)
- services ``<ns>/reset`` (std_srvs/Trigger) and ``<ns>/set_pose`` (vehicle_msgs/SetPose); while
  it owns its world also ``/sim/reset``, ``/sim/pause`` and the ``/initialpose`` input
  (:mod:`.sim_control`)

Bad commands (NaN, ±inf, beyond max_wheel_speed, wrong length) are rejected with a throttled
warning; the command in force stays. A cmd_vel stream is not refused for its size: wheel speeds
beyond max_wheel_speed are scaled down together (curvature kept) with a throttled warning. The
last of the three inputs wins; differential_command and wheel_velocities stand the cmd_vel
watchdog down until the next cmd_vel.
"""

import sys
from types import SimpleNamespace

from vehicle_sim.core.commands.drive_input import DiffDriveInput
from vehicle_sim.core.diffdrive.kinematics import integrate_pose, twist_from_wheel_speeds
from vehicle_sim.core.geometry.chase_camera import ChaseSettings
from vehicle_sim.core.geometry.frames import (
    pose_in_frame,
    quaternion_from_yaw,
    rpy_from_quaternion,
)
from vehicle_sim.core.geometry.geodesy import GeodeticOrigin
from vehicle_sim.core.sensors.sets import enable_sensors, selected_sensors, static_transforms
from vehicle_sim.core.specs.errors import InvalidCommandError, VehicleSimError
from vehicle_sim.core.specs.param_spec import ParamSpec
from vehicle_sim.core.specs.simulation import TIME_STEP_MS
from vehicle_sim.core.world.params import RobotSpec, WorldSpec
from vehicle_sim.core.world.placement import WORLD_EXTENT_M
from vehicle_sim.physics.diff_robot import load_robot
from vehicle_sim.physics.gui import ChaseCamera, shortcuts_text
from vehicle_sim.physics.scene import build_scene
from vehicle_sim.physics.sensor_urdf import with_sensor_links
from vehicle_sim.physics.sensors import SensorFeed
from vehicle_sim.ros import robot_interfaces as ri
from vehicle_sim.ros.endpoints import (
    CMD_VEL_INPUTS,
    CMD_VEL_STAMPED_PARAMETER,
    CMD_VEL_TIMEOUT_PARAMETER,
    EACH_PUBLISH,
    EACH_SAMPLE,
    EACH_STEP,
    ON_EVENT,
    ONCE_LATCHED,
    Outputs,
    serve,
    subscribe,
)
from vehicle_sim.ros.messages import stamp_builder
from vehicle_sim.ros.node_support import declare_parameters, run_main
from vehicle_sim.ros.sensor_interfaces import (
    check_names,
    sensor_rows,
    SENSORS_PARAMETER,
)
from vehicle_sim.ros.sim_control import serve_vehicle, WorldControl
from vehicle_sim.ros.time_step import TimeStepService
from vehicle_sim.transport.logger import ThrottledWarning
from vehicle_sim.transport.names import resolve_name
from vehicle_sim.transport.selection import create_node


def _private(name):
    """Return a relative endpoint name as a private one (under the node's name)."""
    return name if name.startswith('/') else '~/' + name


ROBOT_NODE_PARAMETERS = (
    ParamSpec('robot', kind='str', default='caster_robot',
              doc='robot preset in config/robots (name or YAML path)'),
    ParamSpec('x', kind='float', default=0.0, unit='m', doc='spawn x of base_link in the world',
              ge=-WORLD_EXTENT_M, le=WORLD_EXTENT_M),
    ParamSpec('y', kind='float', default=0.0, unit='m', doc='spawn y of base_link in the world',
              ge=-WORLD_EXTENT_M, le=WORLD_EXTENT_M),
    ParamSpec('yaw', kind='float', default=0.0, unit='rad', doc='spawn heading, positive = left'),
    ParamSpec('synchronous', kind='bool', default=False,
              doc='true: the world advances only through robot/time_step; false: in real time'),
    TIME_STEP_MS,
    ParamSpec('wheel_joints', kind='str_list', default=('',), empty=True,
              doc="wheel_velocities order; [''] = the preset's joints, left first"),
    ParamSpec('publish_tf', kind='bool', default=True,
              doc='publish <p>odom -> <p>base_link on /tf (wheel odometry)'),
    SENSORS_PARAMETER,
    CMD_VEL_STAMPED_PARAMETER,
    CMD_VEL_TIMEOUT_PARAMETER,
    ParamSpec('gui', kind='bool', default=False,
              doc="open PyBullet's window, a chase camera following the robot (a node that "
                  'owns its world; needs an X display; docs/drive.md)'),
)


class DiffRobotNode:
    """
    The robot node: wiring in ``__init__``, one callback per topic or service.

    :param args: command line (``--ros-args`` part applied).
    :param world: a World to share; None = the node owns one. With a shared world the owner
        steps it and calls :meth:`publish_state` after each step (the node's timer does not step).
    :param parameter_overrides: parameter values that win over the command line.
    :param transport: 'auto', 'rclpy' or 'dds'.
    """

    def __init__(self, args=None, world=None, parameter_overrides=None, transport=None,
                 node_name=ri.ROBOT_NODE_NAME, namespace='', node=None):
        node = self.node = node if node is not None else create_node(
            node_name, namespace, args=args, parameter_overrides=parameter_overrides,
            transport=transport)
        try:
            self._setup(world)
        except BaseException:
            node.shutdown()
            raise

    def _setup(self, world):
        node = self.node
        values = declare_parameters(node, ROBOT_NODE_PARAMETERS)
        self.params = load_robot(values['robot'])
        self._owns_world = world is None
        self.sensors = self._sensors(values['sensors'])
        robot = RobotSpec(self.params.model, self.params.model, values['x'], values['y'],
                          values['yaw'])

        def feed(vehicle, scene):
            # Its sensors at their rates; collisions only in a shared world (its own holds
            # nothing but the ground and the robot).
            return SensorFeed(scene.world, vehicle.body, self.sensors, scene.origin,
                              collisions=world is not None)

        scene = build_scene(WorldSpec(GeodeticOrigin(), (), ()), world,
                            time_step_s=values['time_step_ms'] / 1000.0, gui=values['gui'],
                            robots=(robot,), params={robot.name: self.params}, mount=feed)
        self.world = scene.world
        self.robot = scene.vehicles[robot.name].body
        self._feed = scene.vehicles[robot.name].sensors
        self._gui_closed = False
        if values['gui'] and self._owns_world:
            ChaseCamera(self.world, [self.robot], ChaseSettings(distance_m=3.0, pitch_deg=-25.0,
                                                                target_height_m=0.3))
            node.get_logger().info(f'PyBullet window open; keys: {shortcuts_text()}')
        self._spawn = (values['x'], values['y'], values['yaw'])
        self.spawn_xyz = (values['x'], values['y'], 0.0)
        self.spawn_q = quaternion_from_yaw(values['yaw'])
        joints = [j for j in values['wheel_joints'] if j] or list(self.params.wheel_joints)
        if sorted(joints) != sorted(self.params.wheel_joints):
            raise VehicleSimError(
                f'wheel_joints {joints}: must list each of {list(self.params.wheel_joints)} once')
        self._array_order = [self.params.wheel_joints.index(j) for j in joints]
        self.wheel_joints = tuple(joints)
        self.synchronous = values['synchronous']
        self._publish_tf = values['publish_tf']
        prefix = node.get_fully_qualified_name().strip('/') + '/'
        self.odom_frame = f'{prefix}odom'
        self.base_frame = f'{prefix}base_link'
        self._odom_pose = (0.0, 0.0, 0.0)
        self._warn = ThrottledWarning(node.get_logger())
        self._warn_saturated = ThrottledWarning(node.get_logger())
        self._drive = DiffDriveInput(self.params.wheel_tread_m, self.params.wheel_radius_m,
                                     self.params.max_wheel_speed_radps,
                                     values['cmd_vel_timeout_s'])
        self._cmd_vel = CMD_VEL_INPUTS[values['cmd_vel_stamped']]
        self._time_step = TimeStepService(node, self.world.time_step_s * 1000.0, self.step,
                                          self.synchronous)
        self._time_step_name = (f'{node.get_fully_qualified_name().rstrip("/")}/'
                                f'{ri.ROBOT_TIME_STEP.name}')
        self.frame_prefix = prefix
        self._wire()
        # /sim/reset, /sim/pause and /initialpose belong to the node that steps the world.
        self._control = WorldControl(node, self.world, (self,), self.synchronous, self) \
            if self._owns_world else None
        self._timer = None
        if self._owns_world and not self.synchronous:
            self._timer = node.create_timer(self.world.time_step_s, self._on_timer)
        self.publish_state()
        node.announce_ready(
            f'{self.params.model} ({self.params.drive}) ready: '
            f'{"synchronous" if self.synchronous else "real time"}, step '
            f'{self.world.time_step_s * 1000:g} ms, wheel_joints {list(self.wheel_joints)}')

    def _sensors(self, value):
        # The preset's sensors, those the sensors parameter names mounted.
        specs = self.params.sensor_set
        names = selected_sensors(value)
        if names is not None:
            specs = enable_sensors(specs, names, f'{self.node.get_fully_qualified_name()}: '
                                                 'parameter sensors')
        self._sensor_rows = sensor_rows(specs)
        node = self.node

        def full_name(row_name):
            return resolve_name(_private(row_name), node.get_namespace(), node.get_name())

        taken = {full_name(row.name): f"the robot's {row.name!r}" for row in
                 ri.ROBOT_INPUTS + ri.ROBOT_OUTPUTS + ri.ROBOT_SERVICES}
        check_names(self._sensor_rows, taken, full_name,
                    f'{node.get_fully_qualified_name()}: robot {self.params.model!r}')
        return specs

    def _wire(self):
        # Rows of robot_interfaces and the sensor rows; self._ctx is their wiring and call
        # context.
        node = self.node
        x, y, yaw = self._spawn
        prefix = self.frame_prefix
        self._stamp = stamp_builder(node.msg)
        self._ctx = ctx = SimpleNamespace(
            joint_names=tuple(self.robot.wheel_joints), odom_frame=self.odom_frame,
            base_frame=self.base_frame, frame_prefix=prefix,
            urdf=with_sensor_links(self.robot.urdf, self.sensors),
            tf_frames=[(self.odom_frame, self.base_frame)],
            static_transforms=[
                ('world', self.odom_frame, (x, y, 0.0), quaternion_from_yaw(yaw))] + [
                (t.parent, t.child, t.xyz, t.quaternion)
                for t in static_transforms(self.sensors, prefix)],
            stamp=self._stamp(self.world.time_s), joints=None, odom=None, ground_truth=None,
            tf_poses=None, readings={}, sample_stamp=None, event=None, event_stamp=None)
        self._outputs = Outputs(node, ri.ROBOT_OUTPUTS + self._sensor_rows, ctx, _private)
        self._pub = self._outputs.publishers
        self._subs = subscribe(node, {
            ri.ROBOT_DIFFERENTIAL_COMMAND: self._on_differential_command,
            ri.ROBOT_WHEEL_VELOCITIES: self._on_wheel_velocities,
            self._cmd_vel: self._on_cmd_vel}, _private)
        self._time_step_srv = serve(node, {ri.ROBOT_TIME_STEP: self._handle_time_step},
                                    _private)[ri.ROBOT_TIME_STEP]
        self._pose_srvs = serve_vehicle(node, ri.ROBOT_POSE_SERVICES, self, _private)
        self._outputs.publish(ONCE_LATCHED, ctx)

    # ---------------------------------------------------------------- commands
    def _on_differential_command(self, msg):
        radius = self.params.wheel_radius_m
        try:
            left, right = ri.ROBOT_DIFFERENTIAL_COMMAND.converter(msg)
            self.robot.set_wheel_velocities(left / radius, right / radius)
        except (InvalidCommandError, TypeError, ZeroDivisionError) as error:
            self._warn.warn(f'differential_command rejected: {error}')
        else:
            self._drive.override()

    def _on_wheel_velocities(self, msg):
        values = ri.ROBOT_WHEEL_VELOCITIES.converter(msg)
        if len(values) != len(self.wheel_joints):
            self._warn.warn(
                f'wheel_velocities rejected: {len(values)} entries, {len(self.wheel_joints)} '
                f'expected ({", ".join(self.wheel_joints)})')
            return
        ordered = [0.0] * len(values)
        for position, index in enumerate(self._array_order):
            ordered[index] = values[position]
        try:
            self.robot.set_joint_velocities(ordered)
        except InvalidCommandError as error:
            self._warn.warn(f'wheel_velocities rejected: {error}')
        else:
            self._drive.override()

    def _on_cmd_vel(self, msg):
        try:
            left, right, notes = self._drive.twist(*self._cmd_vel.converter(msg),
                                                   self.world.time_s)
            self.robot.set_wheel_velocities(left, right)
        except InvalidCommandError as error:
            self._warn.warn(f'cmd_vel rejected: {error}')
            return
        for note in notes:
            self._warn_saturated.warn(note)

    # ---------------------------------------------------------------- stepping
    def _handle_time_step(self, request, response):
        # A deferred reply: answered once this request's own steps are done.
        return self._time_step.handle(self._time_step_name, request, response)

    def _on_timer(self):
        if not self._control.paused:     # /sim/pause
            self.step()

    # ---------------------------------------------------------------- reset and teleport
    @property
    def label(self):
        return f'robot {self.node.get_fully_qualified_name()!r}'

    def reset(self):
        """Put the robot back at its spawn pose, at rest, commands 0, odometry 0 (sim_control)."""
        self.robot.reset()
        self._drive.override()      # a stale command's watchdog must not act on the reset robot
        self._odom_pose = (0.0, 0.0, 0.0)
        self._feed.restart_motion()
        x, y, yaw = self._spawn
        return (f'back at its spawn pose (x {x:g} m, y {y:g} m, yaw {yaw:g} rad) at rest, wheel '
                'commands 0, wheel odometry 0; simulated time goes on '
                f'({self.world.time_s:.3f} s)')

    def teleport(self, place):
        """
        Put the robot at rest at a GroundPose (sim_control); raises InvalidPoseError.

        The wheel odometry restarts at the new pose (expressed in <p>odom), so odom, /tf and
        ground truth agree from the next message on.
        """
        self.robot.teleport(place.position)
        xyz, q = pose_in_frame(self.spawn_xyz, self.spawn_q, (place.x_m, place.y_m, 0.0),
                               quaternion_from_yaw(place.yaw_rad))
        self._odom_pose = (xyz[0], xyz[1], rpy_from_quaternion(q)[2])
        self._feed.restart_motion()

    def step(self):
        """Advance the world by one basic step (only if this node owns it) and publish."""
        if not self._owns_world:
            self.publish_state()
            return
        if self._gui_closed:
            return
        try:
            self.world.step()
            self.publish_state()
        except Exception:
            # The window closes asynchronously: whichever PyBullet call comes next fails.
            if not self.world.gui_closed:
                raise
            self._gui_closed = True
            self.node.get_logger().info('the PyBullet window was closed: shutting down')
            self.node.request_shutdown()

    # ---------------------------------------------------------------- outputs
    def publish_state(self):
        """Publish /clock (owned world), joint states, wheel odometry, ground truth and /tf."""
        ctx = self._ctx
        if self._drive.tick(self.world.time_s):
            self.robot.set_wheel_velocities(0.0, 0.0)
            self.node.get_logger().warn(
                f'cmd_vel: no command for {self._drive.watchdog.timeout_s:g} s: wheels stopped')
        ctx.stamp = self._stamp(self.world.time_s)
        outputs = self._outputs
        if self._owns_world:
            outputs.publish(EACH_STEP, ctx)
        reading = self.robot.read()
        ctx.joints = (reading.wheel_position_rad, reading.wheel_velocity_radps)
        # Wheel odometry: the ideal differential law on the measured wheel speeds.
        radius = self.params.wheel_radius_m
        twist = twist_from_wheel_speeds(reading.left_radps * radius,
                                        reading.right_radps * radius, self.params.wheel_tread_m)
        x, y, yaw = self._odom_pose = integrate_pose(
            *self._odom_pose, twist.speed_mps, twist.yaw_rate_radps, self.world.time_step_s)
        xyz, quat = (x, y, 0.0), quaternion_from_yaw(yaw)
        ctx.odom = (xyz, quat, (twist.speed_mps, 0.0, 0.0), (0.0, 0.0, twist.yaw_rate_radps))
        pose = self.robot.pose()
        linear, angular = self.robot.body_twist()
        ctx.ground_truth = (pose[:3], pose[3:], (linear[0], linear[1], 0.0),
                            (0.0, 0.0, angular[2]))
        ctx.tf_poses = [(xyz, quat)] if self._publish_tf else None
        outputs.publish(EACH_PUBLISH, ctx)
        if self._feed.active:
            self._publish_sensors()

    def _publish_sensors(self):
        # Every reading and collision event since the last call, stamped with its own time.
        samples, events = self._feed.take()
        ctx, outputs, stamp = self._ctx, self._outputs, self._stamp
        for time_s, readings in samples:
            ctx.sample_stamp, ctx.readings = stamp(time_s), readings
            outputs.publish(EACH_SAMPLE, ctx)
        for event in events:
            ctx.event_stamp, ctx.event = stamp(event.time_s), event
            outputs.publish(ON_EVENT, ctx)

    @property
    def odom_pose(self):
        """Wheel-odometry pose (x [m], y [m], yaw [rad]) in the odom frame."""
        return self._odom_pose

    def destroy(self):
        """Leave the graph, stop its sensors (a shared world steps on) and close an owned world."""
        self._time_step.close()
        self.node.shutdown()
        self._feed.close()
        if self._owns_world:
            self.world.close()


def main(args=None):
    """Run the robot node until SIGINT/SIGTERM (``ros2 run vehicle_sim diff_robot``)."""
    app = {}

    def factory(argv):
        app['robot'] = DiffRobotNode(argv)
        return app['robot'].node

    try:
        return run_main(ri.ROBOT_NODE_NAME, factory, args)
    finally:
        if 'robot' in app and app['robot']._owns_world:
            app['robot'].world.close()


if __name__ == '__main__':
    sys.exit(main())
