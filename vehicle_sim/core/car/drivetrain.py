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
Drivetrain math of the Webots driver library as pure functions (Webots' driver.c).

Geometric differential ratios, cruise-control wheel targets and their acceleration ramp, wheel
speed estimation, engine rpm, output torque, torque distribution, the limited-slip differential
integrator and the current-speed estimate. Wheel arrays use the Webots order FRONT_RIGHT,
FRONT_LEFT, REAR_RIGHT, REAR_LEFT (vehicle_io.Wheel); car types are the CarParams names
'traction' (front wheels driven), 'propulsion' (rear) and '4x4'.
"""

from enum import IntEnum
import math

import numpy as np

from vehicle_sim.core.car.vehicle_io import Wheel, WHEEL_COUNT
from vehicle_sim.core.specs.units import kmh_to_mps, radps_to_rpm

# driver.c ACCELERATION_THRESHOLD: wheel acceleration above which output torque is scaled down.
ACCELERATION_THRESHOLD_RADPS2 = 50.0
# Car.proto: driven-wheel motor acceleration = (100 km/h) / time0To100 / tireRadius.
SPEED_100_KMH_MPS = kmh_to_mps(100.0)

_FR, _FL, _RR, _RL = Wheel.FRONT_RIGHT, Wheel.FRONT_LEFT, Wheel.REAR_RIGHT, Wheel.REAR_LEFT


class CarType(IntEnum):
    """Webots WbuCarType values (car.h)."""

    TRACTION = 0
    PROPULSION = 1
    FOUR_BY_FOUR = 2


CAR_TYPE_BY_NAME = {'traction': CarType.TRACTION, 'propulsion': CarType.PROPULSION,
                    '4x4': CarType.FOUR_BY_FOUR}


class ControlMode(IntEnum):
    """Webots WbuDriverControlMode values (driver.h)."""

    UNDEFINED = -1
    SPEED = 0
    TORQUE = 1


class Differential(IntEnum):
    """Indices of the slip-ratio array: front (right/left), rear (right/left), central."""

    FRONT = 0
    REAR = 1
    CENTRAL = 2


def _drives_front(car_type):
    return car_type != 'propulsion'


def _drives_rear(car_type):
    return car_type != 'traction'


# ---------------------------------------------------------------------------------------------
# Geometric differential ratios (driver.c differential_ratio_*). Each is exactly 0.5 when the
# driver's steering angle is exactly 0, as in Webots.

def front_ratio(steering_rad, right_rad, left_rad):
    """
    Return the front right/left speed ratio ratio_f = R_R / (R_L + R_R), R = L / sin(θ).

    The wheelbase cancels: ratio_f = sin θL / (sin θR + sin θL). A degenerate geometry (a wheel
    at 0 rad while δ ≠ 0, possible with set_right/left_steering_angle) gives 0.5 where driver.c
    would produce NaN.

    :param steering_rad: driver steering angle δ [rad] (only its being 0 matters).
    :param right_rad: right front wheel angle θR [rad].
    :param left_rad: left front wheel angle θL [rad].
    :return: share of the axle speed for the right wheel; < 0.5 in a right turn.
    """
    if steering_rad == 0.0:
        return 0.5
    sin_right = math.sin(right_rad)
    sin_left = math.sin(left_rad)
    if sin_right == 0.0 or sin_left == 0.0:
        return 0.5
    return sin_left / (sin_right + sin_left)


def rear_ratio(steering_rad, track_rear_m, wheelbase_m):
    """
    Return the rear right/left speed ratio ratio_r = R_R / (R_L + R_R).

    With R_R,L = L/tan δ ∓ Tr/2 this is 0.5 − Tr·tan δ / (4L), free of the 1/tan(0) of driver.c.

    :param steering_rad: driver steering angle δ [rad], positive = right.
    :param track_rear_m: rear track Tr [m].
    :param wheelbase_m: wheelbase L [m].
    :return: share of the axle speed for the right wheel.
    """
    if steering_rad == 0.0:
        return 0.5
    return 0.5 - track_rear_m * math.tan(steering_rad) / (4.0 * wheelbase_m)


def central_ratio(steering_rad, front_radius_m, rear_radius_m):
    """
    Return the central front/rear ratio ratio_c = k·R_front / (R_front + R_rear), k = rr / rf.

    With R_front = L/sin δ and R_rear = L/tan δ this is k / (1 + cos δ). Webots' shortcut makes it
    exactly 0.5 at δ = 0 (so k only matters while steering; every 4x4 preset has k = 1).

    :param steering_rad: driver steering angle δ [rad].
    :param front_radius_m: front tyre radius rf [m].
    :param rear_radius_m: rear tyre radius rr [m].
    :return: share of the speed (or torque) for the front axle.
    """
    if steering_rad == 0.0:
        return 0.5
    return (rear_radius_m / front_radius_m) / (1.0 + math.cos(steering_rad))


def cruise_wheel_targets(speed_mps, car_type, ratio_f, ratio_r, ratio_c, front_radius_m,
                         rear_radius_m, out=None):
    """
    Return the driven-wheel velocity targets of cruise control (driver.c set_cruising_speed).

    Front axle: vR = 2v·ratio_f, vL = 2v·(1 − ratio_f), both ·2·ratio_c for a 4x4; rear axle:
    ratio_r and 2·(1 − ratio_c). Each tyre speed is divided by its radius.

    :param speed_mps: signed cruising speed [m/s] (negative = reverse).
    :param car_type: 'traction', 'propulsion' or '4x4'.
    :param ratio_f: front ratio; see front_ratio().
    :param ratio_r: rear ratio; see rear_ratio().
    :param ratio_c: central ratio; see central_ratio().
    :param front_radius_m: front tyre radius [m].
    :param rear_radius_m: rear tyre radius [m].
    :param out: optional float array of 4 to fill.
    :return: wheel angular velocity targets [rad/s]; 0 for undriven wheels.
    """
    if out is None:
        out = np.zeros(WHEEL_COUNT)
    else:
        out.fill(0.0)
    four_by_four = car_type == '4x4'
    if _drives_front(car_type):
        scale = 2.0 * speed_mps * (2.0 * ratio_c if four_by_four else 1.0) / front_radius_m
        out[_FR] = scale * ratio_f
        out[_FL] = scale * (1.0 - ratio_f)
    if _drives_rear(car_type):
        scale = 2.0 * speed_mps * (2.0 * (1.0 - ratio_c) if four_by_four else 1.0) / rear_radius_m
        out[_RR] = scale * ratio_r
        out[_RL] = scale * (1.0 - ratio_r)
    return out


def speed_ramp_mps2(time_0_to_100_s):
    """
    Return Car.proto's SPEED-mode acceleration limit at the tyre, (100 km/h) / time0To100.

    The cruise control's ramp, the same for speeding up and slowing down: the driven wheels'
    motors follow it (:func:`wheel_acceleration_radps2`).

    :param time_0_to_100_s: time0To100 [s].
    :return: [m/s²].
    """
    return SPEED_100_KMH_MPS / time_0_to_100_s


def wheel_acceleration_radps2(time_0_to_100_s, radius_m):
    """
    Return the velocity-motor acceleration limit of a driven wheel (Car.proto).

    :param time_0_to_100_s: time0To100 [s].
    :param radius_m: tyre radius [m].
    :return: :func:`speed_ramp_mps2` / r [rad/s²], the same for speeding up and slowing down.
    """
    return speed_ramp_mps2(time_0_to_100_s) / radius_m


def ramp_toward(current, target, max_delta, out=None):
    """
    Move ``current`` toward ``target`` by at most ``max_delta`` (symmetric rate limit).

    This is how a Webots velocity motor with an ``acceleration`` field moves its internal
    set-point each physics step (WbMotor.cpp).

    :param current: current value(s) (scalar or array).
    :param target: target value(s).
    :param max_delta: largest allowed change (>= 0), scalar or per element.
    :param out: optional array receiving the result (may be ``current``).
    :return: the new value(s).
    """
    if type(current) is float and out is None:
        # Scalar fast path: the car logic calls this once per driven wheel every step.
        return current + max(-max_delta, min(max_delta, target - current))
    if out is None:
        return np.asarray(current) + np.clip(np.subtract(target, current),
                                             np.negative(max_delta), max_delta)
    delta = np.subtract(target, current)
    np.clip(delta, np.negative(max_delta), max_delta, out=delta)
    return np.add(current, delta, out=out)


# ---------------------------------------------------------------------------------------------
# Wheel speed estimation (driver.c update_wheels_speed) and rpm (compute_rpm).

def wheel_speeds(position_rad, previous_position_rad, dt_s, out=None):
    """
    Return the backward finite-difference wheel speeds (pos − prev) / dt.

    :param position_rad: wheel encoder values now [rad], array of 4.
    :param previous_position_rad: values one step earlier [rad].
    :param dt_s: time between the two samples [s], > 0.
    :param out: optional array of 4 to fill.
    :return: wheel speeds [rad/s]; a list when both samples are lists and ``out`` is None
        (the car logic's per-step path: numpy calls on 4 elements cost more than the
        arithmetic).
    """
    if out is None and type(position_rad) is list and type(previous_position_rad) is list:
        if len(position_rad) == len(previous_position_rad) == WHEEL_COUNT:
            # written out for the four wheels: a comprehension costs three times as much
            a0, a1, a2, a3 = position_rad
            b0, b1, b2, b3 = previous_position_rad
            return [(a0 - b0) / dt_s, (a1 - b1) / dt_s, (a2 - b2) / dt_s, (a3 - b3) / dt_s]
        return [(now - before) / dt_s for now, before in zip(position_rad, previous_position_rad)]
    out = np.subtract(position_rad, previous_position_rad, out=out)
    out /= dt_s
    return out


def max_signed_acceleration(speed_radps, previous_speed_radps, dt_s):
    """
    Return the wheel acceleration with the largest magnitude, keeping its sign.

    :param speed_radps: wheel speeds now [rad/s].
    :param previous_speed_radps: wheel speeds one step earlier [rad/s].
    :param dt_s: time step [s], > 0.
    :return: signed acceleration [rad/s²] (the first wheel wins a tie, as in driver.c).
    """
    if type(speed_radps) is not list:
        speed_radps = speed_radps.tolist() if hasattr(speed_radps, 'tolist') else speed_radps
    if type(previous_speed_radps) is not list:
        previous_speed_radps = (previous_speed_radps.tolist()
                                if hasattr(previous_speed_radps, 'tolist')
                                else previous_speed_radps)
    if len(speed_radps) == len(previous_speed_radps) == WHEEL_COUNT:
        a0, a1, a2, a3 = speed_radps        # (written out for the four wheels: the car's step)
        b0, b1, b2, b3 = previous_speed_radps
        accelerations = ((a0 - b0) / dt_s, (a1 - b1) / dt_s, (a2 - b2) / dt_s, (a3 - b3) / dt_s)
    else:
        accelerations = [(now - before) / dt_s
                         for now, before in zip(speed_radps, previous_speed_radps)]
    best = largest = 0.0          # (the magnitude kept without abs() calls)
    for acceleration in accelerations:
        magnitude = acceleration if acceleration >= 0.0 else -acceleration
        if magnitude > largest:     # NaN never
            best, largest = acceleration, magnitude
    return best


def _gear_ratio_for(gear, gear_ratio):
    # Forward gear n reads gearRatio[n]; reverse reads gearRatio[0] (negative).
    return gear_ratio[gear] if gear > 0 else gear_ratio[0]


def engine_rpm(wheel_speed_radps, gear, gear_ratio, max_rpm):
    """
    Estimate the engine speed from the wheels (driver.c compute_rpm).

    rpm = |mean(ω of all four wheels)·60/(2π) · g|, g = gearRatio[gear] (forward) or −gearRatio[0]
    (reverse); 0 in neutral; NaN → 0; clamped to engineMaxRPM.

    :param wheel_speed_radps: the four wheel speeds [rad/s], driven or not.
    :param gear: engaged gear (−1 reverse, 0 neutral, 1..N−1 forward).
    :param gear_ratio: CarParams.gear_ratio (reverse ratio first).
    :param max_rpm: engineMaxRPM [rpm].
    :return: engine speed [rpm], in [0, max_rpm].
    """
    if gear == 0:
        return 0.0
    mean_radps = (float(wheel_speed_radps[0]) + float(wheel_speed_radps[1])
                  + float(wheel_speed_radps[2]) + float(wheel_speed_radps[3])) / 4.0
    rpm = abs(radps_to_rpm(mean_radps) * _gear_ratio_for(gear, gear_ratio))
    if math.isnan(rpm):
        return 0.0
    return min(rpm, max_rpm)


def output_torque_nm(engine, rpm, gear, gear_ratio, throttle, max_acceleration_radps2):
    """
    Return the torque delivered to the driven wheels (driver.c compute_output_torque).

    T = engine.torque_nm(rpm) · throttle · g, g = gearRatio[gear] or gearRatio[0] (< 0: reverse);
    0 in neutral; 0 when the rpm estimate sits at engineMaxRPM (its clamp); scaled by
    50 / |max_acc| when a wheel accelerates faster than 50 rad/s².

    :param engine: an engines.EngineModel.
    :param rpm: estimated engine speed [rpm] from engine_rpm().
    :param gear: engaged gear (−1..N−1).
    :param gear_ratio: CarParams.gear_ratio.
    :param throttle: throttle in [0, 1].
    :param max_acceleration_radps2: signed largest wheel acceleration [rad/s²].
    :return: total signed torque [N·m].
    """
    if gear == 0 or rpm >= engine.max_rpm:
        return 0.0
    torque = engine.torque_nm(rpm) * throttle * _gear_ratio_for(gear, gear_ratio)
    magnitude = abs(max_acceleration_radps2)
    if magnitude > ACCELERATION_THRESHOLD_RADPS2:
        torque *= ACCELERATION_THRESHOLD_RADPS2 / magnitude
    return torque


# ---------------------------------------------------------------------------------------------
# Limited-slip differential (driver.c update_slip_ratio) and torque distribution (update_torque).

def _integrate_slip(slip, part, total):
    # s += part/total·2 − 1; NaN (0/0, wheels at rest) resets to 0; ±inf (x/0) saturates.
    if total == 0.0:
        if part == 0.0:
            return 0.0
        return 1.0 if part > 0.0 else -1.0
    slip += part / total * 2.0 - 1.0
    if math.isnan(slip):
        return 0.0
    return -1.0 if slip < -1.0 else (1.0 if slip > 1.0 else slip)


def update_slip_ratios(slip, wheel_speed_radps, car_type):
    """
    Advance the limited-slip integrators in place (one call per step, gain 1 per step).

    s_f += ω_FR/(ω_FR+ω_FL)·2 − 1 (traction, 4x4), s_r likewise for the rear (propulsion, 4x4),
    s_c with the front and rear sums (4x4); each clamped to [−1, 1] and reset to 0 on NaN.
    Positive s: the right (or front) side spins faster, so it will get less torque.

    :param slip: float array of 3 indexed by Differential; modified in place.
    :param wheel_speed_radps: the four wheel speeds [rad/s].
    :param car_type: 'traction', 'propulsion' or '4x4'.
    :return: ``slip``.
    """
    w_fr, w_fl, w_rr, w_rl = (float(w) for w in wheel_speed_radps)
    if _drives_front(car_type):
        slip[Differential.FRONT] = _integrate_slip(
            float(slip[Differential.FRONT]), w_fr, w_fr + w_fl)
    if _drives_rear(car_type):
        slip[Differential.REAR] = _integrate_slip(
            float(slip[Differential.REAR]), w_rr, w_rr + w_rl)
    if car_type == '4x4':
        front = w_fr + w_fl
        slip[Differential.CENTRAL] = _integrate_slip(
            float(slip[Differential.CENTRAL]), front, front + (w_rr + w_rl))
    return slip


def distribute_torque(torque_nm, car_type, ratio_f, ratio_r, ratio_c, slip=None, out=None):
    """
    Split the output torque over the driven wheels (driver.c update_torque).

    With the limited-slip differential each ratio is multiplied by (1 − s) (Webots writes
    2·(1 − (s+1)/2)); the factor may exceed 1, making the other wheel's torque negative.

    :param torque_nm: total torque from output_torque_nm() [N·m].
    :param car_type: 'traction', 'propulsion' or '4x4'.
    :param ratio_f: front geometric ratio.
    :param ratio_r: rear geometric ratio.
    :param ratio_c: central geometric ratio.
    :param slip: slip ratios (array of 3 by Differential) when the LSD is enabled, else None.
    :param out: optional array of 4 to fill.
    :return: wheel torques [N·m]; 0 for undriven wheels.
    """
    if out is None:
        out = np.zeros(WHEEL_COUNT)
    else:
        out.fill(0.0)
    if slip is not None:
        ratio_f *= 1.0 - float(slip[Differential.FRONT])
        ratio_r *= 1.0 - float(slip[Differential.REAR])
        ratio_c *= 1.0 - float(slip[Differential.CENTRAL])
    if car_type == 'traction':
        out[_FR] = torque_nm * ratio_f
        out[_FL] = torque_nm * (1.0 - ratio_f)
    elif car_type == 'propulsion':
        out[_RR] = torque_nm * ratio_r
        out[_RL] = torque_nm * (1.0 - ratio_r)
    else:
        out[_FR] = torque_nm * ratio_f * ratio_c
        out[_FL] = torque_nm * (1.0 - ratio_f) * ratio_c
        out[_RR] = torque_nm * ratio_r * (1.0 - ratio_c)
        out[_RL] = torque_nm * (1.0 - ratio_r) * (1.0 - ratio_c)
    return out


def current_speed_mps(wheel_speed_radps, car_type, front_radius_m, rear_radius_m):
    """
    Estimate the car speed from the DRIVEN wheels (driver.c wbu_driver_get_current_speed).

    traction: ½(ω_FR+ω_FL)·rf; propulsion: ½(ω_RR+ω_RL)·rr; 4x4: ¼(ω_FR+ω_FL)·rf + ¼(ω_RR+ω_RL)·rr.

    :param wheel_speed_radps: the four wheel speeds [rad/s].
    :param car_type: 'traction', 'propulsion' or '4x4'.
    :param front_radius_m: front tyre radius [m].
    :param rear_radius_m: rear tyre radius [m].
    :return: signed speed [m/s].
    """
    front = (float(wheel_speed_radps[_FR]) + float(wheel_speed_radps[_FL])) * front_radius_m
    rear = (float(wheel_speed_radps[_RR]) + float(wheel_speed_radps[_RL])) * rear_radius_m
    if car_type == 'traction':
        return 0.5 * front
    if car_type == 'propulsion':
        return 0.5 * rear
    return 0.25 * front + 0.25 * rear
