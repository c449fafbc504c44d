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

Target: p50 of the embedded transport <= 2x the bare cyclonedds pair. Both use the same
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

from bench_common import use_free_domain

REPO_ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
sys.path.insert(0, REPO_ROOT)

SRV_TYPE = 'vehicle_msgs/srv/SetInt'
SERVICE = '/bench/set_int'
READY = 'READY'
BARE_RESEND_S = 0.5   # a bare request without a reply after this is sent again (warm-up)


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

    from vehicle_sim.transport import dds
    from vehicle_sim.transport.qos import QOS_SERVICES
    wtype, rtype = types_pair
    wsuffix = 'Request' if writer_prefix == 'rq' else 'Reply'
    rsuffix = 'Request' if reader_prefix == 'rq' else 'Reply'
    writer = DataWriter(participant, Topic(participant, writer_prefix + service_name + wsuffix,
                                           wtype),
                        qos=dds.dds_qos(QOS_SERVICES, b'', writer=True))
    reader = DataReader(participant, Topic(participant, reader_prefix + service_name + rsuffix,
                                           rtype),
                        qos=dds.dds_qos(QOS_SERVICES, b'', writer=False))
    return writer, reader


def serve_bare(service_name, ready):
    """Serve SetInt with a plain cyclonedds reader/writer and a WaitSet loop."""
    from cyclonedds.core import InstanceState, ReadCondition, SampleState, ViewState, WaitSet
    from cyclonedds.domain import DomainParticipant

    from vehicle_msgs_py import types as msg_types
    from vehicle_sim.transport import dds
    from vehicle_sim.transport.dds import domain_config
    dds.ensure_domain()
    participant = DomainParticipant(domain_config.domain_id())
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


class EmbeddedCaller:
    """A DdsNode client of one server subprocess; ``call(i)`` makes one timed round trip."""

    def __init__(self, server_spec):
        from vehicle_sim.transport.dds import DdsNode
        self.proc = _start_server(server_spec)
        self.node = DdsNode('bench_client_' + server_spec.replace(':', '_').replace('.', '_'))
        self.client = self.node.create_client(SRV_TYPE, SERVICE_OF.get(server_spec, SERVICE))
        if not self.client.wait_for_service(30.0):
            raise RuntimeError(f'server {server_spec!r} not reachable')
        self.request = self.node.srv(SRV_TYPE).Request

    def call(self, i):
        start = time.perf_counter()
        self.client.call(self.request(value=1 + i % 2), 10.0)   # valid gears 1 and 2
        return time.perf_counter() - start

    def close(self):
        self.node.shutdown()
        self.proc.kill()
        self.proc.wait()


def _bare_reply(reader, sequence):
    return any(s.sample_info.valid_data and s.sequence == sequence for s in reader.take(N=64))


class BareCaller:
    """A plain cyclonedds client (reader, writer, WaitSet) of the bare server subprocess."""

    def __init__(self):
        from cyclonedds.core import InstanceState, ReadCondition, SampleState, ViewState, WaitSet
        from cyclonedds.domain import DomainParticipant

        from vehicle_msgs_py import types as msg_types
        from vehicle_sim.transport.dds import domain_config
        self.proc = _start_server('bare')
        self.participant = DomainParticipant(domain_config.domain_id())
        self.types = msg_types.service_types(SRV_TYPE)
        self.writer, self.reader = _bare_endpoints(
            self.participant, SERVICE, 'rq', 'rr',
            (self.types.request_wire, self.types.response_wire))
        self.waitset = WaitSet(self.participant)
        self.waitset.attach(ReadCondition(self.reader, SampleState.Any | ViewState.Any |
                                          InstanceState.Any))
        deadline = time.monotonic() + 30.0
        while not (self.writer.get_matched_subscriptions() and
                   self.reader.get_matched_publications()):
            if time.monotonic() > deadline:
                raise RuntimeError('bare server not reachable')
            time.sleep(0.01)
        self.client_id = self.writer.get_instance_handle() & 0xFFFFFFFFFFFFFFFF
        self.sequence = 0

    def call(self, i, resend=False):
        """
        Make one round trip; return its wall time [s].

        The server's reply writer may match this reader after the server answered the first
        requests (discovery is not symmetric): with ``resend`` (the warm-up) a lost reply is
        asked for again, within bounds, instead of waiting forever; after it, a lost reply is
        an error.
        """
        self.sequence += 1
        sequence = self.sequence
        start = time.perf_counter()
        request = self.types.request_wire(client_id=self.client_id, sequence=sequence, value=i)
        self.writer.write(request)
        resend_at = time.monotonic() + BARE_RESEND_S
        deadline = time.monotonic() + 30.0
        while not _bare_reply(self.reader, sequence):
            now = time.monotonic()
            if now >= deadline:
                raise RuntimeError(f'bare server: no reply to request {sequence} in 30 s')
            if now >= resend_at:
                if not resend:
                    raise RuntimeError(f'bare server: reply {sequence} lost after the warm-up')
                self.writer.write(request)
                resend_at = now + BARE_RESEND_S
            self.waitset.wait(int(BARE_RESEND_S * 1e9))
        return time.perf_counter() - start

    def close(self):
        self.proc.kill()
        self.proc.wait()


def measure(calls, warmup, servers=('embedded', 'simulation'), block=50):
    """
    Return {'bare': (p50, p99), server: (p50, p99), ...} [us], measured in interleaved blocks.

    Every server runs at once; blocks of ``block`` calls go to each in turn, so load from other
    processes hits them alike.
    """
    callers = {}
    try:
        callers['bare'] = BareCaller()
        for spec in servers:
            callers[spec] = EmbeddedCaller(spec)
        for i in range(warmup):
            for name, caller in callers.items():
                caller.call(i, True) if name == 'bare' else caller.call(i)
        times = {name: [] for name in callers}
        for start in range(0, calls, block):
            for name, caller in callers.items():
                times[name] += [caller.call(i) for i in range(start, min(calls, start + block))]
        return {name: _percentiles(found) for name, found in times.items()}
    finally:
        for caller in callers.values():
            caller.close()


def during_time_step(calls=400):
    """
    Return (p50, p99) [us] of ``robot/get_time`` while a long ``robot/time_step`` runs.

    A synchronous automobile node steps 20000 basic steps for one request; meanwhile another
    client of this process asks for the time, up to ``calls`` times.
    """
    from vehicle_sim.transport.dds import DdsNode
    proc = subprocess.Popen([sys.executable, '-m', 'vehicle_sim.ros.automobile_node',
                             '--ros-args', '-r', '__ns:=/bench_during', '-p',
                             'synchronous:=true'],
                            stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    node = DdsNode('bench_during_step')
    try:
        time_step = node.create_client('vehicle_msgs/srv/SetInt', '/bench_during/robot/time_step')
        get_time = node.create_client('vehicle_msgs/srv/GetFloat',
                                      '/bench_during/robot/get_time')
        if not (time_step.wait_for_service(60.0) and get_time.wait_for_service(60.0)):
            raise RuntimeError('the automobile node did not come up')
        request = node.srv('vehicle_msgs/srv/GetFloat').Request
        for _ in range(20):
            get_time.call(request(), 10.0)
        long_step = time_step.call_async(node.srv('vehicle_msgs/srv/SetInt').Request(
            value=200_000))
        times = []
        while not long_step.done() and len(times) < calls:
            start = time.perf_counter()
            get_time.call(request(), 30.0)
            times.append(time.perf_counter() - start)
        return _percentiles(times)
    finally:
        node.shutdown()
        proc.terminate()     # it leaves the graph at once
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
    use_free_domain()
    from vehicle_sim.transport import dds
    dds.ensure_domain()  # the same loopback-only configuration for the bare participant
    servers = [options.server_for_embedded]
    if options.server_for_embedded == 'embedded':
        servers.append('simulation')
    found = measure(options.calls, options.warmup, servers)
    bare_p50, bare_p99 = found['bare']
    print(f'service round trip, {options.calls} calls of {SRV_TYPE} over loopback per server, '
          'in interleaved blocks')
    print(f'  bare cyclonedds request/reply : p50 {bare_p50:8.1f} us   p99 {bare_p99:8.1f} us')
    for server in servers:
        emb_p50, emb_p99 = found[server]
        ratio = emb_p50 / bare_p50
        verdict = 'meets' if ratio <= 2.0 else 'misses'
        print(f'  embedded transport ({server:>10}): p50 {emb_p50:8.1f} us   p99 {emb_p99:8.1f} us'
              f'   p50 ratio {ratio:.2f}x (target <= 2.0x: {verdict}); '
              f'p99 ratio {emb_p99 / bare_p99:.2f}x')
    during_p50, during_p99 = during_time_step()
    print(f'  robot/get_time during a long robot/time_step: p50 {during_p50:8.1f} us   '
          f'p99 {during_p99:8.1f} us')
    return 0


if __name__ == '__main__':
    sys.exit(main())
