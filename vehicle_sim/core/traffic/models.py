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
The traffic models, one registry each: car-following (the speed) and lane-change models.

A world's ``traffic: {model: {car_following: idm, lane_change: mobil}}`` names one of each (those
two by default); each model's parameters are the mapping under its own name (``traffic: {idm:
{time_headway: 1.2}}``), validated against its ParamSpec table. The traffic manager
(core/traffic/manager.py) looks its two models up once, when it is built, and calls only the
functions they bind to their parameters; the physics side moves whatever poses it gives.

A car-following model (:class:`CarFollowingModel`) binds its parameters into
``acceleration(speed, desired_speed, gap, leader_speed)`` [m/s^2] (``gap``: bumper-to-bumper
[m] to the leader, None on a free road; a gap <= 0 gets its hardest braking), gives the gap a
vehicle at a speed keeps at least (no lane change cuts in closer in front of one of our
vehicles, no vehicle re-enters the map closer behind one) and the comfortable deceleration
(start speeds are the highest at which the model brakes no harder).

A lane-change model (:class:`LaneChangeModel`) binds its parameters into
``should_change(accelerations)``: whether a vehicle changes, given the accelerations of it and
its old and new followers now and after the change (mobil.py's
:class:`~vehicle_sim.core.traffic.mobil.LaneChangeAccelerations`, each from the car-following
model); among the allowed changes, the one with the larger own gain is made.

Adding a model is a module of its own here (pure functions and a ParamSpec table, like idm.py
and mobil.py) and one ``register_*`` row below; docs/traffic.md's tables are generated.
"""

from dataclasses import dataclass
from typing import Callable, Dict, Tuple

from vehicle_sim.core.specs.param_spec import ParamSpec
from vehicle_sim.core.specs.registry import register
from vehicle_sim.core.traffic import idm, mobil


@dataclass(frozen=True)
class CarFollowingModel:
    """
    One car-following model.

    :param name: its name in ``traffic: model: car_following`` and the key of its parameters.
    :param specs: the ParamSpec table of its parameters.
    :param params: ``params(data, source)`` -> its validated parameters (data None: defaults).
    :param bind: ``bind(params)`` -> ``acceleration(speed, desired_speed, gap, leader_speed)``.
    :param min_gap: ``min_gap(params, speed)`` -> the gap [m] it keeps at least at ``speed``.
    :param comfortable_deceleration: ``comfortable_deceleration(params)`` -> [m/s^2] > 0.
    :param doc: one line for docs/traffic.md.
    """

    name: str
    specs: Tuple[ParamSpec, ...]
    params: Callable
    bind: Callable
    min_gap: Callable
    comfortable_deceleration: Callable
    doc: str = ''


@dataclass(frozen=True)
class LaneChangeModel:
    """
    One lane-change model.

    :param name: its name in ``traffic: model: lane_change`` and the key of its parameters.
    :param specs: the ParamSpec table of its parameters.
    :param params: ``params(data, source)`` -> its validated parameters (data None: defaults).
    :param bind: ``bind(params)`` -> ``should_change(LaneChangeAccelerations)`` -> bool.
    :param doc: one line for docs/traffic.md.
    """

    name: str
    specs: Tuple[ParamSpec, ...]
    params: Callable
    bind: Callable
    doc: str = ''


CAR_FOLLOWING_MODELS: Dict[str, CarFollowingModel] = {}
LANE_CHANGE_MODELS: Dict[str, LaneChangeModel] = {}


def _register(registry, model):
    # One name, one key of parameters under traffic: a name of either table is taken.
    return register(registry, model, 'traffic model',
                    taken=(CAR_FOLLOWING_MODELS, LANE_CHANGE_MODELS))


def register_car_following_model(model: CarFollowingModel) -> CarFollowingModel:
    """Add a car-following model to :data:`CAR_FOLLOWING_MODELS` (its name must be new)."""
    return _register(CAR_FOLLOWING_MODELS, model)


def register_lane_change_model(model: LaneChangeModel) -> LaneChangeModel:
    """Add a lane-change model to :data:`LANE_CHANGE_MODELS` (its name must be new)."""
    return _register(LANE_CHANGE_MODELS, model)


def all_models() -> Dict[str, object]:
    """Return every registered model by name (car-following first), in registration order."""
    return {**CAR_FOLLOWING_MODELS, **LANE_CHANGE_MODELS}


register_car_following_model(CarFollowingModel(
    'idm', idm.IDM_SPECS, idm.IdmParams.from_dict, idm.acceleration_function,
    lambda p, speed: p.min_gap_m + speed * p.time_headway_s,
    lambda p: p.deceleration_mps2,
    'the Intelligent Driver Model'))
register_lane_change_model(LaneChangeModel(
    'mobil', mobil.MOBIL_SPECS, mobil.MobilParams.from_dict,
    lambda p: lambda accelerations: mobil.should_change(accelerations, p),
    'MOBIL lane changes'))
