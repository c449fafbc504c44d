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
The automobile node's interface table: every topic and service of a car (docs/ros_interface.md).

Rows are :mod:`.endpoints` rows. Names are relative to the vehicle namespace ``ns`` (empty for
the default car): ``automobile/x`` becomes ``/<ns>/automobile/x``; names with a leading ``/``
are global and published once for all vehicles (``/clock``, ``/tf``, ``/tf_static``, defined in
:mod:`.endpoints`). The automobile node wires and publishes these rows, its tests iterate them,
and ``docs/ros_interface.md`` embeds :func:`interface_table_markdown`, so a name cannot diverge
between them.

Converter contexts of the per-vehicle rows: wiring ``w`` = the vehicle (``base_frame``,
``odom_frame``, ``joint_names``, ``frame_prefix``); call ``ctx`` = the same vehicle after
``sample(stamp)`` (``stamp``, ``status`` (CarStatus), ``torque_mode``, ``odom`` = (xyz, q,
linear, angular) of base_link in odom with the twist in base_link, ``joints`` = (positions,
velocities)), for the latched row ``description()`` (the URDF), and for ``collision`` and the
sensor rows the attributes listed in :mod:`.sensor_interfaces`. A vehicle's sensor rows are made
from its mounted sensors (:func:`.sensor_interfaces.sensor_rows`); the docs list one of each type
(:func:`sensor_table_markdown`).

Values keep Webots semantics on every ``automobile/*`` endpoint: km/h, steering angle in rad with
positive = right, throttle and brake in [0, 1]. Standard ROS outputs are SI / REP 103.
"""

from operator import attrgetter

from vehicle_sim.ros import lane_messages as lm
from vehicle_sim.ros import messages as m
from vehicle_sim.ros.autoware_interfaces import ACKERMANN_DRIVE
from vehicle_sim.ros.endpoints import (  # noqa: F401 - the cadences are part of this table
    CLOCK,
    CMD_VEL,
    CMD_VEL_INPUTS,
    CMD_VEL_STAMPED,
    converter,
    EACH_PUBLISH,
    EACH_STEP,
    IN,
    ON_EVENT,
    ONCE_LATCHED,
    RECEIVED,
    Service,
    TF,
    TF_STATIC,
    Topic,
    topic_table_markdown,
    value_text,
)
from vehicle_sim.ros.sensor_interfaces import COLLISION, QOS_SENSOR, sensor_topic_rows
from vehicle_sim.ros.sim_control import (
    RESET,
    TELEPORT,
    vehicle_services,
    WORLD_INPUTS,
    WORLD_SERVICES,
)
from vehicle_sim.transport.qos import QOS_DEFAULT, QOS_LATCHED

FLOAT64_STAMPED = m.FLOAT64_STAMPED
SET_FLOAT = 'vehicle_msgs/srv/SetFloat'
GET_FLOAT = 'vehicle_msgs/srv/GetFloat'
SET_INT = 'vehicle_msgs/srv/SetInt'
GET_INT = 'vehicle_msgs/srv/GetInt'
SET_BOOL = 'vehicle_msgs/srv/SetBool'
GET_BOOL = 'vehicle_msgs/srv/GetBool'
GET_DIMENSIONS = 'vehicle_msgs/srv/GetDimensions'

# Service kinds: how the node serves them.
SETTER = 'setter'          # request.value -> CarLogic setter; success = accepted
GETTER = 'getter'          # CarLogic getter -> response.value; request.ask ignored
DIMENSIONS = 'dimensions'  # CarLogic.dimensions() -> the five fields
TIME_STEP = 'time_step'    # synchronous stepping of the shared world
WORLD_TIME = 'world_time'  # simulated time [s]
BASIC_TIME_STEP = 'basic_time_step'  # basic time step [ms]

NAN = float('nan')
INF = float('inf')


def _status_value(field, index=None, torque_only=False):
    # ctx -> (stamp, value) of a CarStatus field (one element of a tuple field); None outside
    # TORQUE mode for a torque-only value (Webots publishes rpm in TORQUE mode only).
    get = attrgetter(field)
    if index is not None:
        return lambda v: (v.stamp, get(v.status)[index])
    if torque_only:
        return lambda v: (v.stamp, get(v.status)) if v.torque_mode else None
    return lambda v: (v.stamp, get(v.status))


def _base_frame(v):
    return (v.base_frame,)


def _f64(name, field, unit, doc, index=None, torque_only=False):
    return Topic('automobile/' + name, FLOAT64_STAMPED, QOS_DEFAULT, EACH_PUBLISH,
                 converter(m.float64_stamped_builder, _status_value(field, index, torque_only),
                           _base_frame), unit=unit, doc=doc)


_WHEELS = ('front_right', 'front_left', 'rear_right', 'rear_left')

RPM = _f64('rpm', 'rpm', 'rpm', 'engine speed; published in TORQUE mode only (Webots)',
           torque_only=True)
# Published in TORQUE mode only; the other Float64Stamped topics every publish period.
TORQUE_ONLY_TOPICS = (RPM,)

AUTOMOBILE_TOPICS = (
    _f64('brake_intensity', 'brake_intensity', '1', 'brake intensity in [0, 1]'),
    _f64('current_speed', 'current_speed_kmh', 'km/h',
         'speed estimated from the driven wheels (Webots getCurrentSpeed)'),
    RPM,
    _f64('steering_angle', 'steering_angle_rad', 'rad',
         'mean of the measured front wheel angles, positive = right'),
    _f64('right_steering_angle', 'right_steering_angle_rad', 'rad',
         'measured right front wheel angle, positive = right'),
    _f64('left_steering_angle', 'left_steering_angle_rad', 'rad',
         'measured left front wheel angle, positive = right'),
    _f64('throttle', 'throttle', '1', 'throttle in [0, 1]'),
) + tuple(
    _f64(f'{wheel}_wheel_encoder', 'wheel_encoders_rad', 'rad', f'{wheel} wheel angle',
         index=i) for i, wheel in enumerate(_WHEELS)
) + tuple(
    _f64(f'{wheel}_wheel_speed', 'wheel_speeds_radps', 'rad/s', f'{wheel} wheel speed',
         index=i) for i, wheel in enumerate(_WHEELS)
)

ODOM = Topic('odom', m.ODOMETRY, QOS_DEFAULT, EACH_PUBLISH,
             converter(m.odometry_builder, lambda v: (v.stamp,) + v.odom,
                       lambda v: (v.odom_frame, v.base_frame)),
             unit='m, rad, m/s, rad/s',
             doc='ground truth; frame <p>odom, child <p>base_link, twist in the child frame')
JOINT_STATES = Topic('joint_states', m.JOINT_STATE, QOS_DEFAULT, EACH_PUBLISH,
                     converter(m.joint_state_builder, lambda v: (v.stamp,) + v.joints,
                               lambda v: (v.joint_names,)),
                     unit='rad, m, rad/s, m/s',
                     doc='wheel spin, steering and suspension joints, names prefixed <p>')
ROBOT_DESCRIPTION = Topic('robot_description', m.STRING, QOS_LATCHED, ONCE_LATCHED,
                          converter(m.string_builder, lambda v: (v.description(),)),
                          doc='URDF, link and joint names prefixed <p>')

STANDARD_TOPICS = (CLOCK, ODOM, TF, TF_STATIC, JOINT_STATES, ROBOT_DESCRIPTION, COLLISION)
TOPICS = AUTOMOBILE_TOPICS + STANDARD_TOPICS
# Wired once per vehicle (relative names) and once for the node (global names).
VEHICLE_TOPICS = tuple(row for row in TOPICS if not row.is_global)
WORLD_TOPICS = tuple(row for row in TOPICS if row.is_global)

# Lanes (docs/maps.md): wired per vehicle only in a world with a lane map (a lanelet2 map, a
# SUMO network or roads:), in their own Outputs. Call context: ``lane_state`` (core LaneState
# of this sample), ``lane_event`` and ``lane_event_stamp`` (one core LaneInvasion); wiring:
# ``lanes_frame``.
LANE_STATE = Topic('lane_state', lm.LANE_STATE, QOS_DEFAULT, EACH_PUBLISH,
                   converter(lm.lane_state_builder, lambda v: (v.stamp, v.lane_state),
                             lambda w: (w.lanes_frame,)),
                   unit='m, rad, m/s',
                   doc='the lane base_link is on: lane id, s along its centreline, offset '
                       '(+ left), heading error, width, speed limit; the next stop line ahead '
                       '(id, kind, distance along the lanes) and its traffic light group and '
                       'state; on_lane false off every lane; frame of the lane map (map or '
                       'world)')
LANE_INVASION = Topic('lane_invasion', lm.LANE_INVASION, QOS_SENSOR, ON_EVENT,
                      converter(lm.lane_invasion_builder,
                                lambda v: (v.lane_event_stamp, v.lane_event),
                                lambda w: (w.lanes_frame,)),
                      unit='m',
                      doc='base_link crossed a lane marking: one message per crossing, naming '
                          'the boundary and its line type (virtual and none lines give none)')
LANE_TOPICS = (LANE_STATE, LANE_INVASION)
SET_LANE_POSE_TYPE = 'vehicle_msgs/srv/SetLanePose'
LANE_POSE = 'lane_pose'    # service kind: teleport onto a lane (ros/car_lanes.py)
SET_LANE_POSE = Service('set_lane_pose', SET_LANE_POSE_TYPE, LANE_POSE, value='lane pose',
                        unit='m', webots=False,
                        doc='teleport at rest onto a lane: at s along its centreline, offset to '
                            'its left (+), heading along it; refused: a lane not in the map, s '
                            'outside it, an offset off it, NaN/inf, a place inside an obstacle '
                            'or vehicle')
LANE_SERVICES = (SET_LANE_POSE,)

# Inputs of each car (docs/drive.md): cmd_vel (one of CMD_VEL_INPUTS, by the cmd_vel_stamped
# parameter) and drive; the converters give SI values, steering + = left (REP 103).
DRIVE = Topic('drive', ACKERMANN_DRIVE, QOS_DEFAULT, RECEIVED,
              lambda msg: (msg.drive.speed, msg.drive.steering_angle), IN, unit='m/s, rad',
              doc='drive.speed [m/s] and drive.steering_angle [rad, + left (REP 103)]; the '
                  'other fields are ignored')
INPUT_TOPICS = (CMD_VEL, CMD_VEL_STAMPED, DRIVE)

_NON_FINITE = (NAN, INF, -INF)


def _set(name, srv_type, core, value, observed_by, example, invalid=(), unit='', doc='',
         legacy=False, webots=True):
    if value == 'float':
        invalid = _NON_FINITE + tuple(invalid)
    return Service('automobile/' + name, srv_type, SETTER, core, value, unit, legacy, webots,
                   observed_by, example, tuple(invalid), doc)


def _get(name, srv_type, core, value, unit='', doc='', legacy=False):
    return Service('automobile/' + name, srv_type, GETTER, core, value, unit, legacy, doc=doc)


AUTOMOBILE_SERVICES = (
    # Setters (Webots' ros_automobile order), then the documented-but-missing car-library setters.
    _set('enable_indicator_auto_disabling', SET_BOOL, 'enable_indicator_auto_disabling', 'bool',
         None, False, doc='switch the indicator off after a turn'),
    _set('enable_limited_slip_differential', SET_BOOL, 'enable_limited_slip_differential',
         'bool', None, False, doc='limited-slip differential in TORQUE mode'),
    _set('set_antifog_light', SET_BOOL, 'set_antifog_lights', 'bool',
         'automobile/get_antifog_light', True, doc='antifog lights on/off'),
    _set('set_brake_intensity', SET_FLOAT, 'set_brake_intensity', 'float',
         'automobile/brake_intensity', 0.25, invalid=(-0.1, 1.5), unit='1',
         doc='brake intensity in [0, 1]'),
    _set('set_cruising_speed', SET_FLOAT, 'set_cruising_speed_within_top_kmh', 'float',
         'automobile/get_cruising_speed', 12.0, invalid=(300.0, -300.0, 1e6), unit='km/h',
         doc='switch to SPEED mode, target speed (negative = reverse) up to the top speed'),
    _set('set_dipped_beam', SET_BOOL, 'set_dipped_beams', 'bool', 'automobile/get_dipped_beam',
         True, doc='dipped beams on/off'),
    _set('set_gear', SET_INT, 'set_gear', 'int', 'automobile/get_gear', 1, invalid=(99, -2),
         doc='-1 reverse, 0 neutral, 1..N-1 forward'),
    _set('set_hazard_flashers', SET_BOOL, 'set_hazard_flashers', 'bool',
         'automobile/get_hazard_flashers', True, doc='hazard flashers on/off'),
    _set('set_indicator', SET_INT, 'set_indicator', 'int', 'automobile/get_indicator', 2,
         invalid=(7, -1), doc='0 OFF, 1 RIGHT, 2 LEFT (Webots source: set_int)'),
    _set('set_indicator_period', SET_FLOAT, 'set_indicator_period_s', 'float',
         'automobile/get_indicator_period', 0.5, invalid=(-0.2, 0.0, 5e-324, 9e-4), unit='s',
         doc='length of one indicator ON (or OFF) phase, >= 1 ms'),
    _set('set_steering_angle', SET_FLOAT, 'set_steering_angle', 'float',
         'automobile/steering_angle', 0.2, invalid=(5.0, -5.0), unit='rad',
         doc='Ackermann steering angle, positive = right, within the car limits'),
    _set('set_throttle', SET_FLOAT, 'set_throttle', 'float', 'automobile/throttle', 0.4,
         invalid=(2.0, -0.5), unit='1', doc='switch to TORQUE mode, throttle in [0, 1]'),
    _set('set_wiper_mode', SET_INT, 'set_wiper_mode', 'int', 'automobile/get_wiper_mode', 2,
         invalid=(9, -1), doc='0 DOWN, 1 SLOW, 2 NORMAL, 3 FAST'),
    _set('set_wipers_mode', SET_INT, 'set_wiper_mode', 'int', 'automobile/get_wipers_mode', 3,
         invalid=(9,), doc='legacy name of set_wiper_mode', legacy=True),
    _set('set_right_steering_angle', SET_FLOAT, 'set_right_steering_angle', 'float',
         'automobile/right_steering_angle', 0.15, invalid=(5.0,), unit='rad',
         doc='right front wheel alone (car library; documented, missing in Webots)',
         webots=False),
    _set('set_left_steering_angle', SET_FLOAT, 'set_left_steering_angle', 'float',
         'automobile/left_steering_angle', 0.1, invalid=(-5.0,), unit='rad',
         doc='left front wheel alone (car library; documented, missing in Webots)',
         webots=False),
    # Getters.
    _get('get_antifog_light', GET_BOOL, 'antifog_lights', 'bool'),
    _get('get_backwards_light', GET_BOOL, 'backwards_lights', 'bool'),
    _get('get_brake_light', GET_BOOL, 'brake_lights', 'bool'),
    _get('get_control_mode', GET_INT, 'control_mode', 'int',
         doc='-1 UNDEFINED, 0 SPEED, 1 TORQUE'),
    _get('get_cruising_speed', GET_FLOAT, 'target_cruising_speed_kmh', 'float', unit='km/h',
         doc='target cruising speed'),
    Service('automobile/get_dimensions', GET_DIMENSIONS, DIMENSIONS, 'dimensions',
            value='float', unit='m', doc='track front/rear, wheel base, wheel radii'),
    _get('get_dipped_beam', GET_BOOL, 'dipped_beams', 'bool'),
    _get('get_engine_type', GET_INT, 'engine_type', 'int',
         doc='0 combustion, 1 electric, 2 parallel hybrid, 3 power-split hybrid'),
    _get('get_gear', GET_INT, 'gear', 'int', doc='engaged gear; 0 in SPEED mode (Webots)'),
    _get('get_gear_number', GET_INT, 'gear_number', 'int',
         doc='number of gear ratios including reverse'),
    _get('get_hazard_flashers', GET_BOOL, 'hazard_flashers', 'bool'),
    _get('get_indicator', GET_INT, 'indicator', 'int', doc='0 OFF, 1 RIGHT, 2 LEFT'),
    _get('get_indicator_period', GET_FLOAT, 'indicator_period_s', 'float', unit='s'),
    _get('get_type', GET_INT, 'car_type', 'int', doc='0 traction, 1 propulsion, 2 4x4'),
    _get('get_wiper_mode', GET_INT, 'wiper_mode', 'int', doc='0 DOWN, 1 SLOW, 2 NORMAL, 3 FAST'),
    _get('get_wipers_mode', GET_INT, 'wiper_mode', 'int', doc='legacy name of get_wiper_mode',
         legacy=True),
)

ROBOT_SERVICES = (
    Service('robot/time_step', SET_INT, TIME_STEP, value='int', unit='ms',
            invalid=(7, -10), example=10,
            doc='synchronous mode: advance the shared world by value ms (a multiple of the '
                'basic step; 0 = one step); success=false otherwise'),
    Service('robot/get_time', GET_FLOAT, WORLD_TIME, value='float', unit='s',
            doc='simulated time'),
    Service('robot/get_basic_time_step', GET_FLOAT, BASIC_TIME_STEP, value='float',
            unit='ms', doc='basic time step'),
)

# reset and set_pose (ros/sim_control.py).
POSE_SERVICES = vehicle_services(
    '', 'back to the spawn pose at rest, joints at 0, car logic in its start state (control '
        'mode, gear, cruising speed, throttle, brake, steering, indicators, lights, wipers)')

SERVICES = AUTOMOBILE_SERVICES + ROBOT_SERVICES + POSE_SERVICES
# Served and read once per node (global names): /sim/reset, /sim/pause and /initialpose.
# WORLD_SERVICES, WORLD_INPUTS: imported above from ros/sim_control.py.
# Every service row of an automobile node: each vehicle's, then the node's world services
# (what the docs list and what a client such as vehicle_sim.testing may call).
NODE_SERVICES = SERVICES + WORLD_SERVICES

# Setters of the car's speed: a call after a cmd_vel/drive command holds until the next command
# (the watchdog stands down); steering setters win over the last command's steering only.
LONGITUDINAL_SERVICES = ('automobile/set_cruising_speed', 'automobile/set_throttle',
                         'automobile/set_brake_intensity')

# Webots ros_automobile names that are deliberately not served (documented in the docs).
NOT_SERVED = ('automobile/get_throttle', 'automobile/get_brake_intensity', 'automobile/get_rpm',
              'automobile/set_brake')


def topic(name: str) -> Topic:
    """Return the Topic row called ``name`` (relative name as in the table)."""
    for spec in TOPICS:
        if spec.name == name:
            return spec
    raise KeyError(name)


def service(name: str) -> Service:
    """Return the Service row called ``name`` (relative name as in the table)."""
    for spec in SERVICES:
        if spec.name == name:
            return spec
    raise KeyError(name)


def vehicle_name(name: str, namespace: str) -> str:
    """
    Return an endpoint name for a vehicle namespace.

    :param name: table name; global names (leading ``/``) are returned unchanged.
    :param namespace: vehicle namespace ('' or '/' for the default car, 'car1' or '/car1').
    :return: a relative name (resolved under the node namespace) or the global name.
    """
    if name.startswith('/'):
        return name
    namespace = namespace.strip('/')
    return f'{namespace}/{name}' if namespace else name


def frame_prefix(namespace: str) -> str:
    """Return ``p``: the namespace without its leading slash plus '/' ('' for no namespace)."""
    namespace = namespace.strip('/')
    return namespace + '/' if namespace else ''


def _docs_name(row) -> str:
    return row.name if row.name.startswith('/') else '/<ns>/' + row.name


def sensor_table_markdown() -> str:
    """Return the Markdown table of the sensor topics, one sensor of each type (the docs)."""
    return topic_table_markdown(sensor_topic_rows(), display_name=_docs_name)


def interface_table_markdown() -> str:
    """
    Return the Markdown tables of every topic and service (the body of docs/ros_interface.md).

    :return: three Markdown tables: topics, inputs, services.
    """
    lines = [topic_table_markdown(TOPICS, display_name=_docs_name).rstrip('\n'), '',
             topic_table_markdown(INPUT_TOPICS + WORLD_INPUTS, ('type', 'QoS', 'unit', 'notes'),
                                  _docs_name, first='input').rstrip('\n'), '',
             '| service | type | maps to | value | unit | refused (success=false) | notes |',
             '|---|---|---|---|---|---|---|']
    for spec in NODE_SERVICES:
        if spec.kind in (SETTER, GETTER):
            target = f'CarLogic.{spec.core}'
        elif spec.kind == DIMENSIONS:
            target = 'CarLogic.dimensions()'
        elif spec.kind in (RESET, TELEPORT):
            target = f'SimulatedCar.{"reset" if spec.kind == RESET else "teleport"}()'
        else:
            target = f'world ({spec.kind})'
        refused = ', '.join(value_text(v) for v in spec.invalid)
        notes = spec.doc
        if spec.legacy:
            notes += ' (legacy)'
        if not spec.webots:
            notes += " (not in Webots' ros_automobile)"
        lines.append(f'| `{_docs_name(spec)}` | {spec.srv_type} | {target} | {spec.value} | '
                     f'{spec.unit} | {refused} | {notes} |')
    return '\n'.join(lines) + '\n'
