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
Silencing PyBullet's C-level stdout: the notices it prints with printf, which Python cannot catch.

:func:`quiet_stdout` points file descriptor 1 at a pipe for the duration of a block and drops
what arrives, waiting, where asked, for notices that another PyBullet thread prints shortly
after (the GUI window's first frames).
"""

from contextlib import contextmanager
import ctypes
import os
import select
import sys
import time

_LIBC = ctypes.CDLL(None)     # fflush for quiet_stdout


@contextmanager
def quiet_stdout(settle_on=None, settle_count=1, settle_s=0.2, max_wait_s=2.0):
    """
    Silence C-level stdout (PyBullet prints some notices with printf).

    :param settle_on: bytes that another thread of PyBullet prints shortly after the block (the
        GUI window prints ``ven = <GL vendor>`` as it starts): stdout stays silenced until they
        have come ``settle_count`` times and nothing more came for ``settle_s``, at most
        ``max_wait_s`` after the block.
    """
    try:
        sys.stdout.flush()
        saved = os.dup(1)
    except (OSError, ValueError, AttributeError):
        yield
        return
    read_end, write_end = os.pipe()
    try:
        os.dup2(write_end, 1)
        try:
            yield
        finally:
            # printf buffers in the C library when stdout is not a terminal: flush it while
            # fd 1 still goes to the pipe, or the notices come out later.
            _LIBC.fflush(None)
            _drain(read_end, settle_on, settle_count, settle_s, max_wait_s)
            _LIBC.fflush(None)
    finally:
        os.dup2(saved, 1)
        os.close(saved)
        os.close(write_end)
        _drain(read_end, None, 0, 0.0, 0.0)
        os.close(read_end)


def _drain(read_end, settle_on, settle_count, settle_s, max_wait_s):
    # Read (and drop) what the pipe holds; with settle_on, wait for it as quiet_stdout says.
    if settle_on is None:
        settle_s = 0.0          # nothing to wait for: take what is there and return
    missing = 0 if settle_on is None else settle_count
    tail = b''                  # the end of the last read: a notice split over two reads
    start = last = time.monotonic()
    while True:
        now = time.monotonic()
        if not missing and now - last >= settle_s or now - start >= max_wait_s:
            timeout_s = 0.0
        else:
            timeout_s = min(0.05, max_wait_s - (now - start))
            # what the other thread printed may sit in the C library's buffer (stdout is a
            # pipe now, not a terminal): push it into the pipe while waiting for it
            _LIBC.fflush(None)
        ready, _, _ = select.select([read_end], [], [], timeout_s)
        if not ready:
            if timeout_s == 0.0:
                return
            continue
        data = os.read(read_end, 65536)
        if not data:
            return
        last = time.monotonic()
        if missing:
            text = tail + data
            missing = max(0, missing - text.count(settle_on))
            tail = text[-(len(settle_on) - 1):] if len(settle_on) > 1 else b''
