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
ROS QoS profiles and endpoint USER_DATA as rmw_cyclonedds (Jazzy ``rmw_node.cpp``) writes them.

XCDR1 only, autodispose off, ``typehash=`` in every endpoint's USER_DATA.
"""

from typing import Any, Dict, Optional

from cyclonedds.qos import Policy, Qos

from vehicle_msgs_py import types as msg_types
from vehicle_sim.transport.qos import KEEP_ALL, QosProfile, RELIABLE, TRANSIENT_LOCAL

INFINITE_NS = 0x7FFFFFFFFFFFFFFF
ZERO_HASH = 'RIHS01_' + '0' * 64


def userdata_tokens(qos: Optional[Qos]) -> Dict[str, str]:
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


def dds_qos(profile: QosProfile, user_data: bytes, writer: bool) -> Qos:
    """Map a ROS QoS profile to DDS QoS like rmw_cyclonedds ``create_readwrite_qos``."""
    if profile.history == KEEP_ALL:
        history = Policy.History.KeepAll
    else:
        history = Policy.History.KeepLast(max(1, profile.depth))
    policies = [
        history,
        (Policy.Reliability.Reliable(max_blocking_time=INFINITE_NS)
         if profile.reliability == RELIABLE else Policy.Reliability.BestEffort),
        Policy.DataRepresentation(use_cdrv0_representation=True),
        Policy.Userdata(data=user_data),
    ]
    if profile.durability == TRANSIENT_LOCAL:
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
    return dds_qos(profile, endpoint_user_data(ros_type, **tokens), writer)
