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


"""A first request that may be lost is sent again until answered, within its bound."""

import time

import pytest

from vehicle_sim.transport.errors import ServiceTimeoutError
from vehicle_sim.transport.first_call import call_until_answered


class _LosingClient:
    """A client whose first ``lost`` requests are never answered (each waits its timeout)."""

    service_name = '/automobile/robot/get_basic_time_step'

    def __init__(self, lost):
        self.lost = lost
        self.timeouts = []

    def call(self, request, timeout_s):
        self.timeouts.append(timeout_s)
        if len(self.timeouts) <= self.lost:
            time.sleep(timeout_s)
            raise ServiceTimeoutError(f'no reply from {self.service_name} within {timeout_s} s')
        return ('answer to', request)


def test_a_lost_first_request_is_sent_again_and_answered():
    client = _LosingClient(lost=2)
    assert call_until_answered(client, 'get', 5.0, resend_s=0.05) == ('answer to', 'get')
    assert len(client.timeouts) == 3
    assert client.timeouts[:2] == [0.05, 0.05]


def test_no_answer_within_the_bound_names_the_service_and_the_tries():
    client = _LosingClient(lost=1000)
    start = time.monotonic()
    with pytest.raises(ServiceTimeoutError) as raised:
        call_until_answered(client, 'get', 0.3, resend_s=0.05)
    assert str(raised.value) == ('no reply from /automobile/robot/get_basic_time_step within '
                                 f'0.3 s (the request sent {len(client.timeouts)} times)')
    assert len(client.timeouts) >= 2           # 6 or 7 on an idle machine
    assert 0.3 <= time.monotonic() - start < 2.0
    assert all(0.0 <= t <= 0.05 for t in client.timeouts)


@pytest.mark.parametrize('resend_s', [0.0, -1.0, float('nan')])
def test_a_resend_period_that_is_not_positive_is_refused(resend_s):
    with pytest.raises(ValueError, match='resend_s'):
        call_until_answered(_LosingClient(lost=0), 'get', 1.0, resend_s=resend_s)
