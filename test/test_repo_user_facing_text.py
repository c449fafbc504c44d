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
What users read stands on its own: no pointer outside the repository, docs that match the code.

The project's working notes live beside the repository, not in it; README, docs/ and code
say what users need themselves and cite other projects' sources by their own names.
"""

import argparse
from pathlib import Path
import re
import subprocess

import pytest

from vehicle_sim.tools.cli import build_parser

REPO = Path(__file__).resolve().parent.parent
SKIP_DIRS = {'.venv', 'build', 'install', 'log', '.git', '.pytest_cache', '.ruff_cache',
             '__pycache__'}
# The CI entry point is run by the project's CI next to its working notes; users never run it.
NOT_USER_FACING = {'.ci/run'}
OUTSIDE = '..' + '/shared'    # spelt in two parts so that this file does not match itself
# Names of the working notes (a design file, reference notes, source documents).
WORKING_NOTES = re.compile(r'DESIGN[ ]§|DESIGN\.md|STYLE\.md|ros2_wire|webots[_]spec|reference/|'
                           r'seeds/|\bthe seed\b', re.IGNORECASE)


def _tracked_files():
    try:
        listed = subprocess.run(['git', 'ls-files'], cwd=REPO, capture_output=True, text=True,
                                check=True).stdout.split()
        paths = [REPO / name for name in listed]
    except (OSError, subprocess.CalledProcessError):   # not a git checkout: walk the tree
        paths = [p for p in REPO.rglob('*')
                 if not SKIP_DIRS.intersection(p.relative_to(REPO).parts)]
    return sorted(p for p in paths if p.is_file()
                  and p.relative_to(REPO).as_posix() not in NOT_USER_FACING)


def _text(path):
    try:
        return path.read_text(encoding='utf-8')
    except UnicodeDecodeError:
        return ''


def test_no_tracked_file_points_outside_the_repository():
    offenders = [f'{p.relative_to(REPO)}:{n}' for p in _tracked_files()
                 for n, line in enumerate(_text(p).splitlines(), 1) if OUTSIDE in line]
    assert offenders == []


def _user_docs():
    return [REPO / 'README.md', *sorted((REPO / 'docs').glob('*.md'))]


@pytest.mark.parametrize('path', _user_docs(), ids=lambda p: p.relative_to(REPO).as_posix())
def test_user_docs_cite_no_working_note(path):
    offenders = [f'{n}: {line.strip()}' for n, line in enumerate(_text(path).splitlines(), 1)
                 if WORKING_NOTES.search(line)]
    assert offenders == []


# The same notes as code and test comments name them: a section sign after the design file's
# name, a numbered style rule, a part of the wire notes.
NOTE_POINTERS = re.compile(r'DESIGN[ ]§|DESIGN\.md|\bDESIGN\b|STYLE\.md|\bSTYLE\b|ros2_wire|'
                           r'webots[_]spec|reference/ros2|seeds/')
CODE_DIRS = ('vehicle_sim', 'vehicle_msgs_py', 'test', 'benchmarks', 'examples', 'launch',
             'config')


def _code_files():
    this = Path(__file__).resolve()
    return [p for p in _tracked_files()
            if p.relative_to(REPO).parts[0] in CODE_DIRS and p.resolve() != this]


def test_code_and_tests_point_at_no_document_outside_the_repository():
    # A maintainer who clones the project cannot follow such a pointer: the code names the fact
    # or the upstream source (Webots' driver.c, rmw_cyclonedds, REP 103) or a doc in docs/.
    files = _code_files()
    assert len(files) > 100
    offenders = [f'{p.relative_to(REPO)}:{n}: {line.strip()}' for p in files
                 for n, line in enumerate(_text(p).splitlines(), 1) if NOTE_POINTERS.search(line)]
    assert offenders == []


def _subcommands():
    (action,) = [a for a in build_parser()._actions if isinstance(a, argparse._SubParsersAction)]
    return action.choices


@pytest.mark.parametrize('name', sorted(_subcommands()))
def test_cli_doc_row_lists_the_subcommand_and_every_option(name):
    text = (REPO / 'docs' / 'cli.md').read_text(encoding='utf-8')
    rows = [line for line in text.splitlines() if line.startswith(f'| `{name}')]
    assert len(rows) == 1, f'docs/cli.md has no single row for {name}'
    row = rows[0]
    assert 'reserved' not in row
    for action in _subcommands()[name]._actions:
        options = [o for o in action.option_strings if o not in ('-h', '--help')]
        if options:
            assert any(re.search(re.escape(o) + r'\b', row) for o in options), \
                f'{name} {options} missing from docs/cli.md'


# A usage synopsis in the docs: an indented ``vehicle-sim COMMAND ... [--option ...]`` line and
# the indented lines continuing it.
SYNOPSIS = re.compile(r'^    vehicle-sim ([a-z-]+) .*\[-')


def _synopses():
    found = []
    for path in _user_docs():
        lines = _text(path).splitlines()
        for number, line in enumerate(lines):
            match = SYNOPSIS.match(line)
            if not match:
                continue
            text = [line]
            for more in lines[number + 1:]:
                if not re.match(r'^ {5,}[\[-]', more):
                    break
                text.append(more)
            found.append((f'{path.relative_to(REPO)}:{number + 1}', match.group(1),
                          ' '.join(text)))
    return found


@pytest.mark.parametrize('where, name, text', _synopses(), ids=lambda v: str(v)[:40])
def test_doc_usage_synopsis_lists_every_option_of_its_command(where, name, text):
    options = [action.option_strings for action in _subcommands()[name]._actions
               if action.option_strings and '--help' not in action.option_strings]
    missing = [o[-1] for o in options if not any(re.search(re.escape(v) + r'\b', text)
                                                 for v in o)]
    assert missing == [], f'{where}: the usage of vehicle-sim {name} lacks {missing}'


def test_architecture_doc_is_linked_from_the_readme_and_names_only_files_that_exist():
    text = (REPO / 'docs' / 'architecture.md').read_text(encoding='utf-8')
    assert '(docs/architecture.md)' in (REPO / 'README.md').read_text(encoding='utf-8')
    named = set(re.findall(r'`((?:vehicle_sim/|test/|docs/)?[\w/]+\.(?:py|md))`', text))
    named |= set(re.findall(r'\b(docs/\w+\.md)\b', text))
    assert len(named) > 30
    package = REPO / 'vehicle_sim'
    missing = [name for name in sorted(named)
               if not (REPO / name).exists() and not (package / name).exists()
               and 'radar' not in name and 'core/map' not in name]
    assert missing == []
