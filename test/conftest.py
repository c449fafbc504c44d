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
Shared test set-up.

Before anything imports cyclonedds, DDS traffic of this test run is confined to the loopback
interface (``ROS_AUTOMATIC_DISCOVERY_RANGE=LOCALHOST``) and to a ROS_DOMAIN_ID of its own, derived
from the pid (1..101), so that concurrent runs do not see each other. Both are kept when set.

Waits wait for their event, bounded generously. The few wall-clock budgets that cannot (a
command's own ``--wait``, a case timeout that a hanging case must reach, a bound on how soon a
process ends) and pytest-timeout's per-test limit are multiplied by ``TIME_FACTOR``, read here
from ``VEHICLE_SIM_TEST_TIME_FACTOR`` (default 1) for a slow or heavily loaded machine.
"""

import json
import math
import os
import subprocess
import sys
import threading

import pytest

REPO_ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
if REPO_ROOT not in sys.path:
    sys.path.insert(0, REPO_ROOT)

os.environ.setdefault('ROS_AUTOMATIC_DISCOVERY_RANGE', 'LOCALHOST')
os.environ.setdefault('ROS_DOMAIN_ID', str(1 + os.getpid() % 101))

PEER_SCRIPT = os.path.join(REPO_ROOT, 'test', 'transport_peer.py')
# Generous bound for anything that waits on another process (start-up, discovery).
PEER_START_TIMEOUT_S = 60.0
TIME_FACTOR_ENV = 'VEHICLE_SIM_TEST_TIME_FACTOR'


def time_factor(text):
    """Return the factor of the wall-clock budgets from its environment variable's text."""
    try:
        factor = float(text)
    except ValueError:
        factor = math.nan
    if not 1.0 <= factor < math.inf:
        raise pytest.UsageError(f'{TIME_FACTOR_ENV} = {text!r}: must be a number >= 1 (how '
                                'many times longer than usual the wall-clock budgets are)')
    return factor


TIME_FACTOR = time_factor(os.environ.get(TIME_FACTOR_ENV, '1'))


def scaled_s(seconds):
    """Return a wall-clock budget [s] that no event can replace, times ``TIME_FACTOR``."""
    return seconds * TIME_FACTOR


def _rclpy_initialised():
    rclpy = sys.modules.get('rclpy')
    return rclpy is not None and rclpy.ok()


def _check_rclpy_left_alone(initialised, what):
    if not initialised and _rclpy_initialised():
        sys.modules['rclpy'].try_shutdown()     # so that the tests after it are not failed too
        pytest.fail(f"{what} left rclpy's default context initialised: a later rclpy.init() in "
                    'this process would fail with "Context.init() must only be called once"; '
                    'shut it down (rclpy.try_shutdown()), or build the node without initialising '
                    'it (RclpyNode runs on a context of its own where rclpy is not initialised)')


# Where ROS 2 is sourced, nodes run on rclpy (transport auto). The default context belongs to a
# process's node main and to the user's own rclpy.init(): a node built in process runs on a
# context of its own where rclpy is not initialised (docs/transport.md), and a node main called in
# process shuts the default context down when it returns. A test, or a module's fixtures, that
# leave it initialised fail here, naming it.
@pytest.fixture(autouse=True, scope='module')
def _rclpy_default_context_left_by_a_module():
    initialised = _rclpy_initialised()
    yield
    _check_rclpy_left_alone(initialised, 'this module (its fixtures)')


@pytest.fixture(autouse=True)
def _rclpy_default_context_left_by_a_test():
    initialised = _rclpy_initialised()
    yield
    _check_rclpy_left_alone(initialised, 'this test')


def pytest_configure(config):
    config.addinivalue_line(
        'markers', 'transport: cross-process tests over the embedded Cyclone DDS transport')


def pytest_collection_modifyitems(config, items):
    """Multiply pytest-timeout's per-test limit by ``TIME_FACTOR`` (a marker's too)."""
    if TIME_FACTOR == 1.0 or not config.pluginmanager.hasplugin('timeout'):
        return
    limit = config.getoption('timeout', None) or os.environ.get('PYTEST_TIMEOUT') \
        or config.getini('timeout')
    for item in items:
        marker = item.get_closest_marker('timeout')
        own = marker.args[0] if marker is not None and marker.args else \
            marker.kwargs.get('timeout') if marker is not None else limit
        if own:
            item.add_marker(pytest.mark.timeout(float(own) * TIME_FACTOR), append=False)


def peer_env(transport=None):
    """
    Return the environment for a peer subprocess: this run's DDS settings, the repo first.

    :param transport: its nodes' transport (``VEHICLE_SIM_TRANSPORT``: 'dds' for a test of the
        embedded transport's own behaviour, also where rclpy is importable); None: the run's.
    """
    env = dict(os.environ)
    if transport is not None:
        env['VEHICLE_SIM_TRANSPORT'] = transport
    env['PYTHONPATH'] = REPO_ROOT + os.pathsep + env.get('PYTHONPATH', '')
    env['PYTHONUNBUFFERED'] = '1'
    return env


class PeerProcess:
    """A running peer subprocess and the JSON line it printed when ready."""

    def __init__(self, args, script=PEER_SCRIPT):
        self.proc = subprocess.Popen(
            [sys.executable, script, *args], env=peer_env(), stdout=subprocess.PIPE,
            stderr=subprocess.PIPE, text=True)
        self.info = None
        self.stderr_lines = []
        self._ready = threading.Event()
        threading.Thread(target=self._read_stdout, daemon=True).start()
        threading.Thread(target=self._read_stderr, daemon=True).start()
        if not self._ready.wait(PEER_START_TIMEOUT_S) or self.info is None:
            self.stop()
            raise RuntimeError('peer did not start:\n' + ''.join(self.stderr_lines))

    def _read_stdout(self):
        for line in self.proc.stdout:
            if self.info is None and line.startswith('{'):
                self.info = json.loads(line)
                self._ready.set()
        self._ready.set()

    def _read_stderr(self):
        for line in self.proc.stderr:
            self.stderr_lines.append(line)

    def terminate(self, timeout_s=PEER_START_TIMEOUT_S):
        """Send SIGTERM and return the exit status."""
        self.proc.terminate()
        return self.proc.wait(timeout_s)

    def stop(self):
        if self.proc.poll() is None:
            self.proc.kill()
            self.proc.wait()


def stop_processes(procs, timeout_s=PEER_START_TIMEOUT_S):
    """SIGTERM every process still running, then SIGKILL any that outlives ``timeout_s``."""
    for proc in procs:
        if proc.poll() is None:
            proc.terminate()
    for proc in procs:
        try:
            proc.wait(timeout_s)
        except subprocess.TimeoutExpired:
            proc.kill()
            proc.wait()


def sleeper_process(*_args, **_kwargs):
    """Start a stand-in for a node process (a fixture test checks that it gets stopped)."""
    return subprocess.Popen([sys.executable, '-c', 'import time; time.sleep(600)'],
                            stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, text=True)


@pytest.fixture(scope='module')
def spawn_peer():
    """Return a function starting peer subprocesses; they are stopped after the module."""
    peers = []

    def spawn(*args):
        peer = PeerProcess(list(args))
        peers.append(peer)
        return peer

    try:
        yield spawn
    finally:
        stop_processes([peer.proc for peer in peers])


@pytest.fixture
def make():
    """Give the Gym tests ``make(**kwargs)``: Drive-v0 environments, closed after the test."""
    import gymnasium
    made = []

    def _make(**kwargs):
        env = gymnasium.make('vehicle_sim/Drive-v0', **kwargs)
        made.append(env)
        return env

    yield _make
    for env in made:
        env.close()
