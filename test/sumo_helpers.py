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
SUMO networks the tests make with the eclipse-sumo package's netgenerate and netconvert.

Import it after ``pytest.importorskip('sumolib', ...)``: the networks need the 'sumo' extra.

:func:`one_lane_grid_net`: the SUMO engine's tests' grid: 100 m blocks, one lane each way (lane 1
of each edge; lane 0 its sidewalk), crossings, a traffic light at every junction (A0 ... C2); edge
A0A1 runs north along x = 1.6 from y = 5.2 to 92.8. :func:`write_routes`: a route file.

:func:`grid_net`: a signalised 3 x 3 grid (``netgenerate --grid``), 100 m blocks, two lanes each
way and a sidewalk, crossings at every junction, traffic lights at the inner ones.
"""

import os
import subprocess

import sumo

BIN = os.path.join(sumo.SUMO_HOME, 'bin')
ENV = dict(os.environ, SUMO_HOME=sumo.SUMO_HOME)
GRID_OPTIONS = ('--grid', '--grid.number', '3', '--grid.length', '100', '--default.lanenumber',
                '2', '--tls.guess', '--sidewalks.guess', '--crossings.guess',
                '--no-turnarounds', 'false')


def run_tool(tool, *args):
    """Run a SUMO tool (netgenerate, netconvert); return its completed process (checked)."""
    done = subprocess.run([os.path.join(BIN, tool), *map(str, args)], capture_output=True,
                          text=True, env=ENV, check=False)
    assert done.returncode == 0, done.stderr
    return done


def grid_net(folder, name='grid.net.xml', *extra):
    """Write the grid network (module text) into ``folder``; return its path."""
    path = os.path.join(str(folder), name)
    run_tool('netgenerate', *GRID_OPTIONS, *extra, '-o', path)
    return path


def opendrive_of(net, folder, name='grid.xodr'):
    """Write a network as OpenDRIVE (netconvert --opendrive-output); return its path."""
    path = os.path.join(str(folder), name)
    run_tool('netconvert', '-s', net, '--opendrive-output', path)
    return path


# netgenerate's options of the test grid
ONE_LANE_GRID_OPTIONS = ('--grid', '--grid.number', '3', '--grid.length', '100',
                '--default.lanenumber', '1', '--default-junction-type', 'traffic_light',
                '--sidewalks.guess', '--crossings.guess', '--seed', '1')


def one_lane_grid_net(folder):
    """Write grid.net.xml into ``folder`` (netgenerate, ONE_LANE_GRID_OPTIONS); return its path."""
    path = os.path.join(str(folder), 'grid.net.xml')
    subprocess.run([os.path.join(sumo.SUMO_HOME, 'bin', 'netgenerate'), *ONE_LANE_GRID_OPTIONS,
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
