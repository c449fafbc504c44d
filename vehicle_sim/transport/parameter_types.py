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
ROS parameter values on the port: type codes, type inference, records and validators.

The type codes and records follow rcl_interfaces' ParameterType, Parameter and
SetParametersResult; a validator accepts or refuses a candidate value with a reason.
"""

from dataclasses import dataclass
from typing import Any, Callable, List, Optional

from vehicle_sim.core.specs.errors import VehicleSimError
from vehicle_sim.transport.errors import TransportError

# rcl_interfaces/msg/ParameterType
PARAMETER_NOT_SET = 0
PARAMETER_BOOL = 1
PARAMETER_INTEGER = 2
PARAMETER_DOUBLE = 3
PARAMETER_STRING = 4
PARAMETER_BYTE_ARRAY = 5
PARAMETER_BOOL_ARRAY = 6
PARAMETER_INTEGER_ARRAY = 7
PARAMETER_DOUBLE_ARRAY = 8
PARAMETER_STRING_ARRAY = 9


def parameter_type_of(value: Any) -> int:
    """
    Return the rcl_interfaces ParameterType code of a plain Python value.

    :raises TransportError: for a value ROS parameters cannot hold.
    """
    if value is None:
        return PARAMETER_NOT_SET
    if isinstance(value, bool):
        return PARAMETER_BOOL
    if isinstance(value, int):
        return PARAMETER_INTEGER
    if isinstance(value, float):
        return PARAMETER_DOUBLE
    if isinstance(value, str):
        return PARAMETER_STRING
    if isinstance(value, (bytes, bytearray)):
        return PARAMETER_BYTE_ARRAY
    if isinstance(value, (list, tuple)):
        if not value:
            raise TransportError('an empty list has no ROS parameter type; give a typed default')
        if all(isinstance(v, bool) for v in value):
            return PARAMETER_BOOL_ARRAY
        if all(isinstance(v, int) and not isinstance(v, bool) for v in value):
            return PARAMETER_INTEGER_ARRAY
        if all(isinstance(v, (int, float)) and not isinstance(v, bool) for v in value):
            return PARAMETER_DOUBLE_ARRAY
        if all(isinstance(v, str) for v in value):
            return PARAMETER_STRING_ARRAY
    raise TransportError(f'value {value!r} cannot be a ROS parameter')


# rclcpp's to_string(ParameterType) names, as `ros2 param describe` prints them
PARAMETER_TYPE_NAMES = ('not set', 'bool', 'integer', 'double', 'string', 'byte_array',
                        'bool_array', 'integer_array', 'double_array', 'string_array')


def wrong_type_reason(name: str, expected: int, value: Any) -> Optional[str]:
    """
    Return why ``value`` cannot be set on a parameter of type ``expected``, or None if it can.

    rclcpp's wording ("Wrong parameter type, parameter {x} is of type {integer}, setting it to
    {string} is not allowed."), with the types named and the value quoted, on both transports.
    """
    kind = parameter_type_of(value)
    if kind == expected:
        return None
    shown = repr(value) if len(repr(value)) <= 80 else repr(value)[:77] + '...'
    return (f'Wrong parameter type, parameter {{{name}}} is of type '
            f'{{{PARAMETER_TYPE_NAMES[expected]}}}, setting it to '
            f'{{{PARAMETER_TYPE_NAMES[kind]}}} {shown} is not allowed.')


def normalize_parameter_value(value: Any) -> Any:
    """Return the canonical Python form of a parameter value (lists, bytes, floats in arrays)."""
    kind = parameter_type_of(value)
    if kind == PARAMETER_DOUBLE_ARRAY:
        return [float(v) for v in value]
    if kind in (PARAMETER_BOOL_ARRAY, PARAMETER_INTEGER_ARRAY, PARAMETER_STRING_ARRAY):
        return list(value)
    if kind == PARAMETER_BYTE_ARRAY:
        return bytes(value)
    return value


@dataclass(frozen=True)
class Parameter:
    """A parameter name and its plain Python value, as handed to on-set callbacks."""

    name: str
    value: Any

    @property
    def type_(self) -> int:
        return parameter_type_of(self.value)


@dataclass(frozen=True)
class SetParametersResult:
    """What an on-set-parameters callback returns (rcl_interfaces/msg/SetParametersResult)."""

    successful: bool
    reason: str = ''


# A validator takes the candidate value and returns None (accept) or a reason string
# (reject); raising ValueError also rejects, with the exception text as the reason.
Validator = Callable[[Any], Optional[str]]
OnSetParametersCallback = Callable[[List[Parameter]], SetParametersResult]


def run_validator(validator: Optional[Validator], value: Any) -> Optional[str]:
    """Apply a validator; return the rejection reason or None when the value is accepted."""
    if validator is None:
        return None
    try:
        reason = validator(value)
    except (ValueError, TypeError, VehicleSimError) as exc:
        return str(exc) or type(exc).__name__
    if reason is None or reason is True:
        return None
    if reason is False:
        return f'value {value!r} rejected'
    return str(reason)
