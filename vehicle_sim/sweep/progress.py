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
The progress of a sweep: a bar on a terminal, plain lines elsewhere.

The bar shows cases done, passed, failed, errors and the ETA; elsewhere (CI logs) a line per
finished case.
"""

import time

BAR_WIDTH = 30


def _clock(seconds):
    seconds = int(round(seconds))
    hours, rest = divmod(seconds, 3600)
    if hours:
        return f'{hours}:{rest // 60:02d}:{rest % 60:02d}'
    return f'{rest // 60}:{rest % 60:02d}'


class Progress:
    """
    Call with (record, result) after each case (:func:`~.run.run_sweep`'s ``progress``).

    :param stream: where to write (a bar when it is a terminal).
    :param total: the cases in the grid; ``skipped`` of them were done before (resume).
    """

    def __init__(self, stream, total, skipped=0):
        self.stream = stream
        self.total = total
        self.skipped = skipped
        self.tty = stream.isatty()
        self.start = time.monotonic()

    def __call__(self, record, result):
        done = result.done
        ran = done - self.skipped
        elapsed = time.monotonic() - self.start
        left = self.total - done
        eta = _clock(elapsed / ran * left) if ran else '?'
        counts = (f'{done}/{self.total} done, {result.count("pass")} passed, '
                  f'{result.count("fail")} failed, {result.count("error")} errors, ETA {eta}')
        if self.tty:
            filled = int(round(BAR_WIDTH * done / max(1, self.total)))
            self.stream.write(f'\r[{"#" * filled}{"." * (BAR_WIDTH - filled)}] {counts} ')
        else:
            status = record['status'].upper()
            self.stream.write(f'[{done}/{self.total}] {status:5} {record["label"]}  ({counts})\n')
        self.stream.flush()

    def done(self):
        if self.tty:
            self.stream.write('\n')
            self.stream.flush()
