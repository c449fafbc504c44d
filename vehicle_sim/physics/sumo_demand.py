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
The trips of a SUMO engine's ``demand:``, made by SUMO's own randomTrips.py.

For each vehicle class of the demand with a rate, ``tools/randomTrips.py`` of the eclipse-sumo
package writes evenly spaced trips (``--period`` 3600 / its rate) between random edges that allow
that class (``--vehicle-class``, ``--vclass``), checked for a route (``--validate``, duarouter);
for the pedestrians, walks (``--pedestrians``). Each class draws with its own seed (the demand's
(its own, else the engine's) plus its position among the classes; the pedestrians' plus
1000). The files are made once per
network content and demand in a cache folder (:func:`cache_dir`, a folder per key, written
aside and renamed into place), and SUMO reads them as route files (it routes the trips itself).
"""

import hashlib
import os
import shutil
import subprocess
import sys
import tempfile

from vehicle_sim.core.specs.errors import InvalidParameterError
from vehicle_sim.physics.sumo_session import sumo_home

CACHE_ENV = 'VEHICLE_SIM_CACHE'      # the cache folder; default $XDG_CACHE_HOME/vehicle_sim
RANDOM_TRIPS_TIMEOUT_S = 600.0
PEDESTRIAN_SEED_OFFSET = 1000


def cache_dir():
    """Return the folder of vehicle_sim's made files (``$VEHICLE_SIM_CACHE``, else XDG's)."""
    folder = os.environ.get(CACHE_ENV)
    if not folder:
        base = os.environ.get('XDG_CACHE_HOME') or os.path.join(os.path.expanduser('~'),
                                                                 '.cache')
        folder = os.path.join(base, 'vehicle_sim')
    return folder


def _runs(net, demand, seed, begin_s):
    """Return [(file name, randomTrips arguments)] of ``demand``."""
    end = begin_s + demand.duration_s
    common = ['-n', net, '-b', f'{begin_s:.17g}', '-e', f'{end:.17g}',
              '--min-distance', f'{demand.min_distance_m:.17g}']
    runs = []
    for index, (vclass, rate) in enumerate(demand.class_rates()):
        runs.append((f'{vclass}.trips.xml', common + [
            '--period', f'{3600.0 / rate:.17g}', '--seed', str(seed + index),
            '--vehicle-class', vclass, '--vclass', vclass, '--prefix', f'{vclass}_',
            '--validate']))
    if demand.pedestrians_per_hour > 0.0:
        runs.append(('pedestrians.trips.xml', common + [
            '--period', f'{3600.0 / demand.pedestrians_per_hour:.17g}',
            '--seed', str(seed + PEDESTRIAN_SEED_OFFSET), '--pedestrians',
            '--prefix', 'ped_']))
    return runs


def demand_routes(net, demand, seed, begin_s, source):
    """
    Return the route files of ``demand`` on network ``net`` (made now or found in the cache).

    :param net: the .net.xml path.
    :param demand: core SumoDemand.
    :param seed: its seed (the demand's own, else the engine's).
    :param begin_s: the first departure [s] (the engine's begin).
    :param source: quoted in errors ('world.yaml: traffic').
    :raises InvalidParameterError: randomTrips failed (its message's last lines).
    """
    home = sumo_home()
    script = os.path.join(home, 'tools', 'randomTrips.py')
    runs = _runs('net.xml', demand, seed, begin_s)
    key = hashlib.sha256()
    with open(net, 'rb') as handle:
        for chunk in iter(lambda: handle.read(1 << 20), b''):
            key.update(chunk)
    key.update(repr((runs, _sumo_version(home))).encode())
    folder = os.path.join(cache_dir(), 'sumo_demand', key.hexdigest()[:32])
    names = [name for name, _ in runs]
    if os.path.isdir(folder) and all(os.path.isfile(os.path.join(folder, n)) for n in names):
        return [os.path.join(folder, name) for name in names]
    os.makedirs(os.path.dirname(folder), exist_ok=True)
    work = tempfile.mkdtemp(prefix='making_', dir=os.path.dirname(folder))
    try:
        os.symlink(os.path.abspath(net), os.path.join(work, 'net.xml'))
        env = dict(os.environ, SUMO_HOME=home)
        for name, args in runs:
            try:
                done = subprocess.run([sys.executable, script, *args, '-o', name], cwd=work,
                                      env=env, capture_output=True, text=True,
                                      timeout=RANDOM_TRIPS_TIMEOUT_S)
            except subprocess.TimeoutExpired:
                raise InvalidParameterError(
                    f'{source}: demand: randomTrips.py took more than '
                    f'{RANDOM_TRIPS_TIMEOUT_S:g} s for {name}') from None
            if done.returncode != 0 or not os.path.isfile(os.path.join(work, name)):
                lines = [line for line in (done.stderr + done.stdout).splitlines()
                         if line.strip()]
                raise InvalidParameterError(
                    f'{source}: demand: randomTrips.py failed on {net} ({name}): '
                    + '; '.join(lines[-6:]))
        os.remove(os.path.join(work, 'net.xml'))
        try:
            os.rename(work, folder)
        except OSError:               # made meanwhile by another process: keep theirs
            shutil.rmtree(work, ignore_errors=True)
    finally:
        if os.path.isdir(work):
            shutil.rmtree(work, ignore_errors=True)
    return [os.path.join(folder, name) for name in names]


def _sumo_version(home):
    try:
        import sumo
        return getattr(sumo, '__version__', home)
    except ImportError:
        return home
