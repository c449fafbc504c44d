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

"""Every Python file carries the Apache-2.0 header that ament_copyright checks."""

from pathlib import Path

import pytest

REPO = Path(__file__).resolve().parent.parent
SKIP_DIRS = {'.venv', 'build', 'install', 'log', '.git', '.pytest_cache', '.ruff_cache'}


def _python_files():
    for path in sorted(REPO.rglob('*.py')):
        if not SKIP_DIRS.intersection(path.relative_to(REPO).parts):
            yield path


@pytest.mark.parametrize('path', list(_python_files()), ids=lambda p: str(p.relative_to(REPO)))
def test_copyright_header_is_apache_2(path):
    head = path.read_text(encoding='utf-8').splitlines()[:14]
    assert head and head[0].startswith('# Copyright ')
    assert '# Licensed under the Apache License, Version 2.0 (the "License");' in head


def test_copyright_licence_file_is_apache_2():
    text = (REPO / 'LICENSE').read_text(encoding='utf-8')
    assert 'Apache License' in text and 'Version 2.0, January 2004' in text
