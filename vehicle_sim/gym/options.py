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
The options of the Gym environment: one ParamSpec table, validated once at construction.

``gymnasium.make('vehicle_sim/Drive-v0', world=..., scenario=..., **options)`` and
``DriveEnv(...)`` take these keys; an unknown key or a bad value raises InvalidParameterError
naming the key and the rule, before anything is built. docs/gym.md shows the table
(:func:`options_markdown`).
"""

from dataclasses import replace

from vehicle_sim.core.learning.actions import LAYOUTS
from vehicle_sim.core.sensors.camera_spec import CameraSpec
from vehicle_sim.core.sensors.lidar_spec import LidarSpec
from vehicle_sim.core.sensors.params import SENSOR_TYPES
from vehicle_sim.core.sensors.range_finder_spec import RangeFinderSpec
from vehicle_sim.core.specs.param_spec import parameter_table_markdown, ParamSpec, validate_table
from vehicle_sim.core.specs.simulation import CHECKED_TIME_STEPS_MS, TIME_STEP_MS

# 'auto' (the vehicle's default) and core's action layouts (core/learning/actions.py).
CONTROLS = ('auto',) + tuple(LAYOUTS)
SOURCE = 'vehicle_sim/Drive-v0'


def registered_type(spec_class):
    """Return the core type name a SensorSpec class is registered under (SENSOR_TYPES)."""
    return next(name for name, row in SENSOR_TYPES.items() if row.spec_class is spec_class)


# The sensor options and observation keys are named after their sensor types.
LIDAR = registered_type(LidarSpec)
CAMERA = registered_type(CameraSpec)
RANGE_FINDER = registered_type(RangeFinderSpec)
DEPTH = 'depth'                     # the range finder's observation key


def _sensor_option(value):
    # None/False: none; True: the default sensor; a name: the ego's own; a mapping: its keys.
    if value is None or isinstance(value, (bool, str, dict)):
        return None
    return 'give null, true, the name of a sensor of the ego vehicle, or a mapping of keys'


def _objects_option(value):
    # None/False: none; True: the default table; a mapping: its keys (checked when built).
    if value is None or isinstance(value, (bool, dict)):
        return None
    return 'give null, true or a mapping of count, range and speed_scale'


def _start_noise(value):
    if any(v < 0.0 for v in value):
        return 'every entry must be >= 0'
    return None


OPTION_SPECS = (
    ParamSpec('vehicle', kind='str', default='', empty=True,
              doc="the ego vehicle; '' = the scenario's vehicle under test, else the robot of "
                  "'robot', else the world's first car"),
    ParamSpec('robot', kind='str', default='', empty=True,
              doc="a robot preset (config/robots) added as the ego at 'start', named 'ego'; "
                  "'' = none"),
    ParamSpec('start', kind='floats', default=(0.0, 0.0, 0.0), unit='m, m, rad', length=3,
              doc="start pose [x, y, yaw] of the 'robot' ego"),
    ParamSpec('control', kind='enum', default='auto', choices=CONTROLS,
              doc='action layout (docs/gym.md "Actions"); auto = speed_steering for a car, '
                  'twist for a robot'),
    ParamSpec('action_repeat', kind='int', default=1, ge=1, le=10000,
              doc='basic steps per env step, each with the same action'),
    replace(TIME_STEP_MS, default=None, optional=True,
            doc=f"basic time step; null = the scenario's, else {TIME_STEP_MS.default} ms (the "
                f"physics car's checks run at "
                f"{' and '.join(str(ms) for ms in CHECKED_TIME_STEPS_MS)} ms: docs/physics.md)"),
    ParamSpec('max_speed', kind='float', default=None, unit='m/s', gt=0.0, optional=True,
              doc="the *speed_steering layouts, lane_speed: largest speed action; null = "
                  "min(the car's top speed, 20 m/s)"),
    ParamSpec('max_steering', kind='float', default=None, unit='rad', gt=0.0, optional=True,
              doc="car controls: largest steering angle action either way (lane_speed: "
                  "its lane-keeping law's limit; at most the car's limit); null = the car's "
                  "own limits"),
    ParamSpec('max_reverse_speed', kind='float', default=5.0, unit='m/s', ge=0.0,
              doc='the *speed_steering layouts: largest reverse speed action (lane_speed '
                  'drives forward only)'),
    ParamSpec(LIDAR, kind='raw', default=None, optional=True, check=_sensor_option,
              doc="lidar observation: null = none, true = a 1080-ray 270 deg lidar, a name = "
                  "that lidar of the ego's world entry, a mapping = lidar keys "
                  '(docs/sensors.md)'),
    ParamSpec(CAMERA, kind='raw', default=None, optional=True, check=_sensor_option,
              doc='camera observation: as lidar (true = 84 x 84 px)'),
    ParamSpec(RANGE_FINDER, kind='raw', default=None, optional=True, check=_sensor_option,
              doc="range finder observation (key 'depth'): as lidar (true = 84 x 84 px, the "
                  "default camera's view: 1.2 rad, 0.05 .. 100 m)"),
    ParamSpec('objects', kind='raw', default=None, optional=True, check=_objects_option,
              doc="objects observation (the nearest traffic bodies and obstacles as a table, "
                  "docs/gym.md): null = none, true = 5 rows within 80 m, a mapping = the "
                  "table's keys (count, range, speed_scale)"),
    ParamSpec('goal', kind='floats', default=None, unit='m', length=2, optional=True,
              doc="goal [x, y]: progress toward it, episode ends inside 'goal_radius'; null = "
                  "the scenario's reach_goal"),
    ParamSpec('goal_radius', kind='float', default=2.0, unit='m', gt=0.0,
              doc='radius of the goal region'),
    ParamSpec('path', kind='rows', default=None, unit='m', length=2, optional=True,
              doc="path [[x, y], ...]: progress along it; null = the scenario's stay_on_path, "
                  'else the goal, else the distance driven forward'),
    ParamSpec('max_episode_s', kind='float', default=None, unit='s', gt=0.0, optional=True,
              doc="truncation time; null = the scenario's duration, else 60 s"),
    ParamSpec('progress_weight', kind='float', default=1.0, unit='1/m',
              doc='reward per metre of progress'),
    ParamSpec('collision_penalty', kind='float', default=10.0, ge=0.0,
              doc='subtracted on a step with a new collision'),
    ParamSpec('goal_reward', kind='float', default=10.0, doc='added when the goal is reached'),
    ParamSpec('off_lane_penalty', kind='float', default=10.0, unit='1/s', ge=0.0,
              doc='with lanes: subtracted per second off every lane (a step that ends off '
                  'them costs this times its duration)'),
    ParamSpec('solid_line_penalty', kind='float', default=1.0, ge=0.0,
              doc='with lanes: subtracted per solid line (or curb, road border, wall) the '
                  'ego crosses'),
    ParamSpec('lane_centre_penalty', kind='float', default=0.0, unit='1/s', ge=0.0,
              doc='with lanes: subtracted per second on a lane, times the distance from its '
                  'centreline over half its width (0 at the centre, 1 at its edge)'),
    ParamSpec('headway_penalty', kind='float', default=0.0, unit='1/s', ge=0.0,
              doc="subtracted per second times max(0, 1 - time headway / 'headway_s'), the "
                  "smallest time headway to a road user in the ego's path (the gap term, "
                  'docs/gym.md)'),
    ParamSpec('headway_s', kind='float', default=1.0, unit='s', gt=0.0,
              doc="time headway (bumper gap / the ego's speed) below which 'headway_penalty' "
                  'starts'),
    ParamSpec('ttc_penalty', kind='float', default=0.0, unit='1/s', ge=0.0,
              doc="subtracted per second times max(0, 1 - time to collision / 'ttc_s'), the "
                  "smallest time to collision with a road user in the ego's path (the gap "
                  'term)'),
    ParamSpec('ttc_s', kind='float', default=3.0, unit='s', gt=0.0,
              doc="time to collision (bumper gap / closing speed) below which 'ttc_penalty' "
                  'starts'),
    ParamSpec('side_gap_penalty', kind='float', default=0.0, unit='1/s', ge=0.0,
              doc="subtracted per second times max(0, 1 - clearance / 'gap_margin'), the "
                  'smallest side-to-side clearance to a road user beside the ego (the gap '
                  'term)'),
    ParamSpec('gap_margin', kind='float', default=1.0, unit='m', gt=0.0,
              doc="side-to-side clearance below which a road user ahead is in the ego's path "
                  "and one beside is penalised ('side_gap_penalty')"),
    ParamSpec('terminate_on_collision', kind='bool', default=True,
              doc='a collision of the ego ends the episode (terminated)'),
    ParamSpec('terminate_off_road', kind='bool', default=False,
              doc='with lanes: a step that ends off every lane ends the episode (terminated)'),
    ParamSpec('start_noise', kind='floats', default=(0.0, 0.0, 0.0), unit='m, m, rad',
              length=3, check=_start_noise,
              doc="half-widths [x, y, yaw] of a uniform offset of the ego's start pose, drawn "
                  'at each reset from the seeded generator'),
    ParamSpec('render_width', kind='int', default=320, unit='px', ge=1, le=3840,
              doc="width of render_mode='rgb_array' pictures"),
    ParamSpec('render_height', kind='int', default=240, unit='px', ge=1, le=2160,
              doc="height of render_mode='rgb_array' pictures"),
)


def validate_options(options, source=SOURCE):
    """
    Validate the environment's keyword options.

    :return: {attribute: value} for every row (defaults filled in).
    :raises InvalidParameterError: naming the key, the value and the rule.
    """
    return validate_table(OPTION_SPECS, dict(options), source, what='options',
                          key_word='option')


def options_markdown():
    """Return the options table of docs/gym.md."""
    return parameter_table_markdown(OPTION_SPECS, key_word='option')
