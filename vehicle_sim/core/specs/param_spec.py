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
(``world/params.py``, ``sensors/params.py``) and every ROS node's parameters (declared on the node
by ``ros/node_support.py``). A refused value raises :class:`InvalidParameterError` naming the
source, the key, the value and the valid range. Docs tables come from
:func:`parameter_table_markdown`.
"""

from dataclasses import dataclass
import math
import re
from typing import Any, Callable, Optional, Tuple

from vehicle_sim.core.specs.errors import InvalidParameterError
from vehicle_sim.core.specs.value_text import brief

# kind -> the type column of the generated docs tables (ROS parameter types for node kinds).
PARAM_KINDS = {
    'float': 'float', 'int': 'int', 'bool': 'bool', 'str': 'str', 'enum': 'str',
    'str_list': 'string[]', 'floats': 'float[]', 'float_list': 'float[]', 'vec3': 'float[3]',
    'inertia': 'float[6]', 'boxes': 'boxes', 'pose': 'pose', 'rgba': 'float[4]', 'rows': 'rows',
    'ros_name': 'str', 'topic': 'str', 'namespace': 'str', 'raw': 'any',
}


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
        result = _CHECKERS[self.kind](self, value)
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


class ParamRefused(ValueError):
    """A value a ParamSpec refuses: the reason, and the part of the value it is about."""

    def __init__(self, reason, shown=None, sub_key=''):
        """
        Create the refusal.

        :param reason: why ('must be > 0', ...).
        :param shown: the offending part of the value (a box of a list); None = the value.
        :param sub_key: the entry of a mapping value it is about ('z' of a pose); '' = none.
        """
        super().__init__(reason)
        self.reason = reason
        self.shown = shown
        self.sub_key = sub_key


def _shown(refused, value):
    return value if refused.shown is None else refused.shown


@dataclass(frozen=True)
class CollisionBox:
    """A chassis collision box in the vehicle frame."""

    size_m: Tuple[float, float, float]
    position_m: Tuple[float, float, float]
    pitch_rad: float = 0.0


def _is_number(value):
    return isinstance(value, (int, float)) and not isinstance(value, bool)


def fail(source, key, value, reason, what='field'):
    if value is REQUIRED:       # nothing to quote: "field 'driver' is required"
        raise InvalidParameterError(f'{source}: {what} {key!r} {reason}')
    raise InvalidParameterError(f'{source}: {what} {key!r} = {brief(value)}: {reason}')


def _range_reason(spec, value):
    if not math.isfinite(value):
        rng = spec.range_text
        return 'must be finite' + (f' and {rng}' if rng else '')
    ok = ((spec.gt is None or value > spec.gt) and (spec.ge is None or value >= spec.ge)
          and (spec.le is None or value <= spec.le) and (spec.lt is None or value < spec.lt))
    return None if ok else _must_be(spec)


def _must_be(spec):
    rng = spec.range_text
    return f'must be {rng}' if rng[:1] in '<>' or rng.startswith('one of') else \
        f'must be in {rng}'


def _check_float(spec, value):
    if not _is_number(value):
        raise ParamRefused('must be a number' + _number_as_text(value))
    value = float(value)
    reason = _range_reason(spec, value)
    if reason:
        raise ParamRefused(reason, value)
    return value


def _number_as_text(value):
    # YAML 1.1 (PyYAML) reads a float in exponent form only with a dot and a signed exponent:
    # 1.0e+12 is a float, 1.0e12 and 1e+12 are strings.
    if isinstance(value, str) and _EXPONENT_FORM.match(value):
        return ' (YAML reads it as a string: a float needs a dot and a signed exponent, ' \
               'e.g. 1.0e+12)'
    return ''


_EXPONENT_FORM = re.compile(r'[-+]?(\d+\.?\d*|\.\d+)[eE][-+]?\d+$')


def _check_int(spec, value):
    if not isinstance(value, int) or isinstance(value, bool):
        raise ParamRefused('must be an integer' + (f' in {spec.range_text}'
                                                   if spec.range_text else ''))
    reason = _range_reason(spec, value)
    if reason:
        raise ParamRefused(reason)
    return value


def _check_bool(spec, value):
    if not isinstance(value, bool):
        raise ParamRefused('must be true or false')
    return value


def _check_str(spec, value):
    if not isinstance(value, str) or not (value or spec.empty):
        raise ParamRefused('must be a string' if spec.empty else 'must be a non-empty string')
    if spec.kind == 'enum' and value not in spec.choices:
        raise ParamRefused(_must_be(spec))
    return value


def _check_str_list(spec, value):
    if not isinstance(value, (list, tuple)) or not value or \
            not all(isinstance(v, str) and (v or spec.empty) for v in value):
        raise ParamRefused('must be a non-empty list of strings' if spec.empty else
                           'must be a non-empty list of non-empty strings')
    return tuple(value)


def _check_floats(spec, value, length=None):
    if not isinstance(value, (list, tuple)) or (length is not None and len(value) != length):
        size = f'{length} numbers' if length else 'numbers'
        raise ParamRefused(f'must be a list of {size}')
    result = []
    for item in value:
        if not _is_number(item) or not math.isfinite(float(item)):
            raise ParamRefused('every entry must be a finite number')
        result.append(float(item))
    return tuple(result)


def _check_vec3(spec, value):
    vector = _check_floats(spec, value, 3)
    if spec.gt is not None and min(vector) <= spec.gt:
        raise ParamRefused(f'every entry must be > {spec.gt:g}')
    return vector


def _check_boxes(spec, value):
    if not isinstance(value, (list, tuple)) or not value:
        raise ParamRefused('must be a non-empty list of boxes')
    boxes = []
    for box in value:
        if not isinstance(box, dict) or not set(box) <= {'size', 'position', 'pitch'} or \
                'size' not in box or 'position' not in box:
            raise ParamRefused('each box needs size and position (and optional pitch)', box)
        try:
            size = _check_floats(spec, box['size'], 3)
            position = _check_floats(spec, box['position'], 3)
        except ParamRefused as refused:
            raise ParamRefused(refused.reason, box) from None
        if min(size) <= 0.0:
            raise ParamRefused('box sizes must be > 0', box)
        pitch = box.get('pitch', 0.0)
        if not _is_number(pitch) or not math.isfinite(pitch):
            raise ParamRefused('pitch must be a finite number', box)
        boxes.append(CollisionBox(size, position, float(pitch)))
    return tuple(boxes)


POSE_KEYS = ('x', 'y', 'z', 'roll', 'pitch', 'yaw')


def _check_pose(spec, value):
    from vehicle_sim.core.geometry.frames import Pose
    if isinstance(value, Pose):
        return value
    keys = spec.choices or POSE_KEYS
    if not isinstance(value, dict):
        raise ParamRefused(f'must be a mapping of {", ".join(keys)}')
    unknown = sorted(set(value) - set(keys))
    if unknown:
        raise ParamRefused(f'unknown key(s) {brief(unknown)}; valid: {", ".join(keys)}')
    numbers = {}
    for key in POSE_KEYS:
        item = value.get(key, 0.0)
        if not _is_number(item) or not math.isfinite(float(item)):
            raise ParamRefused('must be a finite number', item, key)
        numbers[key] = float(item)
    return Pose(numbers['x'], numbers['y'], numbers['z'], numbers['roll'], numbers['pitch'],
                numbers['yaw'])


def _check_rgba(spec, value):
    color = _check_floats(spec, value, 4)
    if min(color) < 0.0 or max(color) > 1.0:
        raise ParamRefused('every entry must be in [0, 1] (red, green, blue, alpha)')
    return color


def _check_rows(spec, value):
    if not isinstance(value, (list, tuple)) or len(value) < 2:
        raise ParamRefused(f'must be a list of at least 2 rows of {spec.length} numbers')
    return tuple(_check_floats(spec, row, spec.length) for row in value)


# ROS 2 name rules (rcl validate_topic_name): tokens of letters, digits and underscores that do
# not start with a digit; no double underscore.
_TOKEN = re.compile(r'[A-Za-z_][A-Za-z0-9_]*$')


def _valid_token(token):
    return bool(_TOKEN.match(token)) and '__' not in token


def _check_ros_name(spec, value):
    if not isinstance(value, str) or not _valid_token(value):
        raise ParamRefused('must be a ROS name: letters, digits and underscores, not starting '
                           'with a digit')
    return value


def _check_topic(spec, value):
    body = value[1:] if isinstance(value, str) and value.startswith('/') else value
    if not isinstance(value, str) or not body or \
            not all(_valid_token(token) for token in body.split('/')):
        raise ParamRefused("must be a ROS topic name: tokens of letters, digits and underscores "
                           "separated by '/'")
    return value


def _check_namespace(spec, value):
    if value is None:
        return ''
    text = value.strip('/') if isinstance(value, str) else None
    if text is None or (text and not all(_valid_token(t) for t in text.split('/'))):
        raise ParamRefused('is not a valid ROS namespace')
    return text


_CHECKERS: dict = {
    'float': _check_float,
    'int': _check_int,
    'bool': _check_bool,
    'str': _check_str,
    'enum': _check_str,
    'str_list': _check_str_list,
    'floats': lambda spec, value: _check_floats(spec, value, spec.length),
    'float_list': lambda spec, value: _check_floats(spec, value),
    'vec3': _check_vec3,
    'inertia': lambda spec, value: _check_floats(spec, value, 6),
    'boxes': _check_boxes,
    'pose': _check_pose,
    'rgba': _check_rgba,
    'rows': _check_rows,
    'ros_name': _check_ros_name,
    'topic': _check_topic,
    'namespace': _check_namespace,
    'raw': lambda spec, value: value,    # checked by the caller (e.g. world sensors)
}


def register_kind(kind, type_text, checker):
    """
    Add a kind of value that a domain module defines (this module knows no domain types).

    :param kind: the kind's name, used as ``ParamSpec(kind=...)``; not one already registered.
    :param type_text: its type column in the docs tables.
    :param checker: ``checker(spec, value)`` -> the validated value; raises ParamRefused, or an
        InvalidParameterError naming its own field (a nested table).
    :return: ``kind``, for the modules whose ParamSpecs use it (importing it registers it).
    """
    if kind in PARAM_KINDS:
        raise ValueError(f'ParamSpec kind {kind!r} is registered already')
    PARAM_KINDS[kind] = type_text
    _CHECKERS[kind] = checker
    return kind


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
