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
The one parameter-spec kind: :class:`ParamSpec` rows, their validation and their docs tables.

Every parameter table of the project is a tuple of ParamSpec rows validated by
:func:`validate_table`: the car presets (``car/params.py``), the robot presets
(``diffdrive/params.py``), the bridge (``bridge/params.py``), world files, sensors and obstacles
(``world/params.py``, ``sensors/*_spec.py``) and every ROS node's parameters (declared on the node
by ``ros/node_support.py``). A refused value raises :class:`InvalidParameterError` naming the
source, the key, the value and the valid range. Docs tables come from
:func:`parameter_table_markdown`. The kinds of value and their checkers are :mod:`.value_kinds`.
"""

from dataclasses import dataclass
from typing import Any, Callable, Optional, Tuple

from vehicle_sim.core.specs.errors import InvalidParameterError
from vehicle_sim.core.specs.value_kinds import PARAM_KINDS, ParamRefused, parse_kind
from vehicle_sim.core.specs.value_text import brief


class _Required:
    """Default of a key that has none: leaving it out is an error."""

    def __repr__(self):
        return 'REQUIRED'


REQUIRED = _Required()


@dataclass(frozen=True)
class ParamSpec:
    """
    One parameter of a preset or a node: key, attribute, kind, default, unit, range and doc.

    :param key: the name in preset files, ROS parameter files and on the node.
    :param attr: the attribute of the validated value object; '' = ``key``.
    :param kind: one of :data:`PARAM_KINDS`: 'float', 'int', 'bool', 'str', 'enum' (one of
        ``choices``), 'str_list' (list of strings), 'floats' (``length`` numbers), 'float_list'
        (any number of numbers), 'vec3', 'inertia', 'boxes', 'pose' (mapping of x, y, z, roll,
        pitch, yaw; ``choices`` restricts the keys), 'rgba', 'rows' (a table of rows of
        ``length`` numbers), 'ros_name', 'topic', 'namespace', 'raw' (passed on; its caller
        validates it) and the kinds a domain module adds with :func:`register_kind` (e.g.
        'sensors', a list of sensor mappings, in core/sensors/sets.py).
    :param default: the default; for node parameters its Python type is the ROS type;
        :data:`REQUIRED` makes a key mandatory.
    :param unit: unit, '' when none.
    :param doc: one-line description (docs tables, ``ros2 param describe``).
    :param gt: exclusive lower bound (numbers; for 'vec3' every entry).
    :param ge: inclusive lower bound.
    :param le: inclusive upper bound.
    :param lt: exclusive upper bound.
    :param choices: the valid values of an 'enum'.
    :param length: the number of entries of a 'floats'.
    :param optional: None is valid (means "derive it").
    :param empty: '' is a valid 'str' (or 'str_list' entry).
    :param check: an extra rule, ``check(value)`` -> None or the reason the value is refused
        (a preset lookup, a naming rule; a ValueError it raises is a refusal too); it runs
        after the kind and range checks.
    :param read_only: node parameters: fixed once the node runs.
    """

    key: str
    attr: str = ''
    kind: str = 'float'
    default: Any = None
    unit: str = ''
    doc: str = ''
    gt: Optional[float] = None
    ge: Optional[float] = None
    le: Optional[float] = None
    lt: Optional[float] = None
    choices: Tuple[str, ...] = ()
    length: Optional[int] = None
    optional: bool = False
    empty: bool = False
    check: Optional[Callable[[Any], Optional[str]]] = None
    read_only: bool = True

    def __post_init__(self):
        """Fill ``attr`` from ``key`` and refuse an unknown kind."""
        if not self.attr:
            object.__setattr__(self, 'attr', self.key)
        if self.kind not in PARAM_KINDS:
            raise InvalidParameterError(f'ParamSpec {self.key!r}: unknown kind {self.kind!r}; '
                                        f'valid: {", ".join(PARAM_KINDS)}')

    @property
    def range_text(self) -> str:
        """The valid range in words ('> 0', '1 .. 1000', 'one of a, b'); '' when unbounded."""
        if self.kind == 'enum':
            return 'one of ' + ', '.join(self.choices)
        if self.kind == 'int' and self.ge is not None and self.le is not None:
            return f'{self.ge:g} .. {self.le:g}'
        parts = [f'{text} {bound:g}' for bound, text in
                 ((self.gt, '>'), (self.ge, '>='), (self.le, '<='), (self.lt, '<'))
                 if bound is not None]
        return ' and '.join(parts)

    @property
    def description(self) -> str:
        """``doc`` with the unit in brackets (the ROS parameter description)."""
        return f'{self.doc} [{self.unit}]' if self.unit else self.doc

    def parse(self, value):
        """
        Return the validated value (floats as float, lists as tuples).

        :raises ParamRefused: naming the reason (and the offending part of ``value``).
        """
        if value is REQUIRED:
            raise ParamRefused('is required')
        if value is None:
            if self.optional:
                return None
            raise ParamRefused('must not be null')
        result = parse_kind(self, value)
        if self.check is not None:
            try:
                reason = self.check(value)
            except ValueError as error:       # a rule may raise instead of returning a reason
                reason = str(error)
            if reason:
                raise ParamRefused(reason)
        return result

    def refusal(self, value) -> Optional[str]:
        """
        Return None when ``value`` is valid, else ``'<key> = <value>: <reason>'``.

        The form a transport validator returns (the node refuses the value with this text).
        """
        try:
            self.parse(value)
        except ParamRefused as refused:
            if value is REQUIRED:
                return f'{self.key} {refused.reason}'
            return f'{self.key} = {brief(_shown(refused, value))}: {refused.reason}'
        return None


def _shown(refused, value):
    return value if refused.shown is None else refused.shown


def fail(source, key, value, reason, what='field'):
    if value is REQUIRED:       # nothing to quote: "field 'driver' is required"
        raise InvalidParameterError(f'{source}: {what} {key!r} {reason}')
    raise InvalidParameterError(f'{source}: {what} {key!r} = {brief(value)}: {reason}')


def check_value(spec, value, source, key_word='field'):
    """
    Validate one value against its ParamSpec.

    :param spec: the ParamSpec.
    :param value: the candidate value.
    :param source: file or node name quoted in the error.
    :param key_word: how the error names the key ('field', 'parameter').
    :return: the validated value.
    :raises InvalidParameterError: ``'<source>: <key_word> '<key>' = <value>: <reason>'``.
    """
    try:
        return spec.parse(value)
    except ParamRefused as refused:
        key = f'{spec.key}.{refused.sub_key}' if refused.sub_key else spec.key
        fail(source, key, _shown(refused, value), refused.reason, key_word)
    except InvalidParameterError as error:    # a nested table (e.g. sensors) names its field
        raise InvalidParameterError(f'{source}: {error}') from None


def table_defaults(specs):
    """Return {key: default} of a ParamSpec table."""
    return {spec.key: spec.default for spec in specs}


_FIELD_TYPES = {'float': float, 'int': int, 'bool': bool, 'str': str, 'enum': str}


def table_dataclass(specs):
    """
    Make a class the frozen dataclass of a ParamSpec table: each default written once, in its row.

    Class decorator. The class gets one field per row (the row's ``attr``, a type from its kind
    and its default), ``SPECS`` (the table) and, unless it has its own,
    ``from_dict(data, source)``: the validated instance of a mapping of the table's keys (missing
    keys take the defaults; None is an empty mapping). Its own methods stay.

    :param specs: the ParamSpec rows; each must have a default.
    :raises InvalidParameterError: for a row without a default.
    """
    def make(cls):
        annotations = dict(cls.__dict__.get('__annotations__', {}))
        for spec in specs:
            if spec.default is REQUIRED:
                raise InvalidParameterError(f'table_dataclass({cls.__name__}): row '
                                            f'{spec.key!r} has no default')
            annotations[spec.attr] = _FIELD_TYPES.get(spec.kind, Any)
            setattr(cls, spec.attr, spec.default)
        cls.__annotations__ = annotations
        cls.SPECS = specs
        if 'from_dict' not in cls.__dict__:
            cls.from_dict = classmethod(_from_dict)
        return dataclass(frozen=True)(cls)
    return make


def _from_dict(cls, data, source):
    """Validate a mapping of the table's keys (missing keys: the defaults)."""
    return cls(**validate_table(cls.SPECS, data or {}, source))


def validate_table(specs, data, source, defaults=None, what='parameters', key_word='field'):
    """
    Validate a mapping against a ParamSpec table: the one validator of every parameter table.

    :param specs: the ParamSpec rows.
    :param data: mapping of keys to values; missing keys take ``defaults``.
    :param source: file or node name quoted in error messages.
    :param defaults: mapping of every key to its default; None = the table's defaults.
    :param what: what ``data`` is, for the error on a non-mapping ('a car preset', ...).
    :param key_word: how errors name a key ('field', 'parameter').
    :return: {attribute name: validated value} for every row.
    :raises InvalidParameterError: naming source, key and value for an unknown key, a wrong
        type or an impossible value.
    """
    if not isinstance(data, dict):
        raise InvalidParameterError(f'{source}: {what} must be a mapping, got {brief(data)}')
    by_key = {spec.key: spec for spec in specs}
    for key, value in data.items():
        if key not in by_key:
            raise InvalidParameterError(
                f'{source}: unknown {key_word} {brief(key)} (value {brief(value)}); '
                f'valid {key_word}s: '
                + ', '.join(sorted(by_key)))
    merged = table_defaults(specs) if defaults is None else dict(defaults)
    merged.update(data)
    return {spec.attr: check_value(spec, merged[spec.key], source, key_word) for spec in specs}


def yaml_text(value) -> str:
    """Return a value the way a YAML file (and the docs tables) write it."""
    if value is None:
        return 'null'
    if value is REQUIRED:
        return 'required'
    if hasattr(value, 'as_dict'):         # a Pose
        return yaml_text(value.as_dict())
    if isinstance(value, bool):
        return 'true' if value else 'false'
    if isinstance(value, str):
        return f"'{value}'"
    if isinstance(value, dict):
        return '{' + ', '.join(f'{k}: {yaml_text(v)}' for k, v in value.items()) + '}'
    if isinstance(value, (list, tuple)):
        return '[' + ', '.join(yaml_text(v) for v in value) + ']'
    return repr(value)


def _cell(text):
    return str(text).replace('|', '\\|')


def parameter_table_markdown(specs, key_word='parameter', extra_rows=(), skip=()):
    """
    Return the Markdown table of a ParamSpec table (the docs tables are generated by this).

    Columns: key, type, default, unit, valid range (every float must be finite), description.

    :param specs: the ParamSpec rows.
    :param key_word: header of the first column ('parameter', 'field').
    :param extra_rows: further rows, each a tuple of the six cells (plain text).
    :param skip: keys to leave out (documented elsewhere, e.g. the common sensor keys).
    """
    lines = [f'| {key_word} | type | default | unit | range | description |',
             '|---|---|---|---|---|---|']
    for spec in specs:
        if spec.key in skip:
            continue
        default = spec.default
        if spec.kind == 'pose' and spec.choices and hasattr(default, 'as_dict'):
            default = {k: v for k, v in default.as_dict().items() if k in spec.choices}
        valid = spec.range_text or ('finite' if spec.kind == 'float' else '')
        lines.append(f'| `{spec.key}` | {PARAM_KINDS[spec.kind]} | `{yaml_text(default)}` | '
                     f'{_cell(spec.unit)} | {_cell(valid)} | {_cell(spec.doc)} |')
    for row in extra_rows:
        lines.append('| ' + ' | '.join(_cell(cell) for cell in row) + ' |')
    return '\n'.join(lines) + '\n'
