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
JUnit XML of a scenario run, in the shape pytest's ``--junitxml`` writes (xunit2).

``<testsuites>`` holds one ``<testsuite>`` (name = the scenario's name; ``tests``, ``failures``,
``errors``, ``skipped``, ``time``, ``timestamp``, ``hostname``) with the run's properties (seed,
simulated time, odometry hash, determinism; ``recording``, the MCAP file of a recorded run) and
one ``<testcase>`` per criterion (``classname`` = ``scenario.<name>``, ``name`` = the
criterion's name, ``time``): a failed criterion carries ``<failure message=...>`` (its text
names the recording), and every test case's ``<system-out>`` gives the measured value. A
run that failed by itself (a controller that raised, a process that died) adds a test case
``run`` with ``<error message=...>``.
"""

from datetime import datetime, timezone
import socket
from xml.etree import ElementTree


def _value_text(result):
    if result.value is None:
        return 'no value measured'
    value = result.value
    shown = f'{value:.6g}' if isinstance(value, float) else str(value)
    return f'{shown} {result.unit}'.strip()


def junit_tree(result, timestamp=None):
    """
    Build the JUnit XML tree of a ScenarioResult.

    :param result: ScenarioResult.
    :param timestamp: the run's start (datetime); now when None.
    :return: ElementTree.ElementTree.
    """
    spec = result.spec
    criteria = result.criteria
    errors = 1 if result.error else 0
    failures = sum(not c.passed for c in criteria)
    when = (timestamp or datetime.now(timezone.utc)).isoformat()
    suites = ElementTree.Element('testsuites', name='vehicle_sim scenarios')
    suite = ElementTree.SubElement(suites, 'testsuite', {
        'name': spec.name, 'errors': str(errors), 'failures': str(failures), 'skipped': '0',
        'tests': str(len(criteria) + errors), 'time': f'{result.wall_time_s:.3f}',
        'timestamp': when, 'hostname': socket.gethostname()})
    properties = ElementTree.SubElement(suite, 'properties')
    for name, value in (('file', spec.source), ('seed', result.seed),
                        ('sim_time_s', f'{result.sim_time_s:g}'),
                        ('odometry_sha256', result.odometry_sha256),
                        ('deterministic', str(result.deterministic).lower()),
                        ('runs', result.runs)):
        ElementTree.SubElement(properties, 'property', name=name, value=str(value))
    recording = getattr(result, 'recording', None)
    if recording:
        ElementTree.SubElement(properties, 'property', name='recording', value=recording)
    seen = f'; recording: {recording} (vehicle-sim play {recording})' if recording else ''
    # Every criterion is judged over the whole run: the run's time is shared out evenly.
    share = result.wall_time_s / max(1, len(criteria))
    classname = f'scenario.{spec.name}'
    for criterion in criteria:
        case = ElementTree.SubElement(suite, 'testcase', classname=classname,
                                      name=criterion.name, time=f'{share:.3f}')
        if not criterion.passed:
            failure = ElementTree.SubElement(case, 'failure', message=criterion.detail)
            failure.text = f'{criterion.kind}: {criterion.detail}{seen}'
        out = ElementTree.SubElement(case, 'system-out')
        text = f'{criterion.kind}: {_value_text(criterion)}; {criterion.detail}'
        if result.spread and criterion.name in result.spread:
            low, high = result.spread[criterion.name]
            text += f'; over {result.runs} runs: min {low}, max {high}'
        out.text = text
    if result.error:
        case = ElementTree.SubElement(suite, 'testcase', classname=classname, name='run',
                                      time='0.000')
        error = ElementTree.SubElement(case, 'error',
                                       message=result.error.splitlines()[0][:200])
        error.text = result.error + seen
    return ElementTree.ElementTree(suites)


def write_junit(result, path, timestamp=None):
    """Write the JUnit XML of a ScenarioResult to ``path`` (UTF-8); return path."""
    tree = junit_tree(result, timestamp)
    ElementTree.indent(tree)
    tree.write(path, encoding='utf-8', xml_declaration=True)
    return path
