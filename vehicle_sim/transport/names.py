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

"""Node, namespace and topic names: validation and expansion as rcl_expand_topic_name does it."""

import re

from vehicle_sim.transport.errors import TransportError

MAX_TOPIC_NAME_LENGTH = 247
_TOKEN = re.compile(r'^[A-Za-z_][A-Za-z0-9_]*$')
_NODE_NAME = re.compile(r'^[A-Za-z_][A-Za-z0-9_]*$')


def validate_node_name(name: str) -> str:
    """Return ``name`` if it is a valid ROS node name, else raise TransportError."""
    if not _NODE_NAME.match(name or ''):
        raise TransportError(f'invalid node name {name!r}: use letters, digits and _')
    return name


def normalize_namespace(namespace: str) -> str:
    """
    Return the absolute form of a node namespace ('' and '/' both mean the root '/').

    :raises TransportError: when a token is invalid.
    """
    namespace = namespace or '/'
    if not namespace.startswith('/'):
        namespace = '/' + namespace
    if namespace != '/':
        namespace = namespace.rstrip('/')
        for token in namespace[1:].split('/'):
            if not _TOKEN.match(token):
                raise TransportError(f'invalid namespace {namespace!r}')
    return namespace


def resolve_name(name: str, namespace: str, node_name: str) -> str:
    """
    Expand a topic or service name to its fully-qualified form like rcl does.

    ``/x`` stays; ``x`` goes under the namespace; ``~/x`` (or ``~``) goes under
    ``<namespace>/<node_name>``.

    :raises TransportError: when the result is not a valid fully-qualified ROS name.
    """
    namespace = normalize_namespace(namespace)
    base = namespace.rstrip('/')
    if name == '~' or name.startswith('~/'):
        fqn = f'{base}/{node_name}{name[1:]}'
    elif name.startswith('/'):
        fqn = name
    else:
        fqn = f'{base}/{name}'
    if fqn == '/' or fqn.endswith('/') or '//' in fqn:
        raise TransportError(f'invalid topic or service name {name!r}')
    for token in fqn[1:].split('/'):
        if not _TOKEN.match(token):
            raise TransportError(f'invalid topic or service name {name!r} (token {token!r})')
    if len(fqn) > MAX_TOPIC_NAME_LENGTH:
        raise TransportError(f'name {fqn!r} longer than {MAX_TOPIC_NAME_LENGTH} characters')
    return fqn


def fully_qualified_node_name(namespace: str, node_name: str) -> str:
    """Return ``/ns/name`` without doubling the slash of the root namespace."""
    return normalize_namespace(namespace).rstrip('/') + '/' + node_name
