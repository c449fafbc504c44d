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
Radar targets in the live view: the entity source ``'radar_targets'`` (foxglove/scene.py).

Each mounted radar of each vehicle is one entity, ``radar/<vehicle>/<sensor>``, redrawn at each
update from its last reading: a sphere at each target's centre, in its label's colour (the label
table, core/sensors/labels.py), and a line from the radar to it. The radar frame is placed where
the radar is now (a reading is at most one radar period old).
"""

from typing import List

import numpy as np

from vehicle_sim.core.sensors.labels import LABELS
from vehicle_sim.core.sensors.readings import RadarReading
from vehicle_sim.foxglove.entities import Entity, Lines, Primitive, WORLD_FRAME

TARGET_DIAMETER_M = 0.6
LINE_WIDTH_M = 0.04
LINE_COLOR = (1.0, 0.85, 0.1, 0.8)
ALPHA = 0.85


def radar_entity(entity_id, origin, rotation, reading) -> Entity:
    """
    Return the entity of one radar reading.

    :param origin: the radar's position in the world (3,) [m].
    :param rotation: its axes in the world, as columns (3, 3).
    :param reading: a RadarReading (target positions in the radar frame).
    """
    if not reading.targets:
        return Entity(entity_id, WORLD_FRAME, ())
    local = np.array([target.position_m for target in reading.targets], dtype=float)
    centres = np.asarray(origin, dtype=float) + local @ np.asarray(rotation, dtype=float).T
    size = (TARGET_DIAMETER_M,) * 3
    spheres = tuple(
        Primitive('sphere', tuple(centre.tolist()), (0.0, 0.0, 0.0, 1.0), size,
                  tuple(c / 255.0 for c in LABELS[target.label].colour) + (ALPHA,))
        for centre, target in zip(centres, reading.targets))
    rays = np.empty((2 * len(centres), 3))
    rays[0::2] = origin
    rays[1::2] = centres
    return Entity(entity_id, WORLD_FRAME, spheres,
                  (Lines('line_list', rays, LINE_WIDTH_M, LINE_COLOR),))


def radar_entities(scene) -> List[Entity]:
    """Return every mounted radar's last targets (the entity source ``'radar_targets'``)."""
    found = []
    for name, vehicle in scene.vehicles.items():
        sensors = getattr(vehicle, 'sensors', None)
        suite = getattr(sensors, 'suite', sensors)       # a SensorFeed's or a SensorSuite
        if suite is None or not hasattr(suite, 'latest'):
            continue
        for sensor_name in suite.specs:
            reading = suite.latest(sensor_name)
            if isinstance(reading, RadarReading):
                origin, rotation, _ = suite.sensors[sensor_name].mount.world_frame()
                found.append(radar_entity(f'radar/{name}/{sensor_name}', origin, rotation,
                                          reading))
    return found
