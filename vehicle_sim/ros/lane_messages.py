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
Message builders of the lane topics: ``<ns>/lane_state`` and ``<ns>/lane_invasion``.

Same form as ros/messages.py's builders: ``<type>_builder(msg, frame_id)`` resolves the classes
once; the ``build`` it returns makes one message from a stamp and a core value
(core/map/lane_state.LaneState, core/map/lane_invasion.LaneInvasion).
"""

HEADER = 'std_msgs/msg/Header'
POINT = 'geometry_msgs/msg/Point'
LANE_STATE = 'vehicle_msgs/msg/LaneState'
LANE_INVASION = 'vehicle_msgs/msg/LaneInvasion'


def lane_state_builder(msg, frame_id: str):
    """Return ``build(stamp, state)``: vehicle_msgs/LaneState of a core LaneState."""
    header_type, state_type = msg(HEADER), msg(LANE_STATE)

    def build(stamp, state):
        return state_type(header=header_type(stamp=stamp, frame_id=frame_id),
                          on_lane=bool(state.on_lane), lane_id=int(state.lane_id),
                          s=float(state.s_m), offset=float(state.offset_m),
                          heading_error=float(state.heading_error_rad),
                          width=float(state.width_m), speed_limit=float(state.speed_limit_mps))
    return build


def lane_invasion_builder(msg, frame_id: str):
    """Return ``build(stamp, event)``: vehicle_msgs/LaneInvasion of a core LaneInvasion."""
    header_type, invasion_type, point_type = msg(HEADER), msg(LANE_INVASION), msg(POINT)

    def build(stamp, event):
        return invasion_type(header=header_type(stamp=stamp, frame_id=frame_id),
                             boundary_id=int(event.boundary_id), line_type=event.line_type,
                             position=point_type(x=float(event.x_m), y=float(event.y_m), z=0.0))
    return build
