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
A node's parameters on the embedded transport, as rclpy's Node has them.

Declared values, validation, on-set callbacks, ``/parameter_events`` and the rcl_interfaces
parameter services.
"""

import dataclasses
from typing import Any, Callable, Dict, List, Mapping, Optional

from vehicle_sim.transport.dds.param_messages import (
    from_parameter_msg,
    to_parameter_msg,
    to_value_msg,
)
from vehicle_sim.transport.errors import TransportError
from vehicle_sim.transport.parameter_types import (
    normalize_parameter_value,
    Parameter,
    PARAMETER_DOUBLE,
    PARAMETER_INTEGER,
    parameter_type_of,
    run_validator,
    SetParametersResult,
    wrong_type_reason,
)
from vehicle_sim.transport.qos import QOS_PARAMETER_EVENTS, QOS_PARAMETERS
from vehicle_sim.transport.ros_args import read_only_reason, unknown_overrides_warning

SERVICE_PREFIX = 'rcl_interfaces/srv/'


@dataclasses.dataclass
class _ParamEntry:
    value: Any
    type_: int
    description: str = ''
    validator: Optional[Callable] = None
    read_only: bool = False
    additional_constraints: str = ''


class ParameterStore:
    """
    The parameters of one node; creates its ``/parameter_events`` publisher and services.

    :param node: the DdsNode (endpoints, message types, clock, name).
    :param overrides: initial values from the command line and the code, by name.
    :param applied: ``applied(name, value)`` after a value is declared or set.
    """

    def __init__(self, node, overrides: Mapping[str, Any],
                 applied: Callable[[str, Any], None]):
        self._node = node
        self._overrides = overrides
        self._applied = applied
        self._params: Dict[str, _ParamEntry] = {}
        self._on_set_callbacks: List[Callable] = []
        self._events = node.create_publisher(
            'rcl_interfaces/msg/ParameterEvent', '/parameter_events', QOS_PARAMETER_EVENTS)
        qos = QOS_PARAMETERS
        for srv, name, handler in (
                ('ListParameters', '~/list_parameters', self._handle_list_parameters),
                ('GetParameters', '~/get_parameters', self._handle_get_parameters),
                ('SetParameters', '~/set_parameters', self._handle_set_parameters),
                ('SetParametersAtomically', '~/set_parameters_atomically',
                 self._handle_set_parameters_atomically),
                ('DescribeParameters', '~/describe_parameters',
                 self._handle_describe_parameters),
                ('GetParameterTypes', '~/get_parameter_types',
                 self._handle_get_parameter_types)):
            node.create_service(SERVICE_PREFIX + srv, name, handler, qos)

    def unknown_overrides_warning(self) -> Optional[str]:
        """Return the warning for overrides that name no declared parameter, or None."""
        return unknown_overrides_warning(self._overrides, self._params)

    # ---------------------------------------------------------------- the NodePort methods

    def declare_parameter(self, name: str, default: Any, *, description: str = '',
                          validator=None, read_only: bool = False,
                          additional_constraints: str = '') -> Any:
        if name in self._params:
            raise TransportError(f'parameter {name!r} already declared')
        default = normalize_parameter_value(default)
        entry = _ParamEntry(default, parameter_type_of(default), description, validator,
                            read_only, additional_constraints)
        value = default
        if name in self._overrides:
            value = normalize_parameter_value(self._overrides[name])
            if entry.type_ == PARAMETER_DOUBLE and parameter_type_of(value) == \
                    PARAMETER_INTEGER:
                value = float(value)  # '-p gain:=2' for a double, as the YAML reader gives int
            reason = self._check_value(name, entry, value)
            if reason:
                raise TransportError(f'parameter {name!r} override {value!r} rejected: {reason}')
        entry.value = value
        self._params[name] = entry
        self._applied(name, value)
        self._publish_event(new=[Parameter(name, value)])
        return value

    def _check_value(self, name: str, entry: _ParamEntry, value: Any) -> Optional[str]:
        try:
            wrong_type = wrong_type_reason(name, entry.type_, value)
        except TransportError as exc:
            return str(exc)
        return wrong_type or run_validator(entry.validator, value)

    def get_parameter(self, name: str) -> Any:
        try:
            return self._params[name].value
        except KeyError:
            raise TransportError(f'parameter {name!r} is not declared') from None

    def has_parameter(self, name: str) -> bool:
        return name in self._params

    def add_on_set_parameters_callback(self, callback) -> None:
        self._on_set_callbacks.append(callback)

    def _try_set(self, parameters: List[Parameter]) -> SetParametersResult:
        for param in parameters:
            entry = self._params.get(param.name)
            if entry is None:
                return SetParametersResult(False, f'parameter {param.name!r} is not declared')
            if entry.read_only:
                return SetParametersResult(False, read_only_reason(param.name))
            reason = self._check_value(param.name, entry, param.value)
            if reason:
                return SetParametersResult(False, reason)
        for callback in self._on_set_callbacks:
            result = callback(list(parameters))
            if not result.successful:
                return result
        for param in parameters:
            self._params[param.name].value = param.value
            self._applied(param.name, param.value)
        self._publish_event(changed=parameters)
        return SetParametersResult(True)

    def set_parameters(self, parameters: List[Parameter]) -> List[SetParametersResult]:
        return [self._try_set([Parameter(p.name, normalize_parameter_value(p.value))])
                for p in parameters]

    def set_parameters_atomically(self, parameters: List[Parameter]) -> SetParametersResult:
        return self._try_set(
            [Parameter(p.name, normalize_parameter_value(p.value)) for p in parameters])

    def _publish_event(self, new=(), changed=()) -> None:
        node = self._node
        event_type = node.msg('rcl_interfaces/msg/ParameterEvent')
        self._events.publish(event_type(
            stamp=node.time_msg(), node=node.get_fully_qualified_name(),
            new_parameters=[to_parameter_msg(p.name, p.value) for p in new],
            changed_parameters=[to_parameter_msg(p.name, p.value) for p in changed]))

    # ---------------------------------------------------------------- the services

    def _handle_list_parameters(self, request, response):
        # rclpy Node._list_parameters: depth 0 = recursive; '.' separates name levels.
        names, prefixes = [], set()
        for name in sorted(self._params):
            if request.prefixes:
                matched = [p for p in request.prefixes if name == p or name.startswith(p + '.')]
                if not matched:
                    continue
                rest = name[len(matched[0]) + 1:]
            else:
                rest = name
            if request.depth and rest.count('.') >= request.depth:
                continue
            names.append(name)
            if '.' in name:
                prefixes.add(name.rsplit('.', 1)[0])
        response.result = self._node.msg('rcl_interfaces/msg/ListParametersResult')(
            names=names, prefixes=sorted(prefixes))
        return response

    def _handle_get_parameters(self, request, response):
        response.values = [to_value_msg(self._params[n].value if n in self._params else None)
                           for n in request.names]
        return response

    def _handle_set_parameters(self, request, response):
        result_type = self._node.msg('rcl_interfaces/msg/SetParametersResult')
        results = self.set_parameters([from_parameter_msg(p) for p in request.parameters])
        response.results = [result_type(successful=r.successful, reason=r.reason)
                            for r in results]
        return response

    def _handle_set_parameters_atomically(self, request, response):
        result = self.set_parameters_atomically(
            [from_parameter_msg(p) for p in request.parameters])
        response.result = self._node.msg('rcl_interfaces/msg/SetParametersResult')(
            successful=result.successful, reason=result.reason)
        return response

    def _handle_describe_parameters(self, request, response):
        descriptor_type = self._node.msg('rcl_interfaces/msg/ParameterDescriptor')
        response.descriptors = []
        for name in request.names:
            entry = self._params.get(name)
            if entry is None:
                response.descriptors.append(descriptor_type(name=name))
                continue
            response.descriptors.append(descriptor_type(
                name=name, type=entry.type_, description=entry.description,
                additional_constraints=entry.additional_constraints, read_only=entry.read_only))
        return response

    def _handle_get_parameter_types(self, request, response):
        response.types = [self._params[n].type_ if n in self._params else 0
                          for n in request.names]
        return response
