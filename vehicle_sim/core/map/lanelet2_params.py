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
The keys of a Lanelet2 lane map in a world file: ``map: {type: lanelet2, file: ..., ...}``.

Only the table and its validation live here (ROS-free, file-free); reading the ``.osm`` file is
``vehicle_sim/maps/lanelet2_map.py``'s, with the ``lanelet2`` package.

Projectors (how the file's nodes become world x, y):

- ``local_cartesian``: the east-north-up plane at the world's geodetic ``origin`` (the plane
  core/geometry/geodesy.py and the GNSS sensor use), from each node's ``lat``/``lon``;
- ``utm``: UTM grid coordinates of each node's ``lat``/``lon`` minus those of the world's
  origin (Lanelet2's UtmProjector with that origin); the grid's north differs from true north
  by the meridian convergence, so a GNSS fix and the map disagree slightly away from the origin;
- ``autoware_local``: each node's ``local_x``/``local_y`` tags, as they are (Autoware's map
  loader does the same for its local and MGRS maps: the tags are the map frame); every node must
  carry both. ``lat``/``lon`` are not used (they may be empty), and the world needs no
  ``origin:`` for the map.
"""

from dataclasses import dataclass
from typing import Any

from vehicle_sim.core.specs.param_spec import ParamSpec, REQUIRED, validate_table

LANELET2_PROJECTORS = ('local_cartesian', 'utm', 'autoware_local')

LANELET2_SPECS = (
    ParamSpec('type', 'type', 'enum', 'lanelet2', choices=('lanelet2',), doc='lanelet2'),
    ParamSpec('file', 'file', 'str', REQUIRED, doc='the .osm file, relative to the world file'),
    ParamSpec('projector', 'projector', 'enum', 'local_cartesian', choices=LANELET2_PROJECTORS,
              doc="how nodes become world x, y: the origin's east-north-up plane, UTM minus "
                  "the origin's UTM, or Autoware's local_x/local_y node tags"),
    ParamSpec('default_speed_limit', 'default_speed_limit_mps', 'float', 13.9, 'm/s',
              'speed limit of a lanelet with neither a speed_limit tag nor a speed limit '
              'regulatory element', gt=0.0),
)


@dataclass(frozen=True)
class Lanelet2MapSpec:
    """
    A validated ``map:`` of type lanelet2.

    ``file`` as written (relative to the world file) from :func:`lanelet2_map_from_dict`,
    resolved against the world file's folder from the world's ``map:`` key (core/map/kinds.py),
    which also sets ``world_in_map`` (identity: the projector puts the nodes in the world frame)
    and ``source`` (where it was written, quoted in errors).
    """

    type: str
    file: str
    projector: str
    default_speed_limit_mps: float
    world_in_map: Any = None
    source: str = ''


def lanelet2_map_from_dict(data, source) -> Lanelet2MapSpec:
    """Validate a ``map:`` mapping of type lanelet2; InvalidParameterError names the field."""
    return Lanelet2MapSpec(**validate_table(LANELET2_SPECS, data, source, what='a map'))
