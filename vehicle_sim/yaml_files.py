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
The one reader of the YAML files a user gives: worlds, scenarios, car and robot presets.

Whatever is in the file, reading it ends in data or in one :class:`YamlFileError` naming the
file and, where known, the line; nothing reaches a validator that would take it long to walk:

- bytes that are not UTF-8 are refused with the byte, its offset, line and column;
- a value nested deeper than :data:`MAX_DEPTH` levels is refused while it is composed (PyYAML's
  composer recurses once per level);
- aliases that stand for more than :data:`MAX_ALIAS_NODES` values when written out (the
  "billion laughs" file) are refused, and so is an alias inside the value it names. Both are
  counted on PyYAML's node graph, each node measured once from its children, so that nothing
  is ever expanded to count it;
- a syntax error, or a value PyYAML cannot construct (an integer of more than 4300 digits, the
  13th month of a date), is refused with its line.
"""

from pathlib import Path
from typing import Any, Optional, Tuple

import yaml

from vehicle_sim.core.specs.errors import InvalidParameterError

__all__ = ['load_file', 'MAX_ALIAS_NODES', 'MAX_DEPTH', 'parse', 'read_text', 'YamlFileError']

MAX_DEPTH = 50                 # nested lists and mappings, aliases written out
MAX_ALIAS_NODES = 100_000      # values (scalars, lists, mappings) the aliases of a file stand for


class YamlFileError(InvalidParameterError):
    """
    A YAML file cannot be read: the message is one line, ``file:line: reason``.

    :param source: the file.
    :param line: 1-based line number, or None when unknown.
    :param reason: what is wrong.
    """

    def __init__(self, source, line, reason):
        self.source = str(source)
        self.line = line
        self.reason = reason
        where = f'{source}:{line}' if line else str(source)
        super().__init__(f'{where}: {reason}')


def read_text(path) -> str:
    """
    Read a file as UTF-8 text.

    :raises YamlFileError: when it cannot be read, or naming the first byte that is not UTF-8.
    """
    try:
        data = Path(path).read_bytes()
    except OSError as error:
        raise YamlFileError(path, None, f'cannot read: {error.strerror or error}') from None
    return _decoded(data, path)


def _decoded(data: bytes, source) -> str:
    try:
        return data.decode('utf-8')
    except UnicodeDecodeError as error:
        start = error.start
        line = data.count(b'\n', 0, start) + 1
        column = start - (data.rfind(b'\n', 0, start) + 1) + 1
        raise YamlFileError(source, line, f'not UTF-8: byte 0x{data[start]:02x} at offset '
                                          f'{start} (line {line}, column {column}): '
                                          f'{error.reason}') from None


def load_file(path) -> Any:
    """Read a YAML file and return its data (None for an empty file); see :func:`parse`."""
    return parse(read_text(path), str(path))[0]


def parse(content, source) -> Tuple[Any, Optional[yaml.Node]]:
    """
    Parse one YAML document within the bounds of this module.

    :param content: the text, or the file's bytes (UTF-8).
    :param source: the file name quoted in errors.
    :return: (the data (None for an empty document), PyYAML's root node (None likewise)).
    :raises YamlFileError: naming the file and line of what is wrong.
    """
    text = _decoded(content, source) if isinstance(content, bytes) else content
    loader = None
    try:
        loader = _BoundedLoader(text, source)   # PyYAML's reader checks the characters here
        node = loader.get_single_node()
        data = None if node is None else loader.construct_document(node)
    except YamlFileError:
        raise
    except yaml.MarkedYAMLError as error:
        mark = error.problem_mark or error.context_mark
        problem = error.problem or 'invalid'
        if error.context:
            problem += f' ({error.context})'
        raise YamlFileError(source, mark.line + 1 if mark else None,
                            f'not valid YAML: {problem}') from None
    except yaml.reader.ReaderError as error:
        line = text.count('\n', 0, error.position) + 1
        raise YamlFileError(source, line, f'not valid YAML: character #x{error.character:04x}: '
                                          f'{error.reason}') from None
    except yaml.YAMLError as error:
        raise YamlFileError(source, None, f'not valid YAML: {error}') from None
    except ValueError as error:         # int() of 5000 digits, datetime() of month 13
        reason = str(error).split(';')[0]    # not Python's advice on its own limits
        raise YamlFileError(source, None, f'a value YAML cannot read: {reason}') from None
    finally:
        if loader is not None:
            loader.dispose()
    return data, node


class _BoundedLoader(yaml.SafeLoader):
    """PyYAML's safe loader whose composer measures each node (depth, written-out size)."""

    def __init__(self, text, source):
        super().__init__(text)
        self.name = source          # in PyYAML's marks
        self._source = source
        self._depth = 0             # of the composer's recursion
        self._measured = {}         # id(node) -> (depth, values when written out)
        self._alias_values = 0

    def _refuse(self, event, reason):
        return YamlFileError(self._source, event.start_mark.line + 1, reason)

    def compose_node(self, parent, index):
        event = self.peek_event()
        if isinstance(event, yaml.AliasEvent):
            node = super().compose_node(parent, index)
            measured = self._measured.get(id(node))
            if measured is None:    # its node is still being composed
                raise self._refuse(event, f'alias *{event.anchor} is inside the value it names')
            self._alias_values += measured[1]
            if self._alias_values > MAX_ALIAS_NODES:
                raise self._refuse(event, f'aliases stand for more than {MAX_ALIAS_NODES} '
                                          'values when written out')
            return node
        if self._depth >= MAX_DEPTH:
            raise self._refuse(event, f'nested deeper than {MAX_DEPTH} levels')
        self._depth += 1
        try:
            node = super().compose_node(parent, index)
        finally:
            self._depth -= 1
        if isinstance(node, yaml.MappingNode):
            children = [child for pair in node.value for child in pair]
        elif isinstance(node, yaml.SequenceNode):
            children = node.value
        else:
            children = ()
        depth = 1 + max((self._measured[id(c)][0] for c in children), default=0)
        if depth > MAX_DEPTH:
            raise self._refuse(event, f'nested deeper than {MAX_DEPTH} levels (aliases written '
                                      'out)')
        self._measured[id(node)] = (depth, 1 + sum(self._measured[id(c)][1] for c in children))
        return node
