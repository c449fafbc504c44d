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
A passive view of the ROS 2 graph on the embedded transport.

Like ``ros2 node list / topic list -t / service list -t``, it reads only DDS discovery data:

* endpoints (topics, services, their types and QoS) from the ``DCPSPublication`` /
  ``DCPSSubscription`` built-in topics, demangled (``rt``/``rq``/``rr`` prefixes,
  ``pkg::msg::dds_::Name_`` → ``pkg/msg/Name``);
* nodes from ``ros_discovery_info`` (``rmw_dds_common/msg/ParticipantEntitiesInfo``), kept only
  while their participant is alive in ``DCPSParticipant``; samples of either Gid layout (Humble's
  24 bytes, Jazzy's 16) are read, and a participant of the other distribution than the one this
  process speaks, or a sample that fits neither, adds one line to :attr:`GraphView.warnings`;
* participants from ``DCPSParticipant``, with their DDS vendor (from the GUID prefix).

The view owns a DDS participant of its own (no node: it is invisible to ``ros2 node list``) and
hides the endpoints of this process's participants, so a CLI's helper node is not listed.
"""

from dataclasses import dataclass, field
import difflib
import time
from typing import Callable, Dict, Iterable, List, Optional, Set, Tuple

DISCOVERY_TOPIC = 'ros_discovery_info'
TOPIC_PREFIX = 'rt'
REQUEST_PREFIX = 'rq'
REPLY_PREFIX = 'rr'
REQUEST_SUFFIX = 'Request'
REPLY_SUFFIX = 'Reply'
# Polling period of the built-in readers while waiting for discovery.
POLL_S = 0.05


# --------------------------------------------------------------------------------------------
# Demangling (rmw_cyclonedds demangle.cpp)

def demangle_type(dds_type_name: str) -> str:
    """
    Return the ROS name of a DDS type name; anything not mangled by ROS is returned unchanged.

    ``std_msgs::msg::dds_::String_`` → ``std_msgs/msg/String``;
    ``vehicle_msgs::srv::dds_::SetInt_Request_`` → ``vehicle_msgs/srv/SetInt_Request``.
    """
    if '::dds_::' not in dds_type_name or not dds_type_name.endswith('_'):
        return dds_type_name
    return dds_type_name[:-1].replace('::dds_::', '::').replace('::', '/')


def service_type_of(part_type: str) -> Optional[str]:
    """Return ``pkg/srv/Name`` of a demangled ``pkg/srv/Name_Request``/``_Response``, or None."""
    for suffix in ('_Request', '_Response'):
        if part_type.endswith(suffix) and '/srv/' in part_type:
            return part_type[:-len(suffix)]
    return None


def demangle_topic(dds_topic: str) -> Optional[str]:
    """Return the ROS topic name of a DDS topic (``rt/x`` → ``/x``), None when not a ROS topic."""
    if dds_topic.startswith(TOPIC_PREFIX + '/'):
        return dds_topic[len(TOPIC_PREFIX):]
    return None


def demangle_service(dds_topic: str) -> Optional[str]:
    """Return the ROS service name of ``rq/xRequest`` or ``rr/xReply``, else None."""
    for prefix, suffix in ((REQUEST_PREFIX, REQUEST_SUFFIX), (REPLY_PREFIX, REPLY_SUFFIX)):
        if dds_topic.startswith(prefix + '/') and dds_topic.endswith(suffix):
            name = dds_topic[len(prefix):-len(suffix)]
            if len(name) > 1:
                return name
    return None


def close_names(name: str, candidates: Iterable[str], count: int = 5) -> List[str]:
    """Return up to ``count`` of ``candidates`` that look like ``name`` (typos, missing ns)."""
    candidates = sorted(set(candidates))
    found = difflib.get_close_matches(name, candidates, n=count, cutoff=0.5)
    tail = name.rstrip('/').rsplit('/', 1)[-1]
    for candidate in candidates:
        if len(found) >= count:
            break
        if tail and candidate.endswith('/' + tail) and candidate not in found:
            found.append(candidate)
    return found


# --------------------------------------------------------------------------------------------
# The view

@dataclass(frozen=True)
class Endpoint:
    """A discovered DDS reader or writer."""

    gid: bytes
    participant: bytes
    dds_topic: str
    dds_type: str
    is_writer: bool
    reliable: bool
    transient_local: bool
    user_data: str = ''

    @property
    def ros_type(self) -> str:
        return demangle_type(self.dds_type)


@dataclass
class NodeInfo:
    """A ROS node announced in ``ros_discovery_info``."""

    namespace: str
    name: str
    participant: bytes
    reader_gids: Set[bytes] = field(default_factory=set)
    writer_gids: Set[bytes] = field(default_factory=set)
    distro: str = ''

    @property
    def fqn(self) -> str:
        return self.namespace.rstrip('/') + '/' + self.name


@dataclass(frozen=True)
class ParticipantInfo:
    """A live DDS participant: its GUID, DDS vendor, distribution (if it announced nodes)."""

    guid: bytes
    vendor: str
    distro: str
    nodes: Tuple[str, ...]


def _is_alive(sample) -> bool:
    from cyclonedds.core import InstanceState
    return sample.sample_info.instance_state == InstanceState.Alive


class GraphView:
    """
    Discovery data of one DDS domain, refreshed by :meth:`refresh` / the ``wait*`` methods.

    :param domain_id: default ``ROS_DOMAIN_ID``; the environment's discovery range applies.
    """

    def __init__(self, domain_id: Optional[int] = None):
        from cyclonedds.builtin import (
            BuiltinDataReader,
            BuiltinTopicDcpsParticipant,
            BuiltinTopicDcpsPublication,
            BuiltinTopicDcpsSubscription,
        )
        from cyclonedds.domain import DomainParticipant
        from cyclonedds.sub import DataReader
        from cyclonedds.topic import Topic

        from vehicle_msgs_py import types as msg_types
        from vehicle_sim.transport import dds
        from vehicle_sim.transport.dds import domain_config
        from vehicle_sim.transport.qos import QOS_DISCOVERY_INFO_READER

        self.domain_id = domain_config.domain_id() if domain_id is None else domain_id
        dds.ensure_domain(self.domain_id)
        self._participant = DomainParticipant(self.domain_id)
        self._own_participants = {self._participant.guid.bytes}
        self._participant_reader = BuiltinDataReader(
            self._participant, BuiltinTopicDcpsParticipant)
        self._endpoint_readers = [
            (BuiltinDataReader(self._participant, BuiltinTopicDcpsPublication), True),
            (BuiltinDataReader(self._participant, BuiltinTopicDcpsSubscription), False),
        ]
        info_type = msg_types.message_type('rmw_dds_common/msg/ParticipantEntitiesInfo')
        # The QoS and USER_DATA (typehash=) of rmw_cyclonedds' own ros_discovery_info reader:
        # an rmw_cyclonedds node logs an error for a discovered reader without a type hash.
        self._info_reader = DataReader(
            self._participant, Topic(self._participant, DISCOVERY_TOPIC, info_type),
            qos=dds.endpoint_qos(QOS_DISCOVERY_INFO_READER, info_type.__ros_type__,
                                 writer=False))
        self._participants: Set[bytes] = set()
        self._endpoints: Dict[bytes, Endpoint] = {}
        self._nodes_by_participant: Dict[bytes, List[NodeInfo]] = {}
        self._distro_of: Dict[bytes, str] = {}
        # ros_discovery_info samples that could not be decoded (dropped, the rest is kept).
        self.dropped_samples = 0
        from vehicle_msgs_py import distro
        self.distro = distro.selected()
        # One line per kind of trouble met (another distribution, a sample fitting no layout).
        self.warnings: List[str] = []
        self._warning_keys: Set[str] = set()
        self._closed = False

    # ------------------------------------------------------------------------- life cycle

    def close(self) -> None:
        """Delete the view's participant (its readers go with it)."""
        if self._closed:
            return
        self._closed = True
        from vehicle_sim.transport.dds import cyclone_private
        cyclone_private.delete_participant(self._participant)

    def __enter__(self):
        return self

    def __exit__(self, *exc):
        self.close()

    def ignore_participant(self, guid: Optional[bytes]) -> None:
        """Hide a participant's endpoints and nodes (e.g. the CLI's own node)."""
        if guid:
            self._own_participants.add(bytes(guid))

    # ------------------------------------------------------------------------- refresh

    def refresh(self) -> None:
        """Read what discovery has delivered since the last call."""
        for sample in self._participant_reader.take(N=1000):
            key = sample.key.bytes
            if _is_alive(sample):
                self._participants.add(key)
            else:
                self._participants.discard(key)
                self._nodes_by_participant.pop(key, None)
                self._distro_of.pop(key, None)
        for reader, is_writer in self._endpoint_readers:
            for sample in reader.take(N=1000):
                key = sample.key.bytes
                if not _is_alive(sample) or not getattr(sample, 'topic_name', None):
                    self._endpoints.pop(key, None)
                    continue
                self._endpoints[key] = _endpoint(sample, is_writer)
        self._read_discovery_info()

    def _read_discovery_info(self) -> None:
        from vehicle_msgs_py import distro
        from vehicle_sim.transport.dds import cyclone_private, discovery_info, peers
        for data, info in cyclone_private.take_serialized(self._info_reader, 1000):
            if not info.valid_data:
                continue
            try:
                found = discovery_info.decode(data, prefer=distro.gid_size(self.distro))
            except discovery_info.UndecodableSample as exc:
                self.dropped_samples += 1
                self._warn_once(peers.undecodable_info_warning(self.domain_id, str(exc)))
                continue
            gid = found.gid
            if found.distro != self.distro:
                self._warn_once(peers.other_distro_warning(
                    found.distro, self.distro, gid, self.domain_id, listing=True),
                    key=found.distro)
            self._distro_of[gid] = found.distro
            self._nodes_by_participant[gid] = [
                NodeInfo(n.namespace, n.name, gid, set(n.reader_gids), set(n.writer_gids),
                         found.distro)
                for n in found.nodes]

    def _warn_once(self, text: str, key: str = 'undecodable') -> None:
        if key not in self._warning_keys:
            self._warning_keys.add(key)
            self.warnings.append(text)

    def wait(self, duration_s: float) -> None:
        """Collect discovery data for ``duration_s`` seconds."""
        deadline = time.monotonic() + duration_s
        while True:
            self.refresh()
            remaining = deadline - time.monotonic()
            if remaining <= 0.0:
                return
            time.sleep(min(POLL_S, remaining))

    def wait_until(self, predicate: Callable[[], bool], timeout_s: float) -> bool:
        """Refresh until ``predicate()`` holds; return False when ``timeout_s`` passed first."""
        deadline = time.monotonic() + timeout_s
        while True:
            self.refresh()
            if predicate():
                return True
            if time.monotonic() >= deadline:
                return False
            time.sleep(POLL_S)

    # ------------------------------------------------------------------------- queries

    def endpoints(self) -> List[Endpoint]:
        """Return every discovered endpoint of other processes' participants."""
        return [e for e in self._endpoints.values()
                if e.participant not in self._own_participants]

    def nodes(self) -> List[NodeInfo]:
        """Return the nodes of live participants, sorted by fully-qualified name."""
        found = []
        for gid, nodes in self._nodes_by_participant.items():
            if gid in self._own_participants:
                continue
            if self._participants and gid not in self._participants:
                continue
            found.extend(nodes)
        return sorted(found, key=lambda n: n.fqn)

    def participants(self) -> List[ParticipantInfo]:
        """Return the live participants of other processes, with vendor and distribution."""
        from vehicle_sim.transport.dds import peers
        found = []
        for guid in sorted(self._participants - self._own_participants):
            nodes = tuple(sorted(n.fqn for n in self._nodes_by_participant.get(guid, ())))
            found.append(ParticipantInfo(guid, peers.vendor_of(guid),
                                         self._distro_of.get(guid, ''), nodes))
        return found

    def node_names(self) -> List[str]:
        return sorted({n.fqn for n in self.nodes()})

    def find_node(self, fqn: str) -> Optional[NodeInfo]:
        fqn = fqn if fqn.startswith('/') else '/' + fqn
        for node in self.nodes():
            if node.fqn == fqn:
                return node
        return None

    def topics(self) -> Dict[str, Set[str]]:
        """Return ``{topic: {ros types}}`` of every ``rt/`` endpoint."""
        found: Dict[str, Set[str]] = {}
        for endpoint in self.endpoints():
            name = demangle_topic(endpoint.dds_topic)
            if name is not None:
                found.setdefault(name, set()).add(endpoint.ros_type)
        return found

    def services(self) -> Dict[str, Set[str]]:
        """Return ``{service: {pkg/srv/Name}}`` of every request/reply endpoint."""
        found: Dict[str, Set[str]] = {}
        for endpoint in self.endpoints():
            name = demangle_service(endpoint.dds_topic)
            if name is None:
                continue
            srv_type = service_type_of(endpoint.ros_type) or endpoint.ros_type
            found.setdefault(name, set()).add(srv_type)
        return found

    def publishers(self, topic: str) -> List[Endpoint]:
        """Return the writers of a ROS topic."""
        dds_topic = TOPIC_PREFIX + topic
        return [e for e in self.endpoints() if e.is_writer and e.dds_topic == dds_topic]

    def subscribers(self, topic: str) -> List[Endpoint]:
        """Return the readers of a ROS topic."""
        dds_topic = TOPIC_PREFIX + topic
        return [e for e in self.endpoints() if not e.is_writer and e.dds_topic == dds_topic]

    def service_servers(self, service: str) -> List[Endpoint]:
        """Return the request readers of a service (one per server)."""
        dds_topic = f'{REQUEST_PREFIX}{service}{REQUEST_SUFFIX}'
        return [e for e in self.endpoints() if not e.is_writer and e.dds_topic == dds_topic]

    def node_endpoints(self, node: NodeInfo) -> Tuple[List[Endpoint], List[Endpoint]]:
        """Return ``(readers, writers)`` of a node, joined by gid like ``ros2 node info``."""
        endpoints = self.endpoints()
        readers = [e for e in endpoints if not e.is_writer and e.gid in node.reader_gids]
        writers = [e for e in endpoints if e.is_writer and e.gid in node.writer_gids]
        return readers, writers


def _endpoint(sample, is_writer: bool) -> Endpoint:
    from cyclonedds.qos import Policy
    qos = sample.qos
    reliable = True
    transient_local = False
    user_data = ''
    if qos is not None:
        if Policy.Reliability in qos:
            reliable = qos[Policy.Reliability] != Policy.Reliability.BestEffort
        if Policy.Durability in qos:
            transient_local = qos[Policy.Durability] in (
                Policy.Durability.TransientLocal, Policy.Durability.Transient,
                Policy.Durability.Persistent)
        if Policy.Userdata in qos:
            user_data = (qos[Policy.Userdata].data or b'').decode('ascii', 'replace')
    return Endpoint(
        gid=sample.key.bytes, participant=sample.participant_key.bytes,
        dds_topic=sample.topic_name, dds_type=sample.type_name, is_writer=is_writer,
        reliable=reliable, transient_local=transient_local, user_data=user_data)
