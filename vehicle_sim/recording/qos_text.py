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
QoS profiles as rosbag2 stores them: the ``offered_qos_profiles`` YAML text of a topic.

rosbag2 (metadata version 9, Jazzy) writes a YAML list with one profile per publisher of the
topic: ``history``, ``depth``, ``reliability``, ``durability``, ``deadline``, ``lifespan``,
``liveliness``, ``liveliness_lease_duration`` and ``avoid_ros_namespace_conventions``, the
policies named in lower case and the durations as ``{sec, nsec}`` (an infinite one as
rmw's ``RMW_DURATION_INFINITE``). Of a publisher seen on the graph, vehicle_sim's graph view
knows the reliability and the durability only: its entry says ``history: unknown, depth: 0``
(rosbag2's form of a policy it does not know).
"""

from typing import List, Optional, Sequence

import yaml

from vehicle_sim.transport.qos import (
    BEST_EFFORT,
    KEEP_LAST,
    QOS_DEFAULT,
    QosProfile,
    RELIABLE,
    TRANSIENT_LOCAL,
    VOLATILE,
)

# RMW_DURATION_INFINITE as rosbag2 writes it.
INFINITE = {'sec': 9223372036, 'nsec': 854775807}
# Depth a player's publisher gets when the recorded one is unknown (rosbag2 play's default).
PLAY_DEPTH = 10


class QosTextError(ValueError):
    """An ``offered_qos_profiles`` text that cannot be read."""


def _duration(seconds: Optional[float]) -> dict:
    if seconds is None:
        return dict(INFINITE)
    nanoseconds = int(round(seconds * 1e9))
    return {'sec': nanoseconds // 1_000_000_000, 'nsec': nanoseconds % 1_000_000_000}


def profile_entry(qos: QosProfile) -> dict:
    """Return one publisher's entry of the list, from the profile it was created with."""
    return {
        'history': qos.history,
        'depth': qos.depth,
        'reliability': qos.reliability,
        'durability': qos.durability,
        'deadline': _duration(qos.deadline_s),
        'lifespan': _duration(qos.lifespan_s),
        'liveliness': 'automatic',
        'liveliness_lease_duration': dict(INFINITE),
        'avoid_ros_namespace_conventions': qos.avoid_ros_namespace_conventions,
    }


def discovered_entry(reliable: bool, transient_local: bool) -> dict:
    """Return the entry of a publisher seen on the graph (its depth is not announced)."""
    entry = profile_entry(QosProfile(
        depth=0, reliability=RELIABLE if reliable else BEST_EFFORT,
        durability=TRANSIENT_LOCAL if transient_local else VOLATILE))
    entry['history'] = 'unknown'
    return entry


def dump(entries: Sequence[dict]) -> str:
    """Return the YAML text of the entries (rosbag2 writes an empty string for none)."""
    if not entries:
        return ''
    return yaml.safe_dump(list(entries), default_flow_style=False, sort_keys=False).strip()


def from_rosbags(profiles: Sequence) -> str:
    """
    Return the text of QoS profiles as rosbags reads them from a rosbag2 folder's metadata.

    :param profiles: rosbags' ``Qos`` tuples (enum policies, ``{sec, nsec}`` durations).
    """
    def duration(value) -> dict:
        return {'sec': value.sec, 'nsec': value.nsec}
    return dump([{
        'history': qos.history.name.lower(),
        'depth': qos.depth,
        'reliability': qos.reliability.name.lower(),
        'durability': qos.durability.name.lower(),
        'deadline': duration(qos.deadline),
        'lifespan': duration(qos.lifespan),
        'liveliness': qos.liveliness.name.lower(),
        'liveliness_lease_duration': duration(qos.liveliness_lease_duration),
        'avoid_ros_namespace_conventions': qos.avoid_ros_namespace_conventions,
    } for qos in profiles])


def _policy(value, names: Sequence[str], field: str):
    # Version 8 files name the policies by their rmw enum numbers.
    if isinstance(value, int) and not isinstance(value, bool):
        numbered = {1: names[0], 2: names[1]}
        if value in numbered:
            return numbered[value]
    if isinstance(value, str) and value.lower() in names:
        return value.lower()
    if value in (0, 3, 'system_default', 'unknown', 'best_available'):
        return None
    raise QosTextError(f'{field}: {value!r} is not one of {", ".join(names)}')


def parse(text: str) -> List[dict]:
    """
    Return the entries of an ``offered_qos_profiles`` text.

    :raises QosTextError: when it is not a YAML list of mappings.
    """
    if not text or not text.strip():
        return []
    try:
        entries = yaml.safe_load(text)
    except yaml.YAMLError as error:
        raise QosTextError(f'not YAML: {str(error).splitlines()[0]}') from None
    if not isinstance(entries, list) or not all(isinstance(e, dict) for e in entries):
        raise QosTextError('not a list of QoS profiles')
    return entries


def playback_profile(text: str) -> QosProfile:
    """
    Return the QoS a player publishes a topic with, from its recorded publishers' profiles.

    As rosbag2 play adapts them: reliable when every recorded publisher was, transient local
    when every one was, the largest recorded depth (``PLAY_DEPTH`` when none is known).

    :raises QosTextError: for an unreadable text or policy.
    """
    entries = parse(text)
    if not entries:
        return QOS_DEFAULT
    reliable = all(_policy(e.get('reliability'), (RELIABLE, BEST_EFFORT), 'reliability')
                   in (RELIABLE, None) for e in entries)
    latched = all(_policy(e.get('durability'), (TRANSIENT_LOCAL, VOLATILE), 'durability')
                  == TRANSIENT_LOCAL for e in entries)
    depths = [e.get('depth') for e in entries
              if isinstance(e.get('depth'), int) and e.get('depth') > 0]
    return QosProfile(depth=max(depths) if depths else PLAY_DEPTH, history=KEEP_LAST,
                      reliability=RELIABLE if reliable else BEST_EFFORT,
                      durability=TRANSIENT_LOCAL if latched else VOLATILE)
