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

"""Run a command on a virtual X display (``xvfb-run``, Debian/Ubuntu package ``xvfb``)."""

import shutil
import subprocess

from conftest import peer_env
import pytest

# Larger than PyBullet's default 1024 x 768 window.
SCREEN = '-screen 0 1280x1024x24 -nolisten tcp'
# xvfb-run -a picks a free display number, but two runs starting together can pick the same
# one and one Xvfb then fails to start: that (and only that) is retried.
ATTEMPTS = 3


def require_xvfb():
    """Skip the calling test, with the reason printed, where xvfb-run is missing."""
    if shutil.which('xvfb-run') is None:
        pytest.skip('xvfb-run not found: this test needs a virtual X display '
                    '(Debian/Ubuntu: apt-get install xvfb)')


def xvfb_run(command, timeout_s, tmp_path, screen=SCREEN):
    """
    Run ``command`` under xvfb-run with this run's DDS settings; return the CompletedProcess.

    Xvfb's own messages go to ``tmp_path/xvfb.log`` and are appended to stderr. ``screen`` is
    Xvfb's screen option (default: SCREEN).
    """
    env = peer_env()
    env.pop('DISPLAY', None)
    log = tmp_path / 'xvfb.log'
    for _ in range(ATTEMPTS):
        result = subprocess.run(['xvfb-run', '-a', '-e', str(log), '-s', screen, *command],
                                env=env, capture_output=True, text=True, timeout=timeout_s)
        xvfb_log = log.read_text(errors='replace') if log.exists() else ''
        result.stderr += xvfb_log
        if not (result.returncode != 0 and 'Xvfb failed to start' in result.stderr):
            return result
    return result
