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
The kinds of value a ParamSpec row may hold, each with its checker, and the registry of them.

``PARAM_KINDS`` maps each kind to its type column in the docs tables; a checker takes the row
and a candidate value and returns the validated value or raises :class:`ParamRefused` with the
reason. Domain modules add their own kinds with :func:`register_kind` (``pose``: core/geometry;
the sensors, traffic lane ids), so this package knows no domain types. :mod:`.param_spec` holds
the rows and the table validator.
"""

from dataclasses import dataclass
import math
import re
from typing import Tuple

# kind -> the type column of the generated docs tables (ROS parameter types for node kinds).
PARAM_KINDS = {
    'float': 'float', 'int': 'int', 'bool': 'bool', 'str': 'str', 'enum': 'str',
    'str_list': 'string[]', 'floats': 'float[]', 'float_list': 'float[]', 'vec3': 'float[3]',
    'inertia': 'float[6]', 'boxes': 'boxes', 'rgba': 'float[4]', 'rows': 'rows',
    'ros_name': 'str', 'topic': 'str', 'namespace': 'str', 'raw': 'any',
}


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


@dataclass(frozen=True)
class CollisionBox:
    """A chassis collision box in the vehicle frame."""

    size_m: Tuple[float, float, float]
    position_m: Tuple[float, float, float]
    pitch_rad: float = 0.0


def _is_number(value):
    return isinstance(value, (int, float)) and not isinstance(value, bool)


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
    'rgba': _check_rgba,
    'rows': _check_rows,
    'ros_name': _check_ros_name,
    'topic': _check_topic,
    'namespace': _check_namespace,
    'raw': lambda spec, value: value,    # checked by the caller (e.g. world sensors)
}


def parse_kind(spec, value):
    """Return ``value`` checked as ``spec.kind`` asks (raises ParamRefused with the reason)."""
    return _CHECKERS[spec.kind](spec, value)


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
