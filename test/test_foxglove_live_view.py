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
The live view seen by Foxglove's own client library, from Node.js (test/foxglove_client.js).

The npm packages are installed by this test into pytest's cache directory (``npm install
--prefix``); without node or npm, or when the install fails (offline), the test is skipped and
says why.
"""

import json
import os
import shutil
import socket
import subprocess
import threading
import time

import pytest

pytest.importorskip('foxglove', reason="foxglove-sdk is not installed (pip install "
                                       "'vehicle_sim[foxglove]')")

from vehicle_sim.ros.automobile_node import AutomobileNode  # noqa: E402

REPO_ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
CLIENT_SCRIPT = os.path.join(REPO_ROOT, 'test', 'foxglove_client.js')
# Foxglove's client library, ROS 2 CDR reader/writer and schema parser; protobufjs reads the
# SceneUpdate (its schema is a protobuf FileDescriptorSet); ws is Node's WebSocket.
NPM_PACKAGES = ('@foxglove/ws-protocol@0.8.0', '@foxglove/rosmsg2-serialization@3.1.0',
                '@foxglove/rosmsg@5.0.5', 'protobufjs@8.8.1', 'ws@8.23.0')
NPM_INSTALL_TIMEOUT_S = 300
CLIENT_TIMEOUT_S = 90.0
CRUISING_KMH = 30.0


def free_port() -> int:
    with socket.socket() as probe:
        probe.bind(('127.0.0.1', 0))
        return probe.getsockname()[1]


@pytest.fixture(scope='module')
def node_modules(request, tmp_path_factory):
    """Return the node_modules directory holding NPM_PACKAGES (installed once per cache)."""
    node, npm = shutil.which('node'), shutil.which('npm')
    if node is None or npm is None:
        reason = "node and npm are needed to run Foxglove's client library (not found on PATH)"
        print(f'SKIP: {reason}')
        pytest.skip(reason)
    cache = getattr(request.config, 'cache', None)     # None with -p no:cacheprovider
    prefix = str(cache.mkdir('foxglove_npm') if cache is not None
                 else tmp_path_factory.mktemp('foxglove_npm'))
    stamp = os.path.join(prefix, 'installed.txt')
    wanted = '\n'.join(NPM_PACKAGES)
    if not os.path.exists(stamp) or open(stamp, encoding='utf-8').read() != wanted:
        try:
            done = subprocess.run([npm, 'install', '--prefix', prefix, '--no-audit', '--no-fund',
                                   '--no-save', *NPM_PACKAGES], capture_output=True, text=True,
                                  timeout=NPM_INSTALL_TIMEOUT_S)
        except subprocess.TimeoutExpired:
            done = None
        if done is None or done.returncode != 0:
            tail = '' if done is None else (done.stderr or done.stdout)[-400:]
            reason = f'npm install of {" ".join(NPM_PACKAGES)} failed (offline?): {tail}'
            print(f'SKIP: {reason}')
            pytest.skip(reason)
        with open(stamp, 'w', encoding='utf-8') as out:
            out.write(wanted)
    return os.path.join(prefix, 'node_modules')


def run_client(app, node_modules, port, *args):
    """Run the Node client against ``app``'s live view, spinning the node meanwhile."""
    env = dict(os.environ, NODE_PATH=node_modules)
    proc = subprocess.Popen(['node', CLIENT_SCRIPT, f'ws://127.0.0.1:{port}', *args],
                            stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True, env=env)
    # Read its output while it runs: a full pipe would stall the client.
    output = {}
    readers = [threading.Thread(target=lambda name=name: output.__setitem__(
        name, getattr(proc, name).read()), daemon=True) for name in ('stdout', 'stderr')]
    for reader in readers:
        reader.start()
    deadline = time.monotonic() + CLIENT_TIMEOUT_S
    try:
        while proc.poll() is None and time.monotonic() < deadline:
            app.node.spin_once(0.01)
    finally:
        if proc.poll() is None:
            proc.kill()
        proc.wait()
        for reader in readers:
            reader.join()
    events = [json.loads(line) for line in output['stdout'].splitlines() if line.startswith('{')]
    return proc.returncode, events, output['stderr']


# The one protocol's two names: foxglove-sdk's and the current Foxglove app's; the one of
# @foxglove/ws-protocol's own example, Lichtblick and older Foxglove Studio.
@pytest.mark.parametrize('subprotocol', ['foxglove.sdk.v1', 'foxglove.websocket.v1'])
def test_foxglove_client_decodes_speed_and_scene_drives_and_sets_parameters(node_modules,
                                                                            subprotocol):
    port = free_port()
    app = AutomobileNode(transport='dds', parameter_overrides={
        'foxglove': port, 'real_time_factor': 0.0})
    try:
        code, events, err = run_client(app, node_modules, port, '/automobile/current_speed',
                                       '/foxglove/scene', '/automobile/set_cruising_speed',
                                       str(CRUISING_KMH), subprotocol)
        cruising = app.vehicles[''].logic.status().target_cruising_speed_kmh
        use_sim_time = app.node.get_parameter('use_sim_time')
    finally:
        app.close()
    by_kind = {}
    for event in events:
        by_kind.setdefault(event['event'], []).append(event)
    assert code == 0, (f'client failed: {[e for e in events if e["event"] != "speed"]}, last '
                       f'speed {events[-1:]}; stderr: {err[-2000:]}')
    # The client offered that one name only: the server answered with it.
    assert by_kind['connected'] == [{'event': 'connected', 'protocol': subprotocol}]
    # The topic's channel: the CDR bytes of the transport, with its ros2msg schema.
    channels = by_kind['channels'][0]
    assert channels['speed'] == {'encoding': 'cdr', 'schemaEncoding': 'ros2msg',
                                 'schemaName': 'vehicle_msgs/msg/Float64Stamped'}
    assert channels['scene']['schemaName'] == 'foxglove.SceneUpdate'
    # The speed decoded by Foxglove's CDR reader: a car at rest reads ~0 km/h before the call.
    assert abs(by_kind['speed'][0]['value']) < 1e-6
    # The scene: the car as its chassis collision box (Car preset: 5 x 1.7 x 1 m, centred 2 m
    # ahead of base_link and 0.5 m up), in the world frame, at the spawn pose (0, 0, yaw 0).
    entities = {e['id']: e for e in by_kind['scene'][0]['entities']}
    car = entities['vehicle/Car']
    assert car['frame_id'] == 'world'
    (cube,) = car['cubes']
    assert cube['size'] == pytest.approx({'x': 5.0, 'y': 1.7, 'z': 1.0})
    assert cube['pose']['position']['x'] == pytest.approx(2.0, abs=1e-3)
    assert cube['pose']['position']['y'] == pytest.approx(0.0, abs=1e-3)
    # The transforms: the tree of /tf_static and /tf as foxglove.FrameTransforms.
    tree = {(t['parent'], t['child']): t for t in by_kind['transforms'][0]['transforms']}
    assert set(tree) == {('world', 'odom'), ('odom', 'base_link')}
    assert tree[('world', 'odom')]['rotation'] == pytest.approx(
        {'x': 0.0, 'y': 0.0, 'z': 0.0, 'w': 1.0})
    # The service call went to the node's handler: success, the cruising speed set, the car
    # faster by the client's 1 km/h.
    assert by_kind['call'][0]['requestSchemaName'] == 'vehicle_msgs/srv/SetFloat_Request'
    assert by_kind['response'][0]['success'] is True
    assert cruising == CRUISING_KMH
    risen = by_kind['risen'][0]
    assert abs(risen['from']) < 1e-6 and risen['to'] >= 1.0   # at rest when the request left
    # The parameter capability: values as the node holds them (a float tagged float64), the
    # writable use_sim_time set, the read-only time_step_ms refused with a warning status.
    replies = {event['id']: event['parameters'] for event in by_kind['parameters']}
    assert replies['get'] == [{'name': 'time_step_ms', 'value': 10},
                              {'name': 'cmd_vel_timeout_s', 'type': 'float64', 'value': 0.5}]
    assert replies['set'] == [{'name': 'use_sim_time', 'value': True}]
    assert use_sim_time is True
    assert replies['refused'] == [{'name': 'time_step_ms', 'value': 10}]
    assert by_kind['status'][0]['message'] == (
        'parameter time_step_ms: Trying to set a read-only parameter: time_step_ms; '
        'nothing changed')


def test_foxglove_client_receives_the_highway_lanes_in_the_scene(node_modules):
    # The highway world's lanes (roads:) reach the client in its first scene update: the
    # markings as line strips (solid) and line lists (dashes) on the lane boundaries, the road
    # surface as an indexed triangle list.
    from vehicle_sim.foxglove.map_scene import lane_map_entities
    port = free_port()
    app = AutomobileNode(transport='dds', parameter_overrides={
        'foxglove': port, 'real_time_factor': 0.0, 'world': 'highway'})
    try:
        expected = {e.id: e for e in lane_map_entities(app.scene.lanes)}
        code, events, err = run_client(app, node_modules, port, '/automobile/current_speed',
                                       '/foxglove/scene', '/automobile/set_cruising_speed',
                                       str(CRUISING_KMH))
    finally:
        app.close()
    assert code == 0, f'client failed: {events[-3:]}; stderr: {err[-2000:]}'
    scene = next(e for e in events if e['event'] == 'scene')
    entities = {e['id']: e for e in scene['entities']}
    assert {'vehicle/Car', 'lanes/surface', 'lanes/markings', 'lanes/centerlines'} <= set(
        entities)
    markings, want = entities['lanes/markings']['lines'], expected['lanes/markings'].lines
    assert len(markings) == len(want) == 40
    line_type = {'line_strip': 0, 'line_list': 2}      # foxglove.LinePrimitive.Type
    for got, lines in zip(markings, want):
        assert got['type'] == line_type[lines.kind]
        assert got['count'] == len(lines.points_m)
        assert got['thickness'] == pytest.approx(lines.thickness_m)
        for point, (x, y, z) in zip(got['first'], lines.points_m[:2].tolist()):
            assert (point['x'], point['y'], point['z']) == pytest.approx((x, y, z), abs=0.01)
    assert sum(got['type'] == 2 for got in markings) == 20          # the dashed lane lines
    (surface,) = entities['lanes/surface']['triangles']
    (mesh,) = expected['lanes/surface'].triangles
    assert surface['indices'] == mesh.indices.size > 0
    assert surface['points'] == len(mesh.points_m)
