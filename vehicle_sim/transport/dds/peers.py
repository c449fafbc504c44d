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
Who else is on the domain: a participant's DDS vendor, and the warnings about peers.

The peers warned about are those we cannot fully serve: another distribution's graph layout,
Fast DDS service clients.

The vendor comes from the first two bytes of the participant GUID: the RTPS specification
recommends that a GUID prefix start with the vendor id, and Cyclone DDS (01.10) and Fast DDS
(01.0f) do so; other implementations may not, so any other value reads as ``unknown``.
"""

from typing import Optional, Sequence

from vehicle_msgs_py import distro

CYCLONE = 'Eclipse Cyclone DDS'
FAST_DDS = 'eProsima Fast DDS'
UNKNOWN = 'unknown'

# OMG's DDSI-RTPS vendor ids (the ones a ROS 2 graph meets).
VENDORS = {
    b'\x01\x01': 'RTI Connext DDS',
    b'\x01\x03': 'OpenDDS',
    b'\x01\x06': 'Twin Oaks CoreDX',
    b'\x01\x0f': FAST_DDS,
    b'\x01\x10': CYCLONE,
    b'\x01\x11': 'GurumNetworks GurumDDS',
    b'\x01\x12': 'RustDDS',
}

FIX_FAST_DDS_CLIENT = ('set RMW_IMPLEMENTATION=rmw_cyclonedds_cpp on the ROS side, or run '
                       'this node on rclpy (VEHICLE_SIM_TRANSPORT=rclpy on a ROS machine)')


def vendor_of(guid: Optional[bytes]) -> str:
    """Return the DDS implementation named by a participant (or endpoint) GUID's prefix."""
    if not guid or len(guid) < 2:
        return UNKNOWN
    return VENDORS.get(bytes(guid[:2]), UNKNOWN)


def guid_text(guid: bytes) -> str:
    """Return a GUID as rmw_cyclonedds prints gids: dotted hex bytes."""
    return '.'.join(f'{b:02x}' for b in guid)


def other_distro_warning(theirs: str, ours: str, participant: bytes, domain_id: int,
                         listing: bool = False) -> str:
    """
    Return the one warning about a participant that speaks the other distribution.

    :param listing: for the graph view of ``vehicle-sim list`` (which has no nodes of its own)
        rather than a node.
    """
    sizes = f'{distro.GID_SIZES[theirs]}-byte Gids in ros_discovery_info'
    if listing:
        effect = (f'its nodes are listed here, but nodes started in this environment speak '
                  f'{distro.title(ours)} and the two cannot list each other')
    elif theirs == distro.HUMBLE:
        effect = ("it would misread this process's node list (its `ros2 node list` would fail "
                  'for every node on the domain), so this process no longer announces its nodes')
    else:
        effect = "it does not see this process's nodes"
    return (f'a ROS 2 {distro.title(theirs)} participant ({sizes}, participant '
            f'{guid_text(participant)}) is on domain {domain_id}, but this process speaks '
            f'{distro.title(ours)}: {effect}; set {distro.ENV_VAR}={theirs} to speak '
            f'{distro.title(theirs)}')


def undecodable_info_warning(domain_id: int, reason: str) -> str:
    """Return the one warning about a ros_discovery_info sample that fits no layout."""
    return (f'a ros_discovery_info sample on domain {domain_id} fits neither the Humble nor the '
            f"Jazzy layout ({reason}); its participant's nodes are not listed")


def foreign_server_note(service: str, vendor: str, participant: bytes) -> str:
    """Return why a server that does not run rmw_cyclonedds never answers this client."""
    who = 'runs Fast DDS' if vendor == FAST_DDS else f'does not run rmw_cyclonedds ({vendor})'
    return (f'the server of {service} (participant {guid_text(participant)}) {who}: it cannot '
            'read requests that carry the rmw_cyclonedds request header and never answers '
            'them; set RMW_IMPLEMENTATION=rmw_cyclonedds_cpp for the server, or run this '
            'client on rclpy (VEHICLE_SIM_TRANSPORT=rclpy on a ROS machine)')


def fast_dds_client_warning(services: Sequence[str], vendor: str, participant: bytes) -> str:
    """Return the warning about a client whose requests Cyclone cannot deliver to ``services``."""
    who = 'runs Fast DDS' if vendor == FAST_DDS else f'does not run rmw_cyclonedds ({vendor})'
    what = f'service {services[0]}' if len(services) == 1 else \
        f'services {", ".join(services)}'
    return (f'{what}: a client (participant {guid_text(participant)}) {who}; its requests carry '
            'no rmw_cyclonedds request header, so Cyclone DDS drops them and the client gets no '
            f'answer: {FIX_FAST_DDS_CLIENT}')
