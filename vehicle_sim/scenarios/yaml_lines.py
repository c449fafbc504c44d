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
YAML with line numbers: the data of a document and the line of every value in it.

PyYAML's composer keeps a mark (line, column) on every node; the document is composed once,
constructed to plain Python data, and the node tree walked to map each value's path (a tuple of
mapping keys and list indices) to its 1-based line. Errors then name ``file:line``.
"""

import re
from typing import Dict, Tuple

import yaml

from vehicle_sim.core.errors import InvalidParameterError

Path = Tuple
Lines = Dict[Path, int]


class ScenarioError(InvalidParameterError):
    """
    A scenario file is invalid: the message starts with ``file:line:``.

    :param source: the file.
    :param line: 1-based line number, or None when unknown.
    :param message: what is wrong.
    """

    def __init__(self, source, line, message):
        self.source = str(source)
        self.line = line
        self.reason = message
        where = f'{source}:{line}' if line else str(source)
        super().__init__(f'{where}: {message}')


def load_with_lines(text, source):
    """
    Parse one YAML document and return ``(data, lines)``.

    :param text: the YAML text.
    :param source: file name for errors.
    :return: (the data (None for an empty document), {path: 1-based line}).
    :raises ScenarioError: on a YAML syntax error (with its line).
    """
    loader = yaml.SafeLoader(text)
    try:
        node = loader.get_single_node()
        if node is None:
            return None, {}
        data = loader.construct_document(node)
    except yaml.MarkedYAMLError as error:
        mark = error.problem_mark or error.context_mark
        line = mark.line + 1 if mark is not None else None
        raise ScenarioError(source, line, f'not valid YAML: {error.problem or error}') from None
    except yaml.YAMLError as error:
        raise ScenarioError(source, None, f'not valid YAML: {error}') from None
    finally:
        loader.dispose()
    lines: Lines = {}
    _walk(node, (), lines)
    return data, lines


def _walk(node, path, lines):
    lines[path] = node.start_mark.line + 1
    if isinstance(node, yaml.MappingNode):
        for key_node, value_node in node.value:
            if isinstance(key_node, yaml.ScalarNode):
                key = _typed_key(key_node, key_node.value)
                _walk(value_node, path + (key,), lines)
                # the key's own line (a multi-line value starts on the next one)
                lines[path + (key,)] = key_node.start_mark.line + 1
    elif isinstance(node, yaml.SequenceNode):
        for index, item in enumerate(node.value):
            _walk(item, path + (index,), lines)


def _typed_key(node, text):
    # Mapping keys are plain strings in scenario files; an int key (rare) keeps its type.
    if node.tag == 'tag:yaml.org,2002:int':
        try:
            return int(text)
        except ValueError:
            return text
    return text


def line_of(lines, path):
    """Return the line of ``path``, or of its nearest ancestor that has one (None if none)."""
    path = tuple(path)
    while path:
        if path in lines:
            return lines[path]
        path = path[:-1]
    return lines.get(())


# How validators name a key in their messages ("field 'x'", "unknown key 'x'") and a list
# entry ("vehicles[2]", ".sensors[0]").
_KEY = re.compile(r"(?:field|key|parameter)\(?s?\)? '([^']+)'")
_ENTRY = re.compile(r'([A-Za-z_]+)\[(\d+)\]')


def refine(lines, path, message):
    """
    Return the deepest path under ``path`` that a validator's message points at.

    The entries (``vehicles[2]``) and the key (``field 'pose'``, dotted for nested keys) named in
    the message are followed as far as the file has them.
    """
    path = tuple(path)
    for name, index in _ENTRY.findall(message):
        for candidate in (path + (name, int(index)), path + (int(index),)):
            if candidate in lines:
                path = candidate
                break
    found = _KEY.search(message)
    if found:
        for part in found.group(1).split('.'):
            if path + (part,) in lines:
                path = path + (part,)
    return path


def error_at(source, lines, path, error):
    """Turn a validator's InvalidParameterError about ``path`` into a ScenarioError."""
    message = str(error)
    return ScenarioError(source, line_of(lines, refine(lines, path, message)), message)
