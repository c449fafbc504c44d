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
The URDF of each simulated car, as the automobile node publishes it on ``<ns>/robot_description``.

One source for two users: the node (:mod:`.automobile_node`) and ``launch/automobile.launch.py``,
whose ``rviz:=true`` feeds the same text to one robot_state_publisher per vehicle (RViz's
RobotModel needs the TF of every link, which robot_state_publisher computes from it and
``joint_states``).
"""

from dataclasses import replace
from typing import List, Sequence, Tuple

from vehicle_sim.config import load_car
from vehicle_sim.core.sensors.sets import enable_sensors, selected_sensors
from vehicle_sim.core.specs.errors import VehicleSimError
from vehicle_sim.physics.sensor_urdf import with_sensor_links
from vehicle_sim.physics.urdf import car_urdf
from vehicle_sim.ros.automobile_interfaces import frame_prefix
from vehicle_sim.ros.sim_params import AUTOMOBILE_PARAMETERS, SimSettings, world_spec


def mounted_sensors(spec, sensors_value: Sequence[str], source: str):
    """
    Return a vehicle's sensors: its world's, plus the preset sensors the parameter mounts.

    :param spec: the VehicleSpec (its ``sensors``).
    :param sensors_value: the node parameter ``sensors``.
    :param source: where the value comes from, for error messages.
    """
    names = selected_sensors(sensors_value)
    if names is None:
        return spec.sensors
    return enable_sensors(spec.sensors, names, source)


def vehicle_description(spec, sensors, params=None) -> str:
    """
    Return a vehicle's URDF: the car body plus its sensor links, names prefixed ``<p>``.

    :param spec: the VehicleSpec (name, namespace, model).
    :param sensors: its SensorSpecs (:func:`mounted_sensors`).
    :param params: its CarParams; None = loaded from ``spec.model``.
    """
    prefix = frame_prefix(spec.namespace)
    params = load_car(spec.model) if params is None else params
    return with_sensor_links(car_urdf(params, name=spec.name, prefix=prefix), sensors, prefix)


def robot_descriptions(car_model='Car', world='', sensors=('',)) -> List[Tuple[str, str]]:
    """
    Return (vehicle namespace, URDF) of every vehicle the node runs with these parameters.

    The other parameters keep their defaults (they do not change a URDF).

    :raises InvalidParameterError: for an unknown car model, world or sensor name.
    """
    settings = SimSettings(**{spec.attr: spec.default for spec in AUTOMOBILE_PARAMETERS})
    settings = replace(settings, car_model=car_model, world=world, sensors=tuple(sensors))
    return [(spec.namespace, vehicle_description(
                spec, mounted_sensors(spec, settings.sensors,
                                      f'parameter sensors, vehicle {spec.name!r}')))
            for spec in world_spec(settings).vehicles]


def main(argv=None) -> int:
    """
    Print :func:`robot_descriptions` as JSON: ``[[namespace, urdf], ...]``.

    Usage: ``python -m vehicle_sim.ros.descriptions CAR_MODEL WORLD [SENSOR ...]``. The launch
    file runs it with the node's own interpreter (the one that has PyBullet), since ``ros2
    launch`` itself may run on a Python without it.
    """
    import json
    import sys
    args = sys.argv[1:] if argv is None else list(argv)
    if len(args) < 2:
        print('usage: python -m vehicle_sim.ros.descriptions CAR_MODEL WORLD [SENSOR ...]',
              file=sys.stderr)
        return 2
    try:
        descriptions = robot_descriptions(args[0], args[1], tuple(args[2:]) or ('',))
    except VehicleSimError as error:   # an unknown car, world or sensor: said in one line
        print(error, file=sys.stderr)
        return 2
    json.dump(descriptions, sys.stdout)
    return 0


if __name__ == '__main__':
    raise SystemExit(main())
