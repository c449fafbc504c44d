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

"""Autoware simple_planning_simulator models against their equations (kinematic_models)."""

import math

import pytest

from vehicle_sim.config import load_car
from vehicle_sim.core.car.kinematic_drive import (
    model_inputs,
    SPEED_GAIN_PER_S,
)
from vehicle_sim.core.car.kinematic_models import KinematicModel, vehicle_model_from
from vehicle_sim.core.car.logic import CarLogic
from vehicle_sim.core.car.speed_braking import cruise_ramp_mps2
from vehicle_sim.core.specs.errors import InvalidParameterError

DT = 0.01
WHEELBASE_M = 2.8
# RK4 with a constant input is exact to ~1e-8 on these lags; the tolerance covers the sampling
TOL = 1e-4


def _model(kind='DELAY_STEER_ACC', dt=DT, **changes):
    return KinematicModel(vehicle_model_from({'type': kind, **changes}), WHEELBASE_M, dt)


def _run(model, seconds, longitudinal, steer, gear=1):
    rows = []
    for _ in range(int(round(seconds / model.dt_s))):
        model.step(longitudinal, steer, gear)
        rows.append((model.vx_mps, model.steer_rad, model.acc_mps2))
    return rows


def test_defaults_are_the_simple_planning_simulator_readme_values():
    params = vehicle_model_from('DELAY_STEER_ACC')
    assert (params.vel_lim_mps, params.vel_rate_lim_mps2, params.steer_lim_rad,
            params.steer_rate_lim_radps) == (50.0, 7.0, 1.0, 5.0)
    assert (params.acc_time_delay_s, params.acc_time_constant_s, params.steer_time_delay_s,
            params.steer_time_constant_s) == (0.1, 0.1, 0.24, 0.27)
    assert vehicle_model_from(None) is None


def test_delayed_steering_step_response_dead_time_then_63_percent_at_tau():
    model = _model()
    rows = _run(model, 2.0, 0.0, 0.2)
    delay_steps = 24                    # round(0.24 / 0.01)
    assert all(steer == 0.0 for _, steer, _ in rows[:delay_steps])
    for k in (delay_steps + 1, delay_steps + 27, delay_steps + 100):
        t_after = (k - delay_steps) * DT
        expected = 0.2 * (1.0 - math.exp(-t_after / 0.27))
        assert rows[k - 1][1] == pytest.approx(expected, abs=TOL)
    # the time constant: 63.2 % of the step at tau after the dead time
    assert rows[delay_steps + 27 - 1][1] / 0.2 == pytest.approx(1.0 - math.exp(-1.0), abs=1e-3)


def test_delayed_acceleration_step_response_and_the_speed_it_gives():
    model = _model()
    rows = _run(model, 1.0, 1.0, 0.0)
    delay_steps = 10                    # round(0.1 / 0.01)
    assert all(acc == 0.0 and vx == 0.0 for vx, _, acc in rows[:delay_steps])
    tau = 0.1
    for k in (delay_steps + 10, delay_steps + 50):
        t = (k - delay_steps) * DT
        assert rows[k - 1][2] == pytest.approx(1.0 - math.exp(-t / tau), abs=TOL)
        assert rows[k - 1][0] == pytest.approx(t - tau * (1.0 - math.exp(-t / tau)), abs=TOL)
    assert rows[delay_steps + 10 - 1][2] == pytest.approx(0.632, abs=1e-3)


def test_delays_follow_the_parameters():
    model = _model(acc_time_delay=0.3, steer_time_delay=0.05)
    rows = _run(model, 0.5, 1.0, 0.1)
    assert rows[29][2] == 0.0 and rows[30][2] > 0.0           # 30 steps of dead time
    assert rows[4][1] == 0.0 and rows[5][1] > 0.0             # 5 steps
    assert _model(acc_time_delay=0.0)._acc_queue == type(_model()._acc_queue)()
    # a delay of half a step is one step (std::round), not none (Python's round to even)
    coarse = _model(dt=0.2)                     # acc 0.1 s, steer 0.24 s
    rows = _run(coarse, 0.6, 1.0, 0.1)
    assert rows[0][2] == 0.0 and rows[1][2] > 0.0
    assert rows[0][1] == 0.0 and rows[1][1] > 0.0


def test_steering_rate_and_angle_limits():
    rate_limited = _run(_model(steer_rate_lim=0.5, steer_time_delay=0.0), 0.5, 0.0, 0.8)
    # the lag would start at 0.8 / 0.27 = 3 rad/s: the limit holds it to 0.5 rad/s
    assert rate_limited[-1][1] == pytest.approx(0.25, abs=TOL)
    limited = _run(_model(steer_time_delay=0.0), 5.0, 0.0, 2.0)
    assert limited[-1][1] == pytest.approx(1.0, abs=1e-3)      # steer_lim
    assert max(steer for _, steer, _ in limited) <= 1.0 + 1e-9


def test_acceleration_and_velocity_limits():
    rows = _run(_model(acc_time_delay=0.0), 2.0, 20.0, 0.0)
    assert rows[-1][2] == pytest.approx(7.0, abs=1e-3)          # vel_rate_lim
    fast = _run(_model(acc_time_delay=0.0, vel_lim=5.0), 3.0, 7.0, 0.0)
    assert max(vx for vx, _, _ in fast) == pytest.approx(5.0)   # vel_lim


def test_geared_model_stops_instead_of_rolling_against_its_gear():
    model = _model('DELAY_STEER_ACC_GEARED', acc_time_delay=0.0)
    rows = _run(model, 1.0, -2.0, 0.0, gear=1)
    assert all(vx == 0.0 and acc == 0.0 for vx, _, acc in rows)
    rows = _run(model, 1.0, -2.0, 0.0, gear=-1)
    assert rows[-1][0] < -0.5
    assert rows[-1][2] == pytest.approx((rows[-1][0] - rows[-2][0]) / DT)
    # the plain model rolls backwards in a forward gear
    assert _run(_model(acc_time_delay=0.0), 1.0, -2.0, 0.0, gear=1)[-1][0] < -0.5


def test_ideal_steer_vel_follows_its_inputs_at_once_on_a_circle():
    model = _model('IDEAL_STEER_VEL')
    _run(model, 1.0, 5.0, 0.1)
    assert (model.vx_mps, model.steer_rad) == (5.0, 0.1)
    yaw_rate = 5.0 * math.tan(0.1) / WHEELBASE_M
    assert model.yaw_rad == pytest.approx(yaw_rate * 1.0, abs=1e-9)
    radius = 5.0 / yaw_rate
    assert model.x_m == pytest.approx(radius * math.sin(yaw_rate), abs=1e-6)
    assert model.y_m == pytest.approx(radius * (1.0 - math.cos(yaw_rate)), abs=1e-6)


def test_ideal_steer_acc_integrates_the_acceleration():
    model = _model('IDEAL_STEER_ACC')
    _run(model, 1.0, 2.0, 0.0)
    assert model.vx_mps == pytest.approx(2.0, abs=1e-9)
    assert model.x_m == pytest.approx(1.0, abs=1e-9)
    assert model.steer_rad == 0.0


@pytest.mark.parametrize('data, field', [
    ('FOO', "'type'"),
    ({'type': 'DELAY_STEER_ACC', 'steer_time_constant': 0.0}, "'steer_time_constant'"),
    ({'type': 'DELAY_STEER_ACC', 'acc_time_constant': -0.1}, "'acc_time_constant'"),
    ({'type': 'DELAY_STEER_ACC', 'acc_time_delay': -0.1}, "'acc_time_delay'"),
    ({'type': 'DELAY_STEER_ACC', 'steer_lim': 0.0}, "'steer_lim'"),
    ({'type': 'DELAY_STEER_ACC', 'tau': 0.1}, "'tau'"),
])
def test_bad_vehicle_model_refused_naming_the_field(data, field):
    with pytest.raises(InvalidParameterError, match=field):
        vehicle_model_from(data, 'w.yaml: vehicles[0].vehicle_model')


def test_driver_commands_become_the_model_inputs():
    params = load_car('ToyotaPrius')
    a_ramp = cruise_ramp_mps2(params)
    assert a_ramp == pytest.approx(100.0 / 3.6 / 10.7)
    logic = CarLogic(params)
    model = _model()
    # no command yet: held at 0
    assert model_inputs(logic, model, a_ramp) == (0.0, -0.0, 0)
    logic.set_steering_angle(0.1)                       # Webots: right
    logic.set_cruising_speed_kmh(36.0)
    longitudinal, steer, gear = model_inputs(logic, model, a_ramp)
    assert (longitudinal, steer, gear) == (a_ramp, -0.1, 1)   # saturated cruise gain
    model.vx_mps = 9.5
    assert model_inputs(logic, model, a_ramp)[0] == pytest.approx(SPEED_GAIN_PER_S * 0.5)
    ideal = _model('IDEAL_STEER_VEL')
    assert model_inputs(logic, ideal, a_ramp)[0] == pytest.approx(a_ramp * DT)   # the ramp
    logic.set_throttle(0.5)
    logic.set_gear(-1)
    assert model_inputs(logic, model, a_ramp)[0] == pytest.approx(-0.5 * a_ramp)
    logic.set_gear(1)
    logic.set_throttle(0.0)
    logic.set_brake_intensity(0.5)
    assert model_inputs(logic, model, a_ramp) == (pytest.approx(-3.5), -0.1, 1)
    model.vx_mps = 0.01                  # the brake stops the car, no further
    assert model_inputs(logic, model, a_ramp)[0] == pytest.approx(-1.0)


def test_physics_doc_has_the_generated_parameter_table():
    from pathlib import Path

    from vehicle_sim.core.car.kinematic_models import VEHICLE_MODEL_SPECS
    from vehicle_sim.core.specs.param_spec import parameter_table_markdown
    text = (Path(__file__).resolve().parent.parent / 'docs' / 'physics.md').read_text(
        encoding='utf-8')
    assert parameter_table_markdown(VEHICLE_MODEL_SPECS, 'key') in text
    for name in ('IDEAL_STEER_VEL', 'IDEAL_STEER_ACC', 'DELAY_STEER_ACC_GEARED'):
        assert f'`{name}`' in text
