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
Cost of the Foxglove live view on the automobile node's step, printed as ratios.

Three nodes in this process (default car, 10 ms step, synchronous, stepped in-process), blocks
of steps interleaved: without a live view; with one and no client (each topic's reader gate
reads its sink's subscriber flag); with one whose every channel is forced open (each message is
built and its bytes go to the SDK, which drops them for want of a client: the forwarding cost
without the WebSocket send). Median of the block ratios.

Then the relay in front of the SDK's server (vehicle_sim/foxglove/front.py, which lets both
subprotocol names in): a server answering the opening handshake and then sending a stream of
921600-byte messages (a 640 x 480 RGB camera image each), read by a client directly and through
the relay, interleaved; the throughput of each and the relay's share of one core (CPU time of
this process, which runs the relay, per second of transfer) at 30 images/s. Run:
``.venv/bin/python benchmarks/bench_foxglove.py`` (needs the foxglove extra).
"""

import argparse
import os
import socket
import statistics
import threading
import time

from bench_common import use_free_domain


def _free_port():
    with socket.socket() as probe:
        probe.bind(('127.0.0.1', 0))
        return probe.getsockname()[1]


def _block(app, steps):
    start = time.perf_counter()
    app.step(steps)
    return (time.perf_counter() - start) / steps


IMAGE_BYTES = 640 * 480 * 3
IMAGES_PER_S = 30


def _image_server(images):
    """Listen; answer each opening handshake with 101 and send ``images`` images; the port."""
    listener = socket.create_server(('127.0.0.1', 0))
    payload = bytes(IMAGE_BYTES)

    def serve():
        while True:
            try:
                conn, _ = listener.accept()
            except OSError:
                return
            with conn:
                head = b''
                while b'\r\n\r\n' not in head:
                    head += conn.recv(65536)
                conn.sendall(b'HTTP/1.1 101 Switching Protocols\r\n'
                             b'sec-websocket-protocol: foxglove.sdk.v1\r\n\r\n')
                for _ in range(images):
                    conn.sendall(payload)

    threading.Thread(target=serve, daemon=True).start()
    return listener


def _read_images(port, images):
    """Connect, offer the subprotocol, read ``images`` images; return (wall, CPU) seconds."""
    buffer = memoryview(bytearray(1 << 20))
    with socket.create_connection(('127.0.0.1', port)) as client:
        client.sendall(b'GET / HTTP/1.1\r\nHost: x\r\nUpgrade: websocket\r\n'
                       b'Connection: Upgrade\r\nSec-WebSocket-Key: dGhlIHNhbXBsZSBub25jZQ==\r\n'
                       b'Sec-WebSocket-Version: 13\r\n'
                       b'Sec-WebSocket-Protocol: foxglove.websocket.v1\r\n\r\n')
        head = b''
        while b'\r\n\r\n' not in head:
            head += client.recv(1)
        wall, cpu = time.perf_counter(), time.process_time()
        left = images * IMAGE_BYTES
        while left:
            count = client.recv_into(buffer, min(left, len(buffer)))
            assert count, 'the server closed early'
            left -= count
        return time.perf_counter() - wall, time.process_time() - cpu


def relay(blocks, images):
    """Print the relay's throughput against a direct connection, and its CPU at 30 images/s."""
    from vehicle_sim.foxglove.front import SubprotocolFront
    server = _image_server(images)
    front = SubprotocolFront('127.0.0.1', 0, server.getsockname()[1], log=lambda text: None)
    direct_s, relayed_s, direct_cpu, relayed_cpu = [], [], [], []
    try:
        for _ in range(blocks):
            wall, cpu = _read_images(server.getsockname()[1], images)
            direct_s.append(wall)
            direct_cpu.append(cpu)
            wall, cpu = _read_images(front.port, images)
            relayed_s.append(wall)
            relayed_cpu.append(cpu)
    finally:
        front.close()
        server.close()
    megabytes = images * IMAGE_BYTES / 1e6
    direct, relayed = statistics.median(direct_s), statistics.median(relayed_s)
    # CPU of this process (client + relay) per image, less the client's own (direct runs)
    relay_cpu_per_image = (statistics.median(relayed_cpu) - statistics.median(direct_cpu)) / images
    print(f'Relay in front of the SDK server (front.py), {blocks} interleaved blocks of {images} '
          f'images of {IMAGE_BYTES} bytes')
    print(f'  direct : {megabytes / direct:8.0f} MB/s (median)')
    print(f'  relayed: {megabytes / relayed:8.0f} MB/s (median); direct / relayed time '
          f'{relayed / direct:.2f}x')
    print(f'  relay CPU at {IMAGES_PER_S} images/s: '
          f'{100 * relay_cpu_per_image * IMAGES_PER_S:.1f} % of one core')


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[1])
    parser.add_argument('--blocks', type=int, default=15)
    parser.add_argument('--steps', type=int, default=200)
    parser.add_argument('--images', type=int, default=300,
                        help='images per block of the relay measurement')
    parser.add_argument('--relay-only', action='store_true')
    args = parser.parse_args(argv)
    if args.relay_only:
        relay(args.blocks, args.images)
        return 0
    os.environ.setdefault('ROS_AUTOMATIC_DISCOVERY_RANGE', 'LOCALHOST')
    use_free_domain()
    from vehicle_sim.foxglove.topics import ChannelSink
    from vehicle_sim.ros.automobile_node import AutomobileNode

    base = {'synchronous': True}
    plain = AutomobileNode(transport='dds', parameter_overrides=base)
    idle = AutomobileNode(transport='dds', parameter_overrides=dict(base, foxglove=_free_port()))
    forced = AutomobileNode(transport='dds',
                            parameter_overrides=dict(base, foxglove=_free_port()))
    for sink in forced._live.topics.sinks.values():
        if isinstance(sink, ChannelSink):
            sink.open = True
    apps = {'without': plain, 'idle': idle, 'forced': forced}
    for app in apps.values():
        app.vehicles[''].logic.set_cruising_speed_within_top_kmh(30.0)
        app.step(50)
    times = {name: [] for name in apps}
    try:
        for _ in range(args.blocks):
            for name, app in apps.items():
                times[name].append(_block(app, args.steps))
    finally:
        for app in apps.values():
            app.close()
    idle_ratio = statistics.median(i / w for i, w in zip(times['idle'], times['without']))
    forced_ratio = statistics.median(f / w for f, w in zip(times['forced'], times['without']))
    print('Foxglove live view, automobile node (Car, 10 ms step, synchronous, in-process), '
          f'{args.blocks} interleaved blocks of {args.steps} steps')
    for name in apps:
        print(f'  {name:8s}: {1e6 * statistics.median(times[name]):7.1f} us per step (median)')
    print(f'  live view, no client       / without: {idle_ratio:.2f}x')
    print(f'  every channel forwarding   / without: {forced_ratio:.2f}x')
    relay(args.blocks, args.images)
    return 0


if __name__ == '__main__':
    raise SystemExit(main())
