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
A repository script (an example, a map's generator) loaded as a module, by its path.

The scripts are not in a package: examples/ and config/maps/ hold programs a user runs. Tests
read their functions and constants through :func:`load_script`, the one place that does it.
"""

import importlib.util
from pathlib import Path

REPO = Path(__file__).resolve().parents[1]


def load_script(path):
    """
    Return the module of the script at ``path``, executed afresh (its ``main`` not run).

    :param path: the script's path, absolute or relative to the repository's root.
    """
    path = REPO / path
    spec = importlib.util.spec_from_file_location(path.stem, path)
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module
