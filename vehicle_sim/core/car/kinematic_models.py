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
Autoware's simple_planning_simulator vehicle models: a kinematic bicycle, ideal or delayed.

The models of Autoware's ``simple_planning_simulator`` (autoware.universe, its README and
``sim_model_*.cpp``), re-written here from their documented equations; no ROS, no physics.
State (x, y, yaw, vx, steer, acc) in the world frame (REP 103: yaw and steer positive to the
left), L the wheelbase:

- ``IDEAL_STEER_VEL``: input (vx_des, steer_des); vx = vx_des, steer = steer_des at once.
- ``IDEAL_STEER_ACC``: input (ax_des, steer_des); dvx = ax_des, steer = steer_des at once.
- ``DELAY_STEER_ACC``: input (ax_des, steer_des), each held back by its dead time (a queue of
  round(delay / dt) steps, halves up, as Autoware's), then first-order lags:
  d steer = clip(-(steer - clip(steer_des, +-steer_lim)) / steer_time_constant,
  +-steer_rate_lim); d acc = -(clip(acc, +-vel_rate_lim) - clip(ax_des, +-vel_rate_lim)) /
  acc_time_constant; dvx = clip(acc, +-vel_rate_lim); vx kept within +-vel_lim.
- ``DELAY_STEER_ACC_GEARED``: as DELAY_STEER_ACC, then the gear: forward gears keep vx >= 0,
  reverse keeps vx <= 0 (a sign change becomes a stop), acc = the change of vx over the step.

Every model: dx = vx cos(yaw), dy = vx sin(yaw), dyaw = vx tan(steer) / L, integrated with
the classic Runge-Kutta method over each step (Autoware's updateRungeKutta).
"""

from collections import deque
from dataclasses import dataclass
import math

from vehicle_sim.core.specs.errors import InvalidParameterError
from vehicle_sim.core.specs.param_spec import ParamSpec, validate_table

MODEL_TYPES = ('IDEAL_STEER_VEL', 'IDEAL_STEER_ACC', 'DELAY_STEER_ACC', 'DELAY_STEER_ACC_GEARED')
# the models whose input is a velocity (the others take an acceleration)
VELOCITY_INPUT = ('IDEAL_STEER_VEL',)
DELAYED = ('DELAY_STEER_ACC', 'DELAY_STEER_ACC_GEARED')

# Defaults: simple_planning_simulator's README parameter table.
VEHICLE_MODEL_SPECS = (
    ParamSpec('type', 'type', 'enum', 'DELAY_STEER_ACC', choices=MODEL_TYPES,
              doc='the simple_planning_simulator model'),
    ParamSpec('vel_lim', 'vel_lim_mps', 'float', 50.0, 'm/s', 'limit of velocity', gt=0.0),
    ParamSpec('vel_rate_lim', 'vel_rate_lim_mps2', 'float', 7.0, 'm/s^2',
              'limit of acceleration', gt=0.0),
    ParamSpec('steer_lim', 'steer_lim_rad', 'float', 1.0, 'rad', 'limit of steering angle',
              gt=0.0),
    ParamSpec('steer_rate_lim', 'steer_rate_lim_radps', 'float', 5.0, 'rad/s',
              'limit of steering angle change rate', gt=0.0),
    ParamSpec('acc_time_delay', 'acc_time_delay_s', 'float', 0.1, 's',
              'dead time of the acceleration input', ge=0.0),
    ParamSpec('acc_time_constant', 'acc_time_constant_s', 'float', 0.1, 's',
              'time constant of the first-order acceleration dynamics', gt=0.0),
    ParamSpec('steer_time_delay', 'steer_time_delay_s', 'float', 0.24, 's',
              'dead time of the steering input', ge=0.0),
    ParamSpec('steer_time_constant', 'steer_time_constant_s', 'float', 0.27, 's',
              'time constant of the first-order steering dynamics', gt=0.0),
)


@dataclass(frozen=True)
class VehicleModelParams:
    """A validated ``vehicle_model:`` (SI units; meaning in VEHICLE_MODEL_SPECS)."""

    type: str
    vel_lim_mps: float
    vel_rate_lim_mps2: float
    steer_lim_rad: float
    steer_rate_lim_radps: float
    acc_time_delay_s: float
    acc_time_constant_s: float
    steer_time_delay_s: float
    steer_time_constant_s: float


def vehicle_model_from(data, source='vehicle_model'):
    """
    Validate a ``vehicle_model:`` value: None (full physics), a model name, or a mapping.

    :return: VehicleModelParams, or None for the full physics car.
    :raises InvalidParameterError: naming the field and the value.
    """
    if data is None:
        return None
    if isinstance(data, str):
        data = {'type': data}
    return VehicleModelParams(**validate_table(VEHICLE_MODEL_SPECS, data, source,
                                               what='a vehicle model'))


def _clip(value, limit):
    return -limit if value < -limit else limit if value > limit else value


class KinematicModel:
    """
    One simple_planning_simulator model's state, advanced a fixed step at a time.

    :param params: VehicleModelParams.
    :param wheelbase_m: L of the bicycle [m].
    :param dt_s: the step [s] (sets the dead-time queues, as Autoware's initializeInputQueue).
    :param pose: start (x [m], y [m], yaw [rad]).
    """

    def __init__(self, params, wheelbase_m, dt_s, pose=(0.0, 0.0, 0.0)):
        if not wheelbase_m > 0.0:
            raise InvalidParameterError(f'wheelbase = {wheelbase_m!r}: must be > 0')
        if not dt_s > 0.0:
            raise InvalidParameterError(f'time step = {dt_s!r}: must be > 0')
        self.params = params
        self.wheelbase_m = float(wheelbase_m)
        self.dt_s = float(dt_s)
        # std::round of Autoware's initializeInputQueue: halves away from zero (Python's round
        # goes to even: 0.1 s / 0.2 s would give no delay at all)
        self._acc_steps = math.floor(params.acc_time_delay_s / dt_s + 0.5)
        self._steer_steps = math.floor(params.steer_time_delay_s / dt_s + 0.5)
        self.reset(pose)

    def reset(self, pose=(0.0, 0.0, 0.0)):
        """At rest at ``pose``, every delayed input 0."""
        self.x_m, self.y_m, self.yaw_rad = (float(v) for v in pose)
        self.vx_mps = self.steer_rad = self.acc_mps2 = 0.0
        self._acc_queue = deque([0.0] * self._acc_steps)
        self._steer_queue = deque([0.0] * self._steer_steps)

    @property
    def yaw_rate_radps(self):
        """Yaw rate vx tan(steer) / L [rad/s]."""
        return self.vx_mps * math.tan(self.steer_rad) / self.wheelbase_m

    def step(self, longitudinal, steer_des_rad, gear=1):
        """
        Advance one step.

        :param longitudinal: vx_des [m/s] (IDEAL_STEER_VEL) or ax_des [m/s^2] (the others).
        :param steer_des_rad: the desired steering angle (positive = left) [rad].
        :param gear: > 0 forward, < 0 reverse, 0 neutral (only DELAY_STEER_ACC_GEARED uses it).
        """
        kind = self.params.type
        if kind == 'IDEAL_STEER_VEL':
            self.vx_mps, self.steer_rad = float(longitudinal), float(steer_des_rad)
            self.acc_mps2 = 0.0
            self._kinematics(0.0)
            return
        if kind == 'IDEAL_STEER_ACC':
            self.steer_rad, self.acc_mps2 = float(steer_des_rad), float(longitudinal)
            self._kinematics(self.acc_mps2)
            return
        self._acc_queue.append(float(longitudinal))
        acc_des = self._acc_queue.popleft()
        self._steer_queue.append(float(steer_des_rad))
        steer_des = self._steer_queue.popleft()
        previous_vx = self.vx_mps
        self._delayed(acc_des, steer_des)
        if kind == 'DELAY_STEER_ACC_GEARED':
            if (gear > 0 and self.vx_mps < 0.0) or (gear < 0 and self.vx_mps > 0.0):
                self.vx_mps = 0.0
            self.acc_mps2 = (self.vx_mps - previous_vx) / self.dt_s

    def _kinematics(self, acc):
        # RK4 of the ideal models (no limits, as Autoware's): steer held, dvx = acc.
        wheelbase = self.wheelbase_m

        def f(s):
            _, _, yaw, vx, steer = s
            return (vx * math.cos(yaw), vx * math.sin(yaw), vx * math.tan(steer) / wheelbase,
                    acc, 0.0)

        self._rk4((self.x_m, self.y_m, self.yaw_rad, self.vx_mps, self.steer_rad), f)

    def _delayed(self, acc_des, steer_des):
        p = self.params
        rate_lim = p.vel_rate_lim_mps2
        acc_des = _clip(acc_des, rate_lim)
        steer_des = _clip(steer_des, p.steer_lim_rad)

        def f(s):
            _, _, yaw, vx, steer, acc = s
            vel = _clip(vx, p.vel_lim_mps)
            acc_c = _clip(acc, rate_lim)
            steer_rate = _clip(-(steer - steer_des) / p.steer_time_constant_s,
                               p.steer_rate_lim_radps)
            return (vel * math.cos(yaw), vel * math.sin(yaw),
                    vel * math.tan(steer) / self.wheelbase_m, acc_c, steer_rate,
                    -(acc_c - acc_des) / p.acc_time_constant_s)

        state = (self.x_m, self.y_m, self.yaw_rad, self.vx_mps, self.steer_rad, self.acc_mps2)
        self._rk4(state, f)
        self.vx_mps = _clip(self.vx_mps, p.vel_lim_mps)

    def _rk4(self, state, f):
        h = self.dt_s
        k1 = f(state)
        k2 = f(tuple(s + 0.5 * h * k for s, k in zip(state, k1)))
        k3 = f(tuple(s + 0.5 * h * k for s, k in zip(state, k2)))
        k4 = f(tuple(s + h * k for s, k in zip(state, k3)))
        new = [s + h / 6.0 * (a + 2.0 * b + 2.0 * c + d)
               for s, a, b, c, d in zip(state, k1, k2, k3, k4)]
        self.x_m, self.y_m, self.yaw_rad, self.vx_mps, self.steer_rad = new[:5]
        if len(new) == 6:
            self.acc_mps2 = new[5]
