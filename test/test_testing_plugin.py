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
The pytest plugin ``vehicle_sim.testing``: the user example runs and passes in a fresh pytest.

The child pytest gets a ROS_DOMAIN_ID of its own (102..201, outside conftest's 1..101) so that
its simulations cannot meet the peers of this run.
"""

import os
import subprocess
import sys

from conftest import peer_env, REPO_ROOT, sleeper_process
import pytest

EXAMPLE = os.path.join(REPO_ROOT, 'examples', 'test_user_example.py')
# Generous bound for a child pytest starting three simulations.
CHILD_TIMEOUT_S = 240.0

pytestmark = pytest.mark.transport


def _child_pytest(cwd, *args):
    """Run pytest in a child process (the installed plugin) on a domain of its own."""
    env = peer_env()
    env['ROS_DOMAIN_ID'] = str(102 + os.getpid() % 100)
    return subprocess.run(
        [sys.executable, '-m', 'pytest', '-p', 'no:cacheprovider', *args],
        cwd=cwd, env=env, capture_output=True, text=True, timeout=CHILD_TIMEOUT_S)


def test_user_example_passes_with_the_plugin():
    result = _child_pytest(REPO_ROOT, EXAMPLE, '-q')
    assert result.returncode == 0, result.stdout[-4000:] + result.stderr[-2000:]
    assert '3 passed' in result.stdout


def test_user_example_passes_when_the_installed_plugin_is_also_named_with_p():
    # What users of other pytest plugins type; it used to fail with "Plugin already registered
    # under a different name" and run no test.
    result = _child_pytest(REPO_ROOT, EXAMPLE, '-q', '-p', 'vehicle_sim.testing')
    assert result.returncode == 0, result.stdout[-4000:] + result.stderr[-2000:]
    assert '3 passed' in result.stdout


def test_plugin_named_in_a_conftest_is_the_installed_one(tmp_path):
    (tmp_path / 'conftest.py').write_text("pytest_plugins = ['vehicle_sim.testing']\n",
                                          encoding='utf-8')
    (tmp_path / 'test_fixture.py').write_text(
        'def test_fixture_is_there(request):\n'
        "    assert request.config.pluginmanager.has_plugin('vehicle_sim.testing')\n",
        encoding='utf-8')
    result = _child_pytest(tmp_path, '-q')
    assert result.returncode == 0, result.stdout[-4000:] + result.stderr[-2000:]
    assert '1 passed' in result.stdout


def test_stamp_helpers_read_header_and_clock_stamps():
    from vehicle_msgs_py import message_type
    from vehicle_sim.testing import stamp_ns, stamp_s
    clock = message_type('rosgraph_msgs/msg/Clock')()
    clock.clock.sec, clock.clock.nanosec = 2, 500_000_000
    value = message_type('vehicle_msgs/msg/Float64Stamped')()
    value.header.stamp.sec = 3
    assert stamp_ns(clock) == 2_500_000_000
    assert stamp_s(value) == 3.0


def test_automobile_sim_stops_its_node_process_when_its_client_node_fails(monkeypatch):
    import types

    from vehicle_sim import testing
    started = []

    def popen(*_args, **_kwargs):
        started.append(sleeper_process())
        return started[-1]

    class FailingClient:
        def __init__(self, *_args, **_kwargs):
            raise OSError('the client node could not start')

    monkeypatch.setattr(testing, 'subprocess', types.SimpleNamespace(
        Popen=popen, STDOUT=subprocess.STDOUT, TimeoutExpired=subprocess.TimeoutExpired))
    monkeypatch.setattr(testing, 'AutomobileClient', FailingClient)
    with pytest.raises(RuntimeError, match='did not start'):
        testing.AutomobileSim()
    (proc,) = started
    assert proc.poll() is not None


def test_plugin_collects_scenario_files_one_test_per_criterion(tmp_path):
    # scenario_*.yaml files become tests (one per criterion); run_scenario() serves test code.
    for name, controller in (('scenario_stop.yaml', 'lidar_stop_controller.py'),
                             ('scenario_blind.yaml', 'blind_controller.py')):
        text = open(os.path.join(REPO_ROOT, 'scenarios', 'stop_before_obstacle.yaml')).read()
        text = text.replace('../examples/lidar_stop_controller.py',
                            os.path.join(REPO_ROOT, 'examples', controller))
        (tmp_path / name).write_text(text, encoding='utf-8')
    (tmp_path / 'test_use.py').write_text(
        'from vehicle_sim.testing import run_scenario\n\n\n'
        'def test_run_scenario_returns_the_values():\n'
        "    result = run_scenario('scenario_stop.yaml')\n"
        "    assert result.passed and result.criterion('no_collision').value == 0\n",
        encoding='utf-8')
    result = _child_pytest(tmp_path, '-v', str(tmp_path))
    out = result.stdout
    assert result.returncode == 1, out[-4000:] + result.stderr[-2000:]
    # the blind controller fails no_collision and clearance (it touched the wall: 0 m)
    assert '2 failed, 7 passed' in out, out[-4000:]
    assert 'scenario_blind.yaml::no_collision FAILED' in out
    assert 'scenario_blind.yaml::clearance FAILED' in out
    assert 'scenario_stop.yaml::no_collision PASSED' in out
    assert 'no_collision: 1 collision: wall' in out


def test_client_topics_subscribes_clock_and_the_named_topics_only_and_latest_is_exact():
    from vehicle_sim.testing import AutomobileSim, stamp_s
    sim = AutomobileSim(topics=('current_speed', '/automobile/current_speed'))
    try:
        car = sim.client
        assert car.subscribed_topics == ('/clock', '/automobile/current_speed')
        start_s = car.sim_time()
        assert car.call('set_cruising_speed', 30.0).success
        end_s = car.step(50)
        assert end_s - start_s == pytest.approx(0.5, abs=1e-9)
        speed = car.latest('current_speed')
        assert stamp_s(speed) == pytest.approx(end_s, abs=1e-9)
        assert speed.data > 0.0
        for _ in range(3):
            now_s = car.step()
            assert stamp_s(car.latest('current_speed')) == pytest.approx(now_s, abs=1e-9)
        # A topic outside the list, first used after a step, missed that step's message: said
        # at once (not after the timeout) and naming the way out.
        with pytest.raises(TimeoutError, match='first used after the last step.*topics='):
            car.latest('throttle', timeout_s=600.0)
        assert car.subscribed_topics[-1] == '/automobile/throttle'
    finally:
        sim.close()


def test_client_calls_every_service_the_node_serves_sim_reset_and_sim_pause_too():
    from vehicle_sim.testing import AutomobileSim
    from vehicle_sim.transport.dds.graph import demangle_service, GraphView
    sim = AutomobileSim(topics=('current_speed',))
    try:
        car = sim.client
        assert car.call('set_cruising_speed', 30.0).success
        car.step(100)
        assert car.latest('current_speed').data > 5.0
        assert car.call('/sim/reset').success
        car.step()
        assert car.latest('current_speed').data == pytest.approx(0.0, abs=0.05)
        # Reached the node: a synchronous simulation refuses to pause (its clients step it).
        assert car.call('/sim/pause', True).success is False
        # One table: every service the node announces (its own, not rcl_interfaces' parameter
        # services) is a name the client takes. Every ROS 2 node's own services: the
        # rcl_interfaces parameter services, and on rclpy (Jazzy) type_description_interfaces'
        # get_type_description.
        node_services = {'/automobile/' + name for name in (
            'describe_parameters', 'get_parameters', 'get_parameter_types', 'list_parameters',
            'set_parameters', 'set_parameters_atomically', 'get_type_description')}
        expected = node_services - {'/automobile/get_type_description'}

        def served_by_the_node(graph):
            # the request readers of the node's process (the one serving /sim/pause); the
            # client's request writers are on the graph too, and may be discovered first
            readers = [e for e in graph.endpoints()
                       if not e.is_writer and e.dds_topic.startswith('rq/')]
            node = {e.participant for e in readers
                    if demangle_service(e.dds_topic) == '/sim/pause'}
            return {demangle_service(e.dds_topic) for e in readers
                    if e.participant in node} - {None}

        with GraphView() as graph:
            graph.wait_until(lambda: expected <= served_by_the_node(graph), 30.0)
            served = served_by_the_node(graph)
        assert expected <= served
        served -= node_services
        assert '/sim/reset' in served and '/automobile/set_gear' in served
        for name in served:
            assert car._find(name, car._itf.NODE_SERVICES, 'service')[1] == name
    finally:
        sim.close()


def test_client_topics_refuses_unknown_names_and_a_single_string_before_starting_a_node():
    from vehicle_sim.testing import AutomobileClient
    with pytest.raises(KeyError, match='did you mean: /automobile/current_speed'):
        AutomobileClient(topics=('curent_speed',))
    with pytest.raises(TypeError, match='sequence of topic names'):
        AutomobileClient(topics='current_speed')


def test_plugin_topics_from_the_ini_option_and_the_marker(tmp_path):
    (tmp_path / 'pytest.ini').write_text(
        '[pytest]\nvehicle_sim_topics = throttle brake_intensity\n', encoding='utf-8')
    (tmp_path / 'test_topics.py').write_text(
        'import pytest\n\n\n'
        'def test_ini(automobile_node):\n'
        '    assert automobile_node.client.subscribed_topics == (\n'
        "        '/clock', '/automobile/throttle', '/automobile/brake_intensity')\n\n\n"
        "@pytest.mark.vehicle_sim(topics=('odom',))\n"
        'def test_marker(automobile_node):\n'
        "    assert automobile_node.client.subscribed_topics == ('/clock', '/odom')\n"
        '    automobile_node.client.step()\n'
        "    assert automobile_node.client.latest('odom').header.frame_id == 'odom'\n",
        encoding='utf-8')
    result = _child_pytest(tmp_path, '-q', str(tmp_path))
    assert result.returncode == 0, result.stdout[-4000:] + result.stderr[-2000:]
    assert '2 passed' in result.stdout
