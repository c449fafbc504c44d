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

"""The exported vehicle_msgs ament package is complete and parses as ROS interfaces."""

from pathlib import Path
import re
import subprocess
import sys
import xml.etree.ElementTree as ElementTree

import pytest
from rosbags.typesys import get_types_from_msg

from vehicle_msgs_py.catalog import definitions, split_service
from vehicle_msgs_py.export import export_interfaces, main

# catkin_pkg's maintainer e-mail check (package.py), which rejects the package otherwise.
REPO_ROOT = Path(__file__).resolve().parent.parent

CATKIN_EMAIL = re.compile(
    r'^[-a-zA-Z0-9_%+]+(\.[-a-zA-Z0-9_%+]+)*@[-a-zA-Z0-9%]+(\.[-a-zA-Z0-9%]+)*\.[a-zA-Z]{2,}$')

EXPECTED_FILES = {
    'msg/Float64Stamped.msg', 'msg/WheelCommand.msg', 'msg/DifferentialCommand.msg',
    'msg/Collision.msg', 'msg/LaneState.msg', 'msg/LaneInvasion.msg',
    'srv/SetFloat.srv', 'srv/GetFloat.srv', 'srv/SetInt.srv', 'srv/GetInt.srv',
    'srv/SetBool.srv', 'srv/GetBool.srv', 'srv/GetDimensions.srv', 'srv/SetPose.srv',
    'srv/SetLanePose.srv',
}


@pytest.fixture
def package_dir(tmp_path):
    return export_interfaces(tmp_path)


def _interface_files(package_dir):
    return {str(p.relative_to(package_dir)) for p in package_dir.glob('*/*') if p.is_file()}


def test_export_writes_every_vehicle_msgs_definition_and_nothing_else(package_dir):
    assert package_dir.name == 'vehicle_msgs'
    assert _interface_files(package_dir) == EXPECTED_FILES
    assert {f'{d.kind}/{d.path.name}' for d in definitions('vehicle_msgs')} == EXPECTED_FILES


def test_exported_files_parse_and_name_every_type(package_dir):
    names = set()
    for path in sorted(package_dir.glob('msg/*.msg')):
        names.update(get_types_from_msg(path.read_text(), f'vehicle_msgs/msg/{path.stem}'))
    for path in sorted(package_dir.glob('srv/*.srv')):
        request, response = split_service(path.read_text())
        for suffix, text in (('_Request', request), ('_Response', response)):
            names.update(get_types_from_msg(text, f'vehicle_msgs/msg/{path.stem}{suffix}'))
    assert names == {
        'vehicle_msgs/msg/Float64Stamped', 'vehicle_msgs/msg/WheelCommand',
        'vehicle_msgs/msg/DifferentialCommand', 'vehicle_msgs/msg/Collision',
        'vehicle_msgs/msg/LaneState', 'vehicle_msgs/msg/LaneInvasion',
        *(f'vehicle_msgs/msg/{srv}_{part}'
          for srv in ('SetFloat', 'GetFloat', 'SetInt', 'GetInt', 'SetBool', 'GetBool',
                      'GetDimensions', 'SetPose', 'SetLanePose')
          for part in ('Request', 'Response')),
    }


def test_cmakelists_generates_every_file_with_dependencies(package_dir):
    text = (package_dir / 'CMakeLists.txt').read_text()
    block = re.search(r'rosidl_generate_interfaces\((.*?)\)', text, re.DOTALL).group(1)
    assert set(re.findall(r'"([^"]+)"', block)) == EXPECTED_FILES
    # SetPose's request holds a geometry_msgs/Pose.
    assert re.search(r'DEPENDENCIES builtin_interfaces geometry_msgs std_msgs\s*$', block)
    for dep in ('ament_cmake', 'rosidl_default_generators', 'builtin_interfaces', 'std_msgs',
                'geometry_msgs'):
        assert f'find_package({dep} REQUIRED)' in text
    assert 'ament_package()' in text


def test_package_xml_is_valid_format_3_interface_package(package_dir):
    root = ElementTree.parse(package_dir / 'package.xml').getroot()
    assert root.tag == 'package' and root.get('format') == '3'
    assert root.findtext('name') == 'vehicle_msgs'
    assert CATKIN_EMAIL.match(root.find('maintainer').get('email'))
    assert [e.text for e in root.findall('buildtool_depend')] == \
        ['ament_cmake', 'rosidl_default_generators']
    assert {e.text for e in root.findall('depend')} == {'builtin_interfaces', 'geometry_msgs',
                                                        'std_msgs'}
    assert [e.text for e in root.findall('exec_depend')] == ['rosidl_default_runtime']
    assert root.findtext('member_of_group') == 'rosidl_interface_packages'
    assert root.find('export').findtext('build_type') == 'ament_cmake'


def test_export_again_removes_stale_files(package_dir):
    (package_dir / 'msg' / 'Stale.msg').write_text('int32 x\n')
    export_interfaces(package_dir.parent)
    assert _interface_files(package_dir) == EXPECTED_FILES


def test_main_exports_into_given_directory(tmp_path, capsys):
    assert main([str(tmp_path)]) == 0
    assert _interface_files(tmp_path / 'vehicle_msgs') == EXPECTED_FILES
    assert 'colcon build' in capsys.readouterr().out


def test_cli_export_needs_only_what_a_ros_machine_has(tmp_path):
    # The README's Jazzy path runs the exporter from the checkout before anything else is
    # installed: none of the embedded-transport or physics packages may be imported.
    blocked = ('cyclonedds', 'rosbags', 'pybullet')
    code = (
        'import sys\n'
        f'for name in {blocked!r}:\n'
        '    sys.modules[name] = None\n'
        'import runpy\n'
        'sys.argv = ["vehicle_sim", "export-interfaces", sys.argv[1]]\n'
        'runpy.run_module("vehicle_sim", run_name="__main__")\n')
    result = subprocess.run([sys.executable, '-c', code, str(tmp_path / 'cli')], cwd=REPO_ROOT,
                            capture_output=True, text=True, timeout=120)
    assert result.returncode == 0, result.stderr
    produced = tmp_path / 'cli' / 'vehicle_msgs'
    expected = export_interfaces(tmp_path / 'direct')
    def files(root):
        return sorted(str(p.relative_to(root)) for p in root.rglob('*') if p.is_file())

    names = files(expected)
    assert files(produced) == names
    for name in names:
        assert (produced / name).read_bytes() == (expected / name).read_bytes(), name
