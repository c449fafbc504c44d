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
The ``signals:`` key of world files: the plan of the lane map's traffic lights.

The form (every key optional; a world whose lane map has traffic light groups runs the default
plan without it)::

    signals:
      plan: fixed_time
      green: 20.0       # s, each phase
      yellow: 3.0       # s, after each green
      all_red: 2.0      # s, after each yellow
      offset: 0.0       # s, the cycles' start
      phases:           # optional: the groups green together, in order (group ids)
        - [4000100101, 4000100151]
        - [4000200101, 4000200151]
      intersections:    # optional: an intersection's own times (the one holding the group)
        - {group: 4000300101, offset: 12.0}    # keys not given: the values above

Without ``phases`` the plan computes them from the groups' conflicts (core/map/signal_plan.py:
per intersection, the fewest phases a greedy colouring finds). ``phases`` lists them for the
whole map: one cycle of ``len(phases)`` phases, every group in exactly one phase. What needs
the map (a group id not in it, a group in no phase, two conflicting groups in one phase) is
checked when the world is built (physics/signal_part.py), naming the same file and field.
"""

from dataclasses import dataclass
from typing import Optional, Tuple

from vehicle_sim.core.map.signal_plan import FixedTimePlan
from vehicle_sim.core.specs.errors import InvalidParameterError
from vehicle_sim.core.specs.param_spec import (
    parameter_table_markdown,
    ParamSpec,
    REQUIRED,
    validate_table,
)
from vehicle_sim.core.specs.value_kinds import ParamRefused, register_kind
from vehicle_sim.core.specs.value_text import brief

PLAN_KINDS = ('fixed_time',)
_DEFAULT = FixedTimePlan()


def _check_phases(spec, value):
    if value is None:
        return None
    if not isinstance(value, (list, tuple)) or not value:
        raise ParamRefused('must be a non-empty list of phases (lists of group ids)')
    phases = []
    for index, phase in enumerate(value):
        if not isinstance(phase, (list, tuple)) or not phase or not all(
                isinstance(v, int) and not isinstance(v, bool) for v in phase):
            raise ParamRefused(f'phase {index} = {phase!r} must be a non-empty list of traffic '
                               'light group ids (integers)')
        phases.append(tuple(phase))
    seen = [group for phase in phases for group in phase]
    twice = sorted({group for group in seen if seen.count(group) > 1})
    if twice:
        raise ParamRefused(f'group(s) {twice} in more than one phase: a group is green in one '
                           'phase of the cycle')
    return tuple(phases)


SIGNAL_PHASES = register_kind('signal_phases', 'int[][]', _check_phases)

SIGNAL_SPECS = (
    ParamSpec('plan', 'plan', 'enum', 'fixed_time', choices=PLAN_KINDS,
              doc='the kind of plan: fixed_time (a fixed cycle at each intersection)'),
    ParamSpec('green', 'green_s', 'float', _DEFAULT.green_s, 's', 'green time of each phase',
              gt=0.0),
    ParamSpec('yellow', 'yellow_s', 'float', _DEFAULT.yellow_s, 's', 'yellow time after each '
              'green', ge=0.0),
    ParamSpec('all_red', 'all_red_s', 'float', _DEFAULT.all_red_s, 's', 'all-red time after '
              'each yellow (every group of the intersection red)', ge=0.0),
    ParamSpec('offset', 'offset_s', 'float', _DEFAULT.offset_s, 's', "the cycles' start: the "
              'first phase is green from then'),
    ParamSpec('phases', 'phases', SIGNAL_PHASES, None, '', 'the groups green together, in '
              'order: lists of traffic light group ids, every group of the map in one; null = '
              "computed from the groups' conflicts, per intersection", optional=True),
    ParamSpec('intersections', 'intersections', 'raw', (), '', "intersections' own times: a "
              'list of {group, green, yellow, all_red, offset} (the keys below), each for the '
              'intersection that has the group'),
)

# One entry of ``intersections``: the times not given are the map's (the keys above).
INTERSECTION_SPECS = (
    ParamSpec('group', 'group', 'int', REQUIRED, '', 'a traffic light group of the '
              'intersection (any one of its groups)'),
) + tuple(spec for spec in SIGNAL_SPECS if spec.key in ('green', 'yellow', 'all_red', 'offset'))


@dataclass(frozen=True)
class SignalSpec:
    """A validated ``signals:`` key (defaults: a world without one); ``source`` = where."""

    plan: str = 'fixed_time'
    green_s: float = _DEFAULT.green_s
    yellow_s: float = _DEFAULT.yellow_s
    all_red_s: float = _DEFAULT.all_red_s
    offset_s: float = _DEFAULT.offset_s
    phases: Optional[Tuple[Tuple[int, ...], ...]] = None
    intersections: Tuple[Tuple[int, FixedTimePlan], ...] = ()
    source: str = 'signals'

    def fixed_time_plan(self) -> FixedTimePlan:
        """Return the FixedTimePlan of these times."""
        return FixedTimePlan(self.green_s, self.yellow_s, self.all_red_s, self.offset_s)

    def intersection_plans(self):
        """Return {group id: FixedTimePlan} of the intersections with times of their own."""
        return dict(self.intersections)


def signals_from_dict(data, source) -> SignalSpec:
    """
    Validate a world's ``signals:`` mapping (None: the defaults).

    :raises InvalidParameterError: naming the source and the field.
    """
    values = validate_table(SIGNAL_SPECS, {} if data is None else data, source,
                            what='the signal plan')
    entries = values['intersections']
    if not isinstance(entries, (list, tuple)):
        raise InvalidParameterError(f"{source}: field 'intersections' = {brief(entries)}: must "
                                    'be a list of {group, green, yellow, all_red, offset}')
    defaults = {spec.key: values[spec.attr] for spec in INTERSECTION_SPECS[1:]}
    own = []
    for index, entry in enumerate(entries):
        where = f'{source}.intersections[{index}]'
        times = validate_table(INTERSECTION_SPECS, entry, where, dict(defaults, group=REQUIRED),
                               what='an intersection plan')
        try:
            plan = FixedTimePlan(times['green_s'], times['yellow_s'], times['all_red_s'],
                                 times['offset_s'])
        except InvalidParameterError as error:
            raise InvalidParameterError(f'{where}: {error}') from None
        own.append((times['group'], plan))
    twice = sorted({g for g, _ in own if [h for h, _ in own].count(g) > 1})
    if twice:
        raise InvalidParameterError(f"{source}: field 'intersections': group(s) {twice} given "
                                    'twice')
    values['intersections'] = tuple(own)
    return SignalSpec(source=source, **values)


def signals_markdown():
    """Return the key tables of ``signals:`` and its ``intersections`` entries, for the docs."""
    return (parameter_table_markdown(SIGNAL_SPECS, 'key')
            + "\n`intersections` entries (a time not given is the map's, above):\n\n"
            + parameter_table_markdown(INTERSECTION_SPECS, 'key'))
