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
Cities on SUMO (docs/sumo.md): SUMO alone and co-simulated, netconvert of 1 MB of OpenDRIVE.

The traffic: the shipped city (config/maps/city_sumo.net.xml: a 4 x 4 signalised grid with
sidewalks and crossings), SUMO stepping at 0.1 s, about 200 vehicles and 50 pedestrians (routes
made by SUMO's randomTrips.py in a temporary folder, seeded: a vehicle every 0.5 s and a person
every 5.5 s from anywhere to anywhere, which keeps about that many in the city once it has
filled; the first 300 simulated seconds fill it and are not timed). Each figure is simulated
seconds / wall seconds over the next 60 (30 with ``--quick``); the same on CPU time is printed
beside it (less moved by other work on a shared machine).

- SUMO alone: libsumo steps the city, nothing else; the mean numbers of vehicles and persons
  over the window, the process's RSS. SUMO runs with the same options on both sides
  (:data:`SUMO_OPTIONS`: its warnings off, which the engine gets as ``options:``).
- Co-simulated: the world of the city map with ``traffic: {engine: sumo, routes: ...}`` (the
  same routes) and one ego car (ToyotaPrius, at rest on lane A1B1_1) with a 1080-ray lidar
  (270 degrees, 30 m) sampled at 10 Hz, built by the scene builder and stepped by
  ``World.step`` at 10 ms (target >= 20x real time); before it, in the same process, the same
  car and lidar in an empty world (no map, no traffic). The cost: the co-simulation's time per
  simulated second over SUMO alone's plus the empty world's (target <= 2x). Its RSS. The same
  again (both worlds) at 20 ms steps, the coarsest step at which the physics car's checks run
  (``CHECKED_TIME_STEPS_MS``, docs/physics.md), with the same targets; and again at 10 ms with
  ``transport: worker`` (libsumo in a process of its own, stepping while the physics runs:
  physics/sumo_worker.py), the same targets; its CPU time figures add the worker's (read from
  /proc) to the world process's.
- netconvert: an OpenDRIVE file of about 1 MB made by the benchmark (netgenerate's 6 x 6 grid of
  two-lane roads with traffic lights, written as OpenDRIVE by netconvert
  ``--opendrive-output``) converted as a world's ``map: {type: opendrive}`` converts it
  (vehicle_sim/maps/netconvert.py, a fresh cache each time): wall time (best of 3),
  netconvert's peak RSS; then the network read as a lane map, timed.

Each part runs in a fresh process (libsumo holds one simulation per process, and a fresh
process's RSS is its own). Needs the ``sumo`` extra (``pip install 'vehicle_sim[sumo]'``; the
``test`` extra has it).

Run: ``.venv/bin/python benchmarks/bench_sumo.py [--quick]``.
"""

import argparse
import json
import math
import os
from pathlib import Path
import resource
import subprocess
import sys
import tempfile
import time
import warnings

HERE = Path(__file__).resolve().parent
REPO = HERE.parent
CITY = REPO / 'config' / 'maps' / 'city_sumo.net.xml'
STEP_S = 0.1
VEHICLE_PERIOD_S = 0.5       # randomTrips: one vehicle every 0.5 s -> about 200 in the city
PERSON_PERIOD_S = 5.5        # one person every 5.5 s -> about 50 walking
FILL_S = 300.0               # simulated seconds before timing: the city fills up
XODR_GRID = 6                # netgenerate grid of 6 x 6 junctions: about 1 MB of OpenDRIVE
TARGET_RTF = 20.0            # co-simulated real-time factor (docs/sumo.md)
PARTS = ('alone', 'cosim', 'cosim_coarse', 'cosim_worker', 'netconvert')
TARGET_COST = 2.0            # co-simulated / (SUMO alone + the empty world), per simulated s
# SUMO's options on both sides (alone, and the engine's ``options:``): its warnings off (SUMO
# writes each to the terminal and the error log; they change no result)
SUMO_OPTIONS = ('--no-warnings', 'true')
# The ego car: at rest on the right lane of A1B1 (eastbound, row 1), 20 m in; its lidar as the
# other benchmarks' (1080 rays over 270 degrees, 30 m) at 10 Hz.
EGO_POSE = {'x': 90.0, 'y': 155.2, 'yaw': 0.0}
LIDAR = {'name': 'lidar', 'type': 'lidar', 'fov': 4.71238898, 'horizontal_resolution': 1080,
         'max_range': 30.0, 'pose': {'x': 1.0, 'z': 0.5}, 'rate_hz': 10.0}


def sumo_home():
    """Return the eclipse-sumo package's SUMO_HOME (bin/netconvert, tools/randomTrips.py)."""
    from vehicle_sim.maps.netconvert import sumo_home as package_home
    return package_home('the SUMO benchmark')


def _run(command, cwd=None):
    env = dict(os.environ, SUMO_HOME=sumo_home())
    result = subprocess.run(command, capture_output=True, text=True, env=env, cwd=cwd,
                            check=False)
    if result.returncode != 0:
        raise RuntimeError(f'{Path(command[0]).name} failed: '
                           f'{(result.stderr or result.stdout).strip()[-2000:]}')
    return result


def city_routes(folder, end_s, seed=1):
    """Write seeded vehicle routes and person trips for the city into ``folder``; return paths."""
    tool = os.path.join(sumo_home(), 'tools', 'randomTrips.py')
    folder = Path(folder)
    vehicles, persons = folder / 'vehicles.rou.xml', folder / 'persons.rou.xml'
    _run([sys.executable, tool, '-n', str(CITY), '-o', str(folder / 'vehicles.trips.xml'),
          '-r', str(vehicles), '--seed', str(seed), '--begin', '0', '--end', f'{end_s:g}',
          '--period', f'{VEHICLE_PERIOD_S:g}', '--fringe-factor', '10', '--validate',
          '--prefix', 'v'], cwd=folder)
    _run([sys.executable, tool, '-n', str(CITY), '-o', str(persons), '--seed', str(seed + 1),
          '--begin', '0', '--end', f'{end_s:g}', '--period', f'{PERSON_PERIOD_S:g}',
          '--pedestrians', '--prefix', 'p'], cwd=folder)
    return vehicles, persons


def _rss_mb(key='VmRSS'):
    with open('/proc/self/status', encoding='ascii') as stream:
        for line in stream:
            if line.startswith(key + ':'):
                return int(line.split()[1]) / 1024.0
    return float('nan')


def alone_arguments(vehicles, persons, seed=1):
    """Return sumo's options for SUMO alone: the city, the routes, SUMO_OPTIONS as the engine's."""
    return ['-n', str(CITY), '-r', f'{vehicles},{persons}', '--step-length', f'{STEP_S:g}',
            '--seed', str(seed), '--no-step-log', 'true', *SUMO_OPTIONS]


def sumo_alone(measure_s, seed=1):
    """Return the SUMO-alone figures (this process runs libsumo: call it in a fresh one)."""
    from vehicle_sim.physics.sumo_session import load_libsumo
    libsumo = load_libsumo()           # without the note it prints about pyarrow's version
    with tempfile.TemporaryDirectory(prefix='bench_sumo_') as folder:
        vehicles, persons = city_routes(folder, FILL_S + measure_s + 60.0, seed)
        rss_before = _rss_mb()
        libsumo.start(['sumo', *alone_arguments(vehicles, persons, seed)])
        try:
            for _ in range(int(round(FILL_S / STEP_S))):
                libsumo.simulationStep()
            steps = int(round(measure_s / STEP_S))
            vehicle_sum = person_sum = 0
            wall = cpu = 0.0
            for _ in range(steps):
                start, start_cpu = time.perf_counter(), time.process_time()
                libsumo.simulationStep()
                wall += time.perf_counter() - start
                cpu += time.process_time() - start_cpu
                vehicle_sum += libsumo.vehicle.getIDCount()
                person_sum += libsumo.person.getIDCount()
            rss = _rss_mb()
        finally:
            libsumo.close()
    return {'rtf': measure_s / wall, 'cpu_rtf': measure_s / cpu,
            'step_ms': wall / steps * 1e3, 'vehicles': vehicle_sum / steps,
            'persons': person_sum / steps, 'rss_mb': rss, 'rss_added_mb': rss - rss_before}


def _ego_world(folder, routes=None, seed=1, transport='auto'):
    """Return the WorldSpec of the ego car and its lidar: in the city with SUMO, or alone."""
    from vehicle_sim.config import world_from_data
    data = {'vehicles': [{'name': 'ego', 'model': 'ToyotaPrius', 'pose': dict(EGO_POSE),
                          'sensors': [dict(LIDAR)]}]}
    if routes is not None:
        data['map'] = {'type': 'sumo', 'net': str(CITY)}
        data['traffic'] = {'engine': 'sumo', 'routes': [str(path) for path in routes],
                           'step': STEP_S, 'seed': seed, 'options': list(SUMO_OPTIONS),
                           'transport': transport}
    return world_from_data(data, 'bench_sumo.yaml', base_dir=str(folder))


def _timed_steps(world, steps):
    start, start_cpu = time.perf_counter(), time.process_time()
    for _ in range(steps):
        world.step()
    return time.perf_counter() - start, time.process_time() - start_cpu


def _children_cpu_s(process):
    # CPU time [s] of a child process so far (/proc/<pid>/stat utime + stime)
    with open(f'/proc/{process.pid}/stat', encoding='ascii') as stream:
        fields = stream.read().rsplit(')', 1)[1].split()
    return (int(fields[11]) + int(fields[12])) / os.sysconf('SC_CLK_TCK')


def cosim(measure_s, seed=1, step_ms=None, transport='auto'):
    """
    Return the co-simulation figures (this process runs libsumo: call it in a fresh one).

    First the empty world (the ego car and its lidar, nothing else), then the city with SUMO's
    traffic filled for :data:`FILL_S` simulated seconds (not timed, the lidar off), each
    stepped by ``World.step`` at ``step_ms`` (None: the default 10 ms) for ``measure_s``
    simulated seconds with the lidar sampled at its 10 Hz; SUMO through ``transport``
    (a worker's CPU time over the window as ``worker_cpu_rtf``).
    """
    from vehicle_sim.core.specs.simulation import TIME_STEP_MS
    from vehicle_sim.physics.scene import build_scene, mount_suite
    step_s = (TIME_STEP_MS.default if step_ms is None else step_ms) / 1000.0
    found = {'step_ms': round(step_s * 1000.0)}
    with tempfile.TemporaryDirectory(prefix='bench_sumo_') as folder:
        empty = build_scene(_ego_world(folder), mount=mount_suite, time_step_s=step_s)
        try:
            world = empty.world
            empty.vehicles['ego'].sensors.start(['lidar'])
            _timed_steps(world, 100)
            steps = int(round(measure_s / world.time_step_s))
            wall, cpu = _timed_steps(world, steps)
            found['empty_rtf'], found['empty_cpu_rtf'] = measure_s / wall, measure_s / cpu
        finally:
            empty.world.close()
        routes = city_routes(folder, FILL_S + measure_s + 60.0, seed)
        rss_before = _rss_mb()
        start = time.perf_counter()
        city = build_scene(_ego_world(folder, routes, seed, transport), mount=mount_suite,
                           time_step_s=step_s)
        found['build_s'] = time.perf_counter() - start
        try:
            world = city.world
            _timed_steps(world, int(round(FILL_S / world.time_step_s)))
            traffic = city.parts['traffic'] if hasattr(city, 'parts') else None
            city.vehicles['ego'].sensors.start(['lidar'])
            worker = None if traffic is None else getattr(traffic.session.api, 'worker', None)
            before = None if worker is None else _children_cpu_s(worker._process)
            wall, cpu = _timed_steps(world, steps)
            found['rtf'], found['cpu_rtf'] = measure_s / wall, measure_s / cpu
            if worker is not None:
                found['worker_cpu_rtf'] = measure_s / (_children_cpu_s(worker._process)
                                                       - before)
            found['agents'] = len(traffic.agents()) if traffic is not None else -1
            found['rss_mb'] = _rss_mb()
            found['rss_added_mb'] = found['rss_mb'] - rss_before
        finally:
            city.world.close()
    return found


def make_xodr(folder, grid=XODR_GRID):
    """Write an OpenDRIVE file of a netgenerate grid into ``folder``; return its path."""
    folder = Path(folder)
    net, xodr = folder / 'grid.net.xml', folder / 'grid.xodr'
    home = sumo_home()
    _run([os.path.join(home, 'bin', 'netgenerate'), '--grid', '--grid.number', str(grid),
          '--grid.length', '100', '--default.lanenumber', '2', '--tls.guess',
          '--no-turnarounds', '-o', str(net)])
    _run([os.path.join(home, 'bin', 'netconvert'), '-s', str(net), '--opendrive-output',
          str(xodr)])
    return xodr


def netconvert_xodr(repeats=3):
    """
    Return the OpenDRIVE figures: size, conversion time, netconvert's peak RSS, the lane map.

    The file converted as a world's ``map: {type: opendrive, file: ...}`` converts it
    (vehicle_sim/maps/netconvert.py: the kind's netconvert options), each time into a fresh
    cache folder (best of ``repeats``); then the converted network read as the lane map
    (sumolib, the lanes, the rules, the conflicts) once, timed.
    """
    from vehicle_sim.core.map.kinds import map_from_dict
    from vehicle_sim.maps.netconvert import convert
    from vehicle_sim.maps.sumo_net import load_sumo_net
    with tempfile.TemporaryDirectory(prefix='bench_sumo_xodr_') as folder:
        xodr = make_xodr(folder)
        best, net = float('inf'), None
        for index in range(repeats):
            spec = map_from_dict({'type': 'opendrive', 'file': str(xodr),
                                  'cache': f'cache{index}'},
                                 'bench_sumo.yaml: map', folder)
            start = time.perf_counter()
            net = convert(spec)
            best = min(best, time.perf_counter() - start)
        # ru_maxrss of the children: the largest netconvert run by this process [KiB]
        peak = resource.getrusage(resource.RUSAGE_CHILDREN).ru_maxrss / 1024.0
        start = time.perf_counter()
        with warnings.catch_warnings():
            warnings.simplefilter('ignore')       # lanes left out, said once: not timed here
            graph, _ = load_sumo_net(net, 'passenger', 'bench_sumo.yaml: map.file')
        load_s = time.perf_counter() - start
        return {'size_mb': xodr.stat().st_size / 1e6, 'seconds': best, 'peak_mb': peak,
                'lanes': len(graph.lanes), 'groups': len(graph.rules.groups),
                'load_s': load_s}


def _in_fresh_process(part, quick):
    command = [sys.executable, str(Path(__file__).resolve()), '--part', part]
    if quick:
        command.append('--quick')
    env = dict(os.environ, PYTHONPATH=str(REPO) + os.pathsep + os.environ.get('PYTHONPATH', ''))
    result = subprocess.run(command, capture_output=True, text=True, env=env, check=False)
    if result.returncode != 0:
        raise RuntimeError(f'bench_sumo --part {part} failed: {result.stderr[-3000:]}')
    return json.loads(result.stdout.strip().splitlines()[-1])


def measure(quick=False):
    """Return every figure of this benchmark, each part measured in a fresh process."""
    found = {part: _in_fresh_process(part, quick) for part in PARTS}
    alone = found['alone']
    # per simulated second: the co-simulation's wall time over SUMO alone's plus the empty
    # world's (the ego car and its lidar, nothing else), at each step
    # (through a worker, its CPU time added to the world process's)
    for part in ('cosim', 'cosim_coarse', 'cosim_worker'):
        cosim = found[part]
        cosim['cost'] = (1.0 / cosim['rtf']) / (1.0 / alone['rtf'] + 1.0 / cosim['empty_rtf'])
        cpu = 1.0 / cosim['cpu_rtf'] + 1.0 / cosim.get('worker_cpu_rtf', math.inf)
        cosim['cpu_cost'] = cpu / (1.0 / alone['cpu_rtf'] + 1.0 / cosim['empty_cpu_rtf'])
    return found


def figures(quick=False):
    """Return (rows, context lines) for run_all.py; ([], [why]) without the sumo extra."""
    import importlib.util
    missing = [name for name in ('sumo', 'libsumo') if importlib.util.find_spec(name) is None]
    if missing:
        return [], [f"SUMO figures skipped: no {', '.join(missing)} "
                    "(pip install 'vehicle_sim[sumo]')"]
    found = measure(quick)
    alone, cosim, convert = found['alone'], found['cosim'], found['netconvert']
    coarse = found['cosim_coarse']
    rows = [
        (f'SUMO city co-simulated ({alone["vehicles"]:.0f} vehicles + {alone["persons"]:.0f} '
         'persons, 0.1 s; ego with a 1080-ray lidar, 10 ms): real-time factor', cosim['rtf'],
         '>=', TARGET_RTF, 'x'),
        ('  same: cost / (SUMO alone + the empty world), per simulated second', cosim['cost'],
         '<=', TARGET_COST, 'x'),
        (f'  same at {coarse["step_ms"]} ms steps (the coarsest checked step): real-time '
         'factor', coarse['rtf'], '>=', TARGET_RTF, 'x'),
        (f'  same at {coarse["step_ms"]} ms steps: cost / (SUMO alone + the empty world at '
         f'{coarse["step_ms"]} ms)', coarse['cost'], '<=', TARGET_COST, 'x'),
        ('  same through a SUMO worker (transport: worker, 10 ms): real-time factor',
         found['cosim_worker']['rtf'], '>=', TARGET_RTF, 'x'),
        ('  same through a SUMO worker: cost / (SUMO alone + the empty world)',
         found['cosim_worker']['cost'], '<=', TARGET_COST, 'x'),
        ('  same: SUMO alone (libsumo), real-time factor', alone['rtf'], None, None, 'x'),
        ('  same: RSS of the co-simulating process', cosim['rss_mb'], None, None, 'MB'),
        (f'netconvert of a {convert["size_mb"]:.2f} MB OpenDRIVE file', convert['seconds'],
         None, None, 's'),
    ]
    return rows, [describe(found)]


def describe(found):
    """Return one line of context about the figures."""
    alone, cosim, convert = found['alone'], found['cosim'], found['netconvert']
    return (f'SUMO city: alone {alone["step_ms"]:.2f} ms per 0.1 s step ({alone["rtf"]:.0f}x '
            f'real time, {alone["cpu_rtf"]:.0f}x on CPU time), {alone["vehicles"]:.0f} vehicles '
            f'and {alone["persons"]:.0f} persons on average, RSS {alone["rss_mb"]:.0f} MB '
            f'({alone["rss_added_mb"]:+.0f} MB by SUMO); co-simulated {cosim["rtf"]:.1f}x '
            f'({cosim["cpu_rtf"]:.1f}x on CPU time, {cosim["agents"]} SUMO bodies at the end), '
            f'the empty world with the lidar {cosim["empty_rtf"]:.0f}x '
            f'({cosim["empty_cpu_rtf"]:.0f}x on CPU time); cost '
            f'{cosim["cost"]:.2f}x SUMO alone + the empty world ({cosim["cpu_cost"]:.2f}x on CPU '
            f'time); through a SUMO worker {found["cosim_worker"]["rtf"]:.1f}x '
            f'({found["cosim_worker"]["cpu_rtf"]:.1f}x on the world process\'s CPU time, the '
            f'worker {found["cosim_worker"]["worker_cpu_rtf"]:.0f}x on its own), cost '
            f'{found["cosim_worker"]["cost"]:.2f}x ({found["cosim_worker"]["cpu_cost"]:.2f}x '
            'on the CPU time of both processes); built in '
            f'{cosim["build_s"]:.1f} s, RSS {cosim["rss_mb"]:.0f} MB '
            f'({cosim["rss_added_mb"]:+.0f} MB by the city and SUMO); netconvert: '
            f'{convert["size_mb"]:.2f} MB of OpenDRIVE in {convert["seconds"]:.2f} s (peak RSS '
            f'{convert["peak_mb"]:.0f} MB), read as a lane map of {convert["lanes"]} lanes and '
            f'{convert["groups"]} signal groups in {convert["load_s"]:.2f} s')


def _part(name, quick):
    if name == 'alone':
        return sumo_alone(30.0 if quick else 60.0)
    if name == 'cosim':
        return cosim(30.0 if quick else 60.0)
    if name == 'cosim_worker':
        return cosim(30.0 if quick else 60.0, transport='worker')
    if name == 'cosim_coarse':
        from vehicle_sim.core.specs.simulation import CHECKED_TIME_STEPS_MS
        return cosim(30.0 if quick else 60.0, step_ms=max(CHECKED_TIME_STEPS_MS))
    return netconvert_xodr(2 if quick else 3)


def _met(value, relation, target):
    return value >= target if relation == '>=' else value <= target


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.split('\n\n')[0])
    parser.add_argument('--quick', action='store_true', help='fewer samples')
    parser.add_argument('--part', choices=PARTS,
                        help='measure one part in this process and print it as JSON')
    options = parser.parse_args(argv)
    if options.part:
        print(json.dumps(_part(options.part, options.quick)))
        return 0
    rows, context = figures(options.quick)
    for name, value, relation, target, unit in rows:
        verdict = '' if relation is None else (
            f'  (target {relation} {target:g}: '
            f'{"met" if _met(value, relation, target) else "MISSED"})')
        print(f'{name}: {value:.2f} {unit}{verdict}')
    for line in context:
        print(line)
    print(f'load average {"/".join(f"{x:.1f}" for x in os.getloadavg())} on '
          f'{os.cpu_count()} cores')
    return 0


if __name__ == '__main__':
    sys.exit(main())
