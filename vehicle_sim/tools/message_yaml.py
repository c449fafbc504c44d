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
Messages as plain data for the graph commands: YAML out (``echo``, ``call`` replies), typed in.

:func:`format_message` prints a message like ``ros2 topic echo``; :func:`from_plain` and
:func:`build_request` build a message or a service request from the user's YAML, checking every
field's type and integer range.
"""

import dataclasses
import functools
import math
import re
import typing
from typing import Any, List, Optional, Sequence

import yaml

from vehicle_sim.tools.command import CliError, EXIT_USAGE

# Fields generated for empty messages (rosidl); never shown, never set.
_HIDDEN_FIELDS = ('structure_needs_at_least_one_member',)
_INT_RANGES = {
    'int8': (-2 ** 7, 2 ** 7 - 1), 'uint8': (0, 2 ** 8 - 1),
    'int16': (-2 ** 15, 2 ** 15 - 1), 'uint16': (0, 2 ** 16 - 1),
    'int32': (-2 ** 31, 2 ** 31 - 1), 'uint32': (0, 2 ** 32 - 1),
    'int64': (-2 ** 63, 2 ** 63 - 1), 'uint64': (0, 2 ** 64 - 1),
}


@dataclasses.dataclass(frozen=True)
class Abbreviation:
    """
    How ``ros2 topic echo`` shortens long values (rosidl_runtime_py's ``message_to_yaml``).

    :param truncate_length: strings longer than this keep their first ``truncate_length``
        characters and end in ``...``; sequences and arrays keep their first
        ``truncate_length`` items and get an item ``'...'``; None keeps everything.
    :param no_arr: show each sequence or array field as its type and length
        (``<sequence type: double, length: 130>``, ``<array type: double[36]>``).
    :param no_str: show each string as its length (``<string length: <130>>``).
    """

    truncate_length: Optional[int] = None
    no_arr: bool = False
    no_str: bool = False


FULL_LENGTH = Abbreviation()
# rosidl names basic types by their IDL names in --no-arr's text ('sequence type: double').
_IDL_NAMES = {'float64': 'double', 'float32': 'float', 'bool': 'boolean', 'byte': 'octet',
              'char': 'uint8', 'str': 'string'}
TRUNCATED = '...'


def to_plain(msg: Any, abbreviation: Abbreviation = FULL_LENGTH) -> Any:
    """
    Return a message as nested dicts/lists/scalars in field order (for YAML output).

    :param abbreviation: what to shorten, as ``ros2 topic echo`` does (default: nothing).
    """
    return _plain(msg, abbreviation, None)


def _plain(value: Any, abbreviation: Abbreviation, annotation) -> Any:
    if dataclasses.is_dataclass(value) and not isinstance(value, type):
        hints = _hints(type(value))
        return {f.name: _plain(getattr(value, f.name), abbreviation, hints.get(f.name))
                for f in dataclasses.fields(value) if f.name not in _HIDDEN_FIELDS}
    if hasattr(value, 'get_fields_and_field_types'):  # an rclpy message
        return {name: _plain(getattr(value, name), abbreviation, field_type)
                for name, field_type in value.get_fields_and_field_types().items()}
    limit = abbreviation.truncate_length
    if isinstance(value, str):
        if abbreviation.no_str:
            return f'<string length: <{len(value)}>>'
        return value if limit is None or len(value) <= limit else value[:limit] + TRUNCATED
    if isinstance(value, (bytes, bytearray)):
        value = list(value)
    elif hasattr(value, 'tolist'):  # numpy arrays of rclpy messages
        value = value.tolist()
    if isinstance(value, (list, tuple)):
        if abbreviation.no_arr and annotation is not None:
            return _array_info(annotation, len(value))
        kept = value if limit is None or len(value) <= limit else value[:limit]
        items = [_plain(item, abbreviation, None) for item in kept]
        return items + [TRUNCATED] if len(kept) < len(value) else items
    return value


@functools.lru_cache(maxsize=None)
def _hints(cls) -> dict:
    return typing.get_type_hints(cls, include_extras=True)


def _element_name(element) -> str:
    ros_type = getattr(element, '__ros_type__', None)
    if ros_type is not None:
        return ros_type
    args = typing.get_args(element)
    name = args[1] if len(args) > 1 and isinstance(args[1], str) else (
        getattr(args[0] if args else element, '__name__', str(element)))
    return _IDL_NAMES.get(name, name)


def _array_info(annotation, length: int) -> str:
    """
    Return rosidl's ``--no-arr`` text of a sequence or array field.

    :param annotation: the field's annotation (generated types) or its type string (rclpy:
        ``sequence<double>``, ``sequence<double, 5>``, ``double[36]``).
    """
    if isinstance(annotation, str):
        match = re.fullmatch(r'sequence<([^,>]+)(?:, (\d+))?>', annotation)
        if match:
            element, bound = match.groups()
        else:
            match = re.fullmatch(r'(.+)\[(\d+)\]', annotation)
            if match is None:
                return 'unknown'
            return f'<array type: {match.group(1)}[{match.group(2)}]>'
    else:
        meta = typing.get_args(annotation)[1]
        element = _element_name(meta.subtype)
        if hasattr(meta, 'length'):
            return f'<array type: {element}[{meta.length}]>'
        bound = meta.max_length
    bounded = f'[{bound}]' if bound else ''
    return f'<sequence type: {element}{bounded}, length: {length}>'


class _OrderedDumper(yaml.SafeDumper):
    pass


def _represent_dict(dumper, data):
    return dumper.represent_mapping('tag:yaml.org,2002:map', data.items())


def _represent_float(dumper, value):
    if math.isnan(value):
        text = '.nan'
    elif math.isinf(value):
        text = '.inf' if value > 0 else '-.inf'
    else:
        text = repr(float(value))
    return dumper.represent_scalar('tag:yaml.org,2002:float', text)


_OrderedDumper.add_representer(dict, _represent_dict)
_OrderedDumper.add_representer(float, _represent_float)


def format_message(msg: Any, abbreviation: Abbreviation = FULL_LENGTH) -> str:
    """Return a message as YAML (fields in definition order), like ``ros2 topic echo``."""
    plain = to_plain(msg, abbreviation)
    if not isinstance(plain, dict):
        plain = {'data': plain}
    return format_plain(plain)


def format_plain(plain: Any) -> str:
    """Return plain data as YAML; a lone scalar as its YAML text (``30.0``), no end marker."""
    text = yaml.dump(plain, Dumper=_OrderedDumper, default_flow_style=False, sort_keys=False,
                     allow_unicode=True, width=1000)
    return text[:-len('...\n')] if text.endswith('\n...\n') else text


def format_line(msg: Any) -> str:
    """Return a message as one line of flow-style YAML (``{linear: {x: 1.0, ...}, ...}``)."""
    return yaml.dump(to_plain(msg), Dumper=_OrderedDumper, default_flow_style=True,
                     sort_keys=False, allow_unicode=True, width=float('inf')).strip()


def field_path(cls, path: str) -> List[str]:
    """
    Return the field names of ``path`` (``twist.linear``), checked against a message class.

    :raises CliError: (usage) for a name the message has not, listing the fields it has.
    """
    names = path.split('.')
    plain = to_plain(cls())
    for depth, name in enumerate(names):
        where = '.'.join(names[:depth]) or cls.__ros_type__
        if not isinstance(plain, dict) or name not in plain:
            fields = ', '.join(plain) if isinstance(plain, dict) else '(none: not a message)'
            raise CliError(f'--field {path}: {where} has no field {name!r}; fields: {fields}',
                           EXIT_USAGE)
        plain = plain[name]
    return names


def pick_field(msg: Any, names: Sequence[str],
               abbreviation: Abbreviation = FULL_LENGTH) -> Any:
    """Return the plain value of the field at ``names`` (from :func:`field_path`) of ``msg``."""
    plain = to_plain(msg, abbreviation)
    for name in names:
        plain = plain[name]
    return plain


def _field_shape(annotation) -> tuple:
    """
    Describe a field annotation of a generated type.

    :return: ``('message', cls)``, ``('list', element_annotation)`` or ``('scalar', py, name)``.
    """
    args = typing.get_args(annotation)
    if typing.get_origin(annotation) is typing.Annotated or (
            args and not dataclasses.is_dataclass(annotation)):
        base = args[0] if args else annotation
        meta = args[1] if len(args) > 1 else None
        if typing.get_origin(base) in (list, tuple, Sequence, typing.Sequence) or \
                str(typing.get_origin(base)) == "<class 'collections.abc.Sequence'>":
            return ('list', typing.get_args(base)[0])
        if isinstance(meta, str):
            return ('scalar', base, meta)
        return _field_shape(base)
    if dataclasses.is_dataclass(annotation):
        return ('message', annotation)
    if annotation in (bool, int, float, str):
        return ('scalar', annotation, annotation.__name__)
    return ('scalar', annotation, str(annotation))


def _coerce_scalar(value: Any, py_type, type_name: str, where: str) -> Any:
    if py_type is bool:
        if isinstance(value, bool):
            return value
        raise CliError(f'{where}: expected a boolean (true/false), got {value!r}')
    if py_type is int:
        if isinstance(value, bool) or not isinstance(value, int):
            if isinstance(value, float) and value.is_integer():
                value = int(value)
            else:
                raise CliError(f'{where}: expected an integer ({type_name}), got {value!r}')
        low, high = _INT_RANGES.get(type_name, (None, None))
        if low is not None and not low <= value <= high:
            raise CliError(f'{where}: {value} outside the {type_name} range {low}..{high}')
        return value
    if py_type is float:
        if isinstance(value, bool) or not isinstance(value, (int, float)):
            raise CliError(f'{where}: expected a number ({type_name}), got {value!r}')
        return float(value)
    if py_type is str:
        return value if isinstance(value, str) else yaml.safe_dump(value).strip()
    return value


def _coerce(value: Any, annotation, where: str) -> Any:
    shape = _field_shape(annotation)
    if shape[0] == 'message':
        return from_plain(shape[1], value, where)
    if shape[0] == 'list':
        if not isinstance(value, (list, tuple)):
            raise CliError(f'{where}: expected a list, got {value!r}')
        return [_coerce(v, shape[1], f'{where}[{i}]') for i, v in enumerate(value)]
    return _coerce_scalar(value, shape[1], shape[2], where)


def from_plain(cls, data: Any, where: str = 'request'):
    """
    Build a generated message from a dict (YAML), checking every field's type.

    :raises CliError: for an unknown field or a value of the wrong type.
    """
    if data is None:
        return cls()
    if not isinstance(data, dict):
        raise CliError(f'{where}: expected a mapping of fields, got {data!r}')
    fields = {f.name: f for f in dataclasses.fields(cls) if f.name not in _HIDDEN_FIELDS}
    hints = typing.get_type_hints(cls, include_extras=True)
    values = {}
    for key, value in data.items():
        if key not in fields:
            raise CliError(f'{where}: {cls.__ros_type__} has no field {key!r}; '
                           f'fields: {", ".join(fields) or "(none)"}')
        values[key] = _coerce(value, hints[key], f'{where}.{key}')
    return cls(**values)


def build_request(request_cls, value_text: Optional[str], where: str = 'request'):
    """
    Build a service request from the command-line VALUE.

    A YAML mapping (``"{value: 30}"``) sets fields by name; any other value sets the request's
    single field (``30`` for SetFloat, ``true`` for SetBool); no VALUE gives the defaults.
    A topic message is built the same way (``where='message'`` names it in errors).
    """
    fields = [f.name for f in dataclasses.fields(request_cls) if f.name not in _HIDDEN_FIELDS]
    if value_text is None:
        return request_cls()
    try:
        value = yaml.safe_load(value_text)
    except yaml.YAMLError as exc:
        raise CliError(f'VALUE {value_text!r} is not valid YAML: {exc}') from None
    if isinstance(value, dict):
        return from_plain(request_cls, value, where)
    if len(fields) != 1:
        raise CliError(
            f'{request_cls.__ros_type__} has {len(fields)} fields ({", ".join(fields)}); '
            f'give VALUE as YAML, e.g. "{{{fields[0] if fields else "field"}: ...}}"')
    hints = typing.get_type_hints(request_cls, include_extras=True)
    shape = _field_shape(hints[fields[0]])
    if shape[0] == 'scalar' and shape[1] is str:
        value = value_text  # keep the text verbatim for string fields
    return from_plain(request_cls, {fields[0]: value}, where)
