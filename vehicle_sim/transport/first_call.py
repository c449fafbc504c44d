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
The first call of a client just matched: a request that may be lost is sent again.

``wait_for_service`` is true once the client has matched the server's endpoints; the server may
match the client's request writer later, and a request written before that is never delivered
(on Cyclone DDS a reader that matches a writer late starts at the latest sample the writer's
first heartbeat announces; rmw_cyclonedds has the same race). A caller that gets an answer
knows the server has matched its request writer, and every writer its participant created
before (a participant announces its writers in the order it creates them): clients created
earlier can then call once, without sending again.

Only for requests that may be served twice (getters): a request that was slow, not lost, is
answered twice, and the second answer is dropped with the timed-out call.
"""

import time

from vehicle_sim.transport.errors import ServiceTimeoutError

# How long a first request waits for its answer before it is sent again [s].
RESEND_S = 1.0


def call_until_answered(client, request, timeout_s: float, resend_s: float = RESEND_S):
    """
    Return the answer to ``request``, sent again every ``resend_s`` without one.

    :param client: a port ``Client`` whose service is ready (``wait_for_service``).
    :param timeout_s: the bound on the whole wait [s].
    :raises ServiceTimeoutError: no answer within ``timeout_s``; the message says how many
        times the request was sent.
    """
    if not resend_s > 0.0:
        raise ValueError(f'resend_s = {resend_s!r}: must be > 0')
    deadline = time.monotonic() + timeout_s
    sent = 0
    while True:
        sent += 1
        try:
            return client.call(request, max(0.0, min(resend_s, deadline - time.monotonic())))
        except ServiceTimeoutError:
            if time.monotonic() >= deadline:
                raise ServiceTimeoutError(
                    f'no reply from {client.service_name} within {timeout_s:g} s (the request '
                    f'sent {sent} times)') from None
