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
How an error message quotes a value it refuses: its ``repr``, cut short.

A refused value may be 5 MB of text, or a list that names the same list a thousand times (a YAML
alias): the message quotes at most :data:`SHOWN_CHARS` characters of it, then its type and
length. The text is written piece by piece and the writing stops once it is long enough, so a
value is never expanded (nor walked further than those characters) to quote it.
"""

SHOWN_CHARS = 80


class _Full(Exception):
    """The quoted text has reached its length."""


class _Writer:
    def __init__(self, limit):
        self.parts = []
        self.left = limit

    def write(self, text):
        self.parts.append(text)
        self.left -= len(text)
        if self.left < 0:
            raise _Full

    def value(self, value):
        if isinstance(value, (str, bytes)):
            # Only as much of a long string as can be shown is turned into text.
            self.write(repr(value[:self.left + 1]) if len(value) > self.left else repr(value))
        elif isinstance(value, dict):
            self._items(value.items(), '{', '}', pairs=True)
        elif isinstance(value, list):
            self._items(value, '[', ']')
        elif isinstance(value, tuple):
            self._items(value, '(', ',)' if len(value) == 1 else ')')
        elif isinstance(value, (set, frozenset)) and value:
            self._items(value, '{', '}')
        else:
            try:
                self.write(repr(value))
            except ValueError:      # an int of more digits than Python turns into text
                self.write(f'<{type(value).__name__}>')

    def _items(self, items, opening, closing, pairs=False):
        self.write(opening)
        for index, item in enumerate(items):
            if index:
                self.write(', ')
            if pairs:
                self.value(item[0])
                self.write(': ')
                self.value(item[1])
            else:
                self.value(item)
        self.write(closing)


def brief(value, limit=SHOWN_CHARS) -> str:
    """
    Return ``repr(value)`` when it is at most ``limit`` characters, else its start and size.

    :param value: any value (YAML data, a number, a string).
    :param limit: the most characters of the ``repr`` quoted.
    :return: e.g. ``[1.0, 2.0]``, or ``'aaaaaaaa... (str of 5242880 characters)``.
    """
    writer = _Writer(limit)
    try:
        writer.value(value)
    except _Full:
        text = ''.join(writer.parts)[:limit]
        return f'{text}... ({_size(value)})'
    return ''.join(writer.parts)


def _size(value):
    kind = type(value).__name__
    if isinstance(value, (str, bytes)):
        return f'{kind} of {count(len(value), "character", "characters")}'
    if isinstance(value, dict):
        return f'{kind} of {count(len(value), "key", "keys")}'
    if isinstance(value, (list, tuple, set, frozenset)):
        return f'{kind} of {count(len(value), "entry", "entries")}'
    return kind


def count(number: int, one: str, many: str) -> str:
    """Return ``number`` and the noun that agrees with it: ``1 wall rectangle``, ``2 lanes``."""
    return f'{number} {one if number == 1 else many}'
