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
Reset, teleport and pause: the rows and handlers the automobile and robot nodes share.

Per vehicle: ``reset`` (std_srvs/Trigger: spawn pose, at rest, logic in its start state) and
``set_pose`` (vehicle_msgs/SetPose: teleport at rest onto the ground, pose in ``world``). Per
world (served by the node that owns and steps it): ``/sim/reset`` (every vehicle and every
movable obstacle), ``/sim/pause`` (std_srvs/SetBool: stop / resume simulated time in real-time
mode) and the ``/initialpose`` input (RViz's "2D Pose Estimate").

The vehicles are the nodes' own objects; what this module needs of one (a :class:`Movable`):
``label`` (for messages), ``odom_frame``, ``spawn_xyz``, ``spawn_q`` (the world -> odom
transform), ``reset() -> str`` (what was reset) and ``teleport(GroundPose)`` (raises
InvalidPoseError, nothing moved). Simulated time never goes backwards: no reset touches it, so
/clock stays monotonic (tf2 and RViz drop their buffers on a clock that jumps back).
"""

from typing import Callable, Dict, Optional, Sequence

from vehicle_sim.core.specs.errors import InvalidPoseError
from vehicle_sim.core.world.placement import ground_pose, GroundPose
from vehicle_sim.ros.endpoints import IN, RECEIVED, serve, Service, subscribe, Topic
from vehicle_sim.transport.logger import ThrottledWarning
from vehicle_sim.transport.qos import QOS_DEFAULT

TRIGGER = 'std_srvs/srv/Trigger'
STD_SET_BOOL = 'std_srvs/srv/SetBool'
SET_POSE = 'vehicle_msgs/srv/SetPose'
POSE_WITH_COVARIANCE_STAMPED = 'geometry_msgs/msg/PoseWithCovarianceStamped'

# Service kinds.
RESET = 'reset'
TELEPORT = 'set_pose'
SIM_RESET_KIND = 'sim_reset'
SIM_PAUSE_KIND = 'sim_pause'

# Frames an /initialpose may name for the world frame ('' is RViz's "no frame"; 'map' is the
# world unless the world's map places it elsewhere: then the pose is taken in the map frame).
WORLD_FRAMES = ('', 'world', 'map')

SIM_RESET = Service('/sim/reset', TRIGGER, SIM_RESET_KIND, value='',
                    doc='every vehicle to its spawn pose at rest and its logic reset, every '
                        'movable obstacle to its initial pose; simulated time goes on')
SIM_PAUSE = Service('/sim/pause', STD_SET_BOOL, SIM_PAUSE_KIND, value='bool',
                    doc='data true: stop simulated time, false: resume (real-time mode); '
                        'success=false in synchronous mode')
WORLD_SERVICES = (SIM_RESET, SIM_PAUSE)


def _pose_fields(msg):
    # PoseWithCovarianceStamped -> (frame_id, xyz, q); the covariance is ignored.
    pose = msg.pose.pose
    p, q = pose.position, pose.orientation
    return msg.header.frame_id, (p.x, p.y, p.z), (q.x, q.y, q.z, q.w)


INITIALPOSE = Topic('/initialpose', POSE_WITH_COVARIANCE_STAMPED, QOS_DEFAULT, RECEIVED,
                    _pose_fields, direction=IN, unit='m, rad',
                    doc="teleport one vehicle as set_pose does (automobile: parameter "
                        "initialpose_vehicle; diff_robot: itself); frame_id world, map, '' or a "
                        "vehicle's <p>odom; RViz 2D Pose Estimate")
WORLD_INPUTS = (INITIALPOSE,)


def vehicle_services(prefix: str, reset_doc: str):
    """
    Return a vehicle's reset and set_pose rows, named ``<prefix>reset`` and ``<prefix>set_pose``.

    :param prefix: '' or a relative namespace ending in '/' (the car's ``automobile/``).
    :param reset_doc: what the vehicle's reset does (docs).
    """
    return (
        Service(prefix + 'reset', TRIGGER, RESET, value='',
                doc=reset_doc + '; simulated time goes on'),
        Service(prefix + 'set_pose', SET_POSE, TELEPORT, value='pose', unit='m, rad',
                doc='teleport at rest onto the ground: x, y, yaw from the pose (world frame), '
                    'z, roll, pitch from the ground; refused: NaN/inf, a quaternion norm not '
                    'within 1e-3 of 1, x or y beyond ±1e6 m, a place inside an obstacle or '
                    'vehicle'),
    )


def _place_text(place: GroundPose) -> str:
    return f'x {place.x_m:.3f} m, y {place.y_m:.3f} m, yaw {place.yaw_rad:.4f} rad'


def serve_vehicle(node, rows, vehicle, resolve: Callable[[str], str]):
    """
    Serve a vehicle's reset and set_pose rows (from :func:`vehicle_services`).

    :param resolve: row name -> the name to create.
    :return: {row: service}.
    """
    logger = node.get_logger()

    def on_reset(request, response):
        response.message = vehicle.reset()
        response.success = True
        logger.info(f'{vehicle.label}: {response.message}')
        return response

    def on_set_pose(request, response):
        pose = request.pose
        p, q = pose.position, pose.orientation
        try:
            place = ground_pose((p.x, p.y, p.z), (q.x, q.y, q.z, q.w))
            vehicle.teleport(place)
        except InvalidPoseError as error:
            # Odd input, ROS column (docs/deviations.md): success=false, nothing changed, the
            # reason logged.
            response.success = False
            response.message = f'refused: {error}; nothing moved'
            logger.warn(f'{vehicle.label}: set_pose {response.message}')
        else:
            response.success = True
            response.message = f'{vehicle.label} at rest at {_place_text(place)} (world)'
        return response

    handlers = {RESET: on_reset, TELEPORT: on_set_pose}
    return serve(node, {row: handlers[row.kind] for row in rows}, resolve)


class WorldControl:
    """
    ``/sim/reset``, ``/sim/pause`` and ``/initialpose`` of the node that steps a world.

    :param node: the NodePort.
    :param world: the World (its movable obstacles are reset too).
    :param vehicles: the world's Movables, in order.
    :param synchronous: the world moves only by robot/time_step (pause is refused).
    :param initialpose_vehicle: the Movable that /initialpose moves; None: no /initialpose.
    :param map_in_world: (xyz, q) of the ``map`` frame in the world (a world with a map whose
        map -> world transform is not the identity); None: ``map`` is the world.
    :param resets: further parts reset after the vehicles (the traffic): each ``reset()``
        returns what it did, in words.
    """

    def __init__(self, node, world, vehicles: Sequence, synchronous: bool,
                 initialpose_vehicle=None, map_in_world=None, resets: Sequence = ()):
        self._world = world
        self._vehicles = tuple(vehicles)
        self._resets = tuple(resets)
        self._synchronous = synchronous
        self._logger = node.get_logger()
        # One throttle per reason, as ROS throttles per call site.
        self._warn_frame = ThrottledWarning(self._logger)
        self._warn_pose = ThrottledWarning(self._logger)
        self.paused = False
        self.services = serve(node, {SIM_RESET: self._on_reset, SIM_PAUSE: self._on_pause})
        self._target = initialpose_vehicle
        self._frames: Dict[str, object] = {v.odom_frame: v for v in self._vehicles}
        self._map_in_world = map_in_world
        self.subscriptions = [] if initialpose_vehicle is None else subscribe(
            node, {INITIALPOSE: self._on_initialpose})

    # ---------------------------------------------------------------- /sim/reset
    def reset(self) -> str:
        """Reset every vehicle and every movable obstacle; return what was reset."""
        for vehicle in self._vehicles:
            vehicle.reset()
        obstacles = self._world.reset_obstacles()
        others = ''.join(f'; {part.reset()}' for part in self._resets)
        names = ', '.join(v.label for v in self._vehicles)
        moved = ', '.join(obstacles) if obstacles else 'none'
        return (f'reset {names} (spawn pose, at rest, logic in its start state) and the movable '
                f'obstacles ({moved}){others}; simulated time goes on at '
                f'{self._world.time_s:.3f} s')

    def _on_reset(self, request, response):
        response.message = self.reset()
        response.success = True
        self._logger.info(f'/sim/reset: {response.message}')
        return response

    # ---------------------------------------------------------------- /sim/pause
    def _on_pause(self, request, response):
        now = f'{self._world.time_s:.3f} s'
        if self._synchronous:
            response.success = False
            response.message = ('synchronous mode: simulated time moves only by robot/time_step '
                                f'({self._world.time_step_s * 1000:g} ms per step), there is '
                                f'nothing to pause; time is {now}')
            return response
        wanted = bool(request.data)
        if wanted == self.paused:
            response.message = f'already {"paused" if wanted else "running"} at {now}'
        else:
            self.paused = wanted
            response.message = f'{"paused" if wanted else "resumed"} at {now}'
            self._logger.info(f'/sim/pause: {response.message}')
        response.success = True
        return response

    # ---------------------------------------------------------------- /initialpose
    def _frame(self, frame_id) -> Optional[object]:
        # None for the world, the vehicle whose odom frame it is, or KeyError.
        if frame_id in WORLD_FRAMES:
            return None
        return self._frames[frame_id]

    def _on_initialpose(self, msg):
        frame_id, xyz, q = INITIALPOSE.converter(msg)
        target = self._target
        try:
            owner = self._frame(frame_id)
        except KeyError:
            known = ', '.join(repr(f) for f in WORLD_FRAMES + tuple(self._frames))
            self._warn_frame.warn(f'/initialpose for {target.label} refused: unknown frame_id '
                                  f'{frame_id!r} (known: {known}); nothing moved')
            return
        frame = ((0.0, 0.0, 0.0), (0.0, 0.0, 0.0, 1.0)) if owner is None else \
            (owner.spawn_xyz, owner.spawn_q)
        if frame_id == 'map' and self._map_in_world is not None:
            frame = self._map_in_world
        try:
            place = ground_pose(xyz, q, *frame)
            target.teleport(place)
        except InvalidPoseError as error:
            self._warn_pose.warn(f'/initialpose for {target.label} refused: {error}; '
                                 'nothing moved')
        else:
            self._logger.info(f'/initialpose: {target.label} at rest at {_place_text(place)} '
                              '(world)')
