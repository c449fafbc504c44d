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

"""Unit tests of the transport's pure parts: ROS arguments, names, QoS, env, selection (no DDS)."""

import pytest

from vehicle_sim.transport import ros_args, selection
from vehicle_sim.transport.dds import domain_config
from vehicle_sim.transport.errors import TransportError
from vehicle_sim.transport.names import resolve_name
from vehicle_sim.transport.parameter_types import run_validator
from vehicle_sim.transport.qos import (
    as_qos,
    BEST_EFFORT,
    QOS_CLOCK,
    QOS_ROSOUT,
    QOS_SENSOR_DATA,
    QOS_TF,
    QOS_TF_STATIC,
    QosProfile,
    TRANSIENT_LOCAL,
)
from vehicle_sim.transport.ros_args import (
    params_file_overrides,
    parse_ros_args,
    rosout_wanted,
    without_rosout_flags,
)


def test_ros_args_param_values_are_read_as_yaml_like_rcl():
    args = parse_ros_args(['run', '--ros-args', '-p', 'gain:=2.5', '-p', 'count:=3',
                           '-p', 'on:=true', '--param', 'name:=car', '-p', 'xs:=[1.0, 2]',
                           '-p', "quoted:='7'"])
    assert args.non_ros_args == ['run']
    assert args.parameter_overrides('n', '/') == {
        'gain': 2.5, 'count': 3, 'on': True, 'name': 'car', 'xs': [1.0, 2.0], 'quoted': '7'}


def test_ros_args_later_sources_win_and_node_prefix_limits_scope():
    args = parse_ros_args(['--ros-args', '-p', 'a:=1', '-p', 'other:a:=5', '-p', 'a:=2',
                           '-p', 'me:b:=3', '--', 'tail'])
    assert args.parameter_overrides('me', '/') == {'a': 2, 'b': 3}
    assert args.parameter_overrides('other', '/') == {'a': 2}
    assert args.non_ros_args == ['tail']


def test_ros_args_rosout_flag_is_read_inside_ros_args_only_and_the_last_wins():
    assert rosout_wanted(None) and rosout_wanted(['pytest', '-q'])
    assert not rosout_wanted(['--ros-args', '--disable-rosout-logs'])
    assert rosout_wanted(['--ros-args', '--disable-rosout-logs', '--enable-rosout-logs'])
    assert not rosout_wanted(['--ros-args', '--log-level', 'warn', '--disable-rosout-logs',
                              '-p', 'a:=1'])
    # outside --ros-args it is the program's own argument, as rcl reads it
    assert rosout_wanted(['prog', '--disable-rosout-logs'])
    assert rosout_wanted(['prog', '--ros-args', '--disable-rosout-logs', '--', '--x']) is False
    # a command line the parser refuses: the transport reports it, in its own words
    assert rosout_wanted(['--ros-args', '-p'])
    assert without_rosout_flags(['--ros-args', '--disable-rosout-logs', '--log-level', 'warn']) \
        == ['--ros-args', '--log-level', 'warn']


def test_ros_args_node_and_namespace_remaps_apply():
    args = parse_ros_args(['--ros-args', '-r', '__node:=car', '-r', '__ns:=/fleet'])
    assert args.node_name('vehicle') == 'car'
    assert args.namespace('car', '') == '/fleet'


def test_ros_args_topic_remap_resolves_both_sides():
    args = parse_ros_args(['--ros-args', '-r', 'cmd:=/other/cmd'])
    assert args.remap_name('/ns/cmd', 'n', '/ns') == '/other/cmd'
    assert args.remap_name('/ns/odom', 'n', '/ns') == '/ns/odom'


@pytest.mark.parametrize('bad', [['--ros-args', '-p', 'novalue'], ['--ros-args', '-p'],
                                 ['--ros-args', '--bogus', 'x'],
                                 ['--ros-args', '--log-level', 'loud']])
def test_ros_args_malformed_raise_transport_error(bad):
    with pytest.raises(TransportError):
        parse_ros_args(bad)


def test_params_file_node_wildcard_and_nested_namespace_sections(tmp_path):
    path = tmp_path / 'p.yaml'
    path.write_text(
        '/**:\n  ros__parameters:\n    use_sim_time: true\n    rate: 10\n'
        'vehicle:\n  ros__parameters:\n    rate: 50\n    limits:\n      v_max: 30.0\n'
        '/fleet:\n  car:\n    ros__parameters:\n      rate: 20\n'
        '/*/car:\n  ros__parameters:\n    color: red\n')
    args = parse_ros_args(['--ros-args', '--params-file', str(path), '-p', 'rate:=99'])
    assert args.parameter_overrides('vehicle', '/') == {
        'use_sim_time': True, 'rate': 99, 'limits.v_max': 30.0}
    assert params_file_overrides(
        {'vehicle': {'ros__parameters': {'rate': 1}}}, '/fleet/vehicle') == {}
    assert args.parameter_overrides('car', '/fleet') == {
        'use_sim_time': True, 'rate': 99, 'color': 'red'}


def test_params_file_missing_raises_naming_the_file(tmp_path):
    with pytest.raises(TransportError, match='nope.yaml'):
        parse_ros_args(['--ros-args', '--params-file', str(tmp_path / 'nope.yaml')])


@pytest.mark.parametrize('name, expected', [
    ('/abs/x', '/abs/x'), ('rel', '/car/rel'), ('~/private', '/car/node/private'),
    ('a/b', '/car/a/b')])
def test_resolve_name_expands_like_rcl(name, expected):
    assert resolve_name(name, '/car', 'node') == expected


def test_resolve_name_in_root_namespace_has_no_double_slash():
    assert resolve_name('x', '', 'node') == '/x'
    assert resolve_name('~/x', '/', 'node') == '/node/x'


@pytest.mark.parametrize('bad', ['', 'a//b', 'x/', '1abc', 'sp ace', '/a/9b'])
def test_resolve_name_rejects_invalid_names(bad):
    with pytest.raises(TransportError):
        resolve_name(bad, '/', 'node')


def test_qos_presets_match_rmw_qos_profiles():
    assert (QOS_ROSOUT.depth, QOS_ROSOUT.durability, QOS_ROSOUT.lifespan_s) == (
        1000, TRANSIENT_LOCAL, 10.0)
    assert (QOS_SENSOR_DATA.depth, QOS_SENSOR_DATA.reliability) == (
        5, BEST_EFFORT)
    assert (QOS_CLOCK.depth, QOS_CLOCK.reliability) == (1, BEST_EFFORT)
    assert (QOS_TF_STATIC.depth, QOS_TF_STATIC.durability) == (
        1, TRANSIENT_LOCAL)
    assert as_qos(7) == QosProfile(depth=7)
    assert as_qos('tf') is QOS_TF
    with pytest.raises(TransportError, match='valid'):
        as_qos('fast')


@pytest.mark.parametrize('read, env', [
    (domain_config.domain_id, {'ROS_DOMAIN_ID': 'x'}),
    (domain_config.domain_id, {'ROS_DOMAIN_ID': '300'}),
    (domain_config.discovery_range, {'ROS_AUTOMATIC_DISCOVERY_RANGE': 'PLANET'})])
def test_bad_dds_environment_raises_transport_error(read, env):
    with pytest.raises(TransportError):
        read(env)


def test_domain_id_defaults_to_zero():
    assert domain_config.domain_id({}) == 0


def test_selection_unknown_transport_lists_valid_values():
    with pytest.raises(TransportError, match='auto, rclpy, dds'):
        selection.transport_name('zenoh')


def test_selection_auto_picks_dds_without_rclpy(monkeypatch):
    monkeypatch.setattr(selection, 'rclpy_available', lambda: False)
    assert selection.transport_name('auto') == 'dds'
    with pytest.raises(TransportError, match='not importable'):
        selection.transport_name('rclpy')


def test_parameter_validator_reasons():
    assert run_validator(lambda v: None, 1.0) is None
    assert run_validator(lambda v: 'too big', 1.0) == 'too big'

    def raises(value):
        raise ValueError('bad value')

    assert run_validator(raises, 1.0) == 'bad value'


def test_read_only_reason_is_worded_like_rclpy():
    # rclpy Jazzy, Node._apply_descriptor
    assert ros_args.read_only_reason('car_model') == \
        'Trying to set a read-only parameter: car_model.'


def test_unknown_overrides_warning_names_the_stranger_a_close_match_and_every_parameter():
    warning = ros_args.unknown_overrides_warning(
        ['publish_period', 'car_model'], ['car_model', 'publish_period_ms', 'use_sim_time'])
    assert warning == (
        'ignored parameter override publish_period (did you mean publish_period_ms?): '
        'not declared by this node; its parameters: car_model, publish_period_ms, use_sim_time')


def test_unknown_overrides_warning_is_none_when_every_override_is_declared():
    assert ros_args.unknown_overrides_warning(['a'], ['a', 'b']) is None
    assert ros_args.unknown_overrides_warning([], ['a']) is None
