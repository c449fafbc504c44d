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
ROS 2 message and service types for the embedded Cyclone DDS transport.

One rosbags type store (``Stores.ROS2_JAZZY`` plus the definitions of
:mod:`vehicle_msgs_py.catalog`; in a process that speaks Humble, the few layouts of
``Stores.ROS2_HUMBLE`` that differ, see :mod:`vehicle_msgs_py.distro`) is the single source of
every layout; from it this module generates cyclonedds-python ``IdlStruct`` classes that
serialise exactly like rmw_cyclonedds (final extensibility, classic CDR / XCDR1), with the ROS
field names, defaults for every field (so ``Msg()`` works) and the message constants as class
attributes.

Conventions (ROS 2 Jazzy over rmw_cyclonedds_cpp; docs/transport.md):

* DDS type names ``pkg::msg::dds_::Name_`` and ``pkg::srv::dds_::Name_Request_`` (A1).
* Services: users see plain ``request`` / ``response`` classes; on the wire rmw_cyclonedds puts
  ``uint64 client_id`` and ``int64 sequence`` in front of the fields (A4), which the
  ``request_wire`` / ``response_wire`` classes carry.
* ``char`` is ``uint8`` in ROS 2 (rosidl maps it so); the type store is patched accordingly, which
  also makes the REP-2011 hashes of rmw_dds_common's Gid types right (Part C, A7).
* Service request/response types are registered as ``pkg/srv/Name_Request`` (Part C 8).
"""

import dataclasses
import functools
import keyword
import threading

from cyclonedds.idl import IdlStruct
from cyclonedds.idl import types as idl
from cyclonedds.idl._main import IdlMeta
import numpy as np
from rosbags.typesys import get_types_from_msg, get_typestore, Stores
from rosbags.typesys.base import Nodetype

from vehicle_msgs_py import distro
from vehicle_msgs_py.catalog import definitions, split_service

# rmw_cyclonedds request header members (rmw_cyclonedds' cdds_request_header_t), in wire order.
WIRE_HEADER_FIELDS = ('client_id', 'sequence')
UINT64_MASK = 0xFFFFFFFFFFFFFFFF

# Member that rosidl adds to messages without fields (rosidl).
EMPTY_MEMBER = 'structure_needs_at_least_one_member'

_IDL_PRIMITIVES = {
    'bool': bool,
    'byte': idl.uint8,  # rosidl 'byte' = IDL octet: one unsigned byte
    'char': idl.uint8,  # rosidl 'char' = uint8
    'int8': idl.int8,
    'uint8': idl.uint8,
    'int16': idl.int16,
    'uint16': idl.uint16,
    'int32': idl.int32,
    'uint32': idl.uint32,
    'int64': idl.int64,
    'uint64': idl.uint64,
    'float32': idl.float32,
    'float64': idl.float64,
}

# numpy dtypes rosbags uses for arrays/sequences of primitives (it reads 'byte' as int8).
_NUMPY_DTYPES = {
    'bool': np.bool_,
    'byte': np.int8,
    'char': np.uint8,
    'int8': np.int8,
    'uint8': np.uint8,
    'int16': np.int16,
    'uint16': np.uint16,
    'int32': np.int32,
    'uint32': np.uint32,
    'int64': np.int64,
    'uint64': np.uint64,
    'float32': np.float32,
    'float64': np.float64,
}

# Non-zero defaults that rosidl gives but rosbags' field definitions do not carry.
_FIELD_DEFAULTS = {
    ('geometry_msgs/msg/Quaternion', 'w'): 1.0,
}

# One-byte unsigned element types: cyclonedds-python hands their fixed arrays back as
# ``bytes`` (sequences as lists of int), so defaults and conversions do the same.
_OCTET_TYPES = ('byte', 'char', 'uint8')

_lock = threading.RLock()
_store = None
_services = {}
_message_types = {}
_service_types = {}
_hashes = {}


def normalize_type_name(ros_type):
    """
    Return the canonical ``pkg/msg/Name`` (or ``pkg/srv/Name...``) form of a ROS type name.

    :param ros_type: ``pkg/msg/Name``, ``pkg/Name`` or ``pkg/srv/Name_Request`` style name.
    :return: the canonical name.
    :raises ValueError: for a name that is not of those forms.
    """
    parts = ros_type.strip('/').split('/')
    if len(parts) == 2:
        parts = [parts[0], 'msg', parts[1]]
    if len(parts) != 3 or parts[1] not in ('msg', 'srv', 'action') or not all(parts):
        raise ValueError(f'not a ROS type name: {ros_type!r} (expected pkg/msg/Name)')
    return '/'.join(parts)


def _char_to_uint8(desc):
    kind, rest = desc
    if kind == Nodetype.BASE and rest[0] == 'char':
        return (Nodetype.BASE, ('uint8', 0))
    if kind in (Nodetype.ARRAY, Nodetype.SEQUENCE):
        return (kind, (_char_to_uint8(rest[0]), rest[1]))
    return desc


def _non_empty(fields):
    return list(fields) or [(EMPTY_MEMBER, (Nodetype.BASE, ('uint8', 0)))]


def _parse(text, registered_name):
    # rosbags would rename pkg/srv/X to pkg/srv/msg/X (Part C 8): parse as pkg/msg/X, so that
    # relative field types resolve inside the package, then register under the real name.
    pkg, _, name = registered_name.split('/')
    parse_name = f'{pkg}/msg/{name}'
    consts, fields = get_types_from_msg(text, parse_name)[parse_name][:2]
    return consts, _non_empty(fields)


def _build_store():
    store = get_typestore(Stores.ROS2_JAZZY)
    typs = {}
    services = {}
    for definition in definitions():
        if definition.kind == 'msg':
            typs[definition.ros_type] = _parse(definition.text(), definition.ros_type)
            continue
        srv = definition.ros_type
        request_text, response_text = split_service(definition.text())
        typs[srv + '_Request'] = _parse(request_text, srv + '_Request')
        typs[srv + '_Response'] = _parse(response_text, srv + '_Response')
        # REP-2011 describes a service as request_message, response_message, event_message;
        # the event type is what service introspection publishes.
        typs[srv + '_Event'] = ([], [
            ('info', (Nodetype.NAME, 'service_msgs/msg/ServiceEventInfo')),
            ('request', (Nodetype.SEQUENCE, ((Nodetype.NAME, srv + '_Request'), 1))),
            ('response', (Nodetype.SEQUENCE, ((Nodetype.NAME, srv + '_Response'), 1))),
        ])
        typs[srv] = ([], [
            ('request_message', (Nodetype.NAME, srv + '_Request')),
            ('response_message', (Nodetype.NAME, srv + '_Response')),
            ('event_message', (Nodetype.NAME, srv + '_Event')),
        ])
        services[srv] = (srv + '_Request', srv + '_Response')
    store.register(typs)
    if distro.selected() == distro.HUMBLE:
        # The few layouts Humble has otherwise (vehicle_msgs_py.distro); the Gid of
        # ros_discovery_info is written and read by the transport's discovery_info codec.
        humble = get_typestore(Stores.ROS2_HUMBLE)
        for name in distro.HUMBLE_LAYOUTS:
            store.fielddefs[name] = humble.fielddefs[name]
    for name, (consts, fields) in list(store.fielddefs.items()):
        store.fielddefs[name] = (consts, [(f, _char_to_uint8(d)) for f, d in fields])
    return store, services


def typestore():
    """
    Return the shared rosbags type store: ROS 2 Jazzy plus every shipped definition.

    Services appear as ``pkg/srv/Name_Request``, ``_Response``, ``_Event`` and ``pkg/srv/Name``.
    """
    global _store, _services
    with _lock:
        if _store is None:
            _store, _services = _build_store()
        return _store


def is_service(srv_type):
    """Tell whether ``srv_type`` (``pkg/srv/Name``) names a known service."""
    typestore()
    return normalize_type_name(srv_type) in _services


def known_types():
    """
    List every message type name the store knows, services' request/response included.

    :return: sorted tuple of ``pkg/msg/Name`` / ``pkg/srv/Name_Request`` names.
    """
    store = typestore()
    return tuple(sorted(name for name in store.fielddefs if name not in _services))


def known_services():
    """Return the sorted tuple of known ``pkg/srv/Name`` service type names."""
    typestore()
    return tuple(sorted(_services))


def _fielddefs(ros_type):
    name = normalize_type_name(ros_type)
    store = typestore()
    if name in _services:
        raise ValueError(f'{name} is a service: use service_types({name!r})')
    try:
        return name, store.fielddefs[name]
    except KeyError:
        raise ValueError(f'unknown ROS type {name!r}; known types: see known_types()') from None


def dds_type_name(ros_type):
    """
    Return the DDS type name ROS 2 uses for a message or service request/response type.

    ``std_msgs/msg/String`` → ``std_msgs::msg::dds_::String_``;
    ``std_srvs/srv/SetBool_Request`` → ``std_srvs::srv::dds_::SetBool_Request_`` (rmw_cyclonedds).
    """
    pkg, kind, name = normalize_type_name(ros_type).split('/')
    return f'{pkg}::{kind}::dds_::{name}_'


def type_hash(ros_type):
    """
    Return the REP-2011 type hash ``RIHS01_<64 hex>`` of a message, request/response or service.

    For a service (``pkg/srv/Name``) it is the hash of the whole service description
    (request_message, response_message, event_message), as rosidl computes it.
    """
    name = normalize_type_name(ros_type)
    with _lock:
        if name not in _hashes:
            store = typestore()
            if name not in store.fielddefs:
                raise ValueError(f'unknown ROS type {name!r}')
            _hashes[name] = store.hash_rihs01(name)
        return _hashes[name]



def message_definition(ros_type):
    """
    Return a message's ``ros2msg`` schema text with every type it depends on appended.

    This is the text rosbag2 stores as a topic's schema (and Foxglove reads): the message's own
    fields, then for each dependency a line of 80 ``=`` signs, ``MSG: pkg/Name`` and its fields.
    """
    name = normalize_type_name(ros_type)
    store = typestore()
    if name not in store.fielddefs:
        raise ValueError(f'unknown ROS type {name!r}')
    with _lock:
        text, _md5 = store.generate_msgdef(name, ros_version=2)
    return text

def _idl_annotation(desc):
    kind, rest = desc
    if kind == Nodetype.BASE:
        base, bound = rest
        if base == 'string':
            return idl.bounded_str[bound] if bound else str
        if base not in _IDL_PRIMITIVES:
            raise ValueError(f'unsupported ROS primitive type {base!r}')
        return _IDL_PRIMITIVES[base]
    if kind == Nodetype.NAME:
        return message_type(rest)
    element, size = rest
    inner = _idl_annotation(element)
    if kind == Nodetype.ARRAY:
        return idl.array[inner, size]
    return idl.sequence[inner, size] if size else idl.sequence[inner]


def _is_octet(desc):
    return desc[0] == Nodetype.BASE and desc[1][0] in _OCTET_TYPES


def _default(desc):
    """Return a ``dataclasses.field`` giving the ROS default (zero / empty) for a field."""
    kind, rest = desc
    if kind == Nodetype.BASE:
        base = rest[0]
        if base == 'string':
            return dataclasses.field(default='')
        if base == 'bool':
            return dataclasses.field(default=False)
        if base.startswith('float'):
            return dataclasses.field(default=0.0)
        return dataclasses.field(default=0)
    if kind == Nodetype.NAME:
        return dataclasses.field(default_factory=message_type(rest))
    element, size = rest
    if kind == Nodetype.SEQUENCE:
        return dataclasses.field(default_factory=list)
    if _is_octet(element):
        return dataclasses.field(default=bytes(size))
    make_one = _default(element)
    if make_one.default_factory is not dataclasses.MISSING:
        factory = make_one.default_factory
        return dataclasses.field(default_factory=lambda: [factory() for _ in range(size)])
    value = make_one.default
    return dataclasses.field(default_factory=lambda: [value] * size)


def _field_default(ros_type, field_name, desc):
    if (ros_type, field_name) in _FIELD_DEFAULTS:
        return dataclasses.field(default=_FIELD_DEFAULTS[ros_type, field_name])
    return _default(desc)


def _make_struct(class_name, typename, fields, consts, ros_type, extra=()):
    bases = (IdlStruct,)
    namespace = IdlMeta.__prepare__(class_name, bases, typename=typename)
    annotations = namespace['__annotations__']
    for field_name, annotation, default in list(extra) + [
            (f, _idl_annotation(d), _field_default(ros_type, f, d)) for f, d in fields]:
        if keyword.iskeyword(field_name):
            raise ValueError(f'{ros_type}: field name {field_name!r} is a Python keyword')
        annotations[field_name] = annotation
        namespace[field_name] = default
    namespace['__ros_type__'] = ros_type
    namespace['__module__'] = __name__
    cls = dataclasses.dataclass(IdlMeta(class_name, bases, namespace))
    for const_name, _, value in consts:
        setattr(cls, const_name, value)
    return cls


def message_type(ros_type):
    """
    Return the ``IdlStruct`` class of a ROS message (or service request/response) type.

    Build a message with keyword fields, every field defaulting to zero / empty::

        String = message_type('std_msgs/msg/String')
        String(data='hello').serialize()   # CDR bytes with the 4-byte encapsulation header

    :param ros_type: e.g. ``'std_msgs/msg/String'`` or ``'std_srvs/srv/SetBool_Request'``.
    :return: the cached class; ``cls.__ros_type__`` holds the canonical ROS type name.
    :raises ValueError: for an unknown type or a whole service name.
    """
    name = normalize_type_name(ros_type)
    with _lock:
        cls = _message_types.get(name)
        if cls is None:
            name, (consts, fields) = _fielddefs(name)
            pkg, kind, short = name.split('/')
            # A plain service request/response never goes on the wire; it gets a name of its
            # own so that it cannot be confused with the wire type that carries the header.
            typename = f'{pkg}::srv::{short}' if kind == 'srv' else dds_type_name(name)
            cls = _make_struct(short, typename, fields, consts, name)
            _message_types[name] = cls
        return cls


@dataclasses.dataclass(frozen=True)
class ServiceTypes:
    """
    The four classes of one ROS service.

    ``request`` / ``response`` hold the plain ROS fields (what service callbacks see).
    ``request_wire`` / ``response_wire`` are what rmw_cyclonedds puts on the DDS topics: the
    same fields after two leading members ``client_id`` (uint64) and ``sequence`` (int64).
    Only the wire classes carry the DDS type names ``pkg::srv::dds_::Name_Request_`` /
    ``Name_Response_``.
    """

    srv_type: str
    request: type
    response: type
    request_wire: type
    response_wire: type

    def request_to_wire(self, request, client_id, sequence):
        """Wrap a plain request with the rmw_cyclonedds header (client id, sequence number)."""
        return _to_wire(self.request_wire, request, client_id, sequence)

    def response_to_wire(self, response, client_id, sequence):
        """Wrap a plain response with the header echoed from its request."""
        return _to_wire(self.response_wire, response, client_id, sequence)

    def wire_primitives(self, part):
        """
        Return the wire type's fields as ``[(name, ROS primitive type), ...]``, header first.

        None when a field is not a single primitive (a string, an array, a nested message).

        :param part: 'request' or 'response'.
        """
        typestore()
        fields = _store.fielddefs[_services[self.srv_type][part == 'response']][1]
        found = [('client_id', 'uint64'), ('sequence', 'int64')]
        for name, (kind, rest) in fields:
            if kind != Nodetype.BASE or rest[0] == 'string':
                return None
            found.append((name, rest[0]))
        return found

    def request_from_wire(self, wire):
        """
        Split a wire request into its header and plain request.

        :return: ``(client_id, sequence, request)``.
        """
        return _from_wire(self.request, wire)

    def response_from_wire(self, wire):
        """
        Split a wire response into its header and plain response.

        :return: ``(client_id, sequence, response)``.
        """
        return _from_wire(self.response, wire)


@functools.lru_cache(maxsize=None)
def _plain_field_names(cls):
    # Cached per class: every request and reply of a service goes through it.
    return tuple(f.name for f in dataclasses.fields(cls) if f.name not in WIRE_HEADER_FIELDS)


def _to_wire(wire_cls, plain, client_id, sequence):
    values = {name: getattr(plain, name) for name in _plain_field_names(type(plain))}
    return wire_cls(client_id=client_id & UINT64_MASK, sequence=sequence, **values)


def _from_wire(plain_cls, wire):
    values = {name: getattr(wire, name) for name in _plain_field_names(plain_cls)}
    return wire.client_id, wire.sequence, plain_cls(**values)


def service_types(srv_type):
    """
    Return the :class:`ServiceTypes` of a ROS service, e.g. ``'vehicle_msgs/srv/SetFloat'``.

    :raises ValueError: for an unknown service.
    """
    name = normalize_type_name(srv_type)
    with _lock:
        found = _service_types.get(name)
        if found is not None:
            return found
        typestore()
        if name not in _services:
            raise ValueError(f'unknown ROS service {name!r}; known: {", ".join(_services)}')
        classes = [message_type(part) for part in _services[name]]
        wires = []
        for part in _services[name]:
            consts, fields = _store.fielddefs[part]
            header = [('client_id', idl.uint64, dataclasses.field(default=0)),
                      ('sequence', idl.int64, dataclasses.field(default=0))]
            clash = {f for f, _ in fields} & set(WIRE_HEADER_FIELDS)
            if clash:
                raise ValueError(f'{part}: field(s) {sorted(clash)} collide with the wire header')
            class_name = part.split('/')[2] + 'Wire'
            wires.append(_make_struct(class_name, dds_type_name(part), fields, consts, part,
                                      extra=header))
        found = ServiceTypes(name, classes[0], classes[1], wires[0], wires[1])
        _service_types[name] = found
        return found


def _to_rosbags_value(value, desc, store):
    kind, rest = desc
    if kind == Nodetype.BASE:
        if rest[0] == 'byte' and value > 127:
            return value - 256  # rosbags reads ROS 'byte' as int8
        return value
    if kind == Nodetype.NAME:
        return _to_rosbags_struct(value, rest, store)
    element = rest[0]
    if element[0] == Nodetype.BASE and element[1][0] != 'string':
        dtype = _NUMPY_DTYPES[element[1][0]]
        if isinstance(value, (bytes, bytearray, memoryview)):
            return np.frombuffer(bytes(value), dtype=np.uint8).view(dtype).copy()
        if np.dtype(dtype).itemsize == 1 and dtype is not np.bool_:
            return np.array(value, dtype=np.int64).astype(np.uint8).view(dtype)
        return np.array(value, dtype=dtype)
    return [_to_rosbags_value(item, element, store) for item in value]


def _to_rosbags_struct(obj, ros_type, store):
    values = {f: _to_rosbags_value(getattr(obj, f), d, store)
              for f, d in store.fielddefs[ros_type][1]}
    return store.types[ros_type](**values)


def to_rosbags(obj):
    """
    Convert one of our message objects into the equivalent rosbags message.

    Wire service objects convert to the plain request/response (the header is dropped).
    Serialise the result with ``typestore().serialize_cdr(msg, msg.__msgtype__)``.
    """
    return _to_rosbags_struct(obj, type(obj).__ros_type__, typestore())


def _from_rosbags_value(value, desc):
    kind, rest = desc
    if kind == Nodetype.BASE:
        if rest[0] in ('byte', 'char'):
            return int(value) & 0xFF
        if rest[0] == 'bool':
            return bool(value)
        if rest[0] == 'string':
            return str(value)
        return float(value) if rest[0].startswith('float') else int(value)
    if kind == Nodetype.NAME:
        return from_rosbags(value, rest)
    element = rest[0]
    if _is_octet(element):
        octets = np.asarray(value).astype(np.uint8)
        return octets.tobytes() if kind == Nodetype.ARRAY else octets.tolist()
    if isinstance(value, np.ndarray):
        return value.tolist()
    return [_from_rosbags_value(item, element) for item in value]


def from_rosbags(msg, ros_type=None):
    """
    Convert a rosbags message into our ``IdlStruct`` message.

    :param msg: a message of :func:`typestore`'s classes.
    :param ros_type: its type name; default ``msg.__msgtype__``.
    """
    name = normalize_type_name(ros_type or msg.__msgtype__)
    cls = message_type(name)
    fields = typestore().fielddefs[name][1]
    return cls(**{f: _from_rosbags_value(getattr(msg, f), d) for f, d in fields})
