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
Every use of cyclonedds-python internals by the embedded transport, in one place.

Written against cyclonedds 11.0.1 (the version setup.py pins);
test/test_transport_cyclone_private.py pins the behaviour each function relies on, so an upgrade
that changes it fails there first. Why each internal is needed:

* :func:`take_serialized` / :func:`take` (``cyclonedds._clayer.ddspy_take``): the public
  ``DataReader.take()`` deserializes the whole batch inside the call, so one sample that cannot
  be decoded (a string that is not UTF-8, a truncated buffer) raises out of ``take()`` and the
  rest of the batch, already removed from the reader, is lost. ``ddspy_take`` returns each
  sample's CDR bytes and SampleInfo, so each one is deserialized on its own.
* :func:`write_serialized` (``_clayer.ddspy_write``): writes bytes that are already CDR: the
  publishing fast path (``DdsPublisher.publish_serialized``, bytes of
  ``transport/fast_cdr.py``; the public ``DataWriter.write`` type-checks and serializes a
  message object itself), a malformed
  sample in a test, or recorded bytes re-published unchanged.
* :func:`sample_serializer` (``DataWriter._use_version_2``): the bytes ``DataWriter.write``
  would write for a message, for a publisher whose messages a publish tap also receives.
* :func:`delete_entity` / :func:`delete_participant` (``Entity._entities``, ``Entity._delete``,
  ``Entity._ref``): the public API deletes an entity only when Python collects it (and not at
  all at interpreter exit); a node must leave the graph at once, as an rclpy node does, so
  entities are deleted explicitly, and the children a participant takes with it are forgotten so
  that their finalisers do not delete stale handles.

Everything else in the transport uses the public API: the executor, for one, attaches its
conditions with ``WaitSet.attach`` and, since ``WaitSet.wait`` says only how many fired, asks
each one ``triggered`` (test_transport_private_api checks that no other module touches
cyclonedds internals).
"""

from typing import Any, List, Tuple

from cyclonedds._clayer import ddspy_take, ddspy_write
from cyclonedds.core import (
    DDSException,
    Entity,
    InstanceState,
    SampleState,
    ViewState,
)

ANY_STATE = SampleState.Any | ViewState.Any | InstanceState.Any


def take_serialized(reader, count: int) -> List[Tuple[bytes, Any]]:
    """
    Take up to ``count`` samples of ``reader`` without deserializing them.

    :return: ``(cdr_bytes, sample_info)`` pairs; the bytes start with the 4-byte encapsulation
        header; for ``sample_info.valid_data == False`` they hold the key only.
    :raises DDSException: when Cyclone refuses the take.
    """
    found = ddspy_take(reader._ref, ANY_STATE, count)
    if isinstance(found, int):
        raise DDSException(found, f'Occurred while taking data in {reader!r}')
    return found


def take(reader, count: int, decode=None) -> Tuple[List[Any], List[Exception]]:
    """
    Take up to ``count`` samples and deserialize each one on its own.

    ``decode(data)`` replaces the data type's ``deserialize`` when given (a faster decoder of
    the same type).

    Invalid samples (``valid_data`` false: a writer disposed or went away) are skipped. A sample
    whose bytes cannot be decoded costs only itself.

    :return: ``(samples, errors)``: the decoded samples, each with its ``sample_info``
        attribute set like ``DataReader.take()`` does, and one exception per sample that could
        not be decoded.
    """
    decode = reader.topic.data_type.deserialize if decode is None else decode
    samples, errors = [], []
    for data, info in take_serialized(reader, count):
        if not info.valid_data:
            continue
        try:
            sample = decode(data)
        except Exception as exc:  # noqa: BLE001 - any malformed input, whatever it trips
            errors.append(exc)
            continue
        sample.sample_info = info
        samples.append(sample)
    return samples, errors


def write_serialized(writer, data: bytes) -> None:
    """
    Write ``data`` (CDR with its 4-byte encapsulation header) as one sample of ``writer``.

    :raises DDSException: when Cyclone refuses the write.
    """
    ret = ddspy_write(writer._ref, bytes(data))
    if ret < 0:
        raise DDSException(ret, f'Occurred while writing serialized data in {writer!r}')


def serialized_writer(writer):
    """
    Return ``write(data)``: :func:`write_serialized` bound to ``writer``, for a hot loop.

    The writer's handle is looked up once here; ``write.count`` is a one-element list holding
    how many samples ``write`` wrote.
    """
    ref = writer._ref
    count = [0]

    def write(data: bytes) -> None:
        if type(data) is not bytes:
            data = bytes(data)
        if ddspy_write(ref, data) < 0:
            write_serialized(writer, data)    # raises with Cyclone's error
        count[0] += 1
    write.count = count
    return write


def sample_serializer(writer):
    """
    Return ``serialize(sample)`` -> the bytes ``writer.write(sample)`` would write.

    As ``DataWriter.write`` makes them (its private ``_use_version_2``, padded to 4 bytes), so
    that a publisher whose messages are also handed on (a publish tap) serializes each message
    once and writes those bytes with :func:`serialized_writer`.
    """
    use_version_2 = writer._use_version_2

    def serialize(sample) -> bytes:
        data = sample.serialize(use_version_2=use_version_2)
        return data.ljust((len(data) + 3) & ~3, b'\0')
    return serialize


def delete_entity(entity: Entity) -> None:
    """Delete a DDS entity now (not at garbage collection), exactly once."""
    ref = getattr(entity, '_ref', None)
    if ref is not None and Entity._entities.get(ref) is entity:
        del Entity._entities[ref]
        entity._delete(ref)


def delete_participant(participant: Entity) -> None:
    """Delete a participant with everything it owns, now, and forget its children."""
    for entity in list(Entity._entities.values()):
        if entity is not participant and _owned_by(entity, participant):
            del Entity._entities[entity._ref]
    delete_entity(participant)


def _owned_by(entity: Entity, participant: Entity) -> bool:
    try:
        return entity.participant == participant
    except Exception:  # noqa: BLE001 - entities of deleted participants raise
        return False
