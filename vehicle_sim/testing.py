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
pytest plugin: test ROS 2 code against the simulator with plain pytest, no launch_testing.

Enable it with ``-p vehicle_sim.testing`` (or ``pytest_plugins = ['vehicle_sim.testing']`` in a
``conftest.py``); an installed vehicle_sim registers it as the pytest11 plugin of the same name,
``vehicle_sim.testing``, so naming it again is harmless.

The ``automobile_node`` fixture starts the automobile node in **synchronous** mode in a
subprocess and yields an :class:`AutomobileSim` whose ``client`` is a node on the selected
transport (``VEHICLE_SIM_TRANSPORT``: rclpy on a ROS 2 machine, else the embedded Cyclone DDS
transport). Time only moves when the test calls ``client.step(...)``, so assertions on published
values and on ``/clock`` are deterministic::

    def test_car_moves(automobile_node):
        car = automobile_node.client
        assert car.call('set_cruising_speed', 30.0).success
        car.step(200)                                   # 200 basic steps = 2.0 s
        assert car.latest('current_speed').data > 0.0

Options: ``@pytest.mark.vehicle_sim(car='TeslaModel3', namespace='/sim',
params={'friction': 1.2}, topics=('current_speed',))``, or
``@pytest.mark.parametrize('automobile_node', ['BmwX5'], indirect=True)`` for the car model;
``--vehicle-sim-car`` sets the default model and the ini option ``vehicle_sim_topics`` the
default topics. ``topics`` names the topics the client subscribes to before the first step
(``/clock`` is always one); the default is every Float64Stamped topic. Fewer topics make each
step cheaper (every subscribed topic is a delivery per step); a topic first used later is
subscribed then and misses what was published before (``latest()`` says so at once).

Scenario files: ``run_scenario(path, seed=None)`` runs one and returns its result (each
criterion's verdict and measured value), and files named ``scenario_*.yaml`` are collected as
tests, one per criterion (docs/scenarios.md)::

    def test_stops_before_the_wall():
        result = run_scenario('scenarios/stop_before_obstacle.yaml')
        assert result.passed
        assert result.criterion('reach_goal').value < 5.0     # seconds

Isolation: unless already set, the plugin confines DDS traffic to the loopback interface
(``ROS_AUTOMATIC_DISCOVERY_RANGE=LOCALHOST``) and picks a ROS_DOMAIN_ID from the pid, before
any DDS participant exists; the node subprocess inherits both.

This module is the plugin (hooks, the fixture, :class:`AutomobileSim`); the client itself is
:mod:`vehicle_sim.automobile_client`, and its names are importable from here too.
"""

import os
import signal
import subprocess
import sys
import tempfile
from typing import Any, Dict, Iterable, Optional

import pytest

from vehicle_sim.automobile_client import AutomobileClient, stamp_ns, stamp_s

__all__ = ['AutomobileClient', 'AutomobileSim', 'automobile_node', 'run_scenario', 'stamp_ns',
           'stamp_s']

# Generous bound for the node subprocess to come up (PyBullet import, discovery).
START_TIMEOUT_S = 60.0
STOP_TIMEOUT_S = 10.0
DEFAULT_CAR = 'Car'
# ini option: the topics the fixture's client subscribes to before the first step.
TOPICS_INI = 'vehicle_sim_topics'


# --------------------------------------------------------------------------------------------
# Plugin hooks

def pytest_addoption(parser):
    group = parser.getgroup('vehicle_sim')
    group.addoption('--vehicle-sim-car', default=None, metavar='MODEL',
                    help=f'default car model of the automobile_node fixture ({DEFAULT_CAR})')
    parser.addini(TOPICS_INI, type='args', default=None,
                  help='topics the automobile_node client subscribes to before the first step '
                       '(/clock always; default: every Float64Stamped topic)')


def pytest_configure(config):
    os.environ.setdefault('ROS_AUTOMATIC_DISCOVERY_RANGE', 'LOCALHOST')
    os.environ.setdefault('ROS_DOMAIN_ID', str(1 + os.getpid() % 101))
    config.addinivalue_line(
        'markers', 'vehicle_sim(car=None, namespace=None, params=None, topics=None): options '
                   'of the automobile_node fixture (car model, node namespace, node parameters, '
                   'topics subscribed before the first step)')


def pytest_collect_file(parent, file_path):
    from fnmatch import fnmatch

    from vehicle_sim.scenarios.pytest_items import PATTERN, ScenarioFile
    if fnmatch(file_path.name, PATTERN):
        return ScenarioFile.from_parent(parent, path=file_path)
    return None


def run_scenario(path, seed=None, **options):
    """
    Run a scenario file; return its ScenarioResult (``passed``, ``criteria``, ``criterion(name)``).

    :param path: the scenario file.
    :param seed: overrides the file's seed.
    :param options: ``repeat``, ``gui`` (see vehicle_sim.scenarios.runner.run_scenario).
    """
    from vehicle_sim.scenarios.runner import run_scenario as run
    return run(path, seed=seed, **options)


# --------------------------------------------------------------------------------------------
# The node process

class AutomobileSim:
    """
    A synchronous automobile node in a subprocess and a client to drive it.

    :param car: car preset name.
    :param namespace: node namespace ('' = root: endpoints under /automobile).
    :param params: extra node parameters ``{name: value}``.
    :param transport: transport of node and client (default: ``VEHICLE_SIM_TRANSPORT``).
    :param topics: the topics the client subscribes to before the first step (see
        :class:`AutomobileClient`; None: every Float64Stamped topic).
    """

    def __init__(self, car: str = DEFAULT_CAR, namespace: str = '',
                 params: Optional[Dict[str, Any]] = None, transport: Optional[str] = None,
                 start_timeout_s: float = START_TIMEOUT_S,
                 topics: Optional[Iterable[str]] = None):
        self.car = car
        self.namespace = '/' + namespace.strip('/') if namespace.strip('/') else ''
        params = dict(params or {})
        params.setdefault('car_model', car)
        params['synchronous'] = True
        command = [sys.executable, '-m', 'vehicle_sim.ros.automobile_node', '--ros-args']
        for name, value in params.items():
            command += ['-p', f'{name}:={_ros_arg_value(value)}']
        if self.namespace:
            command += ['-r', f'__ns:={self.namespace}']
        env = dict(os.environ)
        env['PYTHONUNBUFFERED'] = '1'
        if transport:
            env['VEHICLE_SIM_TRANSPORT'] = transport
        self._log = tempfile.TemporaryFile(mode='w+')
        self.process = subprocess.Popen(command, env=env, stdout=self._log,
                                        stderr=subprocess.STDOUT, text=True)
        self.client = None
        try:
            period_ms = float(params.get('publish_period_ms', 0) or 0)
            self.client = AutomobileClient(self.namespace, transport=transport,
                                           publish_period_s=period_ms / 1000.0, topics=topics)
            self.client.wait_until_ready(start_timeout_s,
                                         alive=lambda: self.process.poll() is None)
        except BaseException as exc:
            self.close()
            raise RuntimeError(f'the automobile node did not start ({exc}); its output:\n'
                               f'{self.output()}') from exc

    def output(self) -> str:
        """Return what the node printed so far (stdout and stderr)."""
        self._log.flush()
        self._log.seek(0)
        return self._log.read()

    def close(self) -> int:
        """Leave the graph, stop the node (SIGTERM, then SIGKILL) and return its exit status."""
        if self.client is not None:
            self.client.close()
            self.client = None
        if self.process.poll() is None:
            self.process.send_signal(signal.SIGTERM)
            try:
                self.process.wait(STOP_TIMEOUT_S)
            except subprocess.TimeoutExpired:
                self.process.kill()
                self.process.wait()
        return self.process.returncode


def _ros_arg_value(value: Any) -> str:
    if isinstance(value, bool):
        return 'true' if value else 'false'
    if isinstance(value, str):
        return value if value else "''"
    return repr(value) if isinstance(value, float) else str(value)


@pytest.fixture
def automobile_node(request):
    """
    Start a synchronous automobile node in a subprocess; yield an :class:`AutomobileSim`.

    Options: marker ``vehicle_sim(car=..., namespace=..., params=..., topics=...)``; indirect
    parametrization with a car model name; ``--vehicle-sim-car``; ini ``vehicle_sim_topics``.
    """
    options: Dict[str, Any] = {}
    ini_topics = request.config.getini(TOPICS_INI)
    if ini_topics:
        options['topics'] = tuple(ini_topics)
    marker = request.node.get_closest_marker('vehicle_sim')
    if marker is not None:
        options.update(marker.kwargs)
        if marker.args:
            options.setdefault('car', marker.args[0])
    if getattr(request, 'param', None) is not None:
        param = request.param
        options.update(param if isinstance(param, dict) else {'car': param})
    options.setdefault('car', request.config.getoption('--vehicle-sim-car') or DEFAULT_CAR)
    sim = AutomobileSim(**options)
    try:
        yield sim
    finally:
        sim.close()
