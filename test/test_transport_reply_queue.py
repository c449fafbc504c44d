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
A service's queued replies wait for the client's reply reader, up to the node's bound.

They are sent once the reader matches, kept while the client's request writer stays matched,
dropped at once when the client goes away, and logged when dropped at the bound.
"""

from types import SimpleNamespace

from vehicle_sim.transport.dds import DdsNode
from vehicle_sim.transport.dds.services import _PendingReply, DdsService, REPLY_MATCH_TIMEOUT_S


class _Log:
    def __init__(self):
        self.lines = []

    def warning(self, text):
        self.lines.append(text)


def _service(matched_tokens, live_writers, timeout_s=REPLY_MATCH_TIMEOUT_S):
    """Return a DdsService with fake DDS entities: which clients match, what was written."""
    service = object.__new__(DdsService)
    log = _Log()
    service._node = SimpleNamespace(reply_match_timeout_s=timeout_s, get_logger=lambda: log)
    service.service_name = '/car/set_gear'
    service.written = []
    service._write = service.written.append
    service._reply_reader_matched = lambda token: token in matched_tokens
    service._reader = SimpleNamespace(
        get_matched_publication_data=lambda handle: object() if handle in live_writers else None)
    service._client_tokens = {handle: f'client{handle}' for handle in (1, 2, 3)}
    service.pending = [_PendingReply(f'reply{handle}', handle, f'client{handle}',
                                     100.0 + timeout_s) for handle in (1, 2, 3)]
    return service, log


def test_a_reply_waits_for_its_reply_reader_while_the_client_stays():
    # t = 100 s + 9.9 s of a 10 s bound: client1's reader matched, client2 still matching,
    # client3's request writer gone
    matched, live = {'client1'}, {1, 2}
    service, log = _service(matched, live)
    service.flush_pending(100.0 + REPLY_MATCH_TIMEOUT_S - 0.1)
    assert service.written == ['reply1']
    assert [item.wire for item in service.pending] == ['reply2']
    assert 3 not in service._client_tokens       # forgotten with its client
    assert log.lines == []                        # a client that left is no error
    matched.add('client2')                        # its reply reader matches late: still answered
    service.flush_pending(100.0 + REPLY_MATCH_TIMEOUT_S - 0.05)
    assert service.written == ['reply1', 'reply2']
    assert service.pending == []


def test_a_reply_dropped_at_the_bound_is_logged_with_the_bound():
    service, log = _service(set(), {1, 2, 3}, timeout_s=2.5)
    service.flush_pending(102.49)
    assert len(service.pending) == 3 and log.lines == []
    service.flush_pending(102.5)
    assert service.pending == [] and service.written == []
    assert log.lines == ["/car/set_gear: reply dropped: the client's reply reader was not "
                         'matched within 2.5 s'] * 3


def test_the_bound_is_seconds_long_by_default():
    # rmw_cyclonedds waits 100 ms in the caller; a node here queues instead, and a loaded machine
    # can take seconds to match a client's reply reader after its request arrives
    assert REPLY_MATCH_TIMEOUT_S >= 10.0
    node = DdsNode('reply_queue_default', '/reply_queue')
    try:
        assert node.reply_match_timeout_s == REPLY_MATCH_TIMEOUT_S
    finally:
        node.shutdown()
