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

"""Engine models and output torque (Webots' driver.c, compute_output_torque)."""

import math
from types import SimpleNamespace

import pytest

from vehicle_sim.core.car.drivetrain import engine_rpm, output_torque_nm
from vehicle_sim.core.car.engines import (
    CombustionEngine,
    ElectricEngine,
    ENGINE_MODELS,
    EngineType,
    make_engine,
    ParallelHybridEngine,
    PowerSplitHybridEngine,
)
from vehicle_sim.core.car.params import DEFAULT_CAR, ENGINE_TYPES
from vehicle_sim.core.specs.errors import InvalidParameterError

# Car defaults: a, b, c = 150 N·m, 0.1 N·m/rpm, 0; min 1000 rpm, max 4500 rpm; electric limits
# 250 N·m and 50 kW; power split ratio 0.25 at 3000 rpm. c is made non-zero to test the square.
COEFFICIENTS = (150.0, 0.1, -1e-5)
PARAMS = DEFAULT_CAR.replace(engine_function_coefficients=COEFFICIENTS)


def _engine(engine_type):
    return make_engine(PARAMS.replace(engine_type=engine_type))


def _combustion(rpm):
    a, b, c = COEFFICIENTS
    return a + b * rpm + c * rpm * rpm


def _electric(rpm):
    # min(250, 50000 W / ω), ω = 2π·rpm/60.
    return 250.0 if rpm == 0 else min(250.0, 50000.0 * 60.0 / (2.0 * math.pi * rpm))


def test_engine_registry_covers_every_engine_type():
    assert tuple(ENGINE_MODELS) == ENGINE_TYPES


@pytest.mark.parametrize('name, cls, code', [
    ('combustion', CombustionEngine, EngineType.COMBUSTION),
    ('electric', ElectricEngine, EngineType.ELECTRIC),
    ('parallel hybrid', ParallelHybridEngine, EngineType.PARALLEL_HYBRID),
    ('power-split hybrid', PowerSplitHybridEngine, EngineType.POWER_SPLIT_HYBRID),
])
def test_make_engine_builds_the_registered_class_with_webots_code(name, cls, code):
    engine = _engine(name)
    assert type(engine) is cls
    assert engine.engine_type == code


def test_make_engine_unknown_name_lists_valid_names():
    expected = "'diesel'.*'combustion'.*'power-split hybrid'"
    with pytest.raises(InvalidParameterError, match=expected):
        make_engine(SimpleNamespace(engine_type='diesel'))


@pytest.mark.parametrize('rpm, expected', [
    (0.0, _combustion(1000.0)),     # below engineMinRPM: raised to 1000 → 150 + 100 − 10
    (500.0, _combustion(1000.0)),
    (1000.0, 240.0),                # 150 + 0.1·1000 − 1e-5·1000²
    (3000.0, 360.0),                # 150 + 300 − 90
    (4500.0, _combustion(4500.0)),
])
def test_combustion_torque_is_quadratic_with_idle_floor(rpm, expected):
    assert _engine('combustion').torque_nm(rpm) == pytest.approx(expected, rel=1e-12)


@pytest.mark.parametrize('rpm, expected', [
    (0.0, 250.0),                   # rpm 0: maxPower/0 = inf in C → maxTorque
    (500.0, 250.0),                 # 50 kW / 52.36 rad/s = 955 N·m > 250
    (1909.859, 250.0),              # power limit meets torque limit at 50000/250 = 200 rad/s
    (3000.0, 50000.0 / (2.0 * math.pi * 50.0)),   # 159.15 N·m
    (4500.0, 50000.0 / (2.0 * math.pi * 75.0)),   # 106.10 N·m
])
def test_electric_torque_is_min_of_torque_and_power_limits(rpm, expected):
    assert _engine('electric').torque_nm(rpm) == pytest.approx(expected, rel=1e-6)


@pytest.mark.parametrize('rpm, expected', [
    (0.0, 250.0),                                # combustion off below engineMinRPM
    (999.0, 250.0),
    (1000.0, 250.0 + 240.0),                     # combustion joins at exactly min rpm
    (3000.0, _electric(3000.0) + 360.0),
])
def test_parallel_hybrid_adds_combustion_only_from_min_rpm(rpm, expected):
    assert _engine('parallel hybrid').torque_nm(rpm) == pytest.approx(expected, rel=1e-12)


@pytest.mark.parametrize('rpm, expected', [
    (0.0, 250.0),
    (999.0, 250.0),
    # (1 − 0.25)·(150 + 0.1·3000 − 1e-5·3000²) = 0.75·360 = 270, at the fixed split rpm
    (1000.0, 250.0 + 270.0),
    (4000.0, _electric(4000.0) + 270.0),
])
def test_power_split_hybrid_adds_fixed_rpm_combustion_share_from_min_rpm(rpm, expected):
    assert _engine('power-split hybrid').torque_nm(rpm) == pytest.approx(expected, rel=1e-12)


@pytest.mark.parametrize('engine_type', ENGINE_TYPES)
def test_output_torque_is_zero_at_max_rpm_clamp(engine_type):
    engine = _engine(engine_type)
    # Wheels spinning far too fast for gear 1 (ratio 10): the estimate clamps at 4500 rpm.
    rpm = engine_rpm([100.0] * 4, 1, PARAMS.gear_ratio, PARAMS.engine_max_rpm)
    assert rpm == 4500.0
    assert output_torque_nm(engine, rpm, 1, PARAMS.gear_ratio, 1.0, 0.0) == 0.0
    assert output_torque_nm(engine, 4500.0 - 1e-6, 1, PARAMS.gear_ratio, 1.0, 0.0) != 0.0


@pytest.mark.parametrize('engine_type', ENGINE_TYPES)
def test_output_torque_is_engine_torque_times_throttle_and_gear_ratio(engine_type):
    engine = _engine(engine_type)
    # gear 2 ratio 6.5, throttle 0.4, 2000 rpm.
    expected = engine.torque_nm(2000.0) * 0.4 * 6.5
    assert output_torque_nm(engine, 2000.0, 2, PARAMS.gear_ratio, 0.4, 0.0) == \
        pytest.approx(expected, rel=1e-12)


def test_output_torque_reverse_gear_is_negative():
    engine = _engine('combustion')
    # Reverse uses gearRatio[0] = −12: 240 N·m · 1 · (−12).
    assert output_torque_nm(engine, 1000.0, -1, PARAMS.gear_ratio, 1.0, 0.0) == \
        pytest.approx(-2880.0, rel=1e-12)


def test_output_torque_neutral_is_zero():
    engine = _engine('electric')
    assert output_torque_nm(engine, 1000.0, 0, PARAMS.gear_ratio, 1.0, 0.0) == 0.0


@pytest.mark.parametrize('max_acc, scale', [(50.0, 1.0), (-50.0, 1.0), (100.0, 0.5),
                                            (-200.0, 0.25)])
def test_output_torque_acceleration_limiter_scales_by_50_over_max_acc(max_acc, scale):
    engine = _engine('combustion')
    unlimited = output_torque_nm(engine, 2000.0, 1, PARAMS.gear_ratio, 1.0, 0.0)
    assert output_torque_nm(engine, 2000.0, 1, PARAMS.gear_ratio, 1.0, max_acc) == \
        pytest.approx(unlimited * scale, rel=1e-12)
