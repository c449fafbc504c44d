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
Pins the cyclonedds-python 11.0.1 behaviour that transport/dds/cyclone_private.py relies on.

If an upgrade changes any of it, these tests fail first; the module docstring says why each
internal is used. One participant in this process; samples go through Cyclone's local delivery.
"""

from importlib.metadata import version

from automobile_helpers import wait_for
from cyclonedds.core import DDSException, ReadCondition
from cyclonedds.domain import DomainParticipant
from cyclonedds.pub import DataWriter
from cyclonedds.sub import DataReader
from cyclonedds.topic import Topic
import pytest

from vehicle_msgs_py import types as msg_types
from vehicle_sim.transport import dds
from vehicle_sim.transport.dds import cyclone_private
from vehicle_sim.transport.dds.domain_config import domain_id
from vehicle_sim.transport.qos import QOS_DEFAULT

pytestmark = pytest.mark.transport

STRING = msg_types.message_type('std_msgs/msg/String')
# 'abc' in a std_msgs/String: 4-byte encapsulation header, uint32 length 4, 'abc\0'.
GOOD = STRING(data='abc').serialize()
# The same sample with a string that is not UTF-8.
BAD = GOOD.replace(b'abc', b'\xff\xfe\xc3')


@pytest.fixture(scope='module')
def participant():
    dds.ensure_domain()
    created = DomainParticipant(domain_id())
    yield created
    cyclone_private.delete_participant(created)


@pytest.fixture
def endpoints(participant, request):
    topic = Topic(participant, f'rt/cyclone_private_{request.node.name[:40]}', STRING)
    qos = dds.dds_qos(QOS_DEFAULT, b'', writer=False)
    reader = DataReader(participant, topic, qos=qos)
    writer = DataWriter(participant, topic, qos=dds.dds_qos(QOS_DEFAULT, b'', True))
    assert wait_for(lambda: writer.get_matched_subscriptions())
    return reader, writer


def _wait_readable(reader):
    condition = ReadCondition(reader, cyclone_private.ANY_STATE)
    assert wait_for(lambda: condition.triggered)


def test_the_pinned_cyclonedds_version_is_installed():
    assert version('cyclonedds') == '11.0.1'


def test_public_take_loses_the_whole_batch_on_one_undecodable_sample(endpoints):
    # Why cyclone_private.take exists: DataReader.take() decodes inside the call.
    reader, writer = endpoints
    cyclone_private.write_serialized(writer, BAD)
    writer.write(STRING(data='after'))
    _wait_readable(reader)   # local delivery: both samples are in the reader
    with pytest.raises(UnicodeDecodeError):
        reader.take(N=16)
    assert reader.take(N=16) == []   # the good sample went with the failed take


def test_take_serialized_returns_cdr_bytes_with_header_and_sample_info(endpoints):
    reader, writer = endpoints
    writer.write(STRING(data='abc'))
    _wait_readable(reader)
    ((data, info),) = cyclone_private.take_serialized(reader, 16)
    assert data == GOOD
    assert info.valid_data is True
    # Services find the request writer (and its clientid) from the publication handle.
    assert reader.get_matched_publication_data(info.publication_handle).key == writer.guid


def test_take_decodes_each_sample_on_its_own(endpoints):
    reader, writer = endpoints
    writer.write(STRING(data='before'))
    cyclone_private.write_serialized(writer, BAD)
    writer.write(STRING(data='after'))
    samples, errors = [], []

    def all_three():
        got, failed = cyclone_private.take(reader, 16)
        samples.extend(got)
        errors.extend(failed)
        return len(samples) + len(errors) == 3

    assert wait_for(all_three)
    assert [s.data for s in samples] == ['before', 'after']
    assert all(s.sample_info.valid_data for s in samples)
    assert [type(e) for e in errors] == [UnicodeDecodeError]


def test_write_serialized_delivers_the_exact_bytes(endpoints):
    reader, writer = endpoints
    cyclone_private.write_serialized(writer, GOOD)
    _wait_readable(reader)
    assert [data for data, _ in cyclone_private.take_serialized(reader, 16)] == [GOOD]


def test_serialized_writer_delivers_the_exact_bytes_and_refuses_after_delete(participant):
    topic = Topic(participant, 'rt/cyclone_private_bound_writer', STRING)
    reader = DataReader(participant, topic, qos=dds.dds_qos(QOS_DEFAULT, b'', False))
    writer = DataWriter(participant, topic, qos=dds.dds_qos(QOS_DEFAULT, b'', True))
    assert wait_for(lambda: writer.get_matched_subscriptions())
    write = cyclone_private.serialized_writer(writer)
    write(GOOD)
    write(BAD)
    _wait_readable(reader)
    assert wait_for(lambda: len(reader.get_matched_publications()) == 1)
    found = []
    assert wait_for(lambda: found.extend(cyclone_private.take_serialized(reader, 16)) or
                    len(found) == 2)
    assert [data for data, _ in found] == [GOOD, BAD]
    cyclone_private.delete_entity(writer)
    with pytest.raises(DDSException):
        write(GOOD)


def test_delete_participant_deletes_it_and_its_children_now():
    dds.ensure_domain()
    doomed = DomainParticipant(domain_id())
    topic = Topic(doomed, 'rt/cyclone_private_doomed', STRING)
    writer = DataWriter(doomed, topic)
    cyclone_private.delete_participant(doomed)
    with pytest.raises(Exception):
        writer.write(STRING(data='x'))   # its handle is gone
