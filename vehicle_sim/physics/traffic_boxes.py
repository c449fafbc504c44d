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
What the traffic engines' bodies share: their colours, clearance, parking place, our vehicles.

Every engine's bodies (physics/traffic_bodies.py: the builtin engine's; physics/sumo_traffic.py:
SUMO's) are placed boxes lifted GROUND_CLEARANCE_M off the ground, parked under it while unused,
coloured from COLOURS by index, and see our vehicles as the builtin traffic manager does
(:func:`our_vehicle`: footprint centre, heading, speed, size), and read which bodies touch one of
ours after a step (:func:`touched`, from the world's one contact read).
"""

import math

from vehicle_sim.core.geometry.angles import yaw_from_quaternion
from vehicle_sim.core.traffic.manager import OurVehicle

GROUND_CLEARANCE_M = 0.15        # the box's underside above the ground
PARK_DEPTH_M = -50.0             # where a vehicle off the map waits (under the ground)
# body colours, picked by vehicle index (deterministic)
COLOURS = ((0.80, 0.10, 0.10, 1.0), (0.10, 0.30, 0.80, 1.0), (0.90, 0.90, 0.90, 1.0),
           (0.15, 0.15, 0.15, 1.0), (0.20, 0.60, 0.25, 1.0), (0.95, 0.75, 0.10, 1.0),
           (0.55, 0.55, 0.60, 1.0))
# the contacts of our vehicles are read with the traffic vehicles within this distance of them
# at the last update (both move less than 10 m in 100 ms; the longest box is about 6 m)
NEAR_M = 40.0


def our_vehicle(body, outline=None):
    """Return a VehicleBody as the traffic manager sees it (OurVehicle); ``outline``: cached."""
    pose = body.pose()              # (read once: its speed needs it too)
    x, y, _, qx, qy, qz, qw = pose
    yaw = yaw_from_quaternion(qx, qy, qz, qw)
    outline = body.outline if outline is None else outline
    cx = 0.5 * (outline.x_min_m + outline.x_max_m)
    cy = 0.5 * (outline.y_min_m + outline.y_max_m)
    c, s = math.cos(yaw), math.sin(yaw)
    return OurVehicle(body.name, x + c * cx - s * cy, y + s * cx + c * cy, yaw,
                      body.forward_speed_mps(pose), outline.length_m, outline.width_m)


def touched(world, body_id):
    """
    Return the ids of the bodies in contact with ``body_id`` after the last step.

    One contact read for the body (its wheels' points on the ground among them), shared with
    the world's other post-step hooks (``World.contact_points``), not one per body near it: a
    car in a city has a dozen traffic bodies near it at every step.
    """
    return {other for point in world.contact_points(body_id) for other in point[1:3]}
