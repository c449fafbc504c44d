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
The embedded Cyclone DDS adapter: a ROS 2 Jazzy graph citizen without ROS (ros2_wire Parts A, E).

One DomainParticipant per process (USER_DATA ``enclave=/;``) shared by all nodes of the process;
``rt``/``rq``/``rr`` topic names, exact DDS type names, XCDR1 only, autodispose off, ``typehash=``
in every endpoint's USER_DATA; services with ``serviceid=``/``clientid=`` tokens and the 16-byte
rmw_cyclonedds request header; ``ros_discovery_info`` republished on every change; ``/rosout``,
``/parameter_events`` and the rcl_interfaces parameter services.

Threading: single-threaded like an rclpy SingleThreadedExecutor. Everything (subscription and
service callbacks, replies, timers) runs inside ``spin_once`` on the calling thread. A reply whose
client reply reader is not matched yet is queued and retried on later ``spin_once`` calls for up
to ``reply_match_timeout_s``: the caller is never blocked (rmw_cyclonedds itself blocks up to
100 ms; ros2_wire C10).
"""

import dataclasses
import itertools
import signal
import sys
import threading
import time
from typing import Any, Callable, Dict, List, Optional

from cyclonedds.core import DDSException, GuardCondition, ReadCondition
from cyclonedds.domain import Domain, DomainParticipant
from cyclonedds.pub import DataWriter
from cyclonedds.qos import Policy, Qos
from cyclonedds.sub import DataReader
from cyclonedds.topic import Topic

from vehicle_msgs_py import types as msg_types
from vehicle_sim.transport import cyclone_private, dds_config, port
from vehicle_sim.transport.params import (
    parse_ros_args,
    read_only_reason,
    unknown_overrides_warning,
)
from vehicle_sim.transport.port import (
    as_qos,
    Parameter,
    QosProfile,
    resolve_name,
    SetParametersResult,
    TransportError,
)

UINT64_MASK = 0xFFFFFFFFFFFFFFFF
INFINITE_NS = 0x7FFFFFFFFFFFFFFF
TAKE_BATCH = 256
# How long spin() may block before it looks at shutdown requests (signals) again.
SPIN_SLICE_S = 0.1
# Polling interval while replies wait for their client's reply reader to match.
PENDING_REPLY_POLL_S = 0.002
DISCOVERY_TOPIC = 'ros_discovery_info'
ZERO_HASH = 'RIHS01_' + '0' * 64


_domains: Dict[int, Domain] = {}
_domains_lock = threading.Lock()


def ensure_domain(domain: Optional[int] = None) -> Domain:
    """
    Create (once per process) the Domain with the configuration of the environment.

    Call it before creating raw cyclonedds participants in a process that also runs nodes:
    the first participant of a domain fixes its configuration.

    :param domain: the domain id; default ``ROS_DOMAIN_ID``.
    """
    domain = dds_config.domain_id() if domain is None else domain
    with _domains_lock:
        if domain not in _domains:
            _domains[domain] = dds_config.create_domain(domain)
        return _domains[domain]


def _userdata_tokens(qos: Optional[Qos]) -> Dict[str, str]:
    """Parse ``key=value;`` USER_DATA tokens of a discovered endpoint (values kept verbatim)."""
    if qos is None or Policy.Userdata not in qos:
        return {}
    data = qos[Policy.Userdata].data or b''
    tokens = {}
    for part in data.decode('ascii', 'replace').split(';'):
        key, sep, value = part.partition('=')
        if sep:
            tokens[key] = value
    return tokens


def _type_hash(ros_type: str) -> str:
    try:
        return msg_types.type_hash(ros_type)
    except (ValueError, KeyError):
        return ZERO_HASH


def endpoint_user_data(ros_type: str, **tokens: Any) -> bytes:
    """
    Return the USER_DATA of a reader or writer as rmw_cyclonedds writes it (rmw_node.cpp).

    ``endpoint_user_data('std_srvs/srv/SetBool_Request', serviceid=3)`` gives
    ``b'serviceid=3;typehash=RIHS01_<64 hex>;'``; rmw_cyclonedds parses ``typehash=`` of every
    endpoint it discovers and logs an error when it is missing.
    """
    text = ''.join(f'{key}={value};' for key, value in tokens.items())
    return f'{text}typehash={_type_hash(ros_type)};'.encode()


def _dds_qos(profile: QosProfile, user_data: bytes, writer: bool) -> Qos:
    """Map a ROS QoS profile to DDS QoS like rmw_cyclonedds ``create_readwrite_qos`` (A6)."""
    if profile.history == port.KEEP_ALL:
        history = Policy.History.KeepAll
    else:
        history = Policy.History.KeepLast(max(1, profile.depth))
    policies = [
        history,
        (Policy.Reliability.Reliable(max_blocking_time=INFINITE_NS)
         if profile.reliability == port.RELIABLE else Policy.Reliability.BestEffort),
        Policy.DataRepresentation(use_cdrv0_representation=True),
        Policy.Userdata(data=user_data),
    ]
    if profile.durability == port.TRANSIENT_LOCAL:
        policies += [
            Policy.Durability.TransientLocal,
            Policy.DurabilityService(cleanup_delay=0, history=history, max_samples=-1,
                                     max_instances=-1, max_samples_per_instance=-1),
        ]
    else:
        policies.append(Policy.Durability.Volatile)
    if profile.lifespan_s is not None and writer:
        policies.append(Policy.Lifespan(int(profile.lifespan_s * 1e9)))
    if profile.deadline_s is not None:
        policies.append(Policy.Deadline(int(profile.deadline_s * 1e9)))
    if writer:
        policies.append(Policy.WriterDataLifecycle(autodispose=False))
    return Qos(*policies)


def endpoint_qos(profile: QosProfile, ros_type: str, writer: bool, **tokens: Any) -> Qos:
    """Return the DDS QoS of a ROS reader or writer of ``ros_type``, USER_DATA included."""
    return _dds_qos(profile, endpoint_user_data(ros_type, **tokens), writer)


class _Context:
    """
    The process-wide DDS state: the participant, topics, the graph message, the node registry.

    Created by the first node, its participant deleted when the last node shuts down.
    """

    _lock = threading.Lock()
    _instance: Optional['_Context'] = None

    def __init__(self):
        self.domain_id = dds_config.domain_id()
        ensure_domain(self.domain_id)
        try:
            self.participant = DomainParticipant(
                self.domain_id, qos=Qos(Policy.Userdata(data=b'enclave=/;')))
        except DDSException as exc:
            raise TransportError(dds_config.describe_domain_error(
                self.domain_id, str(exc))) from None
        try:
            self._set_up()
        except BaseException:
            # A signal (KeyboardInterrupt) or an error half-way: no ghost participant.
            cyclone_private.delete_participant(self.participant)
            raise

    def _set_up(self):
        self.participant_gid = self.participant.guid.bytes
        self._topics: Dict[str, Topic] = {}
        self._nodes: List['DdsNode'] = []
        self._token_counter = itertools.count(1)
        self._sequence = itertools.count(1)
        self._closed = False
        info_type = msg_types.message_type('rmw_dds_common/msg/ParticipantEntitiesInfo')
        self._info_type = info_type
        self._node_info_type = msg_types.message_type('rmw_dds_common/msg/NodeEntitiesInfo')
        self._gid_type = msg_types.message_type('rmw_dds_common/msg/Gid')
        self._discovery_writer = DataWriter(
            self.participant, self.topic(DISCOVERY_TOPIC, info_type),
            qos=_dds_qos(port.QOS_DISCOVERY_INFO_WRITER,
                         endpoint_user_data(info_type.__ros_type__), True))

    @classmethod
    def acquire(cls, node: 'DdsNode') -> '_Context':
        with cls._lock:
            if cls._instance is None or cls._instance._closed:
                cls._instance = _Context()
            cls._instance._nodes.append(node)
            return cls._instance

    def release(self, node: 'DdsNode') -> None:
        """Remove ``node`` from the graph; the last node deletes the participant."""
        with _Context._lock:
            if node in self._nodes:
                self._nodes.remove(node)
            last = not self._nodes
            self.publish_graph()
            if last:
                self._close_locked()

    def _close_locked(self) -> None:
        if not self._closed:
            self._closed = True
            cyclone_private.delete_participant(self.participant)
        if _Context._instance is self:
            _Context._instance = None

    @classmethod
    def close_process(cls) -> None:
        """
        Leave the graph with whatever this process built, even half-way through a start-up.

        Publishes an empty node list and deletes the participant (with every entity in it).
        """
        with cls._lock:
            ctx = cls._instance
            if ctx is None:
                return
            for node in list(ctx._nodes):
                node._graph_visible = False
                node._shutdown = True
            ctx._nodes = []
            try:
                ctx.publish_graph()
            finally:
                ctx._close_locked()

    def topic(self, name: str, data_type) -> Topic:
        """Return the one Topic per name of this participant (ros2_wire C4)."""
        found = self._topics.get(name)
        if found is None:
            found = Topic(self.participant, name, data_type)
            self._topics[name] = found
        elif found.data_type is not data_type:
            raise TransportError(
                f'topic {name!r} is already used with type {found.data_type.__ros_type__}')
        return found

    def next_token(self) -> str:
        """Return a new ``serviceid``/``clientid`` token formatted like rmw_cyclonedds (A4)."""
        raw = self.participant_gid[:12] + next(self._token_counter).to_bytes(4, 'big')
        return f'{raw[0]:2x}.' + '.'.join(f'{b:x}' for b in raw[1:])

    def next_sequence(self) -> int:
        return next(self._sequence)

    def publish_graph(self) -> None:
        """Publish the complete ParticipantEntitiesInfo of this process (A5.3)."""
        if self._closed:
            return
        gid = self._gid_type
        nodes = [
            self._node_info_type(
                node_namespace=n.get_namespace(), node_name=n.get_name(),
                reader_gid_seq=[gid(data=g) for g in n._reader_gids.values()],
                writer_gid_seq=[gid(data=g) for g in n._writer_gids.values()])
            for n in self._nodes if n._graph_visible]
        self._discovery_writer.write(self._info_type(
            gid=gid(data=self.participant_gid), node_entities_info_seq=nodes))


class _Intake:
    """
    Takes a reader's samples and decodes each one on its own (cyclone_private.take).

    A sample that cannot be decoded (a string that is not UTF-8, a truncated buffer) is dropped
    and counted, with a throttled warning naming the endpoint; the rest of the batch is kept.
    """

    def __init__(self, node: 'DdsNode', reader: DataReader, what: str):
        self._node = node
        self.reader = reader
        self.what = what
        self.dropped = 0
        self._warning = None

    def take(self) -> list:
        samples, errors = cyclone_private.take(self.reader, TAKE_BATCH)
        for exc in errors:
            self.dropped += 1
            if self._warning is None:
                self._warning = port.ThrottledWarning(self._node.get_logger())
            self._warning.warn(
                f'{self.what}: dropped a sample that cannot be decoded '
                f'({type(exc).__name__}: {exc}); {self.dropped} dropped so far')
        return samples


class DdsPublisher(port.Publisher):
    def __init__(self, node: 'DdsNode', writer: DataWriter, msg_type, topic_name: str):
        self._node = node
        self._writer = writer
        self._type = msg_type
        self.topic_name = topic_name

    def publish(self, msg) -> None:
        if type(msg) is not self._type:
            raise TransportError(
                f'{self.topic_name} takes {self._type.__ros_type__}, got {type(msg).__name__}')
        self._writer.write(msg)

    def get_subscription_count(self) -> int:
        return len(self._writer.get_matched_subscriptions())

    @property
    def gid(self) -> bytes:
        return self._writer.guid.bytes


class DdsSubscription(port.Subscription):
    def __init__(self, reader: DataReader, topic_name: str, intake: _Intake):
        self._reader = reader
        self.topic_name = topic_name
        self._intake = intake

    @property
    def dropped_samples(self) -> int:
        """How many samples could not be decoded and were dropped."""
        return self._intake.dropped

    def get_publisher_count(self) -> int:
        return len(self._reader.get_matched_publications())

    @property
    def gid(self) -> bytes:
        return self._reader.guid.bytes


class _PendingReply:
    __slots__ = ('wire', 'publication_handle', 'token', 'deadline')

    def __init__(self, wire, publication_handle, token, deadline):
        self.wire = wire
        self.publication_handle = publication_handle
        self.token = token
        self.deadline = deadline


class DdsService(port.Service):
    """A service server: request reader + reply writer sharing one ``serviceid`` token."""

    def __init__(self, node: 'DdsNode', srv_type: str, name: str, callback, qos: QosProfile):
        self._node = node
        self.service_name = name
        self._types = msg_types.service_types(srv_type)
        self._callback = callback
        ctx = node._ctx
        self.token = ctx.next_token()
        request, reply = f'{self._types.srv_type}_Request', f'{self._types.srv_type}_Response'
        self._writer = DataWriter(
            ctx.participant, ctx.topic(f'rr{name}Reply', self._types.response_wire),
            qos=_dds_qos(qos, endpoint_user_data(reply, serviceid=self.token), True))
        self._reader = DataReader(
            ctx.participant, ctx.topic(f'rq{name}Request', self._types.request_wire),
            qos=_dds_qos(qos, endpoint_user_data(request, serviceid=self.token), False))
        self._intake = _Intake(node, self._reader, f'service {name} ({srv_type}) request')
        # publication handle of a request writer -> its clientid token ('' when it has none)
        self._client_tokens: Dict[int, Optional[str]] = {}
        # subscription handle of a matched reply reader -> its clientid token
        self._reader_tokens: Dict[int, str] = {}
        self._matched_tokens = set()
        self._pending: List[_PendingReply] = []

    def _request_writer_token(self, handle: int) -> Optional[str]:
        """Return the request writer's clientid ('' if none), None when the writer is gone."""
        token = self._client_tokens.get(handle)
        if token is None:
            data = self._reader.get_matched_publication_data(handle)
            if data is None:
                return None
            token = _userdata_tokens(data.qos).get('clientid', '')
            self._client_tokens[handle] = token
        return token

    def _reply_reader_matched(self, token: str) -> bool:
        if token in self._matched_tokens:
            return True
        handles = set(self._writer.get_matched_subscriptions())
        for handle in handles - self._reader_tokens.keys():
            data = self._writer.get_matched_subscription_data(handle)
            if data is not None:
                self._reader_tokens[handle] = _userdata_tokens(data.qos).get('clientid', '')
        for handle in list(self._reader_tokens):
            if handle not in handles:
                del self._reader_tokens[handle]
        self._matched_tokens = set(self._reader_tokens.values())
        return token in self._matched_tokens

    @property
    def dropped_samples(self) -> int:
        """How many requests could not be decoded and were dropped."""
        return self._intake.dropped

    def _on_data(self) -> None:
        for sample in self._intake.take():
            handle = sample.sample_info.publication_handle
            client_id, sequence, request = self._types.request_from_wire(sample)
            try:
                result = self._callback(request, self._types.response())
            except Exception as exc:  # noqa: BLE001 - a bad request must not kill the node
                self._node.get_logger().error(
                    f'service {self.service_name} callback raised {type(exc).__name__}: {exc}')
                continue
            if isinstance(result, port.Future):
                # A deferred reply (port.NodePort.create_service): sent once the future is done.
                result.add_done_callback(
                    lambda done, c=client_id, s=sequence, h=handle: self._on_deferred(
                        done, c, s, h))
            else:
                self._reply(result, client_id, sequence, handle)

    def _on_deferred(self, done: port.Future, client_id: int, sequence: int,
                     handle: int) -> None:
        if self._node._shutdown:
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
            self._writer.write(wire)
        else:
            self._pending.append(_PendingReply(
                wire, handle, token, time.monotonic() + self._node.reply_match_timeout_s))

    def _flush_pending(self, now: float) -> None:
        keep = []
        for item in self._pending:
            if self._reply_reader_matched(item.token):
                self._writer.write(item.wire)
            elif now >= item.deadline:
                self._node.get_logger().debug(
                    f'{self.service_name}: client reply reader never matched; reply dropped')
            elif self._reader.get_matched_publication_data(item.publication_handle) is None:
                self._client_tokens.pop(item.publication_handle, None)
            else:
                keep.append(item)
        self._pending = keep


class DdsClient(port.Client):
    """A service client: reply reader (created first, C10) + request writer, one ``clientid``."""

    def __init__(self, node: 'DdsNode', srv_type: str, name: str, qos: QosProfile):
        self._node = node
        self.service_name = name
        self._types = msg_types.service_types(srv_type)
        ctx = node._ctx
        self.token = ctx.next_token()
        request, reply = f'{self._types.srv_type}_Request', f'{self._types.srv_type}_Response'
        self._reader = DataReader(
            ctx.participant, ctx.topic(f'rr{name}Reply', self._types.response_wire),
            qos=_dds_qos(qos, endpoint_user_data(reply, clientid=self.token), False))
        self._intake = _Intake(node, self._reader, f'client {name} ({srv_type}) reply')
        self._writer = DataWriter(
            ctx.participant, ctx.topic(f'rq{name}Request', self._types.request_wire),
            qos=_dds_qos(qos, endpoint_user_data(request, clientid=self.token), True))
        self.client_id = self._writer.get_instance_handle() & UINT64_MASK
        self._pending: Dict[int, port.Future] = {}
        self._endpoint_tokens: Dict[int, str] = {}

    def _service_token(self, handle: int, lookup) -> str:
        token = self._endpoint_tokens.get(handle)
        if token is None:
            data = lookup(handle)
            token = _userdata_tokens(data.qos).get('serviceid', '') if data is not None else ''
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

    def wait_for_service(self, timeout_s: Optional[float] = None) -> bool:
        deadline = None if timeout_s is None else time.monotonic() + timeout_s
        while not self.service_is_ready():
            if deadline is not None and time.monotonic() >= deadline:
                return False
            time.sleep(0.01)
        return True

    def call_async(self, request) -> port.Future:
        if not isinstance(request, self._types.request):
            raise TransportError(
                f'{self.service_name} takes {self._types.request.__ros_type__}, '
                f'got {type(request).__name__}')
        sequence = self._node._ctx.next_sequence()
        future = port.Future()
        future.sequence = sequence
        self._pending[sequence] = future
        self._writer.write(self._types.request_to_wire(request, self.client_id, sequence))
        return future

    def call(self, request, timeout_s: float = 5.0):
        future = self.call_async(request)
        if not self._node.spin_until(future.done, timeout_s):
            self._pending.pop(future.sequence, None)
            raise port.ServiceTimeoutError(
                f'no reply from {self.service_name} within {timeout_s} s')
        return future.result()

    @property
    def dropped_samples(self) -> int:
        """How many replies could not be decoded and were dropped."""
        return self._intake.dropped

    def _on_data(self) -> None:
        for sample in self._intake.take():
            client_id, sequence, response = self._types.response_from_wire(sample)
            if client_id != self.client_id:
                continue  # a reply to another client on the same service
            future = self._pending.pop(sequence, None)
            if future is not None:
                future.set_result(response)


class DdsTimer(port.Timer):
    def __init__(self, node: 'DdsNode', period_s: float, callback):
        if not period_s > 0.0:
            raise TransportError(f'timer period must be > 0 s, got {period_s}')
        self._node = node
        self.period_s = period_s
        self.callback = callback
        self.next_due = time.monotonic() + period_s
        self.cancelled = False

    def cancel(self) -> None:
        self.cancelled = True

    def reset(self) -> None:
        self.cancelled = False
        self.next_due = time.monotonic() + self.period_s
        if not self._node._shutdown:
            self._node._schedule(self)


class DdsLogger(port.Logger):
    """Console output like rcutils plus a ``rcl_interfaces/msg/Log`` on /rosout."""

    def __init__(self, node: 'DdsNode', level: int, to_rosout: bool, to_stdout: bool):
        self._node = node
        self.level = level
        self.name = node._logger_name
        self._to_rosout = to_rosout
        self._to_stdout = to_stdout
        self._publisher = None
        self._log_type = None

    _NAMES = {10: 'DEBUG', 20: 'INFO', 30: 'WARN', 40: 'ERROR', 50: 'FATAL'}

    def log(self, level: int, message: str) -> None:
        if level < self.level:
            return
        now_ns = time.time_ns()
        if self._to_stdout:
            sys.stderr.write(f'[{self._NAMES.get(level, level)}] [{now_ns / 1e9:.9f}] '
                             f'[{self.name}]: {message}\n')
        if self._to_rosout and self._publisher is not None and self._node.ok():
            frame = sys._getframe(2) if level != 0 else None
            self._publisher.publish(self._log_type(
                stamp=self._node.time_msg(port.Time(now_ns)), level=level, name=self.name,
                msg=str(message), file=frame.f_code.co_filename if frame else '',
                function=frame.f_code.co_name if frame else '',
                line=frame.f_lineno if frame else 0))


@dataclasses.dataclass
class _ParamEntry:
    value: Any
    type_: int
    description: str = ''
    validator: Optional[Callable] = None
    read_only: bool = False
    additional_constraints: str = ''


class DdsNode(port.NodePort):
    """
    A ROS 2 node on the embedded Cyclone DDS transport.

    :param name: node name (``__node`` remaps in ``args`` win).
    :param namespace: node namespace (``__ns`` remaps in ``args`` win).
    :param args: the full command line; the ``--ros-args`` part is applied.
    :param parameter_overrides: initial values that win over the command line.
    :param reply_match_timeout_s: how long a reply waits for its client's reply reader [s].
    """

    def __init__(self, name: str, namespace: str = '', args=None,
                 parameter_overrides: Optional[Dict[str, Any]] = None,
                 reply_match_timeout_s: float = 1.0):
        ros_args = parse_ros_args(args)
        self._ros_args = ros_args
        self._name = port.validate_node_name(ros_args.node_name(name))
        self._namespace = ros_args.namespace(self._name, namespace)
        self._logger_name = '.'.join(
            [t for t in self._namespace.split('/') if t] + [self._name])
        self.reply_match_timeout_s = reply_match_timeout_s
        self._overrides = ros_args.parameter_overrides(self._name, self._namespace)
        self._overrides.update(parameter_overrides or {})
        self._params: Dict[str, _ParamEntry] = {}
        self._overrides_checked = False
        self._on_set_callbacks: List[Callable] = []
        # id(entity) -> GUID bytes, for ros_discovery_info; the entities, to delete them.
        self._reader_gids: Dict[int, bytes] = {}
        self._writer_gids: Dict[int, bytes] = {}
        self._endpoints: List[Any] = []
        self._handlers: List[Optional[Callable[[], None]]] = []
        self._conditions = []
        self._services: List[DdsService] = []
        self._timers: List[DdsTimer] = []
        self._shutdown = False
        self._shutdown_requested = False
        self._graph_visible = False
        self._sim_time_ns = 0
        self._clock_sub = None
        self._time_type = msg_types.message_type('builtin_interfaces/msg/Time')
        self._ctx = _Context.acquire(self)
        try:
            self._waitset = cyclone_private.IndexedWaitSet(self._ctx.participant)
            self._guard = GuardCondition(self._ctx.participant)
            self._attach(self._guard, None)
            self._logger = DdsLogger(self, ros_args.log_level or 20, ros_args.rosout_logs,
                                     ros_args.stdout_logs)
            if ros_args.rosout_logs:
                self._logger._log_type = self.msg('rcl_interfaces/msg/Log')
                self._logger._publisher = self.create_publisher(
                    'rcl_interfaces/msg/Log', '/rosout', port.QOS_ROSOUT)
            self._param_events = self.create_publisher(
                'rcl_interfaces/msg/ParameterEvent', '/parameter_events',
                port.QOS_PARAMETER_EVENTS)
            self._create_parameter_services()
            self.declare_parameter('use_sim_time', False,
                                   description='use /clock as the node clock')
        except BaseException:
            self._ctx.release(self)
            raise
        self._graph_visible = True
        self._ctx.publish_graph()

    # ---------------------------------------------------------------- naming and types

    def get_name(self) -> str:
        return self._name

    def get_namespace(self) -> str:
        return self._namespace

    def resolve(self, name: str) -> str:
        """Return the fully-qualified, remapped form of a topic or service name."""
        fqn = resolve_name(name, self._namespace, self._name)
        return self._ros_args.remap_name(fqn, self._name, self._namespace)

    def msg(self, ros_type: str):
        try:
            return msg_types.message_type(ros_type)
        except ValueError as exc:
            raise TransportError(str(exc)) from None

    def srv(self, srv_type: str):
        try:
            types = msg_types.service_types(srv_type)
        except ValueError as exc:
            raise TransportError(str(exc)) from None
        return _SrvClasses(types.request, types.response)

    # ---------------------------------------------------------------- endpoints

    def _check_ok(self) -> None:
        if self._shutdown:
            raise TransportError(f'node {self.get_fully_qualified_name()} is shut down')

    def _attach(self, condition, handler) -> None:
        index = len(self._handlers) + 1
        self._handlers.append(handler)
        self._conditions.append(condition)
        try:
            self._waitset.attach(condition, index)
        except DDSException as exc:
            raise TransportError(f'cannot attach {condition!r} to the waitset: {exc}') from None

    def _add_reader(self, reader: DataReader, handler) -> None:
        self._reader_gids[id(reader)] = reader.guid.bytes
        self._endpoints.append(reader)
        self._attach(ReadCondition(reader, cyclone_private.ANY_STATE), handler)

    def _add_writer(self, writer: DataWriter) -> None:
        self._writer_gids[id(writer)] = writer.guid.bytes
        self._endpoints.append(writer)

    def _graph_changed(self) -> None:
        if self._graph_visible:
            self._ctx.publish_graph()

    def create_publisher(self, ros_type: str, topic: str, qos=None) -> DdsPublisher:
        self._check_ok()
        profile = as_qos(qos)
        msg_type = self.msg(ros_type)
        fqn = topic if profile.avoid_ros_namespace_conventions else self.resolve(topic)
        dds_name = fqn if profile.avoid_ros_namespace_conventions else 'rt' + fqn
        writer = DataWriter(
            self._ctx.participant, self._ctx.topic(dds_name, msg_type),
            qos=_dds_qos(profile, endpoint_user_data(msg_type.__ros_type__), True))
        self._add_writer(writer)
        self._graph_changed()
        return DdsPublisher(self, writer, msg_type, fqn)

    def create_subscription(self, ros_type: str, topic: str, callback,
                            qos=None) -> DdsSubscription:
        self._check_ok()
        profile = as_qos(qos)
        msg_type = self.msg(ros_type)
        fqn = topic if profile.avoid_ros_namespace_conventions else self.resolve(topic)
        dds_name = fqn if profile.avoid_ros_namespace_conventions else 'rt' + fqn
        reader = DataReader(
            self._ctx.participant, self._ctx.topic(dds_name, msg_type),
            qos=_dds_qos(profile, endpoint_user_data(msg_type.__ros_type__), False))

        intake = _Intake(self, reader, f'subscription {fqn} ({msg_type.__ros_type__})')

        def on_data():
            for sample in intake.take():
                callback(sample)

        self._add_reader(reader, on_data)
        self._graph_changed()
        return DdsSubscription(reader, fqn, intake)

    def create_service(self, srv_type: str, name: str, callback,
                       qos=port.QOS_SERVICES) -> DdsService:
        self._check_ok()
        try:
            service = DdsService(self, srv_type, self.resolve(name), callback, as_qos(qos))
        except ValueError as exc:
            raise TransportError(str(exc)) from None
        self._add_reader(service._reader, service._on_data)
        self._add_writer(service._writer)
        self._services.append(service)
        self._graph_changed()
        return service

    def create_client(self, srv_type: str, name: str, qos=port.QOS_SERVICES) -> DdsClient:
        self._check_ok()
        try:
            client = DdsClient(self, srv_type, self.resolve(name), as_qos(qos))
        except ValueError as exc:
            raise TransportError(str(exc)) from None
        self._add_reader(client._reader, client._on_data)
        self._add_writer(client._writer)
        self._graph_changed()
        return client

    def create_timer(self, period_s: float, callback) -> DdsTimer:
        self._check_ok()
        timer = DdsTimer(self, period_s, callback)
        self._schedule(timer)
        return timer

    def _schedule(self, timer: 'DdsTimer') -> None:
        if timer not in self._timers:
            self._timers.append(timer)
        self._guard.set(True)  # re-plan the current wait

    # ---------------------------------------------------------------- clock and logging

    def now(self) -> port.Time:
        if self._clock_sub is not None:
            return port.Time(self._sim_time_ns)
        return port.Time(time.time_ns())

    def time_msg(self, t: Optional[port.Time] = None):
        t = self.now() if t is None else t
        return self._time_type(sec=t.sec, nanosec=t.nanosec)

    def get_logger(self) -> DdsLogger:
        return self._logger

    def _on_clock(self, msg) -> None:
        self._sim_time_ns = msg.clock.sec * 1_000_000_000 + msg.clock.nanosec

    def _apply_use_sim_time(self, enabled: bool) -> None:
        if enabled and self._clock_sub is None:
            self._clock_sub = self.create_subscription(
                'rosgraph_msgs/msg/Clock', '/clock', self._on_clock, port.QOS_CLOCK)

    # ---------------------------------------------------------------- parameters

    def declare_parameter(self, name: str, default: Any, *, description: str = '',
                          validator=None, read_only: bool = False,
                          additional_constraints: str = '') -> Any:
        if name in self._params:
            raise TransportError(f'parameter {name!r} already declared')
        default = port.normalize_parameter_value(default)
        entry = _ParamEntry(default, port.parameter_type_of(default), description, validator,
                            read_only, additional_constraints)
        value = default
        if name in self._overrides:
            value = port.normalize_parameter_value(self._overrides[name])
            if entry.type_ == port.PARAMETER_DOUBLE and port.parameter_type_of(value) == \
                    port.PARAMETER_INTEGER:
                value = float(value)  # '-p gain:=2' for a double, as the YAML reader gives int
            reason = self._check_value(name, entry, value)
            if reason:
                raise TransportError(f'parameter {name!r} override {value!r} rejected: {reason}')
        entry.value = value
        self._params[name] = entry
        if name == 'use_sim_time':
            self._apply_use_sim_time(bool(value))
        self._publish_parameter_event(new=[Parameter(name, value)])
        return value

    def _check_value(self, name: str, entry: _ParamEntry, value: Any) -> Optional[str]:
        try:
            kind = port.parameter_type_of(value)
        except TransportError as exc:
            return str(exc)
        if kind != entry.type_:
            return (f'Wrong parameter type, parameter {{{name}}} is of type {{{entry.type_}}}, '
                    f'setting it to {{{kind}}} is not allowed.')
        return port.run_validator(entry.validator, value)

    def get_parameter(self, name: str) -> Any:
        try:
            return self._params[name].value
        except KeyError:
            raise TransportError(f'parameter {name!r} is not declared') from None

    def has_parameter(self, name: str) -> bool:
        return name in self._params

    def add_on_set_parameters_callback(self, callback) -> None:
        self._on_set_callbacks.append(callback)

    def _try_set(self, parameters: List[Parameter]) -> SetParametersResult:
        for param in parameters:
            entry = self._params.get(param.name)
            if entry is None:
                return SetParametersResult(False, f'parameter {param.name!r} is not declared')
            if entry.read_only:
                return SetParametersResult(False, read_only_reason(param.name))
            reason = self._check_value(param.name, entry, param.value)
            if reason:
                return SetParametersResult(False, reason)
        for callback in self._on_set_callbacks:
            result = callback(list(parameters))
            if not result.successful:
                return result
        for param in parameters:
            self._params[param.name].value = param.value
            if param.name == 'use_sim_time':
                self._apply_use_sim_time(bool(param.value))
        self._publish_parameter_event(changed=parameters)
        return SetParametersResult(True)

    def set_parameters(self, parameters: List[Parameter]) -> List[SetParametersResult]:
        return [self._try_set([Parameter(p.name, port.normalize_parameter_value(p.value))])
                for p in parameters]

    def set_parameters_atomically(self, parameters: List[Parameter]) -> SetParametersResult:
        return self._try_set(
            [Parameter(p.name, port.normalize_parameter_value(p.value)) for p in parameters])

    def _publish_parameter_event(self, new=(), changed=()) -> None:
        event_type = self.msg('rcl_interfaces/msg/ParameterEvent')
        self._param_events.publish(event_type(
            stamp=self.time_msg(), node=self.get_fully_qualified_name(),
            new_parameters=[_to_parameter_msg(p.name, p.value) for p in new],
            changed_parameters=[_to_parameter_msg(p.name, p.value) for p in changed]))

    def _create_parameter_services(self) -> None:
        prefix = 'rcl_interfaces/srv/'
        qos = port.QOS_PARAMETERS
        self.create_service(prefix + 'ListParameters', '~/list_parameters',
                            self._handle_list_parameters, qos)
        self.create_service(prefix + 'GetParameters', '~/get_parameters',
                            self._handle_get_parameters, qos)
        self.create_service(prefix + 'SetParameters', '~/set_parameters',
                            self._handle_set_parameters, qos)
        self.create_service(prefix + 'SetParametersAtomically', '~/set_parameters_atomically',
                            self._handle_set_parameters_atomically, qos)
        self.create_service(prefix + 'DescribeParameters', '~/describe_parameters',
                            self._handle_describe_parameters, qos)
        self.create_service(prefix + 'GetParameterTypes', '~/get_parameter_types',
                            self._handle_get_parameter_types, qos)

    def _handle_list_parameters(self, request, response):
        # rclpy Node._list_parameters: depth 0 = recursive; '.' separates name levels.
        names, prefixes = [], set()
        for name in sorted(self._params):
            if request.prefixes:
                matched = [p for p in request.prefixes if name == p or name.startswith(p + '.')]
                if not matched:
                    continue
                rest = name[len(matched[0]) + 1:]
            else:
                rest = name
            if request.depth and rest.count('.') >= request.depth:
                continue
            names.append(name)
            if '.' in name:
                prefixes.add(name.rsplit('.', 1)[0])
        response.result = self.msg('rcl_interfaces/msg/ListParametersResult')(
            names=names, prefixes=sorted(prefixes))
        return response

    def _handle_get_parameters(self, request, response):
        response.values = [_to_value_msg(self._params[n].value if n in self._params else None)
                           for n in request.names]
        return response

    def _handle_set_parameters(self, request, response):
        result_type = self.msg('rcl_interfaces/msg/SetParametersResult')
        results = self.set_parameters([_from_parameter_msg(p) for p in request.parameters])
        response.results = [result_type(successful=r.successful, reason=r.reason)
                            for r in results]
        return response

    def _handle_set_parameters_atomically(self, request, response):
        result = self.set_parameters_atomically(
            [_from_parameter_msg(p) for p in request.parameters])
        response.result = self.msg('rcl_interfaces/msg/SetParametersResult')(
            successful=result.successful, reason=result.reason)
        return response

    def _handle_describe_parameters(self, request, response):
        descriptor_type = self.msg('rcl_interfaces/msg/ParameterDescriptor')
        response.descriptors = []
        for name in request.names:
            entry = self._params.get(name)
            if entry is None:
                response.descriptors.append(descriptor_type(name=name))
                continue
            response.descriptors.append(descriptor_type(
                name=name, type=entry.type_, description=entry.description,
                additional_constraints=entry.additional_constraints, read_only=entry.read_only))
        return response

    def _handle_get_parameter_types(self, request, response):
        response.types = [self._params[n].type_ if n in self._params else 0
                          for n in request.names]
        return response

    # ---------------------------------------------------------------- executor

    def spin_once(self, timeout_s: Optional[float] = None) -> None:
        if self._shutdown:
            return
        if not self._overrides_checked:  # the node's parameters are declared by its first spin
            self._overrides_checked = True
            warning = unknown_overrides_warning(self._overrides, self._params)
            if warning:
                self._logger.warning(warning)
        now = time.monotonic()
        wait_s = SPIN_SLICE_S * 10 if timeout_s is None else max(0.0, timeout_s)
        for timer in self._timers:
            if not timer.cancelled:
                wait_s = min(wait_s, max(0.0, timer.next_due - now))
        if any(s._pending for s in self._services):
            wait_s = min(wait_s, PENDING_REPLY_POLL_S)
        triggered = self._waitset.wait(int(wait_s * 1e9))
        if triggered is None:
            if self._shutdown:
                return
            raise TransportError('waitset wait failed')
        for index in triggered:
            handler = self._handlers[index - 1]
            if handler is None:
                self._guard.set(False)
            else:
                handler()
            if self._shutdown:
                return
        now = time.monotonic()
        for service in self._services:
            if service._pending:
                service._flush_pending(now)
        for timer in list(self._timers):
            if timer.cancelled:
                self._timers.remove(timer)
            elif now >= timer.next_due:
                timer.next_due += timer.period_s
                if timer.next_due < now:  # fell behind: do not fire a burst
                    timer.next_due = now + timer.period_s
                timer.callback()
                if self._shutdown:
                    return

    def spin(self) -> None:
        while self.ok():
            self.spin_once(SPIN_SLICE_S)

    def request_shutdown(self) -> None:
        """Ask spin() to return (signal-handler safe); run_node then calls shutdown()."""
        self._shutdown_requested = True
        try:
            self._guard.set(True)
        except Exception:  # noqa: BLE001 - already deleted
            pass

    def ok(self) -> bool:
        """Return False once a shutdown was requested (a signal) or done, like ``rclpy.ok``."""
        return not (self._shutdown or self._shutdown_requested)

    def shutdown(self) -> None:
        if self._shutdown:
            return
        self._shutdown = True
        self._graph_visible = False
        ctx = self._ctx
        # Leave ros_discovery_info first (A5.3), then delete our endpoints (or, for the last
        # node, the whole participant) so that the node leaves the graph at once (E1).
        if len(ctx._nodes) > 1:
            ctx.release(self)
            for entity in self._conditions + self._endpoints:
                cyclone_private.delete_entity(entity)
            self._waitset.delete()
        else:
            ctx.release(self)
        self._handlers = []
        self._timers = []
        self._services = []


class _SrvClasses:
    def __init__(self, request, response):
        self.Request = request
        self.Response = response


# -------------------------------------------------------------------- parameter messages

def _to_value_msg(value: Any):
    value_type = msg_types.message_type('rcl_interfaces/msg/ParameterValue')
    if value is None:
        return value_type(type=port.PARAMETER_NOT_SET)
    kind = port.parameter_type_of(value)
    field = {
        port.PARAMETER_BOOL: 'bool_value', port.PARAMETER_INTEGER: 'integer_value',
        port.PARAMETER_DOUBLE: 'double_value', port.PARAMETER_STRING: 'string_value',
        port.PARAMETER_BYTE_ARRAY: 'byte_array_value',
        port.PARAMETER_BOOL_ARRAY: 'bool_array_value',
        port.PARAMETER_INTEGER_ARRAY: 'integer_array_value',
        port.PARAMETER_DOUBLE_ARRAY: 'double_array_value',
        port.PARAMETER_STRING_ARRAY: 'string_array_value',
    }[kind]
    if kind == port.PARAMETER_BYTE_ARRAY:
        value = bytes(value)
    elif kind >= port.PARAMETER_BOOL_ARRAY:
        value = list(value)
    return value_type(type=kind, **{field: value})


def _from_value_msg(msg) -> Any:
    kind = msg.type
    if kind == port.PARAMETER_BOOL:
        return bool(msg.bool_value)
    if kind == port.PARAMETER_INTEGER:
        return int(msg.integer_value)
    if kind == port.PARAMETER_DOUBLE:
        return float(msg.double_value)
    if kind == port.PARAMETER_STRING:
        return msg.string_value
    if kind == port.PARAMETER_BYTE_ARRAY:
        return bytes(msg.byte_array_value)
    if kind == port.PARAMETER_BOOL_ARRAY:
        return [bool(v) for v in msg.bool_array_value]
    if kind == port.PARAMETER_INTEGER_ARRAY:
        return [int(v) for v in msg.integer_array_value]
    if kind == port.PARAMETER_DOUBLE_ARRAY:
        return [float(v) for v in msg.double_array_value]
    if kind == port.PARAMETER_STRING_ARRAY:
        return list(msg.string_array_value)
    return None


def _to_parameter_msg(name: str, value: Any):
    return msg_types.message_type('rcl_interfaces/msg/Parameter')(
        name=name, value=_to_value_msg(value))


def _from_parameter_msg(msg) -> Parameter:
    return Parameter(msg.name, _from_value_msg(msg.value))


# -------------------------------------------------------------------- main helper

def run_dds_node(node_factory, args=None) -> int:
    """
    Build a node and spin it until SIGINT/SIGTERM, then leave the graph (E1).

    The signal handlers are installed before anything is created, as ``rclpy.init`` does: a
    signal during start-up abandons the construction (a KeyboardInterrupt raised where it
    stands, whose clean-up paths delete what was built) and ends the process cleanly, without
    leaving a half-built node on the graph; a signal while spinning makes ``spin()`` return.

    :param node_factory: ``node_factory(args)`` returning a DdsNode or an object with ``.node``.
    :param args: the command line (default ``sys.argv``).
    :return: the process exit status (0 after a signal, as an rclpy node).
    """
    args = sys.argv if args is None else args
    state = {'node': None, 'interrupted': False}

    def on_signal(signum, frame):
        node = state['node']
        if node is not None:
            node.request_shutdown()
        elif not state['interrupted']:
            state['interrupted'] = True
            raise KeyboardInterrupt(f'signal {signum} during start-up')

    previous = {}
    if threading.current_thread() is threading.main_thread():
        for signum in (signal.SIGINT, signal.SIGTERM):
            previous[signum] = signal.signal(signum, on_signal)
    node = None
    try:
        app = node_factory(args)
        node = app if isinstance(app, port.NodePort) else app.node
        state['node'] = node   # from here on a signal only asks spin() to return
        node.spin()
    except KeyboardInterrupt:
        pass
    finally:
        state['interrupted'] = True
        if node is not None:
            node.shutdown()
        else:
            _Context.close_process()   # whatever an interrupted start-up left half-built
        for signum, handler in previous.items():
            signal.signal(signum, handler)
    return 0


def create_dds_node(name: str, namespace: str = '', args=None, parameter_overrides=None,
                    **kwargs) -> DdsNode:
    """Create a DdsNode (the factory behind ``selection.create_node``)."""
    return DdsNode(name, namespace, args=args, parameter_overrides=parameter_overrides,
                   **kwargs)


def participant_guid() -> Optional[bytes]:
    """Return the GUID of this process's participant, or None when no node exists."""
    ctx = _Context._instance
    return ctx.participant_gid if ctx is not None else None


def get_participant() -> Optional[DomainParticipant]:
    """Return this process's participant (for raw DDS readers in tests), or None."""
    ctx = _Context._instance
    return ctx.participant if ctx is not None else None


__all__ = ['DdsNode', 'create_dds_node', 'endpoint_qos', 'endpoint_user_data', 'ensure_domain',
           'get_participant', 'participant_guid', 'run_dds_node']
