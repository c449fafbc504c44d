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
