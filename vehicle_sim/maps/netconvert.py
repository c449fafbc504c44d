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
OpenDRIVE files and OpenStreetMap extracts as SUMO networks: SUMO's ``netconvert``, cached.

:func:`net_file` returns the ``.net.xml`` of a SUMO network map spec (core/map/
sumo_net_params.py): a ``sumo`` map's own file, or the network ``netconvert`` made of an
``opendrive`` or ``osm`` map's file. The ``netconvert`` is the one the ``eclipse-sumo`` package
ships (``sumo.SUMO_HOME/bin/netconvert``; the ``sumo`` extra), run as::

    netconvert <input option> <file> <the kind's options> --no-internal-links false
               --no-warnings true <the map's options:> -o <cache>/<key>.net.xml

with ``SUMO_HOME`` set to the package's (its type maps and schemas) and PROJ's data to the
package's ``data/proj`` (the projection of OSM's latitudes and longitudes). The kinds' options are
core/map/sumo_net_params.py's ``OPENDRIVE_INPUT`` and ``OSM_INPUT`` (OSM: sidewalks and
crossings guessed, traffic lights guessed and joined, ramps guessed, junctions joined); a map's
``options:`` come after them, so that they add to or override them (netconvert takes the last
value of an option).

The network is cached in the map's ``cache:`` folder (default
``$XDG_CACHE_HOME/vehicle_sim/netconvert``, ``~/.cache/vehicle_sim/netconvert`` without it) as
``<key>.net.xml``, where the key is a SHA-256 of the file's content, the options and
netconvert's version: a second world with the same file and options reads the cached network
without running netconvert; another file content, option or netconvert version converts anew.
The network is written to a temporary file in the folder and renamed when complete, so that a
conversion that fails or is interrupted leaves no cached network.

A file netconvert refuses is an InvalidParameterError naming the world file's key, the file and
netconvert's first error lines.
"""

import functools
import hashlib
import os
import subprocess
import tempfile

from vehicle_sim.core.map.sumo_net_params import NETCONVERT_ALWAYS
from vehicle_sim.core.specs.errors import InvalidParameterError
from vehicle_sim.maps.sumo_net import EXTRA_HINT, SumoUnavailable

ERROR_LINES = 6             # netconvert's error lines quoted at most
# Options that set netconvert's output: the cache sets it.
OUTPUT_OPTIONS = ('-o', '--output-file', '--sumo-output', '--output')


def sumo_home(needs='converting a map with netconvert'):
    """
    Return the eclipse-sumo package's SUMO_HOME; SumoUnavailable names the extra if none.

    :param needs: what needs it, for the error ('the sumo traffic engine').
    """
    try:
        import sumo
    except ImportError:
        raise SumoUnavailable(f'{needs} needs the eclipse-sumo package: ' + EXTRA_HINT) from None
    return sumo.SUMO_HOME


def netconvert_path():
    """Return the netconvert executable of the eclipse-sumo package."""
    path = os.path.join(sumo_home(), 'bin', 'netconvert')
    if not os.access(path, os.X_OK):
        raise SumoUnavailable(f'the eclipse-sumo package has no netconvert at {path}: '
                              + EXTRA_HINT)
    return path


def _environment():
    """Return netconvert's environment: SUMO_HOME and PROJ's data (the package's)."""
    home = sumo_home()
    environment = dict(os.environ, SUMO_HOME=home)
    proj = os.path.join(home, 'data', 'proj')
    if os.path.isdir(proj):             # the projections of OSM's lat/lon (its proj.db)
        environment.setdefault('PROJ_DATA', proj)
        environment.setdefault('PROJ_LIB', proj)
    return environment


def netconvert_version():
    """Return netconvert's version line ('Eclipse SUMO netconvert 1.28.0')."""
    return _version_of(netconvert_path())


@functools.lru_cache(maxsize=None)
def _version_of(path):
    # once per executable and process: a world's load asks for it every time
    done = subprocess.run([path, '--version'], capture_output=True, text=True,
                          env=_environment(), check=False)
    return done.stdout.splitlines()[0].strip() if done.stdout else 'unknown'


def cache_root():
    """Return the folder of vehicle_sim's made files: $XDG_CACHE_HOME (or ~/.cache)/vehicle_sim."""
    base = os.environ.get('XDG_CACHE_HOME') or os.path.join(os.path.expanduser('~'), '.cache')
    return os.path.join(base, 'vehicle_sim')


def default_cache():
    """Return the default cache folder: $XDG_CACHE_HOME (or ~/.cache)/vehicle_sim/netconvert."""
    return os.path.join(cache_root(), 'netconvert')


def netconvert_options(spec):
    """Return netconvert's options for a map spec, without the output (module text)."""
    for option in spec.options:
        name = option.split('=', 1)[0]
        if name in OUTPUT_OPTIONS:
            raise InvalidParameterError(
                f"{spec.source}: field 'options': {option!r} sets netconvert's output, which "
                'the cache sets: leave it out')
    return ((spec.netconvert_input, spec.file) + tuple(spec.netconvert_options)
            + NETCONVERT_ALWAYS + tuple(spec.options))


def cache_key(spec, version):
    """Return the cache key of a map spec's conversion: its file's content, options, version."""
    digest = hashlib.sha256()
    with open(spec.file, 'rb') as handle:
        for block in iter(lambda: handle.read(1 << 20), b''):
            digest.update(block)
    options = netconvert_options(spec)
    digest.update('\0'.join((version, spec.netconvert_input) + options[2:]).encode('utf-8'))
    return digest.hexdigest()[:32]


def _errors(text):
    """Return netconvert's first error lines (its 'Error:' lines and what follows them)."""
    lines, taking = [], False
    for line in text.splitlines():
        if line.startswith('Error:'):
            taking = True
        elif line.startswith(('Warning:', 'Quitting')) or not line.strip():
            taking = False
        if taking:
            lines.append(line.strip())
    return lines[:ERROR_LINES] or [line.strip() for line in text.splitlines()
                                   if line.strip()][-ERROR_LINES:]


def convert(spec):
    """
    Return the path of the SUMO network of an opendrive or osm map spec (cached).

    :raises InvalidParameterError: the file is missing or netconvert refuses it (its first error
        lines), naming the world file's key and the file.
    :raises SumoUnavailable: the eclipse-sumo package is not installed.
    """
    where = f'{spec.source}.file: {spec.file}'
    if not os.path.isfile(spec.file):
        raise InvalidParameterError(f'{where}: no such file')
    version = netconvert_version()
    folder = spec.cache or default_cache()
    try:
        key = cache_key(spec, version)
    except OSError as error:
        raise InvalidParameterError(f'{where}: cannot be read: {error.strerror}') from None
    target = os.path.join(folder, f'{key}.net.xml')
    if os.path.isfile(target):
        return target
    try:
        os.makedirs(folder, exist_ok=True)
    except OSError as error:
        raise InvalidParameterError(f"{spec.source}: field 'cache': cannot make the folder "
                                    f'{folder}: {error.strerror}') from None
    handle, partial = tempfile.mkstemp(suffix='.net.xml.part', dir=folder)
    os.close(handle)
    try:
        done = subprocess.run([netconvert_path(), *netconvert_options(spec), '-o', partial],
                              capture_output=True, text=True, env=_environment(), check=False)
        if done.returncode != 0:
            raise InvalidParameterError(
                f'{where}: netconvert cannot convert it: '
                + ' / '.join(_errors(done.stderr + done.stdout)))
        os.replace(partial, target)
    finally:
        if os.path.exists(partial):
            os.unlink(partial)
    return target


def net_file(spec):
    """Return the ``.net.xml`` of a SUMO network map spec: its own, or netconvert's (cached)."""
    return spec.net if spec.net else convert(spec)
