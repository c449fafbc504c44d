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
Services and clients of the embedded transport, paired like rmw_cyclonedds (``rmw_node.cpp``).

A service is a request reader and a reply writer sharing one ``serviceid`` token, a client a
reply reader (created first) and a request writer sharing one ``clientid``; every request and
reply carries the 16-byte rmw_cyclonedds header (client id, sequence number). A reply whose
client reply reader is not matched yet is queued and retried by the executor for up to the
node's ``reply_match_timeout_s`` (REPLY_MATCH_TIMEOUT_S by default), while the client's request
writer stays matched: the caller is never blocked (rmw_cyclonedds itself blocks up to 100 ms).
The bound is long because the server matches the client's reply reader when discovery has
handled its announcement, and on a loaded machine that can come seconds after the request; a
reply dropped at the bound is logged as a warning. A service callback may return a port
``Future`` instead of the response: the reply is sent once it is done (a deferred reply).

A client that is not rmw_cyclonedds (Fast DDS: its request carries no header, the request id
travels as the sample identity) cannot be served: Cyclone DDS drops its requests before they
reach Python. Such a client is recognised when its request writer matches (no ``clientid=`` in
its USER_DATA, a participant GUID that is not Cyclone's) and logged once per client and service
(one line per client participant).
"""

from operator import attrgetter
import struct
import time
from typing import Dict, List, Optional, Tuple

from cyclonedds.pub import DataWriter
from cyclonedds.sub import DataReader

from vehicle_msgs_py import types as msg_types
from vehicle_sim.transport import fast_cdr, port
from vehicle_sim.transport.dds import cyclone_private, peers
from vehicle_sim.transport.dds.endpoints import Intake
from vehicle_sim.transport.dds.qos import dds_qos, endpoint_user_data, userdata_tokens
from vehicle_sim.transport.errors import ServiceTimeoutError, TransportError
from vehicle_sim.transport.future import Future
from vehicle_sim.transport.qos import QosProfile

UINT64_MASK = 0xFFFFFFFFFFFFFFFF
# How often the executor wakes while replies wait for their client's reply reader to match [s].
PENDING_REPLY_POLL_S = 0.002
# How often the executor looks for newly matched request writers it cannot serve [s].
CLIENT_CHECK_S = 0.25


class _WireCodec:
    """
    The bytes of a service's wire type made only of fixed-size primitives, with ``struct``.

    Every ``vehicle_msgs`` service of the automobile node is one (``SetInt``, ``GetFloat``, ...):
    a request or reply then costs no generic (de)serialization. Bytes in another encapsulation
    (big endian) are decoded the generic way; values ``struct`` refuses are written the generic
    way, which raises its own error (both accept the same values: cyclonedds-python packs
    primitives with ``struct`` too).
    """

    def __init__(self, wire_cls, fields):
        self._wire_cls = wire_cls
        self._names = tuple(name for name, _ in fields)
        self._pack, self._unpack = fast_cdr.fixed_layout([kind for _, kind in fields])
        self._values = attrgetter(*self._names)

    @classmethod
    def of(cls, types, part: str):
        """Return the codec of ``types``' 'request' or 'response' wire type, or None."""
        fields = types.wire_primitives(part)
        if fields is None or fast_cdr.fixed_layout([kind for _, kind in fields]) is None:
            return None
        return cls(types.request_wire if part == 'request' else types.response_wire, fields)

    def decode(self, data: bytes):
        values = self._unpack(data)
        if values is None:
            return self._wire_cls.deserialize(data)
        return self._wire_cls(**dict(zip(self._names, values)))

    def encode(self, wire) -> Optional[bytes]:
        """Return the bytes of ``wire``, or None when ``struct`` refuses a value."""
        try:
            return self._pack(*self._values(wire))
        except (struct.error, TypeError, OverflowError):
            return None


def _wire_writer(writer, codec: Optional[_WireCodec]):
    """Return ``write(wire)``: the codec's bytes written as they are, else the generic write."""
    if codec is None:
        return writer.write
    write_serialized, encode = cyclone_private.serialized_writer(writer), codec.encode

    def write(wire) -> None:
        data = encode(wire)
        if data is None:
            writer.write(wire)
        else:
            write_serialized(data)
    return write


# How long a reply waits by default for its client's reply reader to be matched [s]; a client
# that went away (its request writer unmatched) drops its replies at once.
REPLY_MATCH_TIMEOUT_S = 10.0


class _PendingReply:
    __slots__ = ('wire', 'publication_handle', 'token', 'deadline')

    def __init__(self, wire, publication_handle, token, deadline):
        self.wire = wire
        self.publication_handle = publication_handle
        self.token = token
        self.deadline = deadline


class DdsService(port.ServiceServer):
    """
    A service server: request reader + reply writer sharing one ``serviceid`` token.

    :param node: the DdsNode (logger, ``shut_down``, ``reply_match_timeout_s``).
    :param ctx: the node's Context.
    """

    def __init__(self, node, ctx, srv_type: str, name: str, callback, qos: QosProfile):
        self._node = node
        self.service_name = name
        self._types = msg_types.service_types(srv_type)
        self._callback = callback
        self.token = ctx.next_token()
        request, reply = f'{self._types.srv_type}_Request', f'{self._types.srv_type}_Response'
        self._writer = DataWriter(
            ctx.participant, ctx.topic(f'rr{name}Reply', self._types.response_wire),
            qos=dds_qos(qos, endpoint_user_data(reply, serviceid=self.token), True))
        self._reader = DataReader(
            ctx.participant, ctx.topic(f'rq{name}Request', self._types.request_wire),
            qos=dds_qos(qos, endpoint_user_data(request, serviceid=self.token), False))
        request_codec = _WireCodec.of(self._types, 'request')
        self._intake = Intake(node, self._reader, f'service {name} ({srv_type}) request',
                              request_codec.decode if request_codec else None)
        self._write = _wire_writer(self._writer, _WireCodec.of(self._types, 'response'))
        # publication handle of a request writer -> its clientid token ('' when it has none)
        self._client_tokens: Dict[int, Optional[str]] = {}
        # subscription handle of a matched reply reader -> its clientid token
        self._reader_tokens: Dict[int, str] = {}
        self._matched_tokens = set()
        self.pending: List[_PendingReply] = []
        # The executor's list of services holding pending replies (set by the node), so that
        # its loop looks at those only, not at every service on every pass.
        self.waiting: Optional[List['DdsService']] = None
        self._match_count = 0
        self._checked_writers = set()

    def _request_writer_token(self, handle: int) -> Optional[str]:
        """Return the request writer's clientid ('' if none), None when the writer is gone."""
        token = self._client_tokens.get(handle)
        if token is None:
            data = self._reader.get_matched_publication_data(handle)
            if data is None:
                return None
            token = userdata_tokens(data.qos).get('clientid', '')
            self._client_tokens[handle] = token
        return token

    def _reply_reader_matched(self, token: str) -> bool:
        if token in self._matched_tokens:
            return True
        handles = set(self._writer.get_matched_subscriptions())
        for handle in handles - self._reader_tokens.keys():
            data = self._writer.get_matched_subscription_data(handle)
            if data is not None:
                self._reader_tokens[handle] = userdata_tokens(data.qos).get('clientid', '')
        for handle in list(self._reader_tokens):
            if handle not in handles:
                del self._reader_tokens[handle]
        self._matched_tokens = set(self._reader_tokens.values())
        return token in self._matched_tokens

    @property
    def dropped_samples(self) -> int:
        """How many requests could not be decoded and were dropped."""
        return self._intake.dropped

    def check_clients(self) -> List[Tuple[bytes, str]]:
        """
        Return ``(participant, vendor)`` of the newly matched clients that cannot be served.

        Those are the request writers that are not rmw_cyclonedds (see the module); each writer
        is returned once.
        """
        total = self._reader.get_subscription_matched_status().total_count
        if total == self._match_count:
            return []
        self._match_count = total
        handles = set(self._reader.get_matched_publications())
        self._checked_writers &= handles
        found = []
        for handle in handles - self._checked_writers:
            self._checked_writers.add(handle)
            data = self._reader.get_matched_publication_data(handle)
            if data is None or 'clientid' in userdata_tokens(data.qos):
                continue
            participant = data.participant_key.bytes
            vendor = peers.vendor_of(participant)
            if vendor != peers.CYCLONE:   # a Cyclone client without an id is served
                found.append((participant, vendor))
        return found

    def on_data(self) -> None:
        """Serve the requests that arrived (the executor's handler of the request reader)."""
        for sample in self._intake.take():
            handle = sample.sample_info.publication_handle
            client_id, sequence, request = self._types.request_from_wire(sample)
            try:
                result = self._callback(request, self._types.response())
            except Exception as exc:  # noqa: BLE001 - a bad request must not kill the node
                self._node.get_logger().error(
                    f'service {self.service_name} callback raised {type(exc).__name__}: {exc}')
                continue
            if isinstance(result, Future):
                # A deferred reply (port.NodePort.create_service): sent once the future is done.
                result.add_done_callback(
                    lambda done, c=client_id, s=sequence, h=handle: self._on_deferred(
                        done, c, s, h))
            else:
                self._reply(result, client_id, sequence, handle)

    def _on_deferred(self, done: Future, client_id: int, sequence: int,
                     handle: int) -> None:
        if self._node.shut_down:
            return
        if done.exception() is not None:
            exc = done.exception()
            self._node.get_logger().error(
                f'service {self.service_name} deferred reply failed {type(exc).__name__}: {exc}')
            return
        self._reply(done.result(), client_id, sequence, handle)

    def _reply(self, response, client_id: int, sequence: int, handle: int) -> None:
        if not isinstance(response, self._types.response):
            self._node.get_logger().error(
                f'service {self.service_name} callback returned {type(response).__name__}')
            return
        wire = self._types.response_to_wire(response, client_id, sequence)
        token = self._request_writer_token(handle)
        if token is None:
            return  # the client went away: drop silently, as rmw does
        if not token or self._reply_reader_matched(token):
            self._write(wire)
        else:
            if not self.pending and self.waiting is not None:
                self.waiting.append(self)
            self.pending.append(_PendingReply(
                wire, handle, token, time.monotonic() + self._node.reply_match_timeout_s))

    def flush_pending(self, now: float) -> None:
        """Send the queued replies whose client reply reader matched; drop the expired ones."""
        keep = []
        for item in self.pending:
            if self._reply_reader_matched(item.token):
                self._write(item.wire)
            elif self._reader.get_matched_publication_data(item.publication_handle) is None:
                self._client_tokens.pop(item.publication_handle, None)   # the client went away
            elif now >= item.deadline:
                self._node.get_logger().warning(
                    f"{self.service_name}: reply dropped: the client's reply reader was not "
                    f'matched within {self._node.reply_match_timeout_s:g} s')
            else:
                keep.append(item)
        self.pending = keep


def warn_unservable_clients(services: List[DdsService]) -> None:
    """
    Log the clients the services cannot serve.

    One warning per client participant, naming every service it newly matched (``ros2 param
    list`` matches all six parameter services at once).
    """
    by_participant: Dict[bytes, Tuple[str, List[str], DdsService]] = {}
    for service in services:
        for participant, vendor in service.check_clients():
            entry = by_participant.setdefault(participant, (vendor, [], service))
            entry[1].append(service.service_name)
    for participant, (vendor, names, service) in by_participant.items():
        service._node.get_logger().warning(
            peers.fast_dds_client_warning(names, vendor, participant))


class DdsClient(port.Client):
    """
    A service client: reply reader (created first) + request writer, one ``clientid``.

    :param node: the DdsNode (its ``spin_until`` waits for replies).
    :param ctx: the node's Context.
    """

    def __init__(self, node, ctx, srv_type: str, name: str, qos: QosProfile):
        self._node = node
        self._ctx = ctx
        self.service_name = name
        self._types = msg_types.service_types(srv_type)
        self.token = ctx.next_token()
        request, reply = f'{self._types.srv_type}_Request', f'{self._types.srv_type}_Response'
        self._reader = DataReader(
            ctx.participant, ctx.topic(f'rr{name}Reply', self._types.response_wire),
            qos=dds_qos(qos, endpoint_user_data(reply, clientid=self.token), False))
        reply_codec = _WireCodec.of(self._types, 'response')
        self._intake = Intake(node, self._reader, f'client {name} ({srv_type}) reply',
                              reply_codec.decode if reply_codec else None)
        self._writer = DataWriter(
            ctx.participant, ctx.topic(f'rq{name}Request', self._types.request_wire),
            qos=dds_qos(qos, endpoint_user_data(request, clientid=self.token), True))
        self._write = _wire_writer(self._writer, _WireCodec.of(self._types, 'request'))
        self.client_id = self._writer.get_instance_handle() & UINT64_MASK
        self._pending: Dict[int, Future] = {}
        self._endpoint_tokens: Dict[int, str] = {}
        self._warned_servers = set()

    def _service_token(self, handle: int, lookup) -> str:
        token = self._endpoint_tokens.get(handle)
        if token is None:
            data = lookup(handle)
            token = userdata_tokens(data.qos).get('serviceid', '') if data is not None else ''
            self._endpoint_tokens[handle] = token
        return token

    def service_is_ready(self) -> bool:
        readers = self._writer.get_matched_subscriptions()
        writers = self._reader.get_matched_publications()
        if not readers or not writers:
            return False
        reader_ids = {self._service_token(h, self._writer.get_matched_subscription_data)
                      for h in readers} - {''}
        if not reader_ids:
            return True
        writer_ids = {self._service_token(h, self._reader.get_matched_publication_data)
                      for h in writers}
        return bool(reader_ids & writer_ids)

    def foreign_servers(self) -> List[Tuple[bytes, str]]:
        """
        Return ``(participant, vendor)`` of the matched servers that are not rmw_cyclonedds.

        Their request readers match this client's request writer, but they cannot read the
        rmw_cyclonedds request header (Fast DDS drops the sample as too large) and never answer.
        """
        found = []
        for handle in self._writer.get_matched_subscriptions():
            data = self._writer.get_matched_subscription_data(handle)
            if data is None:
                continue
            participant = data.participant_key.bytes
            vendor = peers.vendor_of(participant)
            if vendor != peers.CYCLONE:
                found.append((participant, vendor))
        return found

    def wait_for_service(self, timeout_s: Optional[float] = None) -> bool:
        deadline = None if timeout_s is None else time.monotonic() + timeout_s
        while not self.service_is_ready():
            if deadline is not None and time.monotonic() >= deadline:
                return False
            time.sleep(0.01)
        for participant, vendor in self.foreign_servers():
            if participant not in self._warned_servers:   # once per server and client
                self._warned_servers.add(participant)
                self._node.get_logger().warning(
                    peers.foreign_server_note(self.service_name, vendor, participant))
        return True

    def call_async(self, request) -> Future:
        if not isinstance(request, self._types.request):
            raise TransportError(
                f'{self.service_name} takes {self._types.request.__ros_type__}, '
                f'got {type(request).__name__}')
        sequence = self._ctx.next_sequence()
        future = Future()
        future.sequence = sequence
        self._pending[sequence] = future
        self._write(self._types.request_to_wire(request, self.client_id, sequence))
        return future

    def call(self, request, timeout_s: float = 5.0):
        future = self.call_async(request)
        if not self._node.spin_until(future.done, timeout_s):
            self._pending.pop(future.sequence, None)
            why = ''.join(f'; {peers.foreign_server_note(self.service_name, vendor, participant)}'
                          for participant, vendor in self.foreign_servers())
            raise ServiceTimeoutError(
                f'no reply from {self.service_name} within {timeout_s:g} s{why}')
        return future.result()

    @property
    def dropped_samples(self) -> int:
        """How many replies could not be decoded and were dropped."""
        return self._intake.dropped

    def on_data(self) -> None:
        """Complete the futures of the replies that arrived (the reply reader's handler)."""
        for sample in self._intake.take():
            client_id, sequence, response = self._types.response_from_wire(sample)
            if client_id != self.client_id:
                continue  # a reply to another client on the same service
            future = self._pending.pop(sequence, None)
            if future is not None:
                future.set_result(response)
