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
What every node module shares: parameter declaration, the throttled warning, the main wrapper.

Node modules (``*_node.py``) import core, this module and the interface tables, never each
other (a test scans the imports). Parameters: every node declares its core
:class:`~vehicle_sim.core.specs.param_spec.ParamSpec` table through :func:`declare_parameters`, so
every parameter is declared on the transport port and validated the same way; a refused value stops
the node with an error naming the parameter, its value and the valid range.
"""

import gc
import sys

from vehicle_sim.core.specs.errors import VehicleSimError
from vehicle_sim.core.specs.param_spec import (
    parameter_table_markdown,
    ParamSpec,
    validate_table,
    yaml_text,
)
from vehicle_sim.transport import run_node

# Declared by the transport port on every node (ROS standard); listed in the docs and yaml.
USE_SIM_TIME = ParamSpec('use_sim_time', kind='bool', default=False,
                         doc='use /clock as the node clock (ROS standard)', read_only=False)


def _ros_value(value):
    return list(value) if isinstance(value, tuple) else value


def declare_parameters(node, specs):
    """
    Declare every ParamSpec on a node and return the validated values.

    Each parameter is declared with its default, description (unit included), valid range
    (``additional_constraints``), read-only flag and the spec as validator, so a command-line
    override, a parameter file or a later set request is refused with the spec's reason.

    :param node: a transport NodePort.
    :param specs: the node's ParamSpec rows.
    :return: {attribute name: validated value} (lists as tuples).
    :raises TransportError: an override is refused (the message names parameter, value and
        valid range).
    :raises InvalidParameterError: a value is refused by the table (the same message form).
    """
    values = {}
    for spec in specs:
        values[spec.key] = node.declare_parameter(
            spec.key, _ros_value(spec.default), description=spec.description,
            validator=spec.refusal, read_only=spec.read_only,
            additional_constraints=spec.range_text)
    return validate_table(specs, values, node.get_fully_qualified_name(), key_word='parameter')


def node_parameter_table(specs, extra_rows=()):
    """Return the docs table of a node's parameters (``use_sim_time`` included)."""
    return parameter_table_markdown(tuple(specs) + (USE_SIM_TIME,), 'parameter', extra_rows)


def params_file_text(node_name, specs):
    """Return a ROS parameter file listing every parameter with its default and description."""
    lines = [f'{node_name}:', '  ros__parameters:']
    for spec in tuple(specs) + (USE_SIM_TIME,):
        lines.append(f'    # {spec.description}')
        lines.append(f'    {spec.key}: {yaml_text(_ros_value(spec.default))}')
    return '\n'.join(lines) + '\n'


def freezing_start_up(node_factory):
    """
    Return ``node_factory`` followed by ``gc.freeze()``: start-up objects leave the collector.

    What a node builds at start-up (message types, the world, its endpoints: ~65k objects) lives
    as long as the process, yet a full collection scans it all (~100 ms here), stalling the
    simulation loop and every request queued meanwhile. Frozen, it is never scanned again; the
    collector keeps collecting what the node allocates later.
    """
    def build(args):
        app = node_factory(args)
        gc.freeze()
        return app
    return build


def run_main(name, node_factory, args=None):
    """
    Run a node main (Jazzy shape, through the port) and turn a refused start into exit 2.

    :param name: the executable name printed before the error.
    :param node_factory: ``node_factory(args)`` returning a NodePort or an object with ``.node``.
    :param args: the command line (default ``sys.argv``).
    :return: the process exit status: 0, or 2 when a parameter (or a file it names) is refused.
    """
    try:
        return run_node(freezing_start_up(node_factory), sys.argv if args is None else args)
    except VehicleSimError as error:   # a refused parameter, or DDS refused by Cyclone
        print(f'{name}: {error}', file=sys.stderr)
        return 2
