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
What the benchmarks share: a DDS domain of their own, CPU time of a process, the verdict text.

A benchmark on a shared machine must not meet other people's nodes: :func:`use_free_domain`
keeps discovery on loopback and, unless ``ROS_DOMAIN_ID`` is set, picks a domain id in 150..230
where a probe participant sees no other participant.
"""

import os
import random
import subprocess
import sys

_PROBE = """
import sys, time
from cyclonedds.builtin import BuiltinDataReader, BuiltinTopicDcpsParticipant
from vehicle_sim.transport import dds
from cyclonedds.domain import DomainParticipant
dds.ensure_domain()
participant = DomainParticipant(int(sys.argv[1]))
reader = BuiltinDataReader(participant, BuiltinTopicDcpsParticipant)
time.sleep(1.5)
others = {s.key for s in reader.take(N=256) if s.key != participant.guid}
print(len(others))
"""


def use_free_domain(tries: int = 8) -> int:
    """Set ROS_AUTOMATIC_DISCOVERY_RANGE=LOCALHOST and a free ROS_DOMAIN_ID; return the id."""
    os.environ.setdefault('ROS_AUTOMATIC_DISCOVERY_RANGE', 'LOCALHOST')
    if os.environ.get('ROS_DOMAIN_ID'):
        return int(os.environ['ROS_DOMAIN_ID'])
    repo = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
    candidates = random.sample(range(150, 231), tries)
    for domain in candidates:
        env = dict(os.environ, ROS_DOMAIN_ID=str(domain),
                   PYTHONPATH=repo + os.pathsep + os.environ.get('PYTHONPATH', ''))
        found = subprocess.run([sys.executable, '-c', _PROBE, str(domain)], env=env,
                               capture_output=True, text=True, timeout=60)
        if found.returncode == 0 and found.stdout.strip() == '0':
            break
    os.environ['ROS_DOMAIN_ID'] = str(domain)
    return domain


def process_cpu_s(pid) -> float:
    """Return utime + stime [s] of a process, from /proc/<pid>/stat."""
    with open(f'/proc/{pid}/stat', encoding='ascii') as stream:
        fields = stream.read().rsplit(')', 1)[1].split()
    return (int(fields[11]) + int(fields[12])) / os.sysconf('SC_CLK_TCK')
