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
The checkout's folder taken for the package: hand the import on to the installed vehicle_sim.

Not part of the package (that is ``vehicle_sim/`` below). A script beside a checkout named
vehicle_sim (``~/train.py`` next to ``~/vehicle_sim/``) makes Python find the checkout first:
it looks in the script's folder before site-packages. Without this file the checkout would be
taken as a namespace package, and its ``config/`` folder would hide the module
``vehicle_sim.config`` (``cannot import name 'read_yaml' from 'vehicle_sim.config' (unknown
location)``). With it, ``import vehicle_sim`` loads the installed package (an editable install's
is this checkout's ``vehicle_sim/``), or, when none is installed, fails saying what happened.
"""

import importlib.util
import os
import sys


def _installed_spec(name, checkout):
    # The spec of the package ``name`` found anywhere but in the folder holding the checkout.
    beside = os.path.realpath(os.path.dirname(checkout))
    elsewhere = [entry for entry in sys.path
                 if os.path.realpath(entry or os.getcwd()) != beside]
    for finder in sys.meta_path:
        find_spec = getattr(finder, 'find_spec', None)
        spec = find_spec(name, elsewhere) if find_spec is not None else None
        # A namespace portion (no loader, no origin) is not the package, nor is this file.
        if spec is not None and spec.loader is not None and spec.origin is not None and \
                os.path.realpath(spec.origin) != os.path.realpath(__file__):
            return spec
    return None


def _load_installed(name, checkout):
    spec = _installed_spec(name, checkout)
    if spec is None:
        raise ImportError(
            f'{name} is not installed, and Python took the folder {checkout} for it: a '
            f"{name} checkout beside the script being run (Python looks in the script's "
            f'folder, {os.path.dirname(checkout)}, first). Install it (pip install -e '
            f'{checkout}), or run the script from another folder', name=name)
    module = importlib.util.module_from_spec(spec)
    # The import statement returns what sys.modules holds once this file has run.
    sys.modules[name] = module
    spec.loader.exec_module(module)


if __name__ == 'vehicle_sim':
    _load_installed(__name__, os.path.dirname(os.path.abspath(__file__)))
