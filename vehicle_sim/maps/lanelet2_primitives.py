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
The vocabulary shared by the Lanelet2 loader and its rules: tags, lane ids, warnings.

lanelet2_map.py (the lanes) and lanelet2_rules.py (the regulatory elements) both read a
primitive's tags, name a lane by its id, and count and name primitives in one warning per kind.
"""

import warnings

# Lanelet subtypes that are walking areas, and the area kind each becomes.
WALKING_SUBTYPES = {'crosswalk': 'crosswalk', 'walkway': 'walkway', 'shared_walkway': 'walkway',
                    'pedestrian_lane': 'walkway', 'stairs': 'walkway'}


class Lanelet2MapWarning(UserWarning):
    """Part of a Lanelet2 map is not simulated (named in the message); the rest is loaded."""


def warn(message):
    """Warn about a map (one :class:`Lanelet2MapWarning`)."""
    warnings.warn(message, Lanelet2MapWarning, stacklevel=3)


def tags_of(primitive):
    """Return a lanelet2 primitive's attributes as a plain dict of strings."""
    return {key: str(value) for key, value in primitive.attributes.items()}


def lane_id_of(lanelet):
    """Return the lane id of a lanelet: its id, negated for an inverted one."""
    return -lanelet.id if lanelet.inverted() else lanelet.id


def counted(ids, what):
    """Return '1 lanelet' or '3 lanelets': how many ``ids``, ``what`` they are."""
    return f'{len(ids)} {what}' + ('' if len(ids) == 1 else 's')


def id_list(ids, shown=10):
    """Return '(id 7)' or '(ids 1, 2, ... (5 more))': the first ``shown`` ids, sorted."""
    ids = sorted(ids)
    more = f', ... ({len(ids) - shown} more)' if len(ids) > shown else ''
    return f"({'id' if len(ids) == 1 else 'ids'} {', '.join(map(str, ids[:shown]))}{more})"
