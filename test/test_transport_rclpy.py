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
rclpy adapter tests: the same node behaviour on a real rclpy Node.

Run where ROS 2 Jazzy is sourced; elsewhere the module is skipped with the reason printed.
"""

import json
import signal
import subprocess
import sys
import textwrap
import threading
import time

from conftest import peer_env
import pytest

rclpy = pytest.importorskip(
    'rclpy', reason='rclpy not importable: ROS 2 Jazzy is not installed on this machine')

from rclpy.context import Context  # noqa: E402

from vehicle_sim.transport.errors import TransportError  # noqa: E402
from vehicle_sim.transport.future import Future  # noqa: E402
from vehicle_sim.transport.parameter_types import Parameter  # noqa: E402
from vehicle_sim.transport.qos import QOS_ROSOUT, QosProfile  # noqa: E402
from vehicle_sim.transport.rclpy_adapter import RclpyNode, to_rclpy_qos  # noqa: E402


@pytest.fixture
def context():
    ctx = Context()
    rclpy.init(context=ctx)
    yield ctx
    rclpy.try_shutdown(context=ctx)


def test_rclpy_qos_conversion_keeps_rosout_profile():
    from rclpy.qos import DurabilityPolicy
    qos = to_rclpy_qos(QOS_ROSOUT)
    assert qos.depth == 1000 and qos.durability == DurabilityPolicy.TRANSIENT_LOCAL


def test_rclpy_node_parameter_validator_rejects_and_keeps_value(context):
    node = RclpyNode('param_node', context=context)
    try:
        assert node.declare_parameter(
            'gain', 1.0, validator=lambda v: None if 0 <= v <= 10 else 'out of range') == 1.0
        (result,) = node.set_parameters([Parameter('gain', 99.0)])
        assert not result.successful and 'out of range' in result.reason
        assert node.get_parameter('gain') == 1.0
    finally:
        node.shutdown()


def test_rclpy_node_service_round_trip_in_process(context):
    server = RclpyNode('server', '/rt', context=context)
    client_node = RclpyNode('client', '/rt', context=context)
    try:
        def handle(request, response):
            response.success = request.data
            return response

        server.create_service('std_srvs/srv/SetBool', 'enable', handle)
        client = client_node.create_client('std_srvs/srv/SetBool', '/rt/enable')
        assert client.wait_for_service(10.0)
        future = client.call_async(client_node.srv('std_srvs/srv/SetBool').Request(data=True))
        deadline_spins = 1000
        while not future.done() and deadline_spins:
            server.spin_once(0.01)
            client_node.spin_once(0.01)
            deadline_spins -= 1
        assert future.result().success is True
    finally:
        client_node.shutdown()
        server.shutdown()


def test_rclpy_node_logger_reaches_rosout_as_rclpy_does_by_default(context):
    # rclpy's nodes publish their log on /rosout (enable_rosout=True); the adapter's port
    # logger goes through the node's rclpy logger, so a refusal's reason reaches the caller's
    # `vehicle-sim call` on this transport too.
    talker = RclpyNode('logger', '/rt', context=context)
    listener = RclpyNode('listener', '/rt', context=context)
    try:
        records = []
        listener.create_subscription('rcl_interfaces/msg/Log', '/rosout', records.append,
                                     QOS_ROSOUT)
        talker.get_logger().warn('refused 300.0: outside the valid range')
        for _ in range(1000):
            if any(r.name == 'rt.logger' for r in records):
                break
            talker.spin_once(0.01)
            listener.spin_once(0.01)
        assert [(r.level, r.msg) for r in records if r.name == 'rt.logger'] == [
            (30, 'refused 300.0: outside the valid range')]
    finally:
        listener.shutdown()
        talker.shutdown()


# A helper node built where nothing initialised rclpy (vehicle_sim.testing's client, with
# --disable-rosout-logs), then the user's own rclpy.init() and nodes, in one fresh process: its
# logging state is rclpy's per process (the first context configures it), so no other test's
# context can change the outcome.
OWN_CONTEXT_SCRIPT = textwrap.dedent("""
    import json
    import rclpy
    from vehicle_sim.transport.qos import QOS_ROSOUT
    from vehicle_sim.transport.rclpy_adapter import RclpyNode

    helper = RclpyNode('helper', '/ctx', args=['--ros-args', '--disable-rosout-logs'])
    found = {'default_free': not rclpy.ok()}
    rclpy.init()                        # the user's own, after the helper
    talker = RclpyNode('talker', '/ctx')
    listener = RclpyNode('listener', '/ctx')
    records = []
    listener.create_subscription('rcl_interfaces/msg/Log', '/rosout', records.append, QOS_ROSOUT)
    talker.get_logger().warn('heard on rosout')
    helper.get_logger().warn('not on rosout')
    for _ in range(500):
        if any(r.name == 'ctx.talker' for r in records):
            break
        for node in (talker, listener, helper):
            node.spin_once(0.01)
    found['rosout'] = sorted({r.name for r in records if r.name.startswith('ctx.')})
    found['rosout_publishers'] = sorted(
        info.node_name for info in listener.node.get_publishers_info_by_topic('/rosout')
        if info.node_namespace == '/ctx')
    helper_context = helper.node.context
    helper.shutdown()
    found['helper_context_shut'] = not helper_context.ok()
    found['default_still_ok'] = rclpy.ok()
    for node in (talker, listener):
        node.shutdown()
    rclpy.shutdown()
    print(json.dumps(found), flush=True)
""")


def test_rclpy_helper_node_leaves_the_default_context_and_rosout_to_the_user():
    done = subprocess.run([sys.executable, '-c', OWN_CONTEXT_SCRIPT], env=peer_env(),
                          capture_output=True, text=True, timeout=60)
    assert done.returncode == 0, done.stdout + done.stderr
    found = json.loads(done.stdout.strip().splitlines()[-1])
    assert found == {
        'default_free': True,           # the helper did not initialise the default context
        'rosout': ['ctx.talker'],       # the user's node on /rosout; the helper kept off it
        'rosout_publishers': ['listener', 'talker'],
        'helper_context_shut': True,    # its own context ended with it
        'default_still_ok': True,       # and the user's with the user
    }


def test_a_node_main_returning_by_itself_leaves_ctrl_c_to_the_caller_and_its_children():
    # A node main called in process (a test, a script) that returns without a signal (here:
    # exit 2 on a bad parameter) restores the caller's SIGINT handler; it used to leave SIGINT
    # ignored, which every child started later inherited (a sweep's Ctrl-C then hung).
    from vehicle_sim.ros.diff_robot_node import main
    before = signal.getsignal(signal.SIGINT)
    assert main(['node', '--ros-args', '-r', '__ns:=/main_returns', '-p', 'x:=.nan']) == 2
    assert signal.getsignal(signal.SIGINT) is before
    child = subprocess.run(
        [sys.executable, '-c', 'import signal; print(signal.getsignal(signal.SIGINT).__name__)'],
        capture_output=True, text=True, timeout=60)
    assert child.stdout.strip() == 'default_int_handler', child.stderr


def test_rclpy_node_warns_once_about_an_override_it_does_not_declare(context, capfd):
    node = RclpyNode('override_user', context=context,
                     parameter_overrides={'gian': 2.0, 'gain': 3.0})
    try:
        node.declare_parameter('gain', 1.0)
        node.spin_once(0.0)
        node.spin_once(0.0)
        err = capfd.readouterr().err
        assert err.count('ignored parameter override gian (did you mean gain?): not declared by '
                         'this node; its parameters: gain, ') == 1
        assert node.get_parameter('gain') == 3.0
    finally:
        node.shutdown()


def test_rclpy_node_override_of_the_wrong_type_names_both_types_and_the_value(context):
    # As on the embedded transport: rclcpp's type names and the value, not type codes.
    node = RclpyNode('typed_user', context=context, parameter_overrides={'time_step_ms': 'abc'})
    try:
        with pytest.raises(TransportError) as error:
            node.declare_parameter('time_step_ms', 10)
        assert str(error.value) == (
            "parameter 'time_step_ms' override 'abc' rejected: Wrong parameter type, parameter "
            "{time_step_ms} is of type {integer}, setting it to {string} 'abc' is not allowed.")
    finally:
        node.shutdown()


def test_rclpy_node_read_only_refusal_matches_the_embedded_transport(context):
    from vehicle_sim.transport.ros_args import read_only_reason
    node = RclpyNode('read_only_user', context=context)
    try:
        node.declare_parameter('model', 'Car', read_only=True)
        (result,) = node.set_parameters([Parameter('model', 'BmwX5')])
        assert (result.successful, result.reason) == (False, read_only_reason('model'))
    finally:
        node.shutdown()


def _spin_both(a, b, done, spins=2000):
    while not done() and spins:
        a.spin_once(0.01)
        b.spin_once(0.01)
        spins -= 1
    return done()


def test_rclpy_node_deferred_reply_is_sent_when_its_future_completes(context):
    server = RclpyNode('deferred_server', '/rt', context=context)
    client_node = RclpyNode('deferred_client', '/rt', context=context)
    try:
        pending = []

        def handle_later(request, response):
            response.success = request.data
            future = Future()
            pending.append((future, response))
            return future

        def handle_now(request, response):
            response.success = True
            return response

        release = []

        def complete():   # a timer of the server completes the deferred reply when told to
            if pending and release:
                future, response = pending.pop()
                future.set_result(response)

        server.create_service('std_srvs/srv/SetBool', 'later', handle_later)
        server.create_service('std_srvs/srv/SetBool', 'now', handle_now)
        server.create_timer(0.005, complete)
        later = client_node.create_client('std_srvs/srv/SetBool', '/rt/later')
        now = client_node.create_client('std_srvs/srv/SetBool', '/rt/now')
        assert later.wait_for_service(10.0) and now.wait_for_service(10.0)
        request = client_node.srv('std_srvs/srv/SetBool').Request
        waiting = later.call_async(request(data=True))
        assert _spin_both(server, client_node, lambda: bool(pending))
        # While the first reply is deferred, the server answers another service.
        answered = now.call_async(request(data=True))
        assert _spin_both(server, client_node, answered.done)
        assert answered.result().success is True and not waiting.done()
        release.append(True)
        assert _spin_both(server, client_node, waiting.done)
        assert waiting.result().success is True
    finally:
        client_node.shutdown()
        server.shutdown()


def test_rclpy_automobile_time_step_is_answered_after_its_steps(context):
    pytest.importorskip('vehicle_msgs', reason='vehicle_msgs not built (export-interfaces)')
    from vehicle_sim.ros.automobile_node import AutomobileNode
    app = AutomobileNode(transport='rclpy', node=RclpyNode('automobile', '/rt_sync',
                                                             context=context,
                                                             parameter_overrides={
                                                                 'synchronous': True}))
    client_node = RclpyNode('time_step_client', '/rt', context=context)
    try:
        step = client_node.create_client('vehicle_msgs/srv/SetInt', '/rt_sync/robot/time_step')
        get_time = client_node.create_client('vehicle_msgs/srv/GetFloat',
                                             '/rt_sync/robot/get_time')
        assert step.wait_for_service(10.0) and get_time.wait_for_service(10.0)
        first = step.call_async(client_node.srv('vehicle_msgs/srv/SetInt').Request(value=2000))
        second = step.call_async(client_node.srv('vehicle_msgs/srv/SetInt').Request(value=30))
        assert _spin_both(app.node, client_node, lambda: first.done() and second.done(), 20000)
        assert first.result().success and second.result().success
        asked = get_time.call_async(client_node.srv('vehicle_msgs/srv/GetFloat').Request())
        assert _spin_both(app.node, client_node, asked.done)
        assert asked.result().value == pytest.approx(2.03, abs=1e-9)
    finally:
        client_node.shutdown()
        app.close()


# A node main whose destroy_node takes a second, so that a second SIGINT lands inside it; after
# run_node returned it waits a second more (standing for the process's exit) before a last line.
# Its 'ready' line comes once the node exists; with a second argument 'announce' the node is
# made ready first (as a node's ready announcement does), so a signal after the line finds it
# ready; without it, the start-up goes on for argv[1] seconds after the line.
SLOW_SHUTDOWN_MAIN = textwrap.dedent("""
    import sys
    import time
    from vehicle_sim.transport.rclpy_adapter import RclpyNode, run_rclpy_node
    from vehicle_sim.transport.stop_signals import mark_ready

    def factory(args):
        node = RclpyNode('slow_shutdown', '/rt_sigint')
        destroy = node.shutdown

        def slow_shutdown():
            print('shutting down', flush=True)
            time.sleep(1.0)
            destroy()
            print('destroyed', flush=True)
        node.shutdown = slow_shutdown
        if sys.argv[2:] == ['announce']:
            mark_ready()
        print('ready', flush=True)
        time.sleep(float(sys.argv[1]))   # the rest of a start-up, after the node exists
        return node

    status = run_rclpy_node(factory, ['slow_shutdown'])
    print('returned', status, flush=True)
    time.sleep(1.0)
    print('exiting', flush=True)
""")


def _wait_for_line(lines, text, event, timeout_s=30.0):
    assert event.wait(timeout_s), f'no {text!r} line: {lines}'


def test_sigint_during_and_after_shutdown_is_ignored_and_the_node_exits_0():
    # Under `ros2 launch`, Ctrl-C reaches a node twice: from the terminal and from launch.
    # (the node made ready before its line: a signal after the line is one after ready)
    proc = subprocess.Popen([sys.executable, '-c', SLOW_SHUTDOWN_MAIN, '0', 'announce'],
                            env=peer_env(),
                            stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
    lines = []
    seen = {text: threading.Event() for text in ('ready', 'shutting down', 'returned 0')}

    def read():
        for line in proc.stdout:
            lines.append(line)
            for text, event in seen.items():
                if line.startswith(text):
                    event.set()
    reader = threading.Thread(target=read, daemon=True)
    reader.start()
    try:
        _wait_for_line(lines, 'ready', seen['ready'])
        proc.send_signal(signal.SIGINT)
        _wait_for_line(lines, 'shutting down', seen['shutting down'])
        proc.send_signal(signal.SIGINT)       # inside destroy_node
        _wait_for_line(lines, 'returned 0', seen['returned 0'])
        proc.send_signal(signal.SIGINT)       # while the process ends
        assert proc.wait(30) == 0, ''.join(lines)
        reader.join(10)
        text = ''.join(lines)
        assert 'Traceback' not in text and 'KeyboardInterrupt' not in text, text
        assert [line.strip() for line in lines[-3:]] == ['destroyed', 'returned 0', 'exiting']
    finally:
        if proc.poll() is None:
            proc.kill()
            proc.wait()



def test_sigint_after_the_node_exists_during_start_up_still_shuts_it_down():
    # The signal lands while the factory finishes its start-up (the node already exists): it must
    # not unwind past the node unnamed; the node is built, then shut down. It was not ready yet
    # (its start-up had not returned): exit status 128 + SIGINT (transport/stop_signals.py).
    proc = subprocess.Popen([sys.executable, '-c', SLOW_SHUTDOWN_MAIN, '1.0'], env=peer_env(),
                            stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
    try:
        assert proc.stdout.readline().strip() == 'ready'
        proc.send_signal(signal.SIGINT)
        out, _ = proc.communicate(timeout=30)
        assert proc.returncode == 0, out   # the script's own exit, after it printed the status
        assert [line.strip() for line in out.splitlines()] == [
            'shutting down', 'destroyed', 'returned 130', 'exiting'], out
    finally:
        if proc.poll() is None:
            proc.kill()
            proc.wait()


def test_a_node_the_rmw_refuses_exits_2_with_a_line_of_ours_below_the_rmws_and_no_traceback():
    # lo selected twice: Cyclone DDS refuses the domain and rmw_cyclonedds prints why; rcl's
    # error says only 'error creating node'. The embedded transport's line:
    # test_transport_discovery_config.py
    from rclpy.utilities import get_rmw_implementation_identifier
    rmw = get_rmw_implementation_identifier()
    if rmw != 'rmw_cyclonedds_cpp':
        pytest.skip(f"the refusal is Cyclone DDS's: RMW_IMPLEMENTATION is {rmw}")
    lo = ('<CycloneDDS><Domain><General><Interfaces><NetworkInterface name="lo"/>'
          '</Interfaces></General></Domain></CycloneDDS>')
    env = dict(peer_env(transport='rclpy'), CYCLONEDDS_URI=f'{lo},{lo}')
    done = subprocess.run([sys.executable, '-m', 'vehicle_sim.ros.automobile_node',
                           '--ros-args', '-r', '__ns:=/refused'],
                          env=env, capture_output=True, text=True, timeout=120)
    assert done.returncode == 2, done.stdout + done.stderr
    assert 'Traceback' not in done.stdout + done.stderr, done.stderr
    lines = done.stderr.strip().splitlines()
    assert lines[-1].startswith("automobile: rclpy could not create node 'automobile' ("), lines
    assert lines[-1].endswith('): the lines of rmw_cyclonedds_cpp above say why'), lines
    assert any('the same interface may not be selected twice' in line
               for line in lines[:-1]), lines


def test_rclpy_rows_publish_fast_cdr_bytes_and_a_raw_subscription_decodes_them(context):
    from types import SimpleNamespace

    from vehicle_sim.ros import automobile_interfaces as itf
    from vehicle_sim.ros import endpoints
    publisher = RclpyNode('fast_pub', '/rfast', context=context)
    reader = RclpyNode('fast_sub', '/rfast', context=context)
    try:
        rows = (endpoints.CLOCK, itf.topic('automobile/current_speed'), itf.ODOM)
        assert all(publisher.serializer(row.ros_type) is not None for row in rows)
        outputs = endpoints.Outputs(publisher, rows, SimpleNamespace(
            base_frame='car1/base_link', odom_frame='car1/odom'),
            resolve=lambda name: name if name.startswith('/') else f'/rfast/{name}')
        messages, raw = [], []
        speed = outputs.publishers[rows[1]].topic_name
        reader.create_subscription(rows[1].ros_type, speed, messages.append, rows[1].qos)
        reader.create_subscription(rows[1].ros_type, speed, raw.append, rows[1].qos, raw=True)
        odom = []
        reader.create_subscription(itf.ODOM.ros_type, '/rfast/odom', odom.append, itf.ODOM.qos)
        assert reader.spin_until(lambda: outputs.publishers[rows[1]].get_subscription_count()
                                 == 2 and outputs.publishers[itf.ODOM].get_subscription_count(),
                                 30.0)
        stamp = publisher.msg('builtin_interfaces/msg/Time')(sec=3, nanosec=7)
        call = SimpleNamespace(stamp=stamp, status=SimpleNamespace(current_speed_kmh=-12.5),
                               torque_mode=False,
                               odom=((1.0, 2.0, 0.0), (0.0, 0.0, 0.0, 1.0), (4.0, 0.0, 0.0),
                                     (0.0, 0.0, 0.5)))
        outputs.publish(itf.EACH_PUBLISH, call)
        assert reader.spin_until(lambda: messages and raw and odom, 30.0)
        assert (messages[0].header.frame_id, messages[0].header.stamp.sec, messages[0].data) == \
            ('car1/base_link', 3, -12.5)
        assert type(raw[0]) is bytes
        assert reader.deserialize(rows[1].ros_type, raw[0]) == messages[0]
        assert (odom[0].child_frame_id, odom[0].pose.pose.position.y,
                odom[0].twist.twist.angular.z) == ('car1/base_link', 2.0, 0.5)
    finally:
        reader.shutdown()
        publisher.shutdown()


def test_rclpy_spin_once_handles_every_message_already_received(context):
    # The port's spin_once handles what is ready; rclpy's own handles one callback.
    publisher = RclpyNode('drain_pub', '/rdrain', context=context)
    reader = RclpyNode('drain_sub', '/rdrain', context=context)
    try:
        qos = QosProfile(depth=50)
        received = []
        reader.create_subscription('std_msgs/msg/Int32', 'n', lambda m: received.append(m.data),
                                   qos)
        pub = publisher.create_publisher('std_msgs/msg/Int32', 'n', qos)
        assert reader.spin_until(lambda: pub.get_subscription_count() == 1, 30.0)
        for value in range(30):
            pub.publish(publisher.msg('std_msgs/msg/Int32')(data=value))
        time.sleep(1.0)                 # loopback delivery of 30 small samples: far less
        reader.spin_once(0.0)
        assert received == list(range(30))
    finally:
        reader.shutdown()
        publisher.shutdown()


def test_rclpy_publish_tap_gets_the_bytes_a_raw_subscription_receives(context):
    import struct

    from vehicle_sim.transport.publish_tap import PublishTap

    class Sink:
        open = True

        def __init__(self):
            self.data = []

        def write(self, data):
            self.data.append(bytes(data))

    class Tap(PublishTap):
        def __init__(self, sink):
            self.sink = sink

        def topic(self, topic_name, ros_type, qos):
            return self.sink if topic_name == '/rtap/value' else None

    sink = Sink()
    publisher = RclpyNode('tap_pub', '/rtap', context=context)
    reader = RclpyNode('tap_sub', '/rtap', context=context)
    try:
        publisher.add_publish_tap(Tap(sink))
        pub = publisher.create_publisher('std_msgs/msg/Float64', 'value')
        raw = []
        reader.create_subscription('std_msgs/msg/Float64', '/rtap/value', raw.append, raw=True)
        assert reader.spin_until(lambda: pub.get_subscription_count() > 0, 30.0)
        pub.publish(publisher.msg('std_msgs/msg/Float64')(data=2.5))
        assert reader.spin_until(lambda: raw, 30.0)
        # rclpy's serialize_message: XCDR1 little endian, 4-byte header, the float64 2.5; the
        # tap gets the bytes that went out.
        assert sink.data == [bytes(raw[0])] == [b'\x00\x01\x00\x00' + struct.pack('<d', 2.5)]
        with pytest.raises(TransportError, match='std_msgs/msg/Float64'):
            pub.publish(publisher.msg('std_msgs/msg/String')(data='x'))
        assert len(sink.data) == 1
    finally:
        reader.shutdown()
        publisher.shutdown()


def test_rclpy_call_soon_runs_on_the_spinning_thread(context):
    node = RclpyNode('soon', '/rtap', context=context)
    try:
        ran_on = []
        caller = threading.Thread(target=node.call_soon, args=(
            lambda: ran_on.append(threading.get_ident()),))
        caller.start()
        caller.join()
        assert ran_on == []
        assert node.spin_until(lambda: ran_on, 10.0)
        assert ran_on == [threading.get_ident()]
    finally:
        node.shutdown()
