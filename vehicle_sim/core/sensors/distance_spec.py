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
The distance sensor: its ParamSpec table, its spec and its cross-field check.

Registered as ``distance`` in core/sensors/params.py; keys in docs/sensors.md. Its Webots
lookup table is core/sensors/lookup_table.py's.
"""

from dataclasses import dataclass
import math
from typing import Optional, Tuple

from vehicle_sim.core.sensors.lookup_table import LookupTable
from vehicle_sim.core.sensors.sensor_spec import common_specs, MAX_DISTANCE_RAYS, SensorSpec
from vehicle_sim.core.specs.param_spec import fail, ParamSpec

RADIATION_TYPES = ('ultrasound', 'infrared')
DEFAULT_DISTANCE_RANGE_M = 5.0


DISTANCE_SPECS = common_specs('distance', 20.0) + (
    ParamSpec('rays', 'rays', 'int', 1, '', 'rays in the cone (the nearest hit counts)', ge=1,
              le=MAX_DISTANCE_RAYS),
    ParamSpec('aperture', 'aperture_rad', 'float', 0.0, 'rad',
              'opening angle of the cone of rays (sensor_msgs/Range field_of_view)', ge=0.0,
              lt=math.pi),
    ParamSpec('min_range', 'min_range_m', 'float', 0.0, 'm',
              'returns closer than this read -inf (REP 117)', ge=0.0),
    ParamSpec('max_range', 'max_range_m', 'float', None, 'm',
              "length of the rays; null = the lookup table's last distance, or "
              f'{DEFAULT_DISTANCE_RANGE_M:g} m', gt=0.0, optional=True),
    ParamSpec('lookup_table', 'lookup_table', 'rows', None, '',
              'Webots rows [distance, value, noise] for getValue(); null = the distance in m',
              length=3, optional=True),
    ParamSpec('radiation_type', 'radiation_type', 'enum', 'ultrasound',
              choices=RADIATION_TYPES, doc='sensor_msgs/Range radiation_type'),
    ParamSpec('noise', 'noise_m', 'float', 0.0, 'm',
              'standard deviation of the Gaussian range noise', ge=0.0),
)


@dataclass(frozen=True)
class DistanceSpec(SensorSpec):
    """A distance sensor: a ray (or a cone of rays) along the mount's x axis."""

    rays: int
    aperture_rad: float
    min_range_m: float
    max_range_m: float
    lookup_table: Optional[Tuple[Tuple[float, float, float], ...]]
    radiation_type: str
    noise_m: float

    def _default_topic(self):
        return self.name

    def table(self) -> LookupTable:
        """Return the lookup table of getValue(): the given one, or the distance itself."""
        if self.lookup_table is None:
            return LookupTable.identity(self.max_range_m)
        return LookupTable(self.lookup_table)


def check_distance(source, values):
    """Refuse a bad lookup table or ranges; a null ``max_range`` gets its default here."""
    table = values['lookup_table']
    if table is not None:
        try:
            LookupTable(table)
        except ValueError as error:
            fail(source, 'lookup_table', [list(r) for r in table], str(error))
    if values['max_range_m'] is None:
        values['max_range_m'] = (table[-1][0] if table is not None
                                 else DEFAULT_DISTANCE_RANGE_M)
    if values['min_range_m'] >= values['max_range_m']:
        fail(source, 'min_range', values['min_range_m'],
              f'must be < max_range ({values["max_range_m"]:g} m)')
