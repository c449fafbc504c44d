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
Lanelet2 map loading (issue "Real lane maps"): real maps and a 50 MB one, time and memory.

Each map loads in a fresh process (``load_lanelet2``: lanelet2's parse, the lanes, the rules:
signal groups, stop lines, conflicts, areas); printed per map: its size, lanelets, lanes, signal
groups, stop lines, conflicts, the load time and the peak RSS the load added. The maps:
test/data/lanelet2_maps (Lanelet2's example, Autoware's sample and test maps), the shipped
urban map, and maps of rows of straight two-lane roads drawn here (10 and 50 MB; the limit is
``MAX_OSM_BYTES``, 100 MB). No target: the figures size the limit (docs/lanes.md).

Run: ``.venv/bin/python benchmarks/bench_lanelet2_maps.py [--quick]`` (quick: 10 MB only).
"""

import argparse
import json
import os
import subprocess
import sys
import tempfile

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(HERE)
sys.path.insert(0, ROOT)

REAL = [('test/data/lanelet2_maps/lanelet2/mapping_example.osm', 'local_cartesian'),
        ('test/data/lanelet2_maps/autoware_core/vm_03_right_hand.osm', 'autoware_local'),
        ('test/data/lanelet2_maps/autoware_lanelet2_map_validator/sample_map.osm',
         'autoware_local'),
        ('config/maps/urban_map.osm', 'autoware_local')]

_LOAD = """
import json, sys, time, warnings
sys.path.insert(0, {root!r})
def rss_mb(key):
    for line in open('/proc/self/status'):
        if line.startswith(key):
            return int(line.split()[1]) / 1024.0
from vehicle_sim.core.geometry.geodesy import GeodeticOrigin
from vehicle_sim.maps.lanelet2_map import load_lanelet2
import lanelet2.io, lanelet2.routing
before = rss_mb('VmRSS')
open('/proc/self/clear_refs', 'w').write('5')
start = time.perf_counter()
with warnings.catch_warnings():
    warnings.simplefilter('ignore')
    graph, lanelet_map, _ = load_lanelet2({path!r}, GeodeticOrigin(49.0, 8.42, 0.0), {proj!r})
load_s = time.perf_counter() - start
rules = graph.rules
print(json.dumps({{'load_s': load_s, 'peak_mb': rss_mb('VmHWM') - before,
                  'lanelets': len(lanelet_map.laneletLayer), 'lanes': len(graph.lanes),
                  'groups': len(rules.groups), 'stop_lines': len(rules.stop_lines),
                  'conflicts': len(rules.conflicts), 'areas': len(rules.areas)}}))
"""


def measure(path, projector):
    """Load a map in a fresh process; return its figures."""
    done = subprocess.run([sys.executable, '-c', _LOAD.format(root=ROOT, path=path,
                                                              proj=projector)],
                          capture_output=True, text=True, check=True)
    return json.loads(done.stdout.splitlines()[-1])


def big_map(path, megabytes):
    """Write rows of straight two-lane roads until the file has ``megabytes``; return path."""
    sys.path.insert(0, os.path.join(ROOT, 'test'))
    from test_map_lanes_lanelet2 import _write_big_map
    _write_big_map(path, megabytes)
    return path


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[1])
    parser.add_argument('--quick', action='store_true')
    args = parser.parse_args(argv)
    rows = [(os.path.join(ROOT, name), projector) for name, projector in REAL]
    with tempfile.TemporaryDirectory() as folder:
        for megabytes in (10,) if args.quick else (10, 50):
            rows.append((big_map(os.path.join(folder, f'rows_{megabytes}mb.osm'), megabytes),
                         'autoware_local'))
        print(f'{"map":58s} {"MB":>6s} {"lanelets":>8s} {"lanes":>6s} {"groups":>6s} '
              f'{"stops":>5s} {"confl.":>6s} {"load s":>7s} {"peak MB":>8s}')
        for path, projector in rows:
            figures = measure(path, projector)
            print(f'{os.path.relpath(path, ROOT)[-58:]:58s} '
                  f'{os.path.getsize(path) / 1e6:6.1f} {figures["lanelets"]:8d} '
                  f'{figures["lanes"]:6d} {figures["groups"]:6d} {figures["stop_lines"]:5d} '
                  f'{figures["conflicts"]:6d} {figures["load_s"]:7.2f} '
                  f'{figures["peak_mb"]:8.0f}')


if __name__ == '__main__':
    main()
