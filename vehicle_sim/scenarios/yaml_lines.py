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

from vehicle_sim.yaml_files import parse, YamlFileError

Path = Tuple
Lines = Dict[Path, int]


class ScenarioError(YamlFileError):
    """
    A scenario file is invalid: the message starts with ``file:line:``.

    :param source: the file.
    :param line: 1-based line number, or None when unknown.
    :param message: what is wrong.
    """


def load_with_lines(content, source):
    """
    Parse one YAML document and return ``(data, lines)``.

    :param content: the YAML text, or the file's bytes.
    :param source: file name for errors.
    :return: (the data (None for an empty document), {path: 1-based line}).
    :raises ScenarioError: when the file cannot be read within the bounds of
        vehicle_sim/yaml_files.py (a syntax error, a byte that is not UTF-8, nesting too deep,
        aliases that stand for too much), with its line.
    """
    try:
        data, node = parse(content, source)
    except YamlFileError as error:
        raise ScenarioError(error.source, error.line, error.reason) from None
    lines: Lines = {}
    if node is not None:
        _walk(node, (), lines, set())
    return data, lines


def _walk(node, path, lines, walked):
    # A node an alias names again is walked once (its first path): the paths under a later
    # alias fall back to the alias's own line (line_of), and no alias is ever expanded.
    lines[path] = node.start_mark.line + 1
    if id(node) in walked:
        return
    walked.add(id(node))
    if isinstance(node, yaml.MappingNode):
        for key_node, value_node in node.value:
            if isinstance(key_node, yaml.ScalarNode):
                key = _typed_key(key_node, key_node.value)
                _walk(value_node, path + (key,), lines, walked)
                # the key's own line (a multi-line value starts on the next one)
                lines[path + (key,)] = key_node.start_mark.line + 1
    elif isinstance(node, yaml.SequenceNode):
        for index, item in enumerate(node.value):
            _walk(item, path + (index,), lines, walked)


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
