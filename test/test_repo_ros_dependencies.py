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
On a ROS machine the nodes import every message package whose types they name.

So each one is a ``package.xml`` dependency (rosdep installs it), comes with rclpy, or is one of
the Autoware vehicle-interface packages that the README has installed by hand; and the README's
``apt`` line of the ROS 2 Jazzy set-up names each dependency that ``ros-jazzy-ros-base`` lacks.
Found on a real Jazzy: a world with traffic did not start on rclpy without
autoware_perception_msgs, which no ``package.xml`` line asked for.
"""

from pathlib import Path
import re
import xml.etree.ElementTree as ElementTree

REPO = Path(__file__).resolve().parent.parent
# 'pkg/msg/Name' or 'pkg/srv/Name' in a string literal
ROS_TYPE = re.compile(r"""['"]([a-z][a-z0-9_]*)/(?:msg|srv)/[A-Z][A-Za-z0-9]*['"]""")
# rclpy's own dependencies (its parameter services, time, the graph)
WITH_RCLPY = {'builtin_interfaces', 'rcl_interfaces', 'rmw_dds_common'}
# The bridge's and autoware_automobile's types: installed by hand (autoware_auto_control_msgs
# has no Jazzy release), README "On a ROS 2 Jazzy machine"
AUTOWARE_NODES_ONLY = {'autoware_control_msgs', 'autoware_vehicle_msgs',
                       'autoware_auto_control_msgs'}
# The message packages of ros-jazzy-ros-base (REP 2001's ros_core and ros_base: common_interfaces,
# rcl_interfaces, geometry2's tf2_msgs, unique_identifier_msgs) that package.xml names
IN_ROS_BASE = {'std_msgs', 'std_srvs', 'geometry_msgs', 'nav_msgs', 'sensor_msgs',
               'visualization_msgs', 'rosgraph_msgs', 'tf2_msgs', 'unique_identifier_msgs'}
# built in the workspace from this repository (export-interfaces)
OURS = {'vehicle_msgs'}


def named_packages():
    """Return {package: first file naming one of its types} over the vehicle_sim sources."""
    found = {}
    for path in sorted((REPO / 'vehicle_sim').rglob('*.py')):
        for match in ROS_TYPE.finditer(path.read_text(encoding='utf-8')):
            found.setdefault(match.group(1), path.relative_to(REPO).as_posix())
    return found


def exec_depends():
    root = ElementTree.parse(REPO / 'package.xml').getroot()
    return {element.text.strip() for element in root.iter('exec_depend')}


def jazzy_section():
    text = (REPO / 'README.md').read_text(encoding='utf-8')
    start = text.index('## On a ROS 2 Jazzy machine')
    end = text.find('\n## ', start + 1)
    return text[start:end if end > 0 else len(text)]


def test_every_message_package_the_nodes_name_is_installed_on_a_ros_machine():
    named = named_packages()
    # the scan finds what it must: the types of the node, the perception and the bridge
    assert {'ackermann_msgs', 'autoware_perception_msgs', 'radar_msgs', 'vision_msgs',
            'autoware_vehicle_msgs', 'nav_msgs'} <= set(named), sorted(named)
    missing = {package: where for package, where in named.items()
               if package not in exec_depends() | WITH_RCLPY | AUTOWARE_NODES_ONLY}
    assert not missing, f'named in the code, not a package.xml exec_depend: {missing}'


def test_the_readme_installs_what_ros_base_lacks_and_the_autoware_packages():
    section = jazzy_section()
    for package in sorted(exec_depends() - IN_ROS_BASE - OURS):
        if not package.endswith('_msgs'):
            continue       # rclpy, rviz2, robot_state_publisher, the python3-* keys
        apt_name = 'ros-jazzy-' + package.replace('_', '-')
        assert apt_name in section, f"{package}: no {apt_name} in the README's Jazzy set-up"
    for package in sorted(AUTOWARE_NODES_ONLY):
        assert package in section, package
