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
Playing a recording back: each topic republished with its recorded QoS at its recorded pace.

As ``ros2 bag play``: a publisher per recorded topic with the QoS its recorded publishers
offered (:func:`.qos_text.playback_profile`), the messages' bytes published as they were
recorded, spaced by their log times divided by the rate; ``clock_hz`` publishes ``/clock``
from the recorded time at that wall-clock rate (``ros2 bag play --clock``), in place of a
recorded ``/clock`` topic.
"""

import time
from typing import Callable, Dict, Optional, Sequence

from vehicle_sim.recording import qos_text
from vehicle_sim.recording.bag_reader import BagInfo, iter_messages, read_info
from vehicle_sim.recording.bag_writer import RecordingError
from vehicle_sim.transport.qos import QosProfile

CLOCK_TOPIC = '/clock'
CLOCK_TYPE = 'rosgraph_msgs/msg/Clock'
# Reliable, depth 1: best-effort and reliable /clock readers both match.
CLOCK_QOS = QosProfile(depth=1)
# The longest the player waits in one spin [s].
SPIN_SLICE_S = 0.05


class Player:
    """
    Republish a recording on a node.

    :param node: a transport NodePort.
    :param path: the MCAP file.
    :param rate: playback speed (2.0: twice as fast).
    :param start_s: skip the first ``start_s`` seconds of the recording.
    :param topics: only these topics (None: all).
    :param clock_hz: publish /clock at this rate from the recorded time (None: do not).
    :raises RecordingError: for a broken file, a topic not recorded, a start past the end, a
        rate or clock rate <= 0, or a file in another profile than ROS 2's.
    """

    def __init__(self, node, path: str, rate: float = 1.0, start_s: float = 0.0,
                 topics: Optional[Sequence[str]] = None, clock_hz: Optional[float] = None,
                 warn: Callable[[str], None] = print):
        if not rate > 0.0:
            raise RecordingError(f'rate {rate:g}: must be > 0')
        if clock_hz is not None and not clock_hz > 0.0:
            raise RecordingError(f'clock rate {clock_hz:g} Hz: must be > 0')
        if not start_s >= 0.0:
            raise RecordingError(f'start {start_s:g} s: must be >= 0')
        self.info: BagInfo = read_info(path)
        info = self.info
        if info.profile != 'ros2':
            raise RecordingError(f'{path}: profile {info.profile!r}, not a ROS 2 recording')
        recorded = [t.name for t in info.topics]
        if topics:
            missing = [t for t in topics if t not in recorded]
            if missing:
                raise RecordingError(f'{path}: no topic {", ".join(missing)} in the recording '
                                     f'(recorded: {", ".join(recorded)})')
        if start_s * 1e9 > info.duration_ns:
            raise RecordingError(f'start {start_s:g} s: past the end of {path} '
                                 f'({info.duration_ns / 1e9:g} s long)')
        self.node = node
        self.path = path
        self.rate = rate
        self.start_s = start_s
        self.clock_hz = clock_hz
        self.published = 0
        self.counts: Dict[str, int] = {}
        self._publishers = {}
        wanted = set(topics) if topics else set(recorded)
        if clock_hz is not None:
            wanted.discard(CLOCK_TOPIC)
        for topic in info.topics:
            if topic.name not in wanted:
                continue
            if topic.message_encoding != 'cdr':
                warn(f'{topic.name}: message encoding {topic.message_encoding!r}, not cdr: '
                     'not played')
                continue
            try:
                qos = qos_text.playback_profile(topic.offered_qos_profiles)
            except qos_text.QosTextError as error:
                raise RecordingError(f'{path}: topic {topic.name}: offered_qos_profiles: '
                                     f'{error}') from None
            try:
                self._publishers[topic.name] = node.create_publisher(topic.ros_type,
                                                                     topic.name, qos)
            except Exception as error:  # noqa: BLE001 - a type this transport cannot make
                warn(f'{topic.name}: {error}: not played')
                continue
            self.counts[topic.name] = 0
        self._clock = None
        if clock_hz is not None:
            self._clock = node.create_publisher(CLOCK_TYPE, CLOCK_TOPIC, CLOCK_QOS)
            self._clock_msg = node.msg(CLOCK_TYPE)
            self._time_msg = node.msg('builtin_interfaces/msg/Time')

    @property
    def topics(self):
        """The topics played."""
        return sorted(self._publishers)

    def _publish_clock(self, time_ns: int) -> None:
        self._clock.publish(self._clock_msg(clock=self._time_msg(
            sec=time_ns // 1_000_000_000, nanosec=time_ns % 1_000_000_000)))

    def play(self, stop: Callable[[], bool] = lambda: False, loop: bool = False) -> int:
        """
        Play the recording (again and again with ``loop``) until it ends or ``stop()``.

        :return: the number of messages published.
        :raises RecordingError: when the file turns out broken midway.
        """
        while True:
            self._play_once(stop)
            if not loop or stop():
                return self.published

    def _play_once(self, stop) -> None:
        node = self.node
        start_ns = self.info.start_ns
        if start_ns is None:
            return
        first_ns = start_ns + int(round(self.start_s * 1e9))
        wall0 = time.monotonic()
        clock_period = 1.0 / self.clock_hz if self.clock_hz else None
        next_clock = wall0
        rate = self.rate

        def recorded_now() -> int:
            return first_ns + int((time.monotonic() - wall0) * rate * 1e9)

        messages = iter_messages(self.path, topics=list(self._publishers), start_ns=first_ns)
        for topic, log_ns, _, data in messages:
            due = wall0 + (log_ns - first_ns) / 1e9 / rate
            while True:
                now = time.monotonic()
                if clock_period is not None and now >= next_clock:
                    self._publish_clock(min(recorded_now(), log_ns))
                    next_clock += clock_period
                    if next_clock < now:    # fell behind: no burst of old clocks
                        next_clock = now + clock_period
                if now >= due or stop():
                    break
                wait = due - now
                if clock_period is not None:
                    wait = min(wait, max(0.0, next_clock - now))
                node.spin_once(min(wait, SPIN_SLICE_S))
            if stop():
                return
            self._publishers[topic.name].publish_serialized(data)
            self.counts[topic.name] += 1
            self.published += 1
        if self._clock is not None:
            self._publish_clock(self.info.end_ns)
