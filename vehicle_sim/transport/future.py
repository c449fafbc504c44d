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

"""A result completed later, while the node spins (rclpy.task.Future's role)."""

from typing import Callable


class Future:
    """
    A result completed later, while the node spins: a service call's reply, or a deferred reply.

    Single-threaded: ``done()``/``result()`` are read by the thread that spins the node.
    """

    def __init__(self):
        self._done = False
        self._result = None
        self._exception = None
        self._callbacks = []

    def done(self) -> bool:
        return self._done

    def result(self):
        if self._exception is not None:
            raise self._exception
        return self._result

    def exception(self):
        return self._exception

    def set_result(self, result) -> None:
        self._result = result
        self._done = True
        self._run_callbacks()

    def set_exception(self, exception: BaseException) -> None:
        self._exception = exception
        self._done = True
        self._run_callbacks()

    def add_done_callback(self, callback: Callable[['Future'], None]) -> None:
        """Call ``callback(future)`` once the future is done (at once if it already is)."""
        if self._done:
            callback(self)
        else:
            self._callbacks.append(callback)

    def _run_callbacks(self) -> None:
        callbacks, self._callbacks = self._callbacks, []
        for callback in callbacks:
            callback(self)
