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
Engine torque models of the Webots driver library, one class per engine type.

Exactly the ``compute_output_torque`` engine part of Webots' driver.c:
the output torque (gear ratio, throttle, rpm cut, acceleration limiter) is in drivetrain.py.
"""

from enum import IntEnum

from vehicle_sim.core.specs.errors import InvalidParameterError
from vehicle_sim.core.specs.units import rpm_to_radps


class EngineType(IntEnum):
    """Webots WbuCarEngineType values (car.h)."""

    COMBUSTION = 0
    ELECTRIC = 1
    PARALLEL_HYBRID = 2
    POWER_SPLIT_HYBRID = 3


class EngineModel:
    """
    Base class of the engine models: torque as a function of the engine speed.

    Subclasses implement :meth:`torque_nm`; the constructor keeps the parameters every model
    may need, so a model is built from CarParams alone.
    """

    name = ''
    engine_type = None

    def __init__(self, params):
        """
        Keep the engine parameters of a car.

        :param params: CarParams.
        """
        self.min_rpm = params.engine_min_rpm
        self.max_rpm = params.engine_max_rpm
        self.max_torque_nm = params.engine_max_torque_nm
        self.max_power_w = params.engine_max_power_w
        self.coefficients = tuple(params.engine_function_coefficients)
        self.split_ratio = params.hybrid_power_split_ratio
        self.split_rpm = params.hybrid_power_split_rpm

    def torque_nm(self, rpm):
        """
        Return the engine torque at the given (estimated, non-negative) engine speed.

        :param rpm: engine speed [rpm], as estimated from the wheels (§3.4.1).
        :return: engine torque [N·m], before gear ratio and throttle.
        """
        raise NotImplementedError

    def _combustion_nm(self, rpm):
        # Webots automobile doc §2.1.1 (combustion engine): a + b·rpm + c·rpm².
        a, b, c = self.coefficients
        return a + b * rpm + c * rpm * rpm

    def _electric_nm(self, rpm):
        # min(maxTorque, maxPower / ω); driver.c divides by 2π·rpm/60 and relies on x/0 = +inf
        # at rpm 0, which gives maxTorque (Webots' driver.c).
        if rpm <= 0.0:
            return self.max_torque_nm
        return min(self.max_torque_nm, self.max_power_w / rpm_to_radps(rpm))


class CombustionEngine(EngineModel):
    """Combustion engine: a + b·rpm + c·rpm², rpm raised to engineMinRPM (idle)."""

    name = 'combustion'
    engine_type = EngineType.COMBUSTION

    def torque_nm(self, rpm):
        return self._combustion_nm(max(rpm, self.min_rpm))


class ElectricEngine(EngineModel):
    """Electric motor: min(engineMaxTorque, engineMaxPower / ω); engineMinRPM is ignored."""

    name = 'electric'
    engine_type = EngineType.ELECTRIC

    def torque_nm(self, rpm):
        return self._electric_nm(rpm)


class ParallelHybridEngine(EngineModel):
    """Parallel hybrid: electric motor, plus the combustion engine once rpm ≥ engineMinRPM."""

    name = 'parallel hybrid'
    engine_type = EngineType.PARALLEL_HYBRID

    def torque_nm(self, rpm):
        torque = self._electric_nm(rpm)
        if rpm >= self.min_rpm:
            torque += self._combustion_nm(rpm)
        return torque


class PowerSplitHybridEngine(EngineModel):
    """
    Power-split hybrid: electric motor, plus (1 − hybridPowerSplitRatio) of the combustion torque.

    The combustion engine runs at the fixed hybridPowerSplitRPM and only once the estimated
    rpm reaches engineMinRPM (driver.c compute_output_torque).
    """

    name = 'power-split hybrid'
    engine_type = EngineType.POWER_SPLIT_HYBRID

    def torque_nm(self, rpm):
        torque = self._electric_nm(rpm)
        if rpm >= self.min_rpm:
            torque += (1.0 - self.split_ratio) * self._combustion_nm(self.split_rpm)
        return torque


ENGINE_MODELS = {
    CombustionEngine.name: CombustionEngine,
    ElectricEngine.name: ElectricEngine,
    ParallelHybridEngine.name: ParallelHybridEngine,
    PowerSplitHybridEngine.name: PowerSplitHybridEngine,
}


def make_engine(params):
    """
    Build the engine model named by ``params.engine_type``.

    :param params: CarParams.
    :return: an EngineModel instance.
    :raises InvalidParameterError: for an unknown engine type; the message lists the valid names.
    """
    try:
        model = ENGINE_MODELS[params.engine_type]
    except (KeyError, TypeError):
        raise InvalidParameterError(
            f'unknown engineType {params.engine_type!r}; valid: '
            + ', '.join(repr(name) for name in ENGINE_MODELS)) from None
    return model(params)


__all__ = ['CombustionEngine', 'ElectricEngine', 'ENGINE_MODELS', 'EngineModel', 'EngineType',
           'make_engine', 'ParallelHybridEngine', 'PowerSplitHybridEngine']
