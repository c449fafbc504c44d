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
The lane rows of one car of the automobile node, in a world with a lane map (docs/maps.md).

:func:`wire_car_lanes` gives the car (its CarContext) a VehicleLanes (core/map/vehicle_lanes.py)
and wires its rows of ``ros/automobile_interfaces.py``: ``<ns>/lane_state`` and
``<ns>/lane_invasion`` (``LANE_TOPICS``, published by :func:`publish_car_lanes` each publish
period) and the service ``<ns>/set_lane_pose`` (``LANE_SERVICES``: a teleport onto a lane, placed
as a world file's ``pose: {lanelet, s, offset}`` is, core/map/lane_placement.py). The car's reset
and teleport (CarContext) reset its lane tracking.
"""

from vehicle_sim.core.geometry.frames import quaternion_from_yaw
from vehicle_sim.core.map.lane_placement import pose_on_lane
from vehicle_sim.core.map.vehicle_lanes import VehicleLanes
from vehicle_sim.core.specs.errors import InvalidParameterError, InvalidPoseError
from vehicle_sim.core.world.placement import ground_pose
from vehicle_sim.ros import automobile_interfaces as itf
from vehicle_sim.ros.endpoints import EACH_PUBLISH, ON_EVENT, Outputs, serve


def wire_car_lanes(node, vehicle, lanes, frame, resolve, signals=None):
    """
    Wire a car's lane rows.

    :param vehicle: its CarContext.
    :param lanes: the world's LaneGraph.
    :param frame: the frame of the lane messages ('map' or 'world').
    :param resolve: row name -> the name to create (under the car's namespace).
    :param signals: the world's SignalController (the next stop line's signal state), or None.
    """
    vehicle.lanes = VehicleLanes(lanes, signals)
    vehicle.lanes_frame = frame
    vehicle.lane_outputs = Outputs(node, itf.LANE_TOPICS, vehicle, resolve)
    logger = node.get_logger()

    def on_set_lane_pose(request, response):
        where = f'{vehicle.label}: set_lane_pose'
        try:
            x, y, yaw = pose_on_lane({'lanelet': int(request.lanelet), 's': float(request.s),
                                      'offset': float(request.offset)}, lanes, where)
            vehicle.teleport(ground_pose((x, y, 0.0), quaternion_from_yaw(yaw)))
        except (InvalidParameterError, InvalidPoseError) as error:
            # Odd input, ROS column (docs/deviations.md): success=false, nothing moved.
            response.success = False
            # The error names the vehicle and the service already (pose_on_lane's source).
            response.message = f'refused: {error}; nothing moved'
            logger.warn(response.message)
        else:
            response.success = True
            response.message = (f'{vehicle.label} at rest on lane {request.lanelet} at s '
                                f'{request.s:.3f} m, offset {request.offset:.3f} m (x {x:.3f} m, '
                                f'y {y:.3f} m, yaw {yaw:.4f} rad in world)')
        return response

    vehicle.services += serve(node, {itf.SET_LANE_POSE: on_set_lane_pose}, resolve).values()


def publish_car_lanes(vehicle, time_s, stamp):
    """
    Publish a car's lane_state of this sample, then one lane_invasion per marking crossed.

    :param time_s: the simulated time of the sample [s].
    :param stamp: ``stamp(time_s)`` -> a builtin_interfaces/Time (the node's stamp builder).
    """
    crossed = vehicle.update_lanes(time_s)
    outputs = vehicle.lane_outputs
    outputs.publish(EACH_PUBLISH, vehicle)
    for event in crossed:
        vehicle.lane_event_stamp, vehicle.lane_event = stamp(event.time_s), event
        outputs.publish(ON_EVENT, vehicle)
