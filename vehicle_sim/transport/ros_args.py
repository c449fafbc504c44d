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
ROS command-line arguments, parsed the way rcl does it (for the embedded transport and the CLI).

Supported inside ``--ros-args ... [--]``: ``-p``/``--param [node:]name:=value`` (value read as
YAML, like rcl), ``--params-file file.yaml`` (``<node>: ros__parameters:`` with ``/**``, ``*`` and
nested-namespace keys), ``-r``/``--remap [node:]from:=to`` including ``__ns`` and ``__node``
(``__name``), ``--log-level [name:=]level`` and ``-e``/``--enclave``. Everything outside is
returned as ``non_ros_args``.

Also the parameter texts both adapters share: rclpy's read-only refusal and the one warning for
overrides that name no declared parameter.
"""

from dataclasses import dataclass, field
import difflib
import re
from typing import Any, Dict, Iterable, List, Optional, Sequence, Tuple

import yaml

from vehicle_sim.transport.errors import TransportError
from vehicle_sim.transport.names import normalize_namespace, resolve_name
from vehicle_sim.transport.parameter_types import normalize_parameter_value, parameter_type_of

LOG_LEVELS = {'debug': 10, 'info': 20, 'warn': 30, 'warning': 30, 'error': 40, 'fatal': 50}
ROSOUT_FLAGS = ('--enable-rosout-logs', '--disable-rosout-logs')
_FLAGS_WITHOUT_VALUE = {
    *ROSOUT_FLAGS, '--enable-stdout-logs',
    '--disable-stdout-logs', '--enable-external-lib-logs', '--disable-external-lib-logs',
}


@dataclass
class RosArguments:
    """The parsed ROS arguments; apply them per node with the query methods."""

    non_ros_args: List[str] = field(default_factory=list)
    # In command-line order: ('param', node name or None, parameter name, value) and
    # ('file', path, None, None); later sources win.
    parameter_sources: List[Tuple[str, Any, Any, Any]] = field(default_factory=list)
    remaps: List[Tuple[Optional[str], str, str]] = field(default_factory=list)
    log_level: Optional[int] = None
    enclave: Optional[str] = None
    rosout_logs: bool = True
    stdout_logs: bool = True

    def node_name(self, node_name: str) -> str:
        """Return the node name after ``__node``/``__name`` remaps."""
        for target, src, dst in self.remaps:
            if src in ('__node', '__name') and target in (None, node_name):
                return dst
        return node_name

    def namespace(self, node_name: str, namespace: str) -> str:
        """Return the node namespace after an ``__ns`` remap."""
        for target, src, dst in self.remaps:
            if src == '__ns' and target in (None, node_name):
                return normalize_namespace(dst)
        return normalize_namespace(namespace)

    def remap_name(self, fqn: str, node_name: str, namespace: str) -> str:
        """Apply the first topic/service remap whose resolved ``from`` equals ``fqn``."""
        for target, src, dst in self.remaps:
            if src.startswith('__') or target not in (None, node_name):
                continue
            if resolve_name(src, namespace, node_name) == fqn:
                return resolve_name(dst, namespace, node_name)
        return fqn

    def parameter_overrides(self, node_name: str, namespace: str) -> Dict[str, Any]:
        """
        Return the parameter overrides for one node, later sources winning.

        :param node_name: the (remapped) node name.
        :param namespace: the (remapped) absolute namespace.
        """
        fqn = normalize_namespace(namespace).rstrip('/') + '/' + node_name
        overrides: Dict[str, Any] = {}
        for kind, target, name, value in self.parameter_sources:
            if kind == 'file':
                overrides.update(params_file_overrides(load_params_file(target), fqn))
            elif target is None or target in (node_name, fqn):
                overrides[name] = value
        return overrides


def parse_parameter_value(text: str) -> Any:
    """
    Read a ``-p`` value as YAML like rcl: ``true``, ``3``, ``2.5``, ``[1, 2]``, ``'text'``.

    Anything YAML does not turn into a parameter type stays a string.
    """
    try:
        value = yaml.safe_load(text)
    except yaml.YAMLError:
        return text
    try:
        parameter_type_of(value)
    except TransportError:
        return text
    if value is None:
        return text
    return normalize_parameter_value(value)


def _split_assignment(text: str, flag: str) -> Tuple[Optional[str], str, str]:
    if ':=' not in text:
        raise TransportError(f'{flag} expects [node:]name:=value, got {text!r}')
    left, value = text.split(':=', 1)
    node = None
    # A node prefix is "node:" (a ':' before ':='); names themselves have no ':'.
    if ':' in left:
        node, left = left.split(':', 1)
    if not left:
        raise TransportError(f'{flag} expects [node:]name:=value, got {text!r}')
    return node, left, value


def rosout_wanted(args: Optional[Sequence[str]]) -> bool:
    """
    Return whether a command line leaves its node on /rosout (the last rosout flag wins).

    True for a command line :func:`parse_ros_args` refuses: the transport reports it.
    """
    try:
        return parse_ros_args(args).rosout_logs
    except TransportError:
        return True


def without_rosout_flags(args: Sequence[str]) -> List[str]:
    """Return a command line without its ``--enable-rosout-logs``/``--disable-rosout-logs``."""
    return [arg for arg in args if arg not in ROSOUT_FLAGS]


def parse_ros_args(args: Optional[Sequence[str]]) -> RosArguments:
    """
    Parse a full argument list (e.g. ``sys.argv[1:]``).

    :raises TransportError: on a malformed ROS argument, naming it.
    """
    result = RosArguments()
    args = list(args or [])
    i = 0
    in_ros = False
    while i < len(args):
        arg = args[i]
        if arg == '--ros-args':
            in_ros = True
            i += 1
            continue
        if not in_ros:
            result.non_ros_args.append(arg)
            i += 1
            continue
        if arg == '--':
            in_ros = False
            i += 1
            continue
        if arg in _FLAGS_WITHOUT_VALUE:
            if 'rosout' in arg:
                result.rosout_logs = arg.startswith('--enable')
            elif 'stdout' in arg:
                result.stdout_logs = arg.startswith('--enable')
            i += 1
            continue
        if i + 1 >= len(args):
            raise TransportError(f'ROS argument {arg} needs a value')
        value = args[i + 1]
        if arg in ('-p', '--param'):
            node, name, text = _split_assignment(value, arg)
            result.parameter_sources.append(('param', node, name, parse_parameter_value(text)))
        elif arg == '--params-file':
            load_params_file(value)  # fail early, naming the file
            result.parameter_sources.append(('file', value, None, None))
        elif arg in ('-r', '--remap'):
            node, src, dst = _split_assignment(value, arg)
            result.remaps.append((node, src, dst))
        elif arg == '--log-level':
            level = value.split(':=', 1)[-1].lower()
            if level not in LOG_LEVELS:
                raise TransportError(
                    f'unknown log level {level!r}; valid: {", ".join(sorted(LOG_LEVELS))}')
            if ':=' not in value:
                result.log_level = LOG_LEVELS[level]
        elif arg in ('-e', '--enclave'):
            result.enclave = value
        else:
            raise TransportError(f'unknown ROS argument {arg!r}')
        i += 2
    return result


def load_params_file(path: str) -> Dict[str, Any]:
    """
    Read a ROS parameters YAML file.

    :raises TransportError: when the file is missing or not a mapping.
    """
    try:
        with open(path, encoding='utf-8') as stream:
            data = yaml.safe_load(stream)
    except OSError as exc:
        raise TransportError(f'cannot read params file {path!r}: {exc}') from None
    except yaml.YAMLError as exc:
        raise TransportError(f'params file {path!r} is not valid YAML: {exc}') from None
    if data is None:
        return {}
    if not isinstance(data, dict):
        raise TransportError(f'params file {path!r} must hold a mapping of node names')
    return data


def _flatten(prefix: str, value: Any, out: Dict[str, Any]) -> None:
    if isinstance(value, dict):
        for key, sub in value.items():
            _flatten(f'{prefix}.{key}' if prefix else str(key), sub, out)
    else:
        out[prefix] = normalize_parameter_value(value) if value is not None else value


def _node_sections(data: Dict[str, Any], prefix: str = '') -> List[Tuple[str, Dict[str, Any]]]:
    """Yield (node key, ros__parameters) pairs, joining nested namespace keys."""
    sections = []
    for key, value in data.items():
        if not isinstance(value, dict):
            continue
        key = str(key)
        path = (prefix.rstrip('/') + '/' + key.lstrip('/')) if prefix else key
        if 'ros__parameters' in value:
            sections.append((path, value['ros__parameters'] or {}))
        else:
            sections.extend(_node_sections(value, path))
    return sections


def _key_pattern(key: str) -> re.Pattern:
    if not key.startswith('/'):
        key = '/' + key
    parts = []
    for token in key[1:].split('/'):
        if token == '**':
            parts.append('(?:/[^/]+)*')
        else:
            parts.append('/' + re.escape(token).replace(r'\*', '[^/]*'))
    return re.compile('^' + ''.join(parts) + '$')


def params_file_overrides(data: Dict[str, Any], node_fqn: str) -> Dict[str, Any]:
    """
    Return the parameters a params-file mapping gives to the node ``node_fqn``.

    :param data: the loaded YAML mapping.
    :param node_fqn: the node's fully-qualified name, e.g. ``/car1/vehicle``.
    """
    result: Dict[str, Any] = {}
    for key, params in _node_sections(data):
        if _key_pattern(key).match(node_fqn):
            if not isinstance(params, dict):
                raise TransportError(f'ros__parameters of {key!r} must be a mapping')
            _flatten('', params, result)
    return result


def read_only_reason(name: str) -> str:
    """Return the reason a set of a read-only parameter fails, worded like rclpy (Jazzy)."""
    # rclpy Node._apply_descriptor: SetParametersResult.reason for a read-only descriptor.
    return f'Trying to set a read-only parameter: {name}.'


def unknown_overrides_warning(override_names: Iterable[str],
                              declared_names: Iterable[str]) -> Optional[str]:
    """
    Return the warning for parameter overrides that name no declared parameter, or None.

    rcl keeps such an override without a word, so a misspelt ``-p`` does nothing; both adapters
    log this once, at the node's first spin (its parameters are declared by then).

    :param override_names: names given by ``-p``, params files and ``parameter_overrides``.
    :param declared_names: the parameters the node declared.
    """
    declared = sorted(set(declared_names))
    unknown = sorted(set(override_names) - set(declared))
    if not unknown:
        return None
    hints = []
    for name in unknown:
        close = difflib.get_close_matches(name, declared, n=1, cutoff=0.6)
        hints.append(f'{name} (did you mean {close[0]}?)' if close else name)
    return (f'ignored parameter override{"s" if len(unknown) > 1 else ""} {", ".join(hints)}: '
            f'not declared by this node; its parameters: {", ".join(declared)}')
