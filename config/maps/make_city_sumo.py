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
Write config/maps/city_sumo.net.xml: a small signalised city as a SUMO network, by netgenerate.

Run ``python config/maps/make_city_sumo.py`` to remake it (it needs the ``sumo`` extra:
``pip install 'vehicle_sim[sumo]'``, whose ``eclipse-sumo`` package ships netgenerate). The
command it runs is :data:`NETGENERATE_OPTIONS`, printed when it runs::

    netgenerate --grid --grid.number 4 --grid.length 100 --grid.attach-length 60
        --default.lanenumber 2 --default.speed 13.89 --tls.guess
        --sidewalks.guess --crossings.guess --no-turnarounds -o city_sumo.net.xml

A grid of 4 x 4 junctions 100 m apart (junction A0 at (60, 60), P3 at (360, 360): columns A..D
west to east, rows 0..3 south to north), each a traffic light (netgenerate's default static
program: 37 s green, 5 s for the turns, 3 s yellow per axis, a 90 s cycle, pedestrians crossing
with the parallel traffic); 60 m roads out of the grid from each junction of the edge, ending at
a dead end (``left0``, ``bottom2``, ...: where vehicles enter and leave). Every road has two lanes
each way at 50 km/h (13.89 m/s) and a 2 m sidewalk (lane index 0 of each edge, pedestrians only;
the car lanes are ``<edge>_1``, the right one, and ``<edge>_2``), a crossing over each arm of
each signalised junction and walking areas joining the sidewalks at its corners. Edges are
named by their end junctions: ``A0B0`` runs from A0 east to B0, ``B0A0`` back west.
"""

import os
from pathlib import Path
import subprocess
import sys

FOLDER = Path(__file__).resolve().parent
NAME = 'city_sumo.net.xml'

NETGENERATE_OPTIONS = (
    '--grid', '--grid.number', '4', '--grid.length', '100', '--grid.attach-length', '60',
    '--default.lanenumber', '2', '--default.speed', '13.89', '--tls.guess',
    '--sidewalks.guess', '--crossings.guess', '--no-turnarounds',
)


def netgenerate_command(output):
    """Return the netgenerate command line that writes the city to ``output``."""
    import sumo
    return [os.path.join(sumo.SUMO_HOME, 'bin', 'netgenerate'), *NETGENERATE_OPTIONS,
            '-o', str(output)]


def make(output):
    """
    Write the city network to ``output`` (a path) and return the command.

    netgenerate runs in the output's folder with its bare name, so that the file's header
    (netgenerate's configuration) names no folder of this machine. A failure raises
    RuntimeError with netgenerate's own words.
    """
    import sumo
    output = Path(output).resolve()
    command = netgenerate_command(output.name)
    env = dict(os.environ, SUMO_HOME=sumo.SUMO_HOME)
    result = subprocess.run(command, capture_output=True, text=True, env=env, check=False,
                            cwd=output.parent)
    if result.returncode != 0:
        raise RuntimeError(f'netgenerate failed ({result.returncode}): '
                           f'{(result.stderr or result.stdout).strip()}')
    return command


def main():
    """Write the network beside this script."""
    path = FOLDER / NAME
    command = make(path)
    print('netgenerate ' + ' '.join(command[1:]))
    print(f'wrote {path}')
    return 0


if __name__ == '__main__':
    sys.exit(main())
