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
The process-wide DDS state of the embedded transport: domain, participant, topics, graph message.

One DomainParticipant per process (USER_DATA ``enclave=/;``) shared by all nodes of the process,
one Topic per name, ``serviceid``/``clientid`` tokens, and the process's
``ros_discovery_info`` (``rmw_dds_common/msg/ParticipantEntitiesInfo``, read by rmw_dds_common's
graph cache) republished on every change, in the Gid layout of the distribution the process
speaks (:mod:`vehicle_msgs_py.distro`). The process also reads ``ros_discovery_info``, as every
rmw participant does, to warn once about a participant that speaks the other distribution.
"""

import itertools
import threading
from typing import Dict, List, Optional

from cyclonedds.core import DDSException
from cyclonedds.domain import Domain, DomainParticipant
from cyclonedds.pub import DataWriter
from cyclonedds.qos import Policy, Qos
from cyclonedds.sub import DataReader
from cyclonedds.topic import Topic

from vehicle_msgs_py import distro
from vehicle_msgs_py import types as msg_types
from vehicle_sim.transport.dds import cyclone_private, discovery_info, domain_config, peers
from vehicle_sim.transport.dds.qos import dds_qos, endpoint_user_data
from vehicle_sim.transport.errors import TransportError
from vehicle_sim.transport.qos import QOS_DISCOVERY_INFO_READER, QOS_DISCOVERY_INFO_WRITER

DISCOVERY_TOPIC = 'ros_discovery_info'
# How long a Jazzy process listens for Humble participants before it announces its nodes [s]:
# the ros_discovery_info of the participants already on the domain arrives well within it.
JAZZY_ANNOUNCE_DELAY_S = 0.5

_domains: Dict[int, Domain] = {}
_domains_lock = threading.Lock()


def ensure_domain(domain: Optional[int] = None) -> Domain:
    """
    Create (once per process) the Domain with the configuration of the environment.

    Call it before creating raw cyclonedds participants in a process that also runs nodes:
    the first participant of a domain fixes its configuration.

    :param domain: the domain id; default ``ROS_DOMAIN_ID``.
    """
    domain = domain_config.domain_id() if domain is None else domain
    with _domains_lock:
        if domain not in _domains:
            _domains[domain] = domain_config.create_domain(domain)
        return _domains[domain]


class Context:
    """
    The participant, topics, the graph message and the node registry of this process.

    Created by the first node (:meth:`acquire`), its participant deleted when the last node
    leaves (:meth:`release`). A node registered here provides ``get_namespace()``,
    ``get_name()``, ``get_logger()``, ``graph_gids()`` (its reader and writer GUIDs, or None
    while it is not announced) and ``abandon()`` (for :meth:`close_process`).
    """

    _lock = threading.Lock()
    _instance: Optional['Context'] = None

    def __init__(self):
        try:
            self.distro, self.distro_reason = distro.selected_with_reason()
        except ValueError as exc:
            raise TransportError(str(exc)) from None
        self.gid_size = distro.gid_size(self.distro)
        self.domain_id = domain_config.domain_id()
        ensure_domain(self.domain_id)
        try:
            self.participant = DomainParticipant(
                self.domain_id, qos=Qos(Policy.Userdata(data=b'enclave=/;')))
        except DDSException as exc:
            raise TransportError(domain_config.describe_domain_error(
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
        self._nodes: List = []
        self._token_counter = itertools.count(1)
        self._sequence = itertools.count(1)
        self._closed = False
        info_type = msg_types.message_type('rmw_dds_common/msg/ParticipantEntitiesInfo')
        self._info_type = info_type
        # The topic's type is Jazzy's in both modes (so that processes of either mode match);
        # the samples are written and read as bytes by the discovery_info codec.
        user_data = endpoint_user_data(info_type.__ros_type__)
        self._discovery_writer = DataWriter(
            self.participant, self.topic(DISCOVERY_TOPIC, info_type),
            qos=dds_qos(QOS_DISCOVERY_INFO_WRITER, user_data, True))
        # Our own samples are not read back (as rmw_cyclonedds ignores its participant's).
        self.discovery_reader = DataReader(
            self.participant, self.topic(DISCOVERY_TOPIC, info_type),
            qos=dds_qos(QOS_DISCOVERY_INFO_READER, user_data, False)
            + Qos(Policy.IgnoreLocal.Participant))
        self._distro_announced = False
        self._warned = set()
        self._info_lock = threading.Lock()
        # True once a Jazzy process met a Humble participant: it then announces no nodes.
        self.nodes_hidden = False
        # A Jazzy process announces its nodes only once it has listened for Humble participants
        # (a Humble process that received a Jazzy node list keeps it broken): the timer reads
        # what arrived, then publishes. Humble's node lists are harmless to Jazzy.
        self._announce_timer = None
        self.announcing = self.distro != distro.JAZZY
        if not self.announcing:
            self._announce_timer = threading.Timer(JAZZY_ANNOUNCE_DELAY_S, self._start_announcing)
            self._announce_timer.daemon = True
            self._announce_timer.start()

    @classmethod
    def acquire(cls, node) -> 'Context':
        """Register ``node`` with this process's context, creating the context if needed."""
        with cls._lock:
            if cls._instance is None or cls._instance._closed:
                cls._instance = Context()
            cls._instance._nodes.append(node)
            return cls._instance

    @classmethod
    def current(cls) -> Optional['Context']:
        """Return this process's context, or None when no node exists."""
        return cls._instance

    @property
    def node_count(self) -> int:
        """How many nodes are registered."""
        return len(self._nodes)

    def release(self, node) -> None:
        """Remove ``node`` from the graph; the last node deletes the participant."""
        with Context._lock:
            if node in self._nodes:
                self._nodes.remove(node)
            last = not self._nodes
            self.publish_graph()
            if last:
                self._close_locked()

    def _start_announcing(self) -> None:
        with Context._lock:
            if self._closed:
                return
            # The first node's logger (a node still in its constructor may have none yet; its
            # first spin then reads what arrived).
            logger = None
            for node in self._nodes:
                try:
                    logger = node.get_logger()
                    break
                except AttributeError:
                    continue
            try:
                if logger is not None:
                    self.read_discovery_info(logger)
                self.announcing = True
                self.publish_graph()
            except DDSException:
                pass   # the participant is going away

    def _close_locked(self) -> None:
        if self._announce_timer is not None:
            self._announce_timer.cancel()
        if not self._closed:
            self._closed = True
            cyclone_private.delete_participant(self.participant)
        if Context._instance is self:
            Context._instance = None

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
                node.abandon()
            ctx._nodes = []
            try:
                ctx.publish_graph()
            finally:
                ctx._close_locked()

    def topic(self, name: str, data_type) -> Topic:
        """Return the one Topic per name of this participant (Cyclone refuses a second sertype)."""
        found = self._topics.get(name)
        if found is None:
            found = Topic(self.participant, name, data_type)
            self._topics[name] = found
        elif found.data_type is not data_type:
            raise TransportError(
                f'topic {name!r} is already used with type {found.data_type.__ros_type__}')
        return found

    def next_token(self) -> str:
        """Return a new ``serviceid``/``clientid`` token formatted like rmw_cyclonedds."""
        raw = self.participant_gid[:12] + next(self._token_counter).to_bytes(4, 'big')
        return f'{raw[0]:2x}.' + '.'.join(f'{b:x}' for b in raw[1:])

    def next_sequence(self) -> int:
        return next(self._sequence)

    def publish_graph(self) -> None:
        """Publish the complete ParticipantEntitiesInfo of this process."""
        if self._closed or not self.announcing:
            return
        nodes = []
        for node in [] if self.nodes_hidden else self._nodes:
            gids = node.graph_gids()
            if gids is None:
                continue
            readers, writers = gids
            nodes.append(discovery_info.NodeEntry(
                node.get_namespace(), node.get_name(), tuple(readers), tuple(writers)))
        cyclone_private.write_serialized(self._discovery_writer, discovery_info.encode(
            self.participant_gid, nodes, self.gid_size))

    def announce_distro(self) -> str:
        """Return the start-up line naming the distribution spoken, once per process ('' after)."""
        if self._distro_announced:
            return ''
        self._distro_announced = True
        return (f'speaking ROS 2 {distro.title(self.distro)} on domain {self.domain_id} '
                f'({self.gid_size}-byte Gids in ros_discovery_info; {self.distro_reason})')

    def _warn_once(self, logger, key, text: str) -> None:
        if key not in self._warned:
            self._warned.add(key)
            logger.warning(text)

    def read_discovery_info(self, logger) -> None:
        """
        Take the ``ros_discovery_info`` samples that arrived.

        Warns, once per process, about a participant of the other distribution or a sample
        that fits no layout.
        """
        with self._info_lock:
            if not self._closed:
                self._read_discovery_info(logger)

    def _read_discovery_info(self, logger) -> None:
        for data, info in cyclone_private.take_serialized(self.discovery_reader, 256):
            if not info.valid_data:
                continue
            try:
                found = discovery_info.decode(data, prefer=self.gid_size)
            except discovery_info.UndecodableSample as exc:
                self._warn_once(logger, 'undecodable',
                                peers.undecodable_info_warning(self.domain_id, str(exc)))
                continue
            if found.distro == self.distro:
                continue
            if found.distro == distro.HUMBLE and not self.nodes_hidden:
                # Humble reads a Jazzy node list as dozens of nameless nodes, which breaks its
                # node-name queries for the whole domain; an empty list (20 bytes, too short for
                # its 24-byte Gid) adds no node.
                self.nodes_hidden = True
                self.publish_graph()
            self._warn_once(logger, found.distro, peers.other_distro_warning(
                found.distro, self.distro, found.gid, self.domain_id))


def participant_guid() -> Optional[bytes]:
    """Return the GUID of this process's participant, or None when no node exists."""
    ctx = Context.current()
    return ctx.participant_gid if ctx is not None else None


def get_participant() -> Optional[DomainParticipant]:
    """Return this process's participant (for raw DDS readers in tests), or None."""
    ctx = Context.current()
    return ctx.participant if ctx is not None else None
