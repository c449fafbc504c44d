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
The node's parameters through the Foxglove protocol's parameter capability.

Getting reads the node's declared values; setting goes through ``NodePort.set_parameters`` on
the node's thread, so the same checks as ``ros2 param set`` apply (type, range, the table's
rules). A refused value changes nothing: the client gets the value still in force and a
warning status naming the reason.
"""

from typing import Iterable, List, Tuple

from vehicle_sim.foxglove.services import on_node_thread
from vehicle_sim.transport.parameter_types import Parameter


def to_native(value):
    """Return a parameter value as the SDK takes it (tuples as lists)."""
    if isinstance(value, tuple):
        return list(value)
    return value


def from_client(value, current):
    """
    Return a client's value in the type of the value in force, where the protocol blurs it.

    JSON carries a whole-valued float as an integer (``2.0`` arrives as ``2``), so an integer
    for a float parameter (and a list of integers for a list of floats) becomes float; anything
    else is left for the node's own check to accept or refuse.
    """
    if isinstance(current, float) and isinstance(value, int) and not isinstance(value, bool):
        return float(value)
    if isinstance(current, (list, tuple)) and current and isinstance(current[0], float) and \
            isinstance(value, list) and all(isinstance(v, int) and not isinstance(v, bool)
                                            for v in value):
        return [float(v) for v in value]
    return value


class NodeParameters:
    """
    Get and set the node's parameters for Foxglove clients.

    :param sdk: the ``foxglove`` module.
    :param node: the NodePort.
    :param names: the node's parameter names (those a client asking for all of them gets).
    :param logger: the node's logger.
    """

    def __init__(self, sdk, node, names: Iterable[str], logger):
        self._sdk = sdk
        self._node = node
        self.names: Tuple[str, ...] = tuple(names)
        self._logger = logger
        self.server = None

    def _parameter(self, name, value):
        sdk = self._sdk
        if isinstance(value, float):
            return sdk.Parameter(name, value=value, type=sdk.ParameterType.Float64)
        if isinstance(value, (list, tuple)) and value and isinstance(value[0], float):
            return sdk.Parameter(name, value=list(value), type=sdk.ParameterType.Float64Array)
        return sdk.Parameter(name, value=to_native(value))

    def values(self, names: Iterable[str]) -> List[Tuple[str, object]]:
        """Return (name, value) of the asked declared parameters (node thread)."""
        node = self._node
        return [(name, node.get_parameter(name)) for name in names
                if node.has_parameter(name)]

    def get(self, names: List[str]):
        """Answer the SDK's ``on_get_parameters``: every parameter when ``names`` is empty."""
        asked = list(names) or list(self.names)
        found = on_node_thread(self._node, lambda: self.values(asked))
        return [self._parameter(name, value) for name, value in found]

    def set(self, parameters):
        """Answer the SDK's ``on_set_parameters``: set each, return the values now in force."""
        wanted = [(parameter.name, parameter.get_value()) for parameter in parameters]
        results = on_node_thread(self._node, lambda: self.apply(wanted))
        for name, reason in results:
            if reason is not None:
                self._warn(f'parameter {name}: {str(reason).rstrip(".")}; nothing changed')
        return self.get([name for name, _ in wanted])

    def apply(self, wanted) -> List[Tuple[str, object]]:
        """
        Set each (name, value) through the node (node thread).

        :return: (name, reason) per parameter; reason None when it was set.
        """
        node = self._node
        outcome = []
        for name, value in wanted:
            if not node.has_parameter(name):
                outcome.append((name, 'not a parameter of this node'))
                continue
            value = from_client(value, node.get_parameter(name))
            result = node.set_parameters([Parameter(name, value)])[0]
            outcome.append((name, None if result.successful else
                            (result.reason or f'value {value!r} refused')))
        return outcome

    def _warn(self, message: str) -> None:
        self._logger.warn(f'Foxglove: {message}')
        if self.server is not None:
            self.server.publish_status(message, self._sdk.StatusLevel.Warning)
