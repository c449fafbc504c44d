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
DdsNode: a ROS 2 Jazzy node on the embedded Cyclone DDS transport.

It wires the pieces of this package together: the process Context (participant, graph message),
endpoints and services, an Executor, a ParameterStore, and a logger writing the console and
``/rosout``.
"""

import sys
import time
from typing import Any, Dict, List, Optional, Tuple

from cyclonedds.core import ReadCondition
from cyclonedds.pub import DataWriter
from cyclonedds.sub import DataReader

from vehicle_msgs_py import types as msg_types
from vehicle_sim.transport import fast_cdr, port
from vehicle_sim.transport.dds import cyclone_private
from vehicle_sim.transport.dds.context import Context
from vehicle_sim.transport.dds.endpoints import (
    DdsPublisher,
    DdsSubscription,
    Intake,
    reader_gate_listener,
    TAKE_BATCH,
)
from vehicle_sim.transport.dds.executor import DdsTimer, Executor, SPIN_SLICE_S
from vehicle_sim.transport.dds.parameters import ParameterStore
from vehicle_sim.transport.dds.qos import dds_qos, endpoint_user_data
from vehicle_sim.transport.dds.services import DdsClient, DdsService, REPLY_MATCH_TIMEOUT_S
from vehicle_sim.transport.errors import TransportError
from vehicle_sim.transport.logger import LOG_LEVEL_NAMES, Logger
from vehicle_sim.transport.names import resolve_name, validate_node_name
from vehicle_sim.transport.parameter_types import Parameter, SetParametersResult
from vehicle_sim.transport.qos import (
    as_qos,
    QOS_CLOCK,
    QOS_ROSOUT,
    QOS_SERVICES,
    QosProfile,
    VOLATILE,
)
from vehicle_sim.transport.reader_gate import ReaderGate
from vehicle_sim.transport.ros_args import parse_ros_args
from vehicle_sim.transport.ros_time import Time


class DdsLogger(Logger):
    """Console output like rcutils plus a ``rcl_interfaces/msg/Log`` on /rosout."""

    def __init__(self, node: 'DdsNode', name: str, level: int, to_rosout: bool,
                 to_stdout: bool):
        self._node = node
        self.level = level
        self.name = name
        self._to_rosout = to_rosout
        self._to_stdout = to_stdout
        self._publisher = None
        self._log_type = None
        if to_rosout:
            self._log_type = node.msg('rcl_interfaces/msg/Log')
            self._publisher = node.create_publisher(
                'rcl_interfaces/msg/Log', '/rosout', QOS_ROSOUT)

    def log(self, level: int, message: str) -> None:
        if level < self.level:
            return
        now_ns = time.time_ns()
        if self._to_stdout:
            sys.stderr.write(f'[{LOG_LEVEL_NAMES.get(level, level)}] [{now_ns / 1e9:.9f}] '
                             f'[{self.name}]: {message}\n')
        if self._to_rosout and self._publisher is not None and self._node.ok():
            frame = sys._getframe(2) if level != 0 else None
            self._publisher.publish(self._log_type(
                stamp=self._node.time_msg(Time(now_ns)), level=level, name=self.name,
                msg=str(message), file=frame.f_code.co_filename if frame else '',
                function=frame.f_code.co_name if frame else '',
                line=frame.f_lineno if frame else 0))


class _SrvClasses:
    def __init__(self, request, response):
        self.Request = request
        self.Response = response


class DdsNode(port.NodePort):
    """
    A ROS 2 node on the embedded Cyclone DDS transport.

    :param name: node name (``__node`` remaps in ``args`` win).
    :param namespace: node namespace (``__ns`` remaps in ``args`` win).
    :param args: the full command line; the ``--ros-args`` part is applied.
    :param parameter_overrides: initial values that win over the command line.
    :param reply_match_timeout_s: how long a reply waits for its client's reply reader [s]
        (services.REPLY_MATCH_TIMEOUT_S by default).
    """

    def __init__(self, name: str, namespace: str = '', args=None,
                 parameter_overrides: Optional[Dict[str, Any]] = None,
                 reply_match_timeout_s: float = REPLY_MATCH_TIMEOUT_S):
        ros_args = parse_ros_args(args)
        self._ros_args = ros_args
        self._name = validate_node_name(ros_args.node_name(name))
        self._namespace = ros_args.namespace(self._name, namespace)
        self.reply_match_timeout_s = reply_match_timeout_s
        overrides = ros_args.parameter_overrides(self._name, self._namespace)
        overrides.update(parameter_overrides or {})
        self._overrides_checked = False
        # id(entity) -> GUID bytes, for ros_discovery_info; the entities, to delete them.
        self._reader_gids: Dict[int, bytes] = {}
        self._writer_gids: Dict[int, bytes] = {}
        self._endpoints: List[Any] = []
        self._shutdown = False
        self._shutdown_requested = False
        self._graph_visible = False
        self._sim_time_ns = 0
        self._clock_sub = None
        self._time_type = msg_types.message_type('builtin_interfaces/msg/Time')
        self._ctx = Context.acquire(self)
        try:
            self._executor = Executor(self._ctx.participant, lambda: self._shutdown)
            logger_name = '.'.join([t for t in self._namespace.split('/') if t] + [self._name])
            self._logger = DdsLogger(self, logger_name, ros_args.log_level or 20,
                                     ros_args.rosout_logs, ros_args.stdout_logs)
            announcement = self._ctx.announce_distro()
            if announcement:
                self._logger.info(announcement)
            self._executor.add(
                ReadCondition(self._ctx.discovery_reader, cyclone_private.ANY_STATE),
                lambda: self._ctx.read_discovery_info(self._logger))
            self._parameters = ParameterStore(self, overrides, self._parameter_applied)
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

    def serializer(self, ros_type: str):
        return fast_cdr.SERIALIZERS.get(ros_type)

    def srv(self, srv_type: str):
        try:
            types = msg_types.service_types(srv_type)
        except ValueError as exc:
            raise TransportError(str(exc)) from None
        return _SrvClasses(types.request, types.response)

    # ---------------------------------------------------------------- the graph

    def graph_gids(self) -> Optional[Tuple[List[bytes], List[bytes]]]:
        """Return the GUIDs of the node's readers and writers; None while it is not announced."""
        if not self._graph_visible:
            return None
        return list(self._reader_gids.values()), list(self._writer_gids.values())

    def abandon(self) -> None:
        """Mark the node shut down without deleting anything (the participant goes with all)."""
        self._graph_visible = False
        self._shutdown = True

    @property
    def shut_down(self) -> bool:
        """True once :meth:`shutdown` (or a process close) has run."""
        return self._shutdown

    # ---------------------------------------------------------------- endpoints

    def _check_ok(self) -> None:
        if self._shutdown:
            raise TransportError(f'node {self.get_fully_qualified_name()} is shut down')

    def _add_reader(self, reader: DataReader, handler) -> None:
        self._reader_gids[id(reader)] = reader.guid.bytes
        self._endpoints.append(reader)
        self._executor.add(ReadCondition(reader, cyclone_private.ANY_STATE), handler)

    def _add_writer(self, writer: DataWriter) -> None:
        self._writer_gids[id(writer)] = writer.guid.bytes
        self._endpoints.append(writer)

    def _graph_changed(self) -> None:
        if self._graph_visible:
            self._ctx.publish_graph()

    def _dds_topic(self, ros_type: str, topic: str, profile: QosProfile):
        msg_type = self.msg(ros_type)
        fqn = topic if profile.avoid_ros_namespace_conventions else self.resolve(topic)
        dds_name = fqn if profile.avoid_ros_namespace_conventions else 'rt' + fqn
        user_data = endpoint_user_data(msg_type.__ros_type__)
        return msg_type, fqn, self._ctx.topic(dds_name, msg_type), user_data

    def create_publisher(self, ros_type: str, topic: str, qos=None) -> DdsPublisher:
        self._check_ok()
        profile = as_qos(qos)
        msg_type, fqn, dds_topic, user_data = self._dds_topic(ros_type, topic, profile)
        # A volatile writer without a matched reader delivers nothing: its gate lets the node
        # skip building such messages. A transient-local one keeps its last samples for readers
        # matching later, so it is always written.
        gate = ReaderGate() if profile.durability == VOLATILE else None
        writer = DataWriter(self._ctx.participant, dds_topic,
                            qos=dds_qos(profile, user_data, True),
                            listener=reader_gate_listener(gate) if gate is not None else None)
        self._add_writer(writer)
        self._graph_changed()
        return self._tap(DdsPublisher(self, writer, msg_type, fqn, gate), ros_type, profile,
                         cyclone_private.sample_serializer(writer))

    def create_subscription(self, ros_type: str, topic: str, callback,
                            qos=None, *, raw: bool = False) -> DdsSubscription:
        self._check_ok()
        profile = as_qos(qos)
        msg_type, fqn, dds_topic, user_data = self._dds_topic(ros_type, topic, profile)
        reader = DataReader(self._ctx.participant, dds_topic,
                            qos=dds_qos(profile, user_data, False))
        intake = Intake(self, reader, f'subscription {fqn} ({msg_type.__ros_type__})')

        if raw:
            def on_data():
                for data, info in cyclone_private.take_serialized(reader, TAKE_BATCH):
                    if info.valid_data:
                        callback(data)
        else:
            def on_data():
                for sample in intake.take():
                    callback(sample)

        self._add_reader(reader, on_data)
        self._graph_changed()
        return DdsSubscription(reader, fqn, intake)

    def create_service(self, srv_type: str, name: str, callback,
                       qos=QOS_SERVICES) -> DdsService:
        self._check_ok()
        try:
            service = DdsService(self, self._ctx, srv_type, self.resolve(name), callback,
                                 as_qos(qos))
        except ValueError as exc:
            raise TransportError(str(exc)) from None
        self._add_reader(service._reader, service.on_data)
        self._add_writer(service._writer)
        self._executor.add_service(service)
        self._graph_changed()
        self._tap_service(service.service_name, srv_type, callback)
        return service

    def create_client(self, srv_type: str, name: str, qos=QOS_SERVICES) -> DdsClient:
        self._check_ok()
        try:
            client = DdsClient(self, self._ctx, srv_type, self.resolve(name), as_qos(qos))
        except ValueError as exc:
            raise TransportError(str(exc)) from None
        self._add_reader(client._reader, client.on_data)
        self._add_writer(client._writer)
        self._graph_changed()
        return client

    def create_timer(self, period_s: float, callback) -> DdsTimer:
        self._check_ok()
        return self._executor.create_timer(period_s, callback)

    # ---------------------------------------------------------------- clock and logging

    def now(self) -> Time:
        if self._clock_sub is not None:
            return Time(self._sim_time_ns)
        return Time(time.time_ns())

    def time_msg(self, t: Optional[Time] = None):
        t = self.now() if t is None else t
        return self._time_type(sec=t.sec, nanosec=t.nanosec)

    def get_logger(self) -> DdsLogger:
        return self._logger

    def _on_clock(self, msg) -> None:
        self._sim_time_ns = msg.clock.sec * 1_000_000_000 + msg.clock.nanosec

    def _parameter_applied(self, name: str, value: Any) -> None:
        if name == 'use_sim_time' and value and self._clock_sub is None:
            self._clock_sub = self.create_subscription(
                'rosgraph_msgs/msg/Clock', '/clock', self._on_clock, QOS_CLOCK)

    # ---------------------------------------------------------------- parameters

    def declare_parameter(self, name: str, default: Any, *, description: str = '',
                          validator=None, read_only: bool = False,
                          additional_constraints: str = '') -> Any:
        return self._parameters.declare_parameter(
            name, default, description=description, validator=validator,
            read_only=read_only, additional_constraints=additional_constraints)

    def get_parameter(self, name: str) -> Any:
        return self._parameters.get_parameter(name)

    def has_parameter(self, name: str) -> bool:
        return self._parameters.has_parameter(name)

    def add_on_set_parameters_callback(self, callback) -> None:
        self._parameters.add_on_set_parameters_callback(callback)

    def set_parameters(self, parameters: List[Parameter]) -> List[SetParametersResult]:
        return self._parameters.set_parameters(parameters)

    def set_parameters_atomically(self, parameters: List[Parameter]) -> SetParametersResult:
        return self._parameters.set_parameters_atomically(parameters)

    # ---------------------------------------------------------------- spinning and shutdown

    def spin_once(self, timeout_s: Optional[float] = None) -> None:
        if self._shutdown:
            return
        if not self._overrides_checked:  # the node's parameters are declared by its first spin
            self._overrides_checked = True
            warning = self._parameters.unknown_overrides_warning()
            if warning:
                self._logger.warning(warning)
        self._executor.spin_once(timeout_s)

    def serve_pending(self) -> None:
        if not self._shutdown:
            self._executor.serve_pending()

    def call_soon(self, callback) -> None:
        self._executor.call_soon(callback)

    def spin(self) -> None:
        while self.ok():
            self.spin_once(SPIN_SLICE_S)

    def request_shutdown(self) -> None:
        """Ask spin() to return (signal-handler safe); run_node then calls shutdown()."""
        self._shutdown_requested = True
        executor = getattr(self, '_executor', None)   # None: interrupted in the constructor
        if executor is not None:
            executor.wake()

    def ok(self) -> bool:
        """Return False once a shutdown was requested (a signal) or done, like ``rclpy.ok``."""
        return not (self._shutdown or self._shutdown_requested)

    def shutdown(self) -> None:
        if self._shutdown:
            return
        self._shutdown = True
        self._graph_visible = False
        ctx = self._ctx
        last = ctx.node_count <= 1
        self._executor.close()
        # Leave ros_discovery_info first, then delete our endpoints (or, for the last node, the
        # whole participant) so that the node leaves the graph at once.
        ctx.release(self)
        if not last:
            self._executor.delete()
            for entity in self._endpoints:
                cyclone_private.delete_entity(entity)

def create_dds_node(name: str, namespace: str = '', args=None, parameter_overrides=None,
                    **kwargs) -> DdsNode:
    """Create a DdsNode (the factory behind ``selection.create_node``)."""
    return DdsNode(name, namespace, args=args, parameter_overrides=parameter_overrides,
                   **kwargs)
