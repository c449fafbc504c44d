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
One car of the automobile node: the wiring context of its rows and their call context per step.

:class:`CarContext` holds what the rows of ``ros/automobile_interfaces.py`` and
``ros/sensor_interfaces.py`` read: the names and frames fixed when they are wired, and after
:meth:`CarContext.sample` the car's state of that step, each part read from the car once, when the
first row that needs it asks. Reset and teleport of the car go through it (``ros/sim_control.py``),
so that its sensor feed, its drive inputs and the listeners of composing nodes follow.
"""

from vehicle_sim.core.car.drivetrain import ControlMode
from vehicle_sim.core.geometry.angles import yaw_from_quaternion
from vehicle_sim.core.geometry.frames import pose_in_frame, quaternion_from_yaw, twist_in_body
from vehicle_sim.core.sensors.sets import static_transforms
from vehicle_sim.ros import automobile_interfaces as itf
from vehicle_sim.ros.descriptions import vehicle_description


class CarContext:
    """
    One car: the wiring context of its rows and, after :meth:`sample`, their call context.

    The attributes the rows' converters read are listed in ``ros/automobile_interfaces.py``.
    """

    def __init__(self, spec, car, sensors):
        self.spec = spec
        self.car = car
        self.logic = car.logic
        self.body = car.body
        self.sensors = sensors            # its SensorSpecs (the mounted ones are published)
        self.prefix = self.frame_prefix = itf.frame_prefix(spec.namespace)
        self.base_frame = self.prefix + 'base_link'
        self.odom_frame = self.prefix + 'odom'
        self.spawn_xyz = (spec.x_m, spec.y_m, 0.0)
        self.spawn_q = quaternion_from_yaw(spec.yaw_rad)
        names, _, _ = car.body.joint_states()
        self.joint_names = tuple(self.prefix + name for name in names)
        self.outputs = None
        self.services = []
        self.inputs = []
        self.drive = None                 # CarDriveInput: cmd_vel and drive (docs/drive.md)
        self.reset_listeners = []         # called after each reset (a composing node's state)
        self.feed = None                  # SensorFeed: its sensors and collisions
        # Call context, set by sample(): the stamp, and the car's state read on first use.
        self.stamp = None
        self._status = None
        self._odom = None
        self._joints = None
        # Call context of the sensor and collision rows (ros/sensor_interfaces.py).
        self.readings = {}
        self.sample_stamp = None
        self.event = None
        self.event_stamp = None
        # Lanes (a world with a lane map): its VehicleLanes, the rows' Outputs and call context.
        self.lanes = None
        self.lanes_frame = 'world'
        self.lane_outputs = None
        self.lane_state = None
        self.lane_event = None
        self.lane_event_stamp = None

    def sample(self, stamp):
        """
        Start the sample of every row published at ``stamp``.

        Each part of the car's state (status, odometry, joints) is read from the car once, when
        the first row that needs it asks, so a step whose subscribed rows need only the status
        does not read the pose or the joints. Rows are published right after ``sample`` with
        nothing in between that could move the car.
        """
        self.stamp = stamp
        self._status = self._odom = self._joints = None

    @property
    def status(self):
        """The car logic's CarStatus of this sample."""
        status = self._status
        if status is None:
            status = self._status = self.logic.status()
        return status

    @property
    def torque_mode(self):
        """True when the car is in TORQUE control (the rows of that mode only)."""
        return self.status.control_mode == ControlMode.TORQUE

    @property
    def odom(self):
        """(xyz, q, linear, angular) of base_link in <p>odom, the twist in base_link."""
        odom = self._odom
        if odom is None:
            pose, (linear, angular) = self.body.pose_and_velocity()
            xyz, q = pose_in_frame(self.spawn_xyz, self.spawn_q, pose[:3], pose[3:])
            linear_b, angular_b = twist_in_body(pose[3:], linear, angular)
            odom = self._odom = (xyz, q, linear_b, angular_b)
        return odom

    @property
    def joints(self):
        """(positions, velocities) of the joint_states joints."""
        joints = self._joints
        if joints is None:
            _, positions, velocities = self.body.joint_states()
            joints = self._joints = (positions, velocities)
        return joints

    def update_lanes(self, time_s):
        """
        Read the car's lane state now (``lane_state``); return the markings crossed since.

        Called each publish period in a world with a lane map (``lanes`` set), right after
        :meth:`sample`, from base_link's ground-truth pose.
        """
        x, y, _, qx, qy, qz, qw = self.body.pose()
        self.lane_state, crossed = self.lanes.update(x, y, yaw_from_quaternion(qx, qy, qz, qw),
                                                     time_s)
        return crossed

    @property
    def label(self):
        return f'vehicle {self.spec.name!r}'

    def reset(self):
        """Put the car back at its spawn pose and its logic in its start state (sim_control)."""
        self.car.reset()
        self.feed.restart_motion()
        if self.lanes is not None:
            self.lanes.reset()          # the jump back is not a crossing
        if self.drive is not None:
            self.drive.service_override()   # a stale command's watchdog must not brake later
        for listener in self.reset_listeners:
            listener()
        status = self.logic.status()
        x, y, _ = self.spawn_xyz
        return (f'back at its spawn pose (x {x:g} m, y {y:g} m, yaw {self.spec.yaw_rad:g} rad) '
                f'at rest, joints at 0; car logic reset: control mode '
                f'{ControlMode(status.control_mode).name}, gear {status.gear}, cruising speed '
                f'{status.target_cruising_speed_kmh:g} km/h, throttle {status.throttle:g}, '
                f'brake {status.brake_intensity:g}, steering '
                f'{status.commanded_steering_angle_rad:g} rad, indicator off, hazard flashers, '
                f'lights and wipers off; simulated time goes on '
                f'({self.car.world.time_s:.3f} s)')

    def teleport(self, place):
        """Put the car at rest at a GroundPose (sim_control); raises InvalidPoseError."""
        self.car.teleport(place.position)
        self.feed.restart_motion()
        if self.lanes is not None:
            self.lanes.reset()

    def description(self):
        """Return the URDF published on robot_description (names prefixed ``<p>``)."""
        return vehicle_description(self.spec, self.sensors, self.car.params)

    def static_transforms(self):
        """Return the vehicle's /tf_static entries: world -> <p>odom, then its sensor mounts."""
        return [('world', self.odom_frame, self.spawn_xyz, self.spawn_q)] + [
            (t.parent, t.child, t.xyz, t.quaternion)
            for t in static_transforms(self.sensors, self.prefix)]
