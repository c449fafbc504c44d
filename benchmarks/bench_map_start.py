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
Starting on a lane map: how long the automobile node takes to start, and the map's share of it.

The worlds: the shipped ``highway`` (roads:), ``urban`` (a Lanelet2 map, needs lanelet2),
``city_sumo`` (a SUMO network of 4 x 4 signalised junctions with sidewalks and crossings, needs
the sumo extra) and a larger SUMO city made here by netgenerate with the shipped city's options
(config/maps/make_city_sumo.py) on a 12 x 12 grid (about 2.8 MB of network, 16 times the
junctions). For each:

- the node's start: ``vehicle-sim run --world W`` in a fresh process (the embedded transport,
  localhost discovery on a domain of its own), wall time from the command to its ``automobile
  ready`` line, the median of ``--repeats`` starts;
- in this process: the world file and its lane map loaded (``with_lanes``), the scene built
  (``build_scene`` of that spec: bodies, traffic, lamps), and the latched
  ``/map/lanes`` MarkerArray (every point of the map's surface, lines and areas) two ways, in
  the same run: its builder's message serialized by cyclonedds-python's generic serializer (what
  the node did before ros/lane_cdr.py), and the fast serializer the node uses now;
- a basic step of the world (CPU time, the car at rest, no traffic stepping apart from the
  world's own) before anything draws it and after (``World.prepare_render``, what a camera does
  first: the signal lamps are made then, each a body Bullet's step walks over).

Run: ``.venv/bin/python benchmarks/bench_map_start.py [--quick] [--repeats N]``.
"""

import argparse
import os
from pathlib import Path
import statistics
import subprocess
import sys
import tempfile
import time

import bench_common

HERE = Path(__file__).resolve().parent
REPO = HERE.parent
sys.path.insert(0, str(REPO))
sys.path.insert(0, str(REPO / 'config' / 'maps'))
WORLDS = REPO / 'config' / 'worlds'
BIG_GRID = 12            # junctions a side of the generated city
READY = 'automobile ready'
STEPS = 1000           # basic steps timed, before and after the world is first drawn


def _have(module):
    try:
        __import__(module)
    except ImportError:
        return False
    return True


def big_city(folder):
    """Write a world of a 12 x 12 SUMO city (netgenerate, the shipped city's options)."""
    import make_city_sumo
    options = list(make_city_sumo.NETGENERATE_OPTIONS)
    options[options.index('--grid.number') + 1] = str(BIG_GRID)
    net = Path(folder) / 'big_city.net.xml'
    command = [make_city_sumo.netgenerate_command('x')[0], *options, '-o', str(net)]
    result = subprocess.run(command, capture_output=True, text=True, check=False)
    if result.returncode != 0:
        raise RuntimeError(f'netgenerate failed: {(result.stderr or result.stdout)[-2000:]}')
    world = Path(folder) / 'big_city.yaml'
    world.write_text('vehicles:\n  - {name: Car, model: ToyotaPrius, '
                     'pose: {lane: A1B1_1, s: 20.0}}\n'
                     f'map: {{type: sumo, net: {net.name}}}\n', encoding='utf-8')
    return world


def worlds(folder):
    """Return [(name, world path)] of the worlds this machine can load."""
    found = [('highway (roads:)', WORLDS / 'highway.yaml')]
    if _have('lanelet2'):
        found.append(('urban (Lanelet2)', WORLDS / 'urban.yaml'))
    if _have('sumolib'):
        found.append(('city_sumo (SUMO, 4 x 4)', WORLDS / 'city_sumo.yaml'))
        found.append((f'SUMO city {BIG_GRID} x {BIG_GRID}', big_city(folder)))
    return found


def node_start_s(world, repeats):
    """Return the median wall time [s] from ``vehicle-sim run`` to its ready line."""
    env = dict(os.environ, ROS_AUTOMATIC_DISCOVERY_RANGE='LOCALHOST')
    command = [str(Path(sys.executable).with_name('vehicle-sim')), 'run', '--world',
               str(world), '--no-status', '--duration', '0.5']
    times = []
    for _ in range(repeats):
        start = time.perf_counter()
        process = subprocess.Popen(command, stdout=subprocess.PIPE, stderr=subprocess.STDOUT,
                                   text=True, env=env)
        ready = None
        for line in process.stdout:
            if ready is None and READY in line:
                ready = time.perf_counter() - start
        process.wait(timeout=120)
        if ready is None:
            raise RuntimeError(f'{world}: no "{READY}" line (exit {process.returncode})')
        times.append(ready)
    return statistics.median(times)


def _step_us(world, steps=STEPS):
    """Return the CPU time of a basic step of the world [us] (the car at rest)."""
    for _ in range(50):
        world.step()
    start = time.process_time()
    for _ in range(steps):
        world.step()
    return (time.process_time() - start) / steps * 1e6


def in_process(world):
    """Return the map's parts of the start [s] and the size of /map/lanes [MB]."""
    from vehicle_msgs_py import message_type
    from vehicle_sim.config import load_world
    from vehicle_sim.maps.lane_maps import with_lanes
    from vehicle_sim.physics.scene import build_scene
    from vehicle_sim.ros.lane_cdr import lane_markers_serializer
    from vehicle_sim.ros.lane_messages import lane_markers_builder
    start = time.perf_counter()
    spec = with_lanes(load_world(world))
    loaded = time.perf_counter()
    scene = build_scene(spec)
    built = time.perf_counter()
    world = scene.world
    undrawn_us = _step_us(world)
    world.prepare_render()              # what a camera does first: the lamps are made
    drawn_us = _step_us(world)
    world.close()
    stamp = message_type('builtin_interfaces/msg/Time')(sec=1, nanosec=0)
    graph = spec.lanes
    start_generic = time.perf_counter()
    generic = lane_markers_builder(message_type, 'map')(stamp, graph).serialize()
    start_fast = time.perf_counter()
    fast = lane_markers_serializer('map')(stamp, graph)
    end = time.perf_counter()
    if fast != generic:
        raise RuntimeError(f'{world}: the fast /map/lanes bytes differ from the generic ones')
    return {'load_s': loaded - start, 'build_s': built - loaded, 'step_us': undrawn_us,
            'drawn_step_us': drawn_us,
            'generic_s': start_fast - start_generic, 'fast_s': end - start_fast,
            'lanes_mb': len(fast) / 1e6}


def figures(quick=False, repeats=None):
    """Return [(name, figures)] of every world this machine can load."""
    bench_common.use_free_domain()
    repeats = repeats or (1 if quick else 3)
    rows = []
    with tempfile.TemporaryDirectory(prefix='bench_map_start_') as folder:
        for name, world in worlds(folder):
            found = in_process(world)
            found['node_start_s'] = node_start_s(world, repeats)
            rows.append((name, found))
    return rows


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[1])
    parser.add_argument('--quick', action='store_true', help='one node start a world')
    parser.add_argument('--repeats', type=int, default=None, help='node starts a world')
    args = parser.parse_args(argv)
    rows = figures(args.quick, args.repeats)
    print(f'load average {os.getloadavg()[0]:.1f}')
    print(f"{'world':28} {'node ready':>10} {'map load':>9} {'scene':>7} "
          f"{'/map/lanes':>10} {'generic':>8} {'fast':>7} {'step':>8} {'drawn':>8}")
    for name, f in rows:
        print(f"{name:28} {f['node_start_s']:9.2f}s {f['load_s']:8.2f}s {f['build_s']:6.2f}s "
              f"{f['lanes_mb']:8.2f}MB {f['generic_s']:7.3f}s {f['fast_s']:6.3f}s "
              f"{f['step_us']:6.0f}us {f['drawn_step_us']:6.0f}us")
    return 0


if __name__ == '__main__':
    sys.exit(main())
