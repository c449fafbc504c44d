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
The Webots driver API's commands as the inputs of a simple_planning_simulator model.

A car with a ``vehicle_model:`` keeps its CarLogic (every setter, getter, light and gear of the
driver library); each step its commands become the model's (docs/physics.md):

- steering: steer_des = -(the driver's commanded steering angle) (Webots: positive = right;
  the model, REP 103: positive = left), within min/maxSteeringAngle already;
- setCruisingSpeed (SPEED mode, v_c = the effective cruising speed): an acceleration model gets
  ax_des = clip(SPEED_GAIN_PER_S * (v_c - vx), +-a_ramp), a_ramp = (100 km/h) / time0To100
  (Car.proto's SPEED-mode wheel acceleration); IDEAL_STEER_VEL gets vx_des = vx moved toward
  v_c by at most a_ramp * dt (the Webots wheel ramp);
- setThrottle / setBrakeIntensity (TORQUE mode): ax_des = sign(gear) * throttle * a_ramp minus
  brake * vel_rate_lim against the motion (not past standstill); IDEAL_STEER_VEL gets vx + ax_des
  * dt;
- no command yet (UNDEFINED, the driven wheels held): as a cruising speed of 0;
- the gear of DELAY_STEER_ACC_GEARED: the driver's gear in TORQUE mode, the sign of v_c in SPEED
  mode (forward at 0), neutral when UNDEFINED.
"""

import math

from vehicle_sim.core.car.drivetrain import ControlMode
from vehicle_sim.core.car.kinematic_models import VELOCITY_INPUT
from vehicle_sim.core.specs.units import kmh_to_mps

# proportional gain of the cruise control of an acceleration model [1/s]: with the default
# delays (0.1 s dead time, 0.1 s lag) a phase margin of about 67 degrees
SPEED_GAIN_PER_S = 2.0


def model_inputs(logic, model, a_ramp_mps2):
    """
    Return (longitudinal input, steer_des [rad], gear) for ``model`` from ``logic``'s commands.

    :param logic: the car's CarLogic.
    :param model: its KinematicModel (state vx, params, dt).
    :param a_ramp_mps2: the car's cruise ramp (core/car/speed_braking.py
        ``cruise_ramp_mps2``).
    """
    steer_des = -logic.commanded_steering_angle_rad
    vx, dt = model.vx_mps, model.dt_s
    velocity_input = model.params.type in VELOCITY_INPUT
    mode = logic.control_mode
    if mode == ControlMode.TORQUE:
        gear = logic.gear
        direction = (gear > 0) - (gear < 0)
        ax = direction * logic.throttle * a_ramp_mps2
        brake = logic.brake_intensity * model.params.vel_rate_lim_mps2
        if brake > 0.0 and vx != 0.0:
            ax -= math.copysign(min(brake, abs(vx) / dt), vx)
        return (vx + ax * dt if velocity_input else ax), steer_des, direction
    target = kmh_to_mps(logic.effective_cruising_speed_kmh) if mode == ControlMode.SPEED else 0.0
    gear = (1 if target >= 0.0 else -1) if mode == ControlMode.SPEED else 0
    error = target - vx
    if velocity_input:
        step = a_ramp_mps2 * dt
        return vx + max(-step, min(step, error)), steer_des, gear
    gain = SPEED_GAIN_PER_S * error
    return max(-a_ramp_mps2, min(a_ramp_mps2, gain)), steer_des, gear
