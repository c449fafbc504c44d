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
Service round trip: the embedded transport vs a bare cyclonedds request/reply, in one run.

DESIGN §8 target: p50 of the embedded transport <= 2x the bare cyclonedds pair. Both use the same
wire types (vehicle_msgs/srv/SetInt with the rmw_cyclonedds header), the same QoS and the same
loopback-only discovery; each server runs in its own subprocess and spins.

By default two embedded servers are measured against the bare pair: a plain spinning node, and
the automobile node simulating in real time (10 ms steps, every topic published) answering its
real ``/automobile/set_gear``: the issue's "sim running" case. Servers are pluggable: ``SERVERS``
maps a name to ``serve(service_name, ready_callback)``; ``--server-for-embedded module:function``
runs another one.

Usage: ``python benchmarks/bench_service_roundtrip.py [--calls N] [--warmup N]``.
"""

import argparse
import importlib
import os
import statistics
import subprocess
import sys
import time

REPO_ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
sys.path.insert(0, REPO_ROOT)
os.environ.setdefault('ROS_AUTOMATIC_DISCOVERY_RANGE', 'LOCALHOST')
os.environ.setdefault('ROS_DOMAIN_ID', str(102 + os.getpid() % 100))

SRV_TYPE = 'vehicle_msgs/srv/SetInt'
SERVICE = '/bench/set_int'
READY = 'READY'


def _set_int(request, response):
    response.success = request.value % 2 == 0
    return response


def serve_embedded(service_name, ready):
    """Serve SetInt from a DdsNode spinning like any vehicle_sim node."""
    from vehicle_sim.transport.dds import DdsNode
    node = DdsNode('bench_server')
    node.create_service(SRV_TYPE, service_name, _set_int)
    ready()
    node.spin()


def _bare_endpoints(participant, service_name, writer_prefix, reader_prefix, types_pair):
    from cyclonedds.pub import DataWriter
    from cyclonedds.sub import DataReader
    from cyclonedds.topic import Topic

    from vehicle_sim.transport import dds, port
    wtype, rtype = types_pair
    wsuffix = 'Request' if writer_prefix == 'rq' else 'Reply'
    rsuffix = 'Request' if reader_prefix == 'rq' else 'Reply'
    writer = DataWriter(participant, Topic(participant, writer_prefix + service_name + wsuffix,
                                           wtype),
                        qos=dds.dds_qos(port.QOS_SERVICES, b'', writer=True))
    reader = DataReader(participant, Topic(participant, reader_prefix + service_name + rsuffix,
                                           rtype),
                        qos=dds.dds_qos(port.QOS_SERVICES, b'', writer=False))
    return writer, reader


def serve_bare(service_name, ready):
    """Serve SetInt with a plain cyclonedds reader/writer and a WaitSet loop."""
    from cyclonedds.core import InstanceState, ReadCondition, SampleState, ViewState, WaitSet
    from cyclonedds.domain import DomainParticipant

    from vehicle_msgs_py import types as msg_types
    from vehicle_sim.transport import dds, dds_config
    dds.ensure_domain()
    participant = DomainParticipant(dds_config.domain_id())
    types = msg_types.service_types(SRV_TYPE)
    writer, reader = _bare_endpoints(participant, service_name, 'rr', 'rq',
                                     (types.response_wire, types.request_wire))
    waitset = WaitSet(participant)
    waitset.attach(ReadCondition(reader, SampleState.Any | ViewState.Any | InstanceState.Any))
    ready()
    response = types.response
    while True:
        waitset.wait(1_000_000_000)
        for sample in reader.take(N=64):
            if sample.sample_info.valid_data:
                writer.write(types.response_wire(client_id=sample.client_id,
                                                 sequence=sample.sequence,
                                                 success=_set_int(sample, response()).success))


def serve_simulation(service_name, ready):
    """Serve /automobile/set_gear from the automobile node simulating in real time."""
    from vehicle_sim.ros.automobile_node import AutomobileNode
    app = AutomobileNode(['--ros-args', '-p', 'real_time_factor:=1.0'], transport='dds')
    app.node.get_logger().info('benchmark server ready')
    ready()
    try:
        app.node.spin()
    finally:
        app.close()


SERVERS = {'embedded': serve_embedded, 'bare': serve_bare, 'simulation': serve_simulation}
# The service each server offers (the simulation serves the car's real set_gear, SetInt).
SERVICE_OF = {'simulation': '/automobile/set_gear'}


def _resolve_server(spec):
    if spec in SERVERS:
        return SERVERS[spec]
    module, _, func = spec.partition(':')
    return getattr(importlib.import_module(module), func)


def _start_server(spec):
    proc = subprocess.Popen([sys.executable, os.path.abspath(__file__), '--serve', spec],
                            stdout=subprocess.PIPE, text=True)
    line = proc.stdout.readline()
    if line.strip() != READY:
        proc.kill()
        raise RuntimeError(f'server {spec!r} did not start')
    return proc


def _percentiles(samples_s):
    ordered = sorted(samples_s)
    p50 = statistics.median(ordered)
    p99 = ordered[min(len(ordered) - 1, int(0.99 * len(ordered)))]
    return p50 * 1e6, p99 * 1e6


def bench_embedded(calls, warmup, server_spec):
    from vehicle_sim.transport.dds import DdsNode
    proc = _start_server(server_spec)
    node = DdsNode('bench_client')
    try:
        client = node.create_client(SRV_TYPE, SERVICE_OF.get(server_spec, SERVICE))
        if not client.wait_for_service(30.0):
            raise RuntimeError('embedded server not reachable')
        request = node.srv(SRV_TYPE).Request
        times = []
        for i in range(warmup + calls):
            start = time.perf_counter()
            client.call(request(value=1 + i % 2), 10.0)   # valid gears 1 and 2
            if i >= warmup:
                times.append(time.perf_counter() - start)
        return _percentiles(times)
    finally:
        node.shutdown()
        proc.kill()
        proc.wait()


def bench_bare(calls, warmup):
    from cyclonedds.core import InstanceState, ReadCondition, SampleState, ViewState, WaitSet
    from cyclonedds.domain import DomainParticipant

    from vehicle_msgs_py import types as msg_types
    from vehicle_sim.transport import dds_config
    proc = _start_server('bare')
    participant = DomainParticipant(dds_config.domain_id())
    try:
        types = msg_types.service_types(SRV_TYPE)
        writer, reader = _bare_endpoints(participant, SERVICE, 'rq', 'rr',
                                         (types.request_wire, types.response_wire))
        waitset = WaitSet(participant)
        waitset.attach(ReadCondition(reader, SampleState.Any | ViewState.Any |
                                     InstanceState.Any))
        deadline = time.monotonic() + 30.0
        while not (writer.get_matched_subscriptions() and reader.get_matched_publications()):
            if time.monotonic() > deadline:
                raise RuntimeError('bare server not reachable')
            time.sleep(0.01)
        client_id = writer.get_instance_handle() & 0xFFFFFFFFFFFFFFFF
        times = []
        for i in range(warmup + calls):
            start = time.perf_counter()
            writer.write(types.request_wire(client_id=client_id, sequence=i + 1, value=i))
            done = False
            while not done:
                waitset.wait(10_000_000_000)
                done = any(s.sample_info.valid_data and s.sequence == i + 1
                           for s in reader.take(N=64))
            if i >= warmup:
                times.append(time.perf_counter() - start)
        return _percentiles(times)
    finally:
        proc.kill()
        proc.wait()


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.split('\n\n')[1])
    parser.add_argument('--calls', type=int, default=2000)
    parser.add_argument('--warmup', type=int, default=200)
    parser.add_argument('--server-for-embedded', default='embedded')
    parser.add_argument('--serve', help=argparse.SUPPRESS)
    options = parser.parse_args(argv)
    if options.serve:
        # Child process: the embedded server creates its participant with the same config.
        _resolve_server(options.serve)(SERVICE_OF.get(options.serve, SERVICE),
                                       lambda: print(READY, flush=True))
        return 0
    from vehicle_sim.transport import dds
    dds.ensure_domain()  # the same loopback-only configuration for the bare participant
    bare_p50, bare_p99 = bench_bare(options.calls, options.warmup)
    servers = [options.server_for_embedded]
    if options.server_for_embedded == 'embedded':
        servers.append('simulation')
    print(f'service round trip, {options.calls} calls of {SRV_TYPE} over loopback')
    print(f'  bare cyclonedds request/reply : p50 {bare_p50:8.1f} us   p99 {bare_p99:8.1f} us')
    for server in servers:
        emb_p50, emb_p99 = bench_embedded(options.calls, options.warmup, server)
        ratio = emb_p50 / bare_p50
        verdict = 'meets' if ratio <= 2.0 else 'misses'
        print(f'  embedded transport ({server:>10}): p50 {emb_p50:8.1f} us   p99 {emb_p99:8.1f} us'
              f'   p50 ratio {ratio:.2f}x (target <= 2.0x: {verdict}); '
              f'p99 ratio {emb_p99 / bare_p99:.2f}x')
    return 0


if __name__ == '__main__':
    sys.exit(main())
