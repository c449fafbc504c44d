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

from typing import Callable, Dict, Iterable, Set, Tuple

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


def priority_test(graph) -> Callable[[int, int], bool]:
    """
    Return ``has_priority(lane_id, other_id)``: whether the other lane's way goes first.

    The rules of the module's text, for any two lanes of the graph (the traffic asks it of the
    pairs whose vehicles' footprints meet as well as of the map's conflicts).

    :param graph: a LaneGraph with its rules (``graph.rules``).
    """
    rules = graph.rules
    ruled = set()
    for rule in rules.right_of_way:
        first = way_of(graph, rule.priority_lanes)
        ruled.update((lane_id, other_id) for lane_id in way_of(graph, rule.yield_lanes)
                     for other_id in first)
    signalled = way_of(graph, (lane for group in rules.groups for lane in group.lanes))
    signed = way_of(graph, (line.lane_id for line in rules.stop_lines
                            if line.kind in GIVE_WAY_KINDS))

    def has_priority(lane_id, other_id):
        if (lane_id, other_id) in ruled:
            return True
        if lane_id in signalled or other_id in signalled:
            return False
        return lane_id in signed and other_id not in signed

    return has_priority


def priority_conflicts(graph) -> Dict[int, Tuple[Conflict, ...]]:
    """
    Return {lane id: the conflicts of that lane (seen from it) whose other lane has priority}.

    :param graph: a LaneGraph with its rules (``graph.rules``).
    """
    has_priority = priority_test(graph)
    found: Dict[int, list] = {}
    for conflict in graph.rules.conflicts:
        for one in (conflict, conflict.reversed()):
            if has_priority(one.lane_id, one.other_id):
                known = found.setdefault(one.lane_id, [])
                if one not in known:
                    known.append(one)
    return {lane_id: tuple(conflicts) for lane_id, conflicts in found.items()}
