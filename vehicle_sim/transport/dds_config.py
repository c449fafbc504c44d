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
Environment handling of the embedded transport: ROS_DOMAIN_ID and the discovery range.

rmw_cyclonedds (Jazzy) turns ``ROS_AUTOMATIC_DISCOVERY_RANGE`` into Cyclone settings
(ros2_wire A9.8); this module does the same and returns the XML handed to ``dds_create_domain``:

* ``LOCALHOST`` (or the deprecated ``ROS_LOCALHOST_ONLY=1`` when the range is unset): loopback
  interface, no multicast, peer 127.0.0.1 plus ``ROS_STATIC_PEERS``, ``ParticipantIndex auto``.
* ``OFF``: loopback, no multicast, only ``ROS_STATIC_PEERS``.
* ``SUBNET`` (the default): Cyclone's defaults (multicast discovery), ``ROS_STATIC_PEERS`` added.
* ``SYSTEM_DEFAULT``: Cyclone's defaults untouched.

A user's ``CYCLONEDDS_URI`` is always respected: it is read by Cyclone itself, after our fragment
(later settings win), as rmw_cyclonedds does.
"""

import os
from typing import Mapping, Optional
from xml.sax.saxutils import quoteattr

from vehicle_sim.transport.port import TransportError

RANGES = ('SUBNET', 'LOCALHOST', 'OFF', 'SYSTEM_DEFAULT')
MAX_DOMAIN_ID = 232
MAX_AUTO_PARTICIPANT_INDEX = 32


def domain_id(env: Optional[Mapping[str, str]] = None) -> int:
    """
    Return ``ROS_DOMAIN_ID`` (default 0).

    :raises TransportError: when it is not an integer in 0..232.
    """
    env = os.environ if env is None else env
    text = env.get('ROS_DOMAIN_ID', '').strip()
    if not text:
        return 0
    try:
        value = int(text)
    except ValueError:
        raise TransportError(f'ROS_DOMAIN_ID={text!r} is not an integer') from None
    if not 0 <= value <= MAX_DOMAIN_ID:
        raise TransportError(f'ROS_DOMAIN_ID={value} outside 0..{MAX_DOMAIN_ID}')
    return value


def discovery_range(env: Optional[Mapping[str, str]] = None) -> str:
    """
    Return the discovery range: one of SUBNET, LOCALHOST, OFF, SYSTEM_DEFAULT.

    :raises TransportError: for an unknown ``ROS_AUTOMATIC_DISCOVERY_RANGE``.
    """
    env = os.environ if env is None else env
    text = env.get('ROS_AUTOMATIC_DISCOVERY_RANGE', '').strip().upper()
    if not text:
        return 'LOCALHOST' if env.get('ROS_LOCALHOST_ONLY', '').strip() == '1' else 'SUBNET'
    if text not in RANGES:
        raise TransportError(
            f'ROS_AUTOMATIC_DISCOVERY_RANGE={text!r} unknown; valid: {", ".join(RANGES)}')
    return text


def static_peers(env: Optional[Mapping[str, str]] = None) -> list:
    """Return the ``ROS_STATIC_PEERS`` addresses (';'-separated)."""
    env = os.environ if env is None else env
    return [p.strip() for p in env.get('ROS_STATIC_PEERS', '').split(';') if p.strip()]


def cyclone_config(env: Optional[Mapping[str, str]] = None) -> Optional[str]:
    """
    Return the Cyclone configuration for the environment, or None for Cyclone's own defaults.

    The result is what would be put in ``CYCLONEDDS_URI``; a user's ``CYCLONEDDS_URI`` follows
    it so that the user's explicit settings win.
    """
    env = os.environ if env is None else env
    scope = discovery_range(env)
    peers = static_peers(env)
    general = ''
    discovery = ''
    if scope in ('LOCALHOST', 'OFF'):
        if scope == 'LOCALHOST':
            peers = ['127.0.0.1'] + peers
        general = ('<General><Interfaces><NetworkInterface address="127.0.0.1"/></Interfaces>'
                   '<AllowMulticast>false</AllowMulticast></General>')
        discovery = ('<ParticipantIndex>auto</ParticipantIndex>'
                     f'<MaxAutoParticipantIndex>{MAX_AUTO_PARTICIPANT_INDEX}'
                     '</MaxAutoParticipantIndex>')
    elif scope == 'SYSTEM_DEFAULT' or not peers:
        peers = []
    if peers:
        discovery += '<Peers>' + ''.join(
            f'<Peer address={quoteattr(p)}/>' for p in peers) + '</Peers>'
    parts = []
    if general or discovery:
        body = general + (f'<Discovery>{discovery}</Discovery>' if discovery else '')
        parts.append(f'<CycloneDDS><Domain id="any">{body}</Domain></CycloneDDS>')
    user = env.get('CYCLONEDDS_URI', '').strip()
    if parts and user:
        parts.append(user)
    return ','.join(parts) if parts else None
