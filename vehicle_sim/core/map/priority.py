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
Who gives way to whom where two lanes conflict, from a lane map's rules (core/map/lane_rules.py).

At a :class:`~vehicle_sim.core.map.lane_rules.Conflict` of lanes ``lane_id`` and ``other_id``,
the other lane has priority over the lane when

- a :class:`~vehicle_sim.core.map.lane_rules.RightOfWay` rule lists the lane's way among its
  yield lanes and the other's among its priority lanes, or
- the conflict is unsignalled (no traffic light group governs either way) and the lane's way
  has a stop sign, yield or road-marking stop line while the other's has none.

A lane's *way* is the lane and its successors: a rule or a stop line names the lanes that lead
to an intersection, whose conflicts lie on the lanes that follow them. A conflict that neither
holds for (two signed or two unsigned ways, a merge with no rule) gives no one priority.
"""

from typing import Dict, Iterable, Set, Tuple

from vehicle_sim.core.map.lane_rules import Conflict

# The stop lines that make a way give way at an unsignalled conflict.
GIVE_WAY_KINDS = ('stop_sign', 'yield', 'road_marking')


def way_of(graph, lane_ids: Iterable[int]) -> Set[int]:
    """Return the lanes and their successors (the way they lead)."""
    way = set()
    for lane_id in lane_ids:
        way.add(lane_id)
        way.update(graph.lanes[lane_id].successors)
    return way


def priority_conflicts(graph) -> Dict[int, Tuple[Conflict, ...]]:
    """
    Return {lane id: the conflicts of that lane (seen from it) whose other lane has priority}.

    :param graph: a LaneGraph with its rules (``graph.rules``).
    """
    rules = graph.rules
    found: Dict[int, list] = {}

    def add(conflict):
        known = found.setdefault(conflict.lane_id, [])
        if conflict not in known:
            known.append(conflict)

    for rule in rules.right_of_way:
        first = way_of(graph, rule.priority_lanes)
        for lane_id in sorted(way_of(graph, rule.yield_lanes)):
            for conflict in rules.conflicts_of(lane_id):
                if conflict.other_id in first:
                    add(conflict)
    signalled = way_of(graph, (lane for group in rules.groups for lane in group.lanes))
    signed = way_of(graph, (line.lane_id for line in rules.stop_lines
                            if line.kind in GIVE_WAY_KINDS))
    for conflict in rules.conflicts:
        for one in (conflict, conflict.reversed()):
            if one.lane_id in signalled or one.other_id in signalled:
                continue
            if one.lane_id in signed and one.other_id not in signed:
                add(one)
    return {lane_id: tuple(conflicts) for lane_id, conflicts in found.items()}
