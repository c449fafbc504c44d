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
The simulated differential-drive robot as a ROS 2 node (``diff_robot``, namespace /diff_robot).

Owns a World and one DiffRobotBody (or shares a World built in-process). Topics, types and QoS:
``ros/bridge_interfaces.py``; summary (``<ns>`` = /diff_robot, ``<p>`` = ``diff_robot/``):

- in  ``<ns>/differential_command`` vehicle_msgs/DifferentialCommand, tyre speeds [m/s]
- in  ``<ns>/wheel_velocities`` std_msgs/Float64MultiArray, [rad/s] in ``wheel_joints`` order
- out ``<ns>/joint_states``, ``<ns>/odom`` (wheel odometry, ``<p>odom`` -> ``<p>base_link``),
  ``<ns>/ground_truth/odom`` (frame ``world``), ``/tf``, ``/tf_static``, ``/clock``,
  ``<ns>/robot_description``
- service ``<ns>/robot/time_step`` vehicle_msgs/SetInt (synchronous mode; queued requests
  run in chunks from the node's loop, see :mod:`.time_step`)

Bad commands (NaN, ±inf, beyond max_wheel_speed, wrong length) are rejected with a throttled
warning; the command in force stays.
"""

import math
import sys

from vehicle_sim.core.diff_drive import integrate_pose, twist_from_wheel_speeds
from vehicle_sim.core.errors import InvalidCommandError, VehicleSimError
from vehicle_sim.core.units import seconds_to_stamp
from vehicle_sim.physics.diff_robot import DiffRobotBody, load_robot
from vehicle_sim.physics.world import World
from vehicle_sim.ros import bridge_interfaces as bi
from vehicle_sim.ros.time_step import TimeStepService
from vehicle_sim.transport.port import ThrottledWarning
from vehicle_sim.transport.selection import create_node, run_node


def _yaw_quaternion(yaw_rad):
    return 0.0, 0.0, math.sin(yaw_rad / 2.0), math.cos(yaw_rad / 2.0)


def _check_string_array(value):
    if not isinstance(value, list) or not all(isinstance(v, str) and v for v in value):
        return 'must be a list of joint names'
    return None


# name, default, description, validator (None or value -> reason)
ROBOT_NODE_PARAMETERS = (
    ('robot', 'caster_robot', 'robot preset in config/robots (name or YAML path)', None),
    ('x', 0.0, 'spawn x of base_link in the world [m]', None),
    ('y', 0.0, 'spawn y of base_link in the world [m]', None),
    ('yaw', 0.0, 'spawn heading [rad], positive = left', None),
    ('synchronous', False, 'true: the world advances only through robot/time_step; '
                           'false: in real time', None),
    ('time_step_ms', 10, 'basic time step [ms]',
     lambda v: None if v > 0 else 'must be > 0 ms'),
    ('wheel_joints', [''], "wheel_velocities order (default: the preset's joints, left first)",
     _check_string_array),
    ('publish_tf', True, 'publish <p>odom -> <p>base_link on /tf (wheel odometry)', None),
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
                 node_name=bi.ROBOT_NODE_NAME, namespace=bi.ROBOT_NAMESPACE):
        node = self.node = create_node(node_name, namespace, args=args,
                                       parameter_overrides=parameter_overrides,
                                       transport=transport)
        try:
            self._setup(world)
        except BaseException:
            node.shutdown()
            raise

    def _setup(self, world):
        node = self.node
        values = {name: node.declare_parameter(name, default, description=doc,
                                               validator=validator)
                  for name, default, doc, validator in ROBOT_NODE_PARAMETERS}
        self.params = load_robot(values['robot'])
        self._owns_world = world is None
        self.world = World(time_step_s=values['time_step_ms'] / 1000.0) if world is None \
            else world
        self.robot = DiffRobotBody(self.world, self.params,
                                   (values['x'], values['y'], values['yaw']))
        self._spawn = (values['x'], values['y'], values['yaw'])
        joints = [j for j in values['wheel_joints'] if j] or list(self.params.wheel_joints)
        if sorted(joints) != sorted(self.params.wheel_joints):
            raise VehicleSimError(
                f'wheel_joints {joints}: must list each of {list(self.params.wheel_joints)} once')
        self._array_order = [self.params.wheel_joints.index(j) for j in joints]
        self.wheel_joints = tuple(joints)
        self.synchronous = values['synchronous']
        self._publish_tf = values['publish_tf']
        ns = node.get_namespace().strip('/')
        prefix = f'{ns}/' if ns else ''
        self.odom_frame = f'{prefix}odom'
        self.base_frame = f'{prefix}base_link'
        self._odom_pose = (0.0, 0.0, 0.0)
        self._warn = ThrottledWarning(node.get_logger())
        self._m = {name: node.msg(name) for name in (
            'rosgraph_msgs/msg/Clock', 'sensor_msgs/msg/JointState', 'nav_msgs/msg/Odometry',
            'tf2_msgs/msg/TFMessage', 'geometry_msgs/msg/TransformStamped',
            'std_msgs/msg/Header', 'std_msgs/msg/String', 'builtin_interfaces/msg/Time')}
        self._pub = {}
        for spec in (bi.CLOCK, bi.ROBOT_JOINT_STATES, bi.ROBOT_ODOM, bi.ROBOT_GROUND_TRUTH_ODOM,
                     bi.TF, bi.TF_STATIC, bi.ROBOT_ROBOT_DESCRIPTION):
            self._pub[spec] = node.create_publisher(spec.ros_type, spec.name, spec.qos)
        self._subs = [
            node.create_subscription(bi.ROBOT_DIFFERENTIAL_COMMAND.ros_type,
                                     bi.ROBOT_DIFFERENTIAL_COMMAND.name,
                                     self._on_differential_command,
                                     bi.ROBOT_DIFFERENTIAL_COMMAND.qos),
            node.create_subscription(bi.ROBOT_WHEEL_VELOCITIES.ros_type,
                                     bi.ROBOT_WHEEL_VELOCITIES.name, self._on_wheel_velocities,
                                     bi.ROBOT_WHEEL_VELOCITIES.qos),
        ]
        self._time_step = TimeStepService(node, self.world.time_step_s * 1000.0, self.step,
                                          self.synchronous)
        self._time_step_name = f'{node.get_namespace().rstrip("/")}/{bi.ROBOT_TIME_STEP.name}'
        self._time_step_srv = node.create_service(
            bi.ROBOT_TIME_STEP.ros_type, bi.ROBOT_TIME_STEP.name, self._handle_time_step)
        self._pub[bi.ROBOT_ROBOT_DESCRIPTION].publish(
            self._m['std_msgs/msg/String'](data=self.robot.urdf))
        self._publish_static_tf()
        self._timer = None
        if self._owns_world and not self.synchronous:
            self._timer = node.create_timer(self.world.time_step_s, self._on_timer)
        self.publish_state()
        node.get_logger().info(
            f'{self.params.model} ({self.params.drive}) ready: '
            f'{"synchronous" if self.synchronous else "real time"}, step '
            f'{self.world.time_step_s * 1000:g} ms, wheel_joints {list(self.wheel_joints)}')

    # ---------------------------------------------------------------- commands
    def _on_differential_command(self, msg):
        radius = self.params.wheel_radius_m
        try:
            left, right = msg.left_wheel.velocity, msg.right_wheel.velocity
            self.robot.set_wheel_velocities(left / radius, right / radius)
        except (InvalidCommandError, TypeError, ZeroDivisionError) as error:
            self._warn.warn(f'differential_command rejected: {error}')

    def _on_wheel_velocities(self, msg):
        values = list(msg.data)
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

    # ---------------------------------------------------------------- stepping
    def _handle_time_step(self, request, response):
        # A deferred reply: answered once this request's own steps are done.
        return self._time_step.handle(self._time_step_name, request, response)

    def _on_timer(self):
        self.step()

    def step(self):
        """Advance the world by one basic step (only if this node owns it) and publish."""
        if self._owns_world:
            self.world.step()
        self.publish_state()

    # ---------------------------------------------------------------- outputs
    def _stamp(self):
        sec, nanosec = seconds_to_stamp(self.world.time_s)
        return self._m['builtin_interfaces/msg/Time'](sec=sec, nanosec=nanosec)

    def _odometry(self, stamp, frame, x, y, z, quat, speed, lateral, yaw_rate):
        msg = self._m['nav_msgs/msg/Odometry']()
        msg.header.stamp = stamp
        msg.header.frame_id = frame
        msg.child_frame_id = self.base_frame
        position = msg.pose.pose.position
        position.x, position.y, position.z = x, y, z
        orientation = msg.pose.pose.orientation
        orientation.x, orientation.y, orientation.z, orientation.w = quat
        msg.twist.twist.linear.x = speed
        msg.twist.twist.linear.y = lateral
        msg.twist.twist.angular.z = yaw_rate
        return msg

    def _transform(self, stamp, parent, child, x, y, z, quat):
        msg = self._m['geometry_msgs/msg/TransformStamped']()
        msg.header.stamp = stamp
        msg.header.frame_id = parent
        msg.child_frame_id = child
        t = msg.transform.translation
        t.x, t.y, t.z = x, y, z
        r = msg.transform.rotation
        r.x, r.y, r.z, r.w = quat
        return msg

    def _publish_static_tf(self):
        x, y, yaw = self._spawn
        self._pub[bi.TF_STATIC].publish(self._m['tf2_msgs/msg/TFMessage'](transforms=[
            self._transform(self._stamp(), 'world', self.odom_frame, x, y, 0.0,
                            _yaw_quaternion(yaw))]))

    def publish_state(self):
        """Publish /clock (owned world), joint states, wheel odometry, ground truth and /tf."""
        stamp = self._stamp()
        if self._owns_world:
            self._pub[bi.CLOCK].publish(self._m['rosgraph_msgs/msg/Clock'](clock=stamp))
        names, positions, velocities = self.robot.joint_states()
        joint_state = self._m['sensor_msgs/msg/JointState']()
        joint_state.header.stamp = stamp
        joint_state.name = list(names)
        joint_state.position = list(positions)
        joint_state.velocity = list(velocities)
        self._pub[bi.ROBOT_JOINT_STATES].publish(joint_state)
        # Wheel odometry: the ideal differential law on the measured wheel speeds.
        reading = self.robot.read()
        radius = self.params.wheel_radius_m
        twist = twist_from_wheel_speeds(reading.left_radps * radius,
                                        reading.right_radps * radius, self.params.wheel_tread_m)
        x, y, yaw = self._odom_pose = integrate_pose(
            *self._odom_pose, twist.speed_mps, twist.yaw_rate_radps, self.world.time_step_s)
        quat = _yaw_quaternion(yaw)
        self._pub[bi.ROBOT_ODOM].publish(self._odometry(
            stamp, self.odom_frame, x, y, 0.0, quat, twist.speed_mps, 0.0,
            twist.yaw_rate_radps))
        pose = self.robot.pose()
        linear, angular = self.robot.body_twist()
        self._pub[bi.ROBOT_GROUND_TRUTH_ODOM].publish(self._odometry(
            stamp, 'world', pose[0], pose[1], pose[2], pose[3:], linear[0], linear[1],
            angular[2]))
        if self._publish_tf:
            self._pub[bi.TF].publish(self._m['tf2_msgs/msg/TFMessage'](transforms=[
                self._transform(stamp, self.odom_frame, self.base_frame, x, y, 0.0, quat)]))

    @property
    def odom_pose(self):
        """Wheel-odometry pose (x [m], y [m], yaw [rad]) in the odom frame."""
        return self._odom_pose

    def destroy(self):
        """Leave the graph and close an owned world."""
        self._time_step.close()
        self.node.shutdown()
        if self._owns_world:
            self.world.close()


def main(args=None):
    """Run the robot node until SIGINT/SIGTERM (``ros2 run vehicle_sim diff_robot``)."""
    app = {}

    def factory(argv):
        app['robot'] = DiffRobotNode(argv)
        return app['robot'].node

    try:
        return run_node(factory, sys.argv if args is None else args)
    except VehicleSimError as error:   # a refused parameter, or DDS refused by Cyclone
        print(f'diff_robot: {error}', file=sys.stderr)
        return 2
    finally:
        if 'robot' in app and app['robot']._owns_world:
            app['robot'].world.close()


if __name__ == '__main__':
    sys.exit(main())
