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
The one kind of ROS interface table: every topic and service of every node is a row.

A :class:`Topic` row is a name, a ROS type, a QoS profile, a cadence (when it is published) and its
converter; a :class:`Service` row is a name, a service type and what the node maps it to. The
tables are ``ros/automobile_interfaces.py`` (the automobile node), ``ros/bridge_interfaces.py``
(the bridge's vehicle side), ``ros/autoware_interfaces.py`` (the Autoware side of the bridge and
``autoware_automobile``) and ``ros/robot_interfaces.py`` (the simulated robot); the rows every node
shares, ``/clock``, ``/tf`` and ``/tf_static``, are defined once, here. Nodes wire rows with
:class:`Outputs`, :func:`subscribe` and :func:`serve` (the only calls that create publishers,
subscriptions and services in the ROS layer; a test checks it), and the docs' tables are generated
from the rows (:func:`topic_table_markdown`).

Converters. An output row's ``converter`` is a factory ``converter(kit, w)``, called once when
a node wires the row, with a :class:`MessageKit` (the transport's message classes, builders
shared by the rows of one context) and the wiring context ``w`` (a vehicle: its frames, joint
names, spawn pose). It returns ``convert(ctx)``, which the node calls at the row's cadence with
the call context ``ctx`` (that vehicle's state at this step, with its ``stamp``) and which
returns the message to publish, or None for "nothing now" (a topic of one control mode, a report
not measured yet, a sensor without a fresh sample: cadence EACH_SAMPLE). Rows build their
converters with :func:`converter`: a value reader (``ctx`` -> the builder's arguments, the only
per-call computation) joined to a message builder of :mod:`.messages` (constant parts fixed at
wiring; a serializer can stand in for it). An input row's ``converter`` maps a received message
to the node's command.
"""

from dataclasses import dataclass
import math
from typing import Callable, Dict, Iterable, Optional, Tuple

from vehicle_sim.core.commands.watchdog import DEFAULT_TIMEOUT_S
from vehicle_sim.core.specs.param_spec import ParamSpec
from vehicle_sim.ros import messages as m
from vehicle_sim.transport.qos import QOS_DEFAULT, QOS_SERVICES, QOS_TF, QOS_TF_STATIC, QosProfile

# Direction of a topic row.
OUT = 'out'
IN = 'in'

# Cadence: when an output row is published (the node calls Outputs.publish with it).
EACH_STEP = 'each basic step'
EACH_PUBLISH = 'each publish period'
ONCE_LATCHED = 'once, latched'
EACH_STATUS = 'each status period'
EACH_COMMAND = 'each accepted command and control tick'
EACH_SAMPLE = "each sensor sample (the sensor's rate)"
ON_EVENT = 'when it happens'
RECEIVED = 'on receipt'    # input rows: the node's callback runs on each message


@dataclass(frozen=True)
class Topic:
    """
    One topic a node publishes (``direction`` OUT) or reads (IN).

    :param name: ROS name; relative names are resolved by the node that wires the row (under a
        vehicle namespace, or private), names with a leading ``/`` are global.
    :param ros_type: message type.
    :param qos: QoS profile of the publisher (OUT) or subscription (IN).
    :param cadence: when it is published (EACH_STEP, EACH_PUBLISH, ONCE_LATCHED, ...);
        RECEIVED for inputs.
    :param converter: OUT: ``converter(kit, w)`` -> ``convert(ctx)`` -> message or None (see the
        module docstring); IN: ``converter(message)`` -> the node's command.
    :param direction: OUT or IN.
    :param unit: units of the values.
    :param doc: one-line description (docs tables).
    :param switch: the bool parameter that enables the row (None: always wired).
    """

    name: str
    ros_type: str
    qos: QosProfile = QOS_DEFAULT
    cadence: str = EACH_PUBLISH
    converter: Optional[Callable] = None
    direction: str = OUT
    unit: str = ''
    doc: str = ''
    switch: Optional[str] = None

    @property
    def is_global(self) -> bool:
        return self.name.startswith('/')

    @property
    def short_name(self) -> str:
        return self.name.rsplit('/', 1)[-1]


@dataclass(frozen=True)
class Service:
    """
    One service a node serves, and what it maps to.

    :param name: ROS name (resolved like a Topic's).
    :param ros_type: service type.
    :param kind: how the node serves it (the node's handler for this kind).
    :param core: the core attribute it maps to (a setter method or a getter property).
    :param value: the value's Python type: 'float', 'int' or 'bool'.
    :param unit: unit of the value.
    :param legacy: an old name kept for old clients (same handler as its modern twin).
    :param webots: True for Webots' own names, False for our additions.
    :param observed_by: the getter service or topic that reports what a setter changed.
    :param example: a valid, non-default request value (tests).
    :param invalid: values the node must refuse with success=false (docs/deviations.md, ROS
    column).
    :param doc: one-line description.
    :param switch: the bool parameter that enables the row (None: always served).
    :param qos: the service QoS profile.
    """

    name: str
    ros_type: str
    kind: str = ''
    core: Optional[str] = None
    value: str = 'float'
    unit: str = ''
    legacy: bool = False
    webots: bool = True
    observed_by: Optional[str] = None
    example: Optional[float] = None
    invalid: Tuple = ()
    doc: str = ''
    switch: Optional[str] = None
    qos: QosProfile = QOS_SERVICES

    @property
    def srv_type(self) -> str:
        """The service type (``ros_type``)."""
        return self.ros_type

    @property
    def short_name(self) -> str:
        return self.name.rsplit('/', 1)[-1]


class MessageKit:
    """
    What a converter factory gets at wiring besides the context: message classes and builders.

    One kit per wiring context (:class:`Outputs` makes it), so rows of that context share one
    builder per (builder, constants): the Float64Stamped rows of a vehicle build one header per
    stamp, not one each.

    :param msg: the transport's ``node.msg`` class lookup.
    :param serializer: the transport's ``node.serializer`` lookup (ROS type -> serializer
        factory or None); None: the transport publishes messages only.
    """

    def __init__(self, msg, serializer=None):
        self.msg = msg
        self._serializer = serializer
        self._builders = {}

    def builder(self, builder, *constants):
        """Return ``builder(msg, *constants)``, the same one for equal (hashable) arguments."""
        key = (builder, constants)
        found = self._builders.get(key)
        if found is None:
            found = self._builders[key] = builder(self.msg, *constants)
        return found

    def serializer(self, builder, *constants, own=None):
        """
        Return the transport's serializer standing in for ``builder``, or None.

        It takes the builder's constants and values and returns the message's bytes
        (``Publisher.publish_serialized``); one per (builder, constants), like builders.

        :param own: the row's own serializer factory for ``builder`` (a type with several
            builders, or one outside ``ros/messages.py``), used where the transport publishes
            bytes (it has serializers); None: the transport's for the builder's type.
        """
        ros_type = m.BUILT_TYPES.get(builder)
        if self._serializer is None:
            factory = None
        elif own is not None:
            factory = own
        else:
            factory = None if ros_type is None else self._serializer(ros_type)
        if factory is None:
            return None
        key = (factory, constants)
        found = self._builders.get(key)
        if found is None:
            found = self._builders[key] = factory(*constants)
        return found


def converter(builder, values, constants=None, serializer=None):
    """
    Make an output row's converter from a message builder and a value reader.

    :param builder: ``builder(msg, *constants(w))`` -> ``build(*args)`` (see :mod:`.messages`).
    :param values: ``values(ctx)`` -> the tuple ``args`` of ``build``, or None (nothing now).
    :param constants: ``constants(w)`` -> the builder's constant arguments (frame ids, names; a
        hashable tuple), read once at wiring; None: the builder takes none.
    :param serializer: a serializer factory standing in for ``builder`` (same constants and
        values; returns the bytes), for a builder the transport has none for; None: the
        transport's, if any (:meth:`MessageKit.serializer`).
    :return: the factory ``converter(kit, w)`` -> ``convert(ctx)`` (``kit`` a MessageKit).
        Where the kit has a serializer for the builder, ``convert`` returns the message's
        bytes instead and its ``serialized`` attribute is True (:class:`Outputs` then publishes
        them with ``publish_serialized``).
    """
    def factory(kit, w):
        fixed = constants(w) if constants is not None else ()
        serialize = kit.serializer(builder, *fixed, own=serializer)
        build = serialize if serialize is not None else kit.builder(builder, *fixed)

        def convert(ctx):
            args = values(ctx)
            return None if args is None else build(*args)
        convert.serialized = serialize is not None
        convert.parts = (values, build)     # Outputs.publish calls them without convert
        return convert
    return factory


# ---------------------------------------------------------------------------------------------
# The rows every node shares. Wiring context: ``tf_frames`` [(parent, child)] and
# ``static_transforms`` [(parent, child, xyz, q)]; call context: ``stamp`` and ``tf_poses``
# [(xyz, q)] in tf_frames order (None: nothing to publish).

# Reliable, depth 1: rclpy's best-effort TimeSource reader and reliable readers both match
# (docs/ros_interface.md, for every node that publishes it).
QOS_CLOCK_PUBLISHER = QosProfile(depth=1)

CLOCK = Topic(
    '/clock', m.CLOCK, QOS_CLOCK_PUBLISHER, EACH_STEP,
    converter(m.clock_builder, lambda ctx: (ctx.stamp,)), unit='s', doc='simulated time')
TF = Topic(
    '/tf', m.TF_MESSAGE, QOS_TF, EACH_PUBLISH,
    converter(m.tf_message_builder,
              lambda ctx: None if ctx.tf_poses is None else (ctx.stamp, ctx.tf_poses),
              lambda w: (tuple(w.tf_frames),)),
    doc='<p>odom -> <p>base_link of every vehicle, one message')


def input_topic(name, ros_type, read, doc, qos=QOS_DEFAULT, unit='', switch=None):
    """Return an input row: ``read(msg)`` turns each received message into the node's command."""
    return Topic(name, ros_type, qos, RECEIVED, read, IN, unit=unit, doc=doc, switch=switch)


def frame_id_wiring(w):
    """Wiring constants of a stamped row whose header names the node's ``frame_id``."""
    return (w.frame_id,)


# The columns of the bridge's, the robot's and the Autoware side's docs tables.
DOC_COLUMNS = ('type', 'direction', 'QoS', 'published', 'switch', 'notes')


def _static_transforms(kit, w):
    transforms = tuple(w.static_transforms)
    build = kit.builder(m.tf_message_builder,
                        tuple((parent, child) for parent, child, _, _ in transforms))
    poses = [(xyz, q) for _, _, xyz, q in transforms]
    return lambda ctx: build(ctx.stamp, poses)


TF_STATIC = Topic('/tf_static', m.TF_MESSAGE, QOS_TF_STATIC, ONCE_LATCHED, _static_transforms,
                  doc='world -> <p>odom at each spawn pose and <p>base_link -> <p><name> at each '
                      'sensor mount, one message holding all')

# cmd_vel, read by the car (automobile node) and the differential robot alike (docs/drive.md):
# a relative name, resolved under the vehicle namespace (car) or privately (robot). The converter
# gives (v [m/s], yaw rate [rad/s, + left]). Twist by default, TwistStamped with the
# cmd_vel_stamped parameter (teleop_twist_keyboard's `stamped`; Jazzy's diff_drive_controller).
CMD_VEL = Topic('cmd_vel', m.TWIST, QOS_DEFAULT, RECEIVED,
                lambda msg: (msg.linear.x, msg.angular.z), IN, unit='m/s, rad/s',
                doc='linear.x [m/s] and angular.z [rad/s, + left] (cmd_vel_stamped false)')
CMD_VEL_STAMPED = Topic('cmd_vel', m.TWIST_STAMPED, QOS_DEFAULT, RECEIVED,
                        lambda msg: (msg.twist.linear.x, msg.twist.angular.z), IN,
                        unit='m/s, rad/s', doc='the same, stamped (cmd_vel_stamped true)')
# cmd_vel_stamped -> the row read.
CMD_VEL_INPUTS = {False: CMD_VEL, True: CMD_VEL_STAMPED}
CMD_VEL_STAMPED_PARAMETER = ParamSpec(
    'cmd_vel_stamped', kind='bool', default=False,
    doc='read cmd_vel as geometry_msgs/TwistStamped instead of Twist')
CMD_VEL_TIMEOUT_PARAMETER = ParamSpec(
    'cmd_vel_timeout_s', kind='float', default=DEFAULT_TIMEOUT_S, unit='s', ge=0.0, le=3600.0,
    doc='age (receipt, simulated time) of the last cmd_vel (or drive) command after which the '
        'vehicle stops (car: a safety stop, throttle released and full brake; robot: wheels '
        '0); 0 disables')


# ---------------------------------------------------------------------------------------------
# Wiring


def _enabled(row, switches):
    # switches None: the node has no switch parameters, every row is wired.
    return row.switch is None or switches is None or bool(switches[row.switch])


class Outputs:
    """
    The publishers of a node's output rows for one wiring context, published by cadence.

    :param node: a transport NodePort.
    :param rows: the Topic rows (OUT) to wire, in publishing order.
    :param context: the wiring context ``w`` handed to each converter.
    :param resolve: ``resolve(row.name)`` -> the name to create (default: the row's name).
    :param switches: parameter values for the rows' ``switch`` (rows switched off are skipped;
        None: every row is wired).
    """

    def __init__(self, node, rows: Iterable[Topic], context=None,
                 resolve: Optional[Callable[[str], str]] = None, switches=None):
        self.publishers: Dict[Topic, object] = {}
        self._groups: Dict[str, list] = {}
        self._msg = node.msg
        kit = MessageKit(node.msg, node.serializer)
        for row in rows:
            if row.direction != OUT:
                raise ValueError(f'{row.name}: an input row cannot be published')
            if not _enabled(row, switches):
                continue
            publisher = node.create_publisher(
                row.ros_type, resolve(row.name) if resolve else row.name, row.qos)
            self.publishers[row] = publisher
            convert = row.converter(kit, context)
            serialized = getattr(convert, 'serialized', False)
            publish = publisher.publish_serialized if serialized else publisher.publish
            # Hot loop: a converter made by converter() is called as its two parts.
            values, build = getattr(convert, 'parts', (convert, None))
            self._groups.setdefault(row.cadence, []).append(
                (row, convert, publish, values, build, publisher.reader_gate))

    @property
    def rows(self) -> Tuple[Topic, ...]:
        """The wired rows."""
        return tuple(self.publishers)

    def publish(self, cadence: str, ctx) -> None:
        """
        Publish every wired row of ``cadence`` whose converter gives a message for ``ctx``.

        A row whose publisher's reader gate is closed (no subscriber would receive it:
        ``port.ReaderGate``) is skipped: its message is not even built.
        """
        for _, _, publish, values, build, gate in self._groups.get(cadence, ()):
            if gate.open:
                found = values(ctx)
                if found is not None:
                    publish(found if build is None else build(*found))

    def wanted(self, cadence: str) -> bool:
        """Say whether a row of ``cadence`` would be published (its reader gate is open)."""
        return any(gate.open for *_, gate in self._groups.get(cadence, ()))

    def messages(self, cadence: str, ctx) -> Dict[Topic, object]:
        """Return {row: message} of the rows of ``cadence`` for ``ctx``, without publishing."""
        found = {}
        for row, convert, _, _, _, _ in self._groups.get(cadence, ()):
            message = convert(ctx)
            if message is not None:
                found[row] = self._msg(row.ros_type).deserialize(message) \
                    if getattr(convert, 'serialized', False) else message
        return found


def subscribe(node, callbacks: Dict[Topic, Callable], resolve=None, switches=None):
    """
    Create a subscription per input row.

    :param callbacks: {row: callback(message)}; the callback applies ``row.converter``.
    :return: the subscriptions, in the order given.
    """
    subscriptions = []
    for row, callback in callbacks.items():
        if row.direction != IN:
            raise ValueError(f'{row.name}: an output row cannot be subscribed to')
        if _enabled(row, switches):
            subscriptions.append(node.create_subscription(
                row.ros_type, resolve(row.name) if resolve else row.name, callback, row.qos))
    return subscriptions


def serve(node, handlers: Dict[Service, Callable], resolve=None, switches=None):
    """
    Create a service per Service row.

    :param handlers: {row: callback(request, response) -> response}.
    :return: {row: service} of the rows served.
    """
    return {row: node.create_service(row.ros_type, resolve(row.name) if resolve else row.name,
                                     callback)
            for row, callback in handlers.items() if _enabled(row, switches)}


# ---------------------------------------------------------------------------------------------
# Docs


def qos_text(qos: QosProfile) -> str:
    return f'{qos.reliability}, {qos.durability}, depth {qos.depth}'


def value_text(value) -> str:
    if isinstance(value, float) and not math.isfinite(value):
        return str(value)
    return repr(value)


def _cell(text: str) -> str:
    return text.replace('|', '\\|')


_COLUMNS = {
    'type': lambda row: row.ros_type,
    'direction': lambda row: row.direction,
    'QoS': lambda row: qos_text(row.qos),
    'published': lambda row: row.cadence if row.direction == OUT else '',
    'switch': lambda row: f'`{row.switch}`' if row.switch else '',
    'unit': lambda row: row.unit,
    'notes': lambda row: row.doc,
}


def topic_table_markdown(rows: Iterable[Topic], columns=('type', 'QoS', 'published', 'unit',
                                                         'notes'),
                         display_name: Callable[[Topic], str] = lambda row: row.name,
                         first='topic') -> str:
    """
    Return a Markdown table of topic rows (docs pages embed it; tests check they do).

    :param columns: the columns after the name, from: type, direction, QoS, published,
        switch, unit, notes.
    :param display_name: the name as the docs write it.
    :param first: header of the name column.
    """
    lines = ['| ' + ' | '.join((first,) + tuple(columns)) + ' |',
             '|' + '---|' * (len(columns) + 1)]
    for row in rows:
        cells = [f'`{display_name(row)}`'] + [_cell(_COLUMNS[column](row)) for column in columns]
        lines.append('| ' + ' | '.join(cells) + ' |')
    return '\n'.join(lines) + '\n'


def service_table_markdown(rows: Iterable[Service],
                           display_name: Callable[[Service], str] = lambda row: row.name) -> str:
    """Return a Markdown table of service rows: name, type, switch, notes."""
    lines = ['| service | type | switch | notes |', '|---|---|---|---|']
    for row in rows:
        switch = f'`{row.switch}`' if row.switch else ''
        lines.append(f'| `{display_name(row)}` | {row.ros_type} | {switch} | {_cell(row.doc)} |')
    return '\n'.join(lines) + '\n'
