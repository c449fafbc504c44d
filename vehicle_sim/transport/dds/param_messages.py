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
Parameter values <-> ``rcl_interfaces`` messages, for the parameter services and the CLI.

A value is the plain Python form the transport port uses (``parameter_type_of``): bool, int,
float, str, bytes and lists of bool, int, float or str; ``None`` is ``PARAMETER_NOT_SET``.
"""

from typing import Any, Optional

from vehicle_msgs_py import types as msg_types
from vehicle_sim.transport.parameter_types import (
    normalize_parameter_value,
    Parameter,
    PARAMETER_BOOL,
    PARAMETER_BOOL_ARRAY,
    PARAMETER_BYTE_ARRAY,
    PARAMETER_DOUBLE,
    PARAMETER_DOUBLE_ARRAY,
    PARAMETER_INTEGER,
    PARAMETER_INTEGER_ARRAY,
    PARAMETER_NOT_SET,
    PARAMETER_STRING,
    PARAMETER_STRING_ARRAY,
    parameter_type_of,
)

# ParameterType code -> the ParameterValue field that holds the value.
VALUE_FIELDS = {
    PARAMETER_BOOL: 'bool_value',
    PARAMETER_INTEGER: 'integer_value',
    PARAMETER_DOUBLE: 'double_value',
    PARAMETER_STRING: 'string_value',
    PARAMETER_BYTE_ARRAY: 'byte_array_value',
    PARAMETER_BOOL_ARRAY: 'bool_array_value',
    PARAMETER_INTEGER_ARRAY: 'integer_array_value',
    PARAMETER_DOUBLE_ARRAY: 'double_array_value',
    PARAMETER_STRING_ARRAY: 'string_array_value',
}
_FROM_MSG = {
    PARAMETER_BOOL: bool,
    PARAMETER_INTEGER: int,
    PARAMETER_DOUBLE: float,
    PARAMETER_STRING: str,
    PARAMETER_BYTE_ARRAY: bytes,
    PARAMETER_BOOL_ARRAY: lambda values: [bool(v) for v in values],
    PARAMETER_INTEGER_ARRAY: lambda values: [int(v) for v in values],
    PARAMETER_DOUBLE_ARRAY: lambda values: [float(v) for v in values],
    PARAMETER_STRING_ARRAY: list,
}


def to_value_msg(value: Any):
    """
    Return the ``rcl_interfaces/msg/ParameterValue`` of a plain value (None: not set).

    :raises TransportError: for a value ROS parameters cannot hold.
    """
    value_type = msg_types.message_type('rcl_interfaces/msg/ParameterValue')
    if value is None:
        return value_type(type=PARAMETER_NOT_SET)
    kind = parameter_type_of(value)
    return value_type(type=kind, **{VALUE_FIELDS[kind]: normalize_parameter_value(value)})


def from_value_msg(msg) -> Optional[Any]:
    """Return the plain value of a ParameterValue; None when not set (or of an unknown type)."""
    convert = _FROM_MSG.get(msg.type)
    return None if convert is None else convert(getattr(msg, VALUE_FIELDS[msg.type]))


def to_parameter_msg(name: str, value: Any):
    """Return the ``rcl_interfaces/msg/Parameter`` of a name and a plain value."""
    return msg_types.message_type('rcl_interfaces/msg/Parameter')(
        name=name, value=to_value_msg(value))


def from_parameter_msg(msg) -> Parameter:
    """Return the port Parameter of an ``rcl_interfaces/msg/Parameter``."""
    return Parameter(msg.name, from_value_msg(msg.value))
