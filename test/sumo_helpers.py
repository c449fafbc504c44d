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
SUMO networks and route files for the tests of the SUMO traffic engine.

:func:`grid_net` makes a 3 x 3 signalised grid with netgenerate (the eclipse-sumo package's):
100 m blocks, one lane each way (lane 1 of each edge; lane 0 its sidewalk), crossings, a
traffic light at every junction (A0 ... C2). Edge A0A1 runs north along x = 1.6 from y = 5.2 to
92.8.
"""

import os
import subprocess

# netgenerate's options of the test grid
GRID_OPTIONS = ('--grid', '--grid.number', '3', '--grid.length', '100',
                '--default.lanenumber', '1', '--default-junction-type', 'traffic_light',
                '--sidewalks.guess', '--crossings.guess', '--seed', '1')


def grid_net(folder):
    """Write grid.net.xml into ``folder`` (``netgenerate`` + GRID_OPTIONS); return its path."""
    import sumo
    path = os.path.join(str(folder), 'grid.net.xml')
    subprocess.run([os.path.join(sumo.SUMO_HOME, 'bin', 'netgenerate'), *GRID_OPTIONS,
                    '-o', path], check=True, capture_output=True, timeout=120)
    return path


def write_routes(folder, vehicles, name='test.rou.xml'):
    """
    Write a route file of ``vehicles``: [(id, depart [s], 'edge edge ...')]; return its path.

    Each departs on the first lane of its first edge that allows it ("best"), at speed 0.
    """
    lines = ['<routes>']
    for vid, depart, edges in vehicles:
        lines.append(f'  <vehicle id="{vid}" depart="{depart}" departLane="best" '
                     f'departSpeed="0"><route edges="{edges}"/></vehicle>')
    lines.append('</routes>')
    path = os.path.join(str(folder), name)
    with open(path, 'w', encoding='utf-8') as handle:
        handle.write('\n'.join(lines) + '\n')
    return path
