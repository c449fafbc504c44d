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
The diff_robot node's names: ``ros2 run vehicle_sim diff_robot`` is ``/diff_robot``.

Its topics and its service are private names, so they stay under ``/diff_robot`` (as
docs/autoware.md lists them) and follow the node when it is renamed or put in a namespace.
Built in-process on the embedded transport, never spun.
"""

import os

from conftest import REPO_ROOT
import pytest

from vehicle_sim.ros.diff_robot_node import DiffRobotNode, ROBOT_NODE_PARAMETERS
from vehicle_sim.transport.ros_args import load_params_file, params_file_overrides

pytestmark = pytest.mark.transport

ROBOT_TOPICS = ['differential_command', 'wheel_velocities', 'cmd_vel', 'joint_states', 'odom',
                'ground_truth/odom', 'robot_description', 'collision']


def _names(robot):
    topics = {pub.topic_name for pub in robot._pub.values()}
    topics |= {sub.topic_name for sub in robot._subs}
    return topics, robot._time_step_srv.service_name


@pytest.mark.parametrize('args, fqn', [
    (['diff_robot'], '/diff_robot'),
    (['diff_robot', '--ros-args', '-r', '__ns:=/fleet'], '/fleet/diff_robot'),
    (['diff_robot', '--ros-args', '-r', '__node:=robot2'], '/robot2'),
])
def test_diff_robot_node_name_prefixes_its_topics_service_and_frames(args, fqn):
    robot = DiffRobotNode(args, transport='dds', parameter_overrides={'synchronous': True})
    try:
        assert robot.node.get_fully_qualified_name() == fqn
        topics, service = _names(robot)
        assert topics == {f'{fqn}/{name}' for name in ROBOT_TOPICS} | {'/clock', '/tf',
                                                                        '/tf_static'}
        assert service == f'{fqn}/robot/time_step'
        assert (robot.odom_frame, robot.base_frame) == (f'{fqn[1:]}/odom',
                                                        f'{fqn[1:]}/base_link')
    finally:
        robot.destroy()


def test_shipped_params_file_configures_the_plain_diff_robot_node():
    data = load_params_file(os.path.join(REPO_ROOT, 'config', 'diff_robot.yaml'))
    assert set(params_file_overrides(data, '/diff_robot')) == {
        spec.key for spec in ROBOT_NODE_PARAMETERS}
