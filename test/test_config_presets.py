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

"""Car presets: every file loads, matches the spec's values, and bad content is named."""

import math

import pytest

from vehicle_sim.config import car_names, find_config, load_car, read_yaml
from vehicle_sim.core.car.params import CAR_PARAM_SPECS, car_params_from_dict, DEFAULT_CAR
from vehicle_sim.core.specs.errors import InvalidParameterError

PRESETS = ['Car', 'BmwX5', 'CitroenCZero', 'ToyotaPrius', 'TeslaModel3', 'LincolnMKZ',
           'RangeRoverSportSVR', 'MercedesBenzSprinter']


def test_presets_every_required_car_is_shipped():
    assert set(PRESETS) <= set(car_names())


@pytest.mark.parametrize('name', PRESETS)
def test_presets_load_and_validate(name):
    params = load_car(name)
    assert params.model == name
    assert params.gear_ratio[0] < 0
    assert params.gear_number == len(params.gear_ratio)


def test_presets_car_yaml_equals_the_parameter_table_defaults():
    # Car.yaml documents the defaults; the ParamSpec table is their single source.
    data = read_yaml(find_config('cars', 'Car'))
    for spec in CAR_PARAM_SPECS:
        assert spec.key in data, spec.key
    assert car_params_from_dict(data, 'Car.yaml') == DEFAULT_CAR


# Values from the Webots PROTO files (a representative subset per car).
SPEC_VALUES = {
    'BmwX5': dict(wheelbase_m=2.995, track_front_m=1.628, time_0_to_100_s=7.0,
                  brake_coefficient_nm=1800.0, engine_max_rpm=6500.0, car_type='traction',
                  gear_ratio=(-12.5, 12.5, 8.0, 5.35, 4.3, 4.0), front_tire_radius_m=0.374),
    'CitroenCZero': dict(car_type='propulsion', engine_type='electric', wheelbase_m=2.55,
                         track_rear_m=1.27, max_steering_angle_rad=0.631,
                         engine_max_power_w=75000.0, gear_ratio=(-6.2329, 6.2329)),
    'ToyotaPrius': dict(engine_type='power-split hybrid', hybrid_power_split_ratio=0.2778,
                        engine_min_rpm=1200.0, engine_max_torque_nm=350.0,
                        front_tire_radius_m=0.317, time_0_to_100_s=10.7),
    'TeslaModel3': dict(car_type='propulsion', engine_max_torque_nm=639.0,
                        engine_max_rpm=25000.0, gear_ratio=(-6.3, 9.0), time_0_to_100_s=4.0),
    'LincolnMKZ': dict(car_type='4x4', time_0_to_100_s=4.97, brake_coefficient_nm=1400.0,
                       gear_ratio=(-2.94, 4.58, 2.96, 1.91, 1.45, 1.0, 0.75)),
    'RangeRoverSportSVR': dict(car_type='4x4', wheelbase_m=2.71, mass_kg=2700.0,
                               time_0_to_100_s=4.7),
    'MercedesBenzSprinter': dict(max_velocity_mps=29.18, wheelbase_m=4.325,
                                 suspension_rear_spring_n_per_m=600000.0,
                                 engine_function_coefficients=(600.0, 0.2, 0.0)),
}


@pytest.mark.parametrize('name', sorted(SPEC_VALUES))
def test_presets_carry_the_spec_values(name):
    params = load_car(name)
    for attr, expected in SPEC_VALUES[name].items():
        assert getattr(params, attr) == expected, attr


def test_presets_unlisted_fields_take_the_car_defaults():
    assert load_car('BmwX5').hybrid_power_split_rpm == DEFAULT_CAR.hybrid_power_split_rpm
    assert load_car('ToyotaPrius').brake_coefficient_nm == 700.0


def test_presets_default_wheel_mass_follows_webots_density():
    # Webots VehicleWheel: Physics {} density 1000 -> pi r^2 h rho = 150.8 kg for r 0.4, h 0.3.
    assert DEFAULT_CAR.wheel_mass_kg(front=True) == pytest.approx(
        1000 * math.pi * 0.4 ** 2 * 0.3, rel=1e-12)


def _write(tmp_path, text):
    path = tmp_path / 'Bad.yaml'
    path.write_text(text)
    return str(path)


@pytest.mark.parametrize('text, field, value', [
    ('trackFront: -1.0\n', 'trackFront', '-1.0'),
    ('wheelbase: abc\n', 'wheelbase', 'abc'),
    ('noSuchField: 3\n', 'noSuchField', '3'),
    ('type: hovercraft\n', 'type', 'hovercraft'),
    ('gearRatio: [3.0, 2.0]\n', 'gearRatio', '3.0'),
    ('gearRatio: [-3.0]\n', 'gearRatio', '-3.0'),
    ('engineMaxRPM: 500.0\n', 'engineMaxRPM', '500.0'),
    ('hybridPowerSplitRatio: 1.5\n', 'hybridPowerSplitRatio', '1.5'),
    ('time0To100: .nan\n', 'time0To100', 'nan'),
    ('inertiaMatrix: [1, 1, 1, 5, 0, 0]\n', 'inertiaMatrix', '5'),
    ('engineFunctionCoefficients: [1, 2]\n', 'engineFunctionCoefficients', '2'),
])
def test_presets_invalid_field_error_names_file_field_and_value(tmp_path, text, field, value):
    path = _write(tmp_path, text)
    with pytest.raises(InvalidParameterError) as error:
        load_car(path)
    message = str(error.value)
    assert path in message and field in message and value in message


def test_presets_unknown_name_lists_the_known_presets():
    with pytest.raises(InvalidParameterError, match='ToyotaPrius'):
        load_car('Trabant')


def test_presets_replace_validates():
    with pytest.raises(InvalidParameterError):
        DEFAULT_CAR.replace(wheelbase_m=0.0)
    assert DEFAULT_CAR.replace(wheelbase_m=3.0).wheelbase_m == 3.0
