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
pybullet, imported without the 'pybullet build time' banner its C extension prints on loading.

The package imports this module before any other, so every ``import pybullet`` of the physics
modules finds the module already loaded.
"""

import ctypes
import importlib
import os
import sys


def _flush_c_stdio() -> None:
    # A banner printed into C's stdout buffer (a pipe or file is fully buffered) would reach the
    # real stream later, at the next flush or at exit: flush it while it still goes nowhere.
    try:
        ctypes.CDLL(None).fflush(None)
    except (OSError, AttributeError, TypeError):  # no C library to call (e.g. Windows)
        pass


def import_quietly(module_name: str):
    """
    Import and return a module with file descriptors 1 and 2 sent to the null device.

    Only what is printed while the module loads is lost (pybullet's 'build time' banner):
    Python-level errors of the import are raised after both descriptors are restored. A module
    already imported is returned as it is.
    """
    if module_name in sys.modules:
        return sys.modules[module_name]
    for stream in (sys.stdout, sys.stderr):
        if stream is not None:
            stream.flush()
    saved = []
    null = os.open(os.devnull, os.O_WRONLY)
    try:
        for fd in (1, 2):
            try:
                saved.append((fd, os.dup(fd)))
            except OSError:  # descriptor closed: nothing to protect
                continue
            os.dup2(null, fd)
        try:
            return importlib.import_module(module_name)
        finally:
            _flush_c_stdio()
            for fd, copy in saved:
                os.dup2(copy, fd)
                os.close(copy)
    finally:
        os.close(null)


pybullet = import_quietly('pybullet')
