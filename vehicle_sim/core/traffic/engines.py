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
Traffic engines: what moves a world's traffic, chosen by ``traffic: engine:``.

A traffic engine is a :class:`TrafficEngine` row in :data:`TRAFFIC_ENGINES`: its name, the
parser of its ``traffic:`` mapping (validated against its own ParamSpec tables; the spec it
returns carries ``engine`` = its name, ``source`` and ``objects_rate_hz``) and the generator of
its key tables for docs/traffic.md. ``builtin`` (the default) is the IDM/MOBIL manager on the
lane graph (core/traffic/params.py, core/traffic/manager.py). The physics layer builds each
engine's bodies from its row of ``TRAFFIC_BUILDERS`` (physics/traffic_bodies.py), under the
same name; test/test_repo_kind_registries.py checks that the two agree.
"""

from dataclasses import dataclass
from typing import Callable, Dict

from vehicle_sim.core.specs.errors import InvalidParameterError
from vehicle_sim.core.specs.registry import register
from vehicle_sim.core.specs.value_text import brief
from vehicle_sim.core.traffic import params as builtin
from vehicle_sim.core.traffic import sumo_params as sumo

DEFAULT_ENGINE = 'builtin'


@dataclass(frozen=True)
class TrafficEngine:
    """
    One traffic engine: its name, its parser and its docs tables.

    :param name: the value of ``traffic: engine:``.
    :param parse: ``parse(data, source, check_model, base_dir)`` -> its spec (``data`` the
        whole ``traffic:`` mapping, ``engine`` included; ``check_model(name)`` raises for an
        unknown car preset, or is None; ``base_dir`` the folder the files it names are resolved
        in, the world file's, or None).
    :param markdown: ``markdown()`` -> its key tables (docs/traffic.md, docs/sumo.md).
    :param doc: one line for the docs.
    """

    name: str
    parse: Callable
    markdown: Callable[[], str]
    doc: str = ''


TRAFFIC_ENGINES: Dict[str, TrafficEngine] = {}


def register_traffic_engine(engine: TrafficEngine) -> TrafficEngine:
    """Add a traffic engine to :data:`TRAFFIC_ENGINES` (its name must be new)."""
    return register(TRAFFIC_ENGINES, engine, 'traffic engine')


register_traffic_engine(TrafficEngine(
    DEFAULT_ENGINE, builtin.traffic_from_dict, builtin.traffic_markdown,
    'IDM car following and MOBIL lane changes on the lane graph, in process (the default)'))
register_traffic_engine(TrafficEngine(
    sumo.ENGINE, sumo.sumo_traffic_from_dict, sumo.sumo_traffic_markdown,
    "Eclipse SUMO on the world's SUMO network (vehicles, persons, its signal programs), "
    'through libsumo or TraCI (docs/sumo.md)'))


def engine_name(data, source) -> str:
    """Return the engine a ``traffic:`` mapping names (``engine``; default builtin)."""
    name = data.get('engine', DEFAULT_ENGINE) if isinstance(data, dict) else DEFAULT_ENGINE
    if not isinstance(name, str) or name not in TRAFFIC_ENGINES:
        raise InvalidParameterError(f"{source}: field 'engine' = {brief(name)}: unknown "
                                    'traffic engine; valid: ' + ', '.join(TRAFFIC_ENGINES))
    return name


def traffic_spec_from_dict(data, source, check_model=None, base_dir=None):
    """
    Validate a ``traffic:`` mapping with its engine's parser; return that engine's spec.

    :param base_dir: the folder files named in it are resolved in (the world file's).
    :raises InvalidParameterError: naming the file and field.
    """
    return TRAFFIC_ENGINES[engine_name(data, source)].parse(data, source, check_model, base_dir)
