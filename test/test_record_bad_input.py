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
Bad input to the recording commands: broken files, unwritable paths, a disk that fills up.

A broken file given to ``bag info`` or ``play`` gives one line naming the file and the fault
and exit 1, no traceback; a path that cannot be written is refused before anything starts
(exit 2); a disk that fills while recording stops the recording with an error on the node's
log, the simulation goes on, and the file keeps what was written before.
"""

import errno
import os
import re
import subprocess
import sys

from conftest import peer_env
import pytest

pytest.importorskip('mcap', reason="recording needs the mcap package (the 'record' extra)")

from vehicle_sim.recording.bag_reader import iter_messages, read_info  # noqa: E402
from vehicle_sim.recording.bag_writer import BagWriter, RecordingError  # noqa: E402
from vehicle_sim.recording.recorder import record_node  # noqa: E402
from vehicle_sim.ros.automobile_node import AutomobileNode, NODE_NAME  # noqa: E402
from vehicle_sim.transport import create_node  # noqa: E402

VEHICLE_SIM = os.path.join(os.path.dirname(sys.executable), 'vehicle-sim')
CLI_TIMEOUT_S = 60.0


def vehicle_sim(*args):
    return subprocess.run([VEHICLE_SIM, *args], env=peer_env(), capture_output=True, text=True,
                          timeout=CLI_TIMEOUT_S)


def _record(path, steps, namespace, opener=None, chunk_size=None):
    node = create_node(NODE_NAME, args=['rt', '--ros-args', '-r', f'__ns:={namespace}',
                                        '-p', 'synchronous:=true'], transport='dds')
    # Smaller chunks than rosbag2's 1 MiB: several of them in a short run.
    recorder = record_node(node, path, opener=opener, chunk_size=chunk_size)
    app = AutomobileNode(node=node)
    try:
        app.vehicles[''].logic.set_cruising_speed_kmh(30.0)
        time_s = app.step(steps)
    finally:
        error = recorder.close()
        app.close()
    return recorder, error, time_s


@pytest.fixture(scope='module')
def good(tmp_path_factory):
    path = str(tmp_path_factory.mktemp('bad') / 'good.mcap')
    _, error, _ = _record(path, 300, '/rt_bad', chunk_size=64 * 1024)
    assert error is None
    return path


def _one_line_error(result, *words):
    assert result.returncode == 1, (result.stdout, result.stderr)
    lines = result.stderr.strip().splitlines()
    assert len(lines) == 1, result.stderr
    assert 'Traceback' not in result.stderr
    for word in words:
        assert word in lines[0]
    return lines[0]


def test_truncated_file_is_one_line_error_for_bag_info_and_play(good, tmp_path):
    data = open(good, 'rb').read()
    cut = tmp_path / 'cut.mcap'
    cut.write_bytes(data[:len(data) * 2 // 3])
    line = _one_line_error(vehicle_sim('bag', 'info', str(cut)), str(cut), 'cut short')
    # Where the cut falls depends on the recording: inside a record's header or its body.
    assert re.search(r'cut short at byte \d+: (a record header at byte \d+ is incomplete|the '
                     r'record at byte \d+ \(opcode 0x[0-9a-f]{2}\) needs \d+ more bytes)', line)
    _one_line_error(vehicle_sim('play', str(cut)), str(cut), 'cut short')


def test_corrupted_chunk_is_one_line_error_for_play(good, tmp_path):
    info = read_info(good)
    assert info.chunk_count >= 2
    data = bytearray(open(good, 'rb').read())
    middle = len(data) // 3             # inside the compressed data of a chunk
    data[middle:middle + 64] = bytes(64)
    broken = tmp_path / 'broken.mcap'
    broken.write_bytes(bytes(data))
    line = _one_line_error(vehicle_sim('play', str(broken), '--rate', '100'), str(broken),
                           'not a readable MCAP recording')
    assert 'Traceback' not in line


def test_corrupted_summary_and_other_files_are_one_line_errors_for_bag_info(good, tmp_path):
    data = bytearray(open(good, 'rb').read())
    summary = bytes(data)
    footer_start = len(summary) - 8 - 29    # the footer record before the closing magic
    wrecked = bytearray(summary)
    wrecked[footer_start + 9:footer_start + 17] = (len(summary) * 3).to_bytes(8, 'little')
    cases = {
        'summary.mcap': bytes(wrecked),                         # summary offset past the end
        'text.mcap': b'not a recording at all\n',
        'empty.mcap': b'',
        'magic_only.mcap': summary[:8],
    }
    for name, content in cases.items():
        path = tmp_path / name
        path.write_bytes(content)
        result = vehicle_sim('bag', 'info', str(path))
        _one_line_error(result, str(path))
    missing = tmp_path / 'missing.mcap'
    _one_line_error(vehicle_sim('bag', 'info', str(missing)), str(missing), 'cannot open')


class FillingDisk:
    """An unbuffered file on a disk with ``free`` bytes: a write past them fails (ENOSPC)."""

    def __init__(self, path, free):
        self._file = open(path, 'wb', buffering=0)
        self.free = free
        self.failures = 0

    def write(self, data):
        if self._file.tell() + len(data) > self.free:
            self.failures += 1
            raise OSError(errno.ENOSPC, os.strerror(errno.ENOSPC))
        return self._file.write(data)

    def __getattr__(self, name):
        return getattr(self._file, name)


def test_full_disk_stops_the_recording_the_simulation_goes_on_the_file_stays_readable(
        tmp_path, capfd):
    path = str(tmp_path / 'full.mcap')
    disks = []

    def opener(name):
        disks.append(FillingDisk(name, 150_000))
        return disks[0]

    recorder, error, time_s = _record(path, 1000, '/rt_full', opener=opener,
                                      chunk_size=64 * 1024)
    assert time_s == pytest.approx(10.0)                # the simulation went on to the end
    assert disks[0].failures == 1                       # no write tried after the failure
    assert 'No space left on device' in error and path in error
    assert 'No space left on device' in capfd.readouterr().err     # the node's log says it
    info = read_info(path)
    assert not info.complete and info.chunk_count >= 1
    assert 0 < info.message_count < 18000
    assert info.topic('/clock').count > 0
    read = sum(1 for _ in iter_messages(path))
    assert read == info.message_count
    result = vehicle_sim('bag', 'info', path)
    assert result.returncode == 0, result.stderr
    assert 'no summary' in result.stdout


def test_unwritable_paths_are_refused_before_anything_starts(tmp_path):
    folder = tmp_path / 'a_folder'
    folder.mkdir()
    missing = tmp_path / 'no' / 'such' / 'x.mcap'
    for args, words in ((('run', '--no-status', '--record', str(missing)), 'does not exist'),
                        (('run', '--no-status', '--record', str(folder)), 'is a folder'),
                        (('record', '-a', '-o', str(folder), '--duration', '1'), 'is a folder'),
                        (('scenario', 'scenarios/stop_before_obstacle.yaml', '--record',
                          str(folder)), 'is a folder')):
        result = subprocess.run([VEHICLE_SIM, *args], env=peer_env(), capture_output=True,
                                text=True, timeout=CLI_TIMEOUT_S,
                                cwd=os.path.dirname(os.path.dirname(__file__)))
        assert result.returncode == 2, (args, result.stderr)
        assert words in result.stderr and 'Traceback' not in result.stderr
        assert 'ready' not in result.stderr and 'scenario' not in result.stdout
    assert not missing.parent.exists()

    def refuse(path):
        raise PermissionError(errno.EACCES, os.strerror(errno.EACCES), path)
    with pytest.raises(RecordingError, match='cannot create it: Permission denied'):
        BagWriter(str(tmp_path / 'x.mcap'), opener=refuse)


def test_record_needs_topics_or_all_and_play_checks_its_options(good):
    result = vehicle_sim('record', '--duration', '1')
    assert result.returncode == 2 and 'TOPICS' in result.stderr
    result = vehicle_sim('play', good, '--rate', '0')
    assert result.returncode == 1 and 'rate 0: must be > 0' in result.stderr
    result = vehicle_sim('play', good, '--start', '100')
    assert result.returncode == 1 and 'past the end' in result.stderr
    result = vehicle_sim('play', good, '--topics', '/nope')
    assert result.returncode == 1 and 'no topic /nope in the recording' in result.stderr
