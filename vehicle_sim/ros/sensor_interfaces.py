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
The sensor rows of a vehicle, its collision row, and the ``sensors`` node parameter.

A vehicle's sensors come from its configuration (docs/sensors.md), so their rows are made per
vehicle by :func:`sensor_rows`: one :class:`~.endpoints.Topic` per topic of each mounted sensor
(a camera has two), named by the sensor's ``topics`` (relative to the vehicle namespace),
reliable, depth 5, cadence EACH_SAMPLE. ``SENSOR_ROWS`` is the ROS registration: core sensor
type -> the function making its rows and the configurations its docs rows show (checked
against the core types when imported; docs/sensors.md, "Adding a sensor type").

Converter contexts. Wiring ``w``: ``frame_prefix`` (``<p>``) and, for :data:`COLLISION`,
``base_frame``. Call ``ctx``: ``readings`` ({sensor name: reading} of one sampled step) and
``sample_stamp`` (their simulated time) for the sensor rows, which give nothing for a sensor
without a reading in ``readings``; ``event`` (a core CollisionEvent) and ``event_stamp`` (its
time) for :data:`COLLISION`, published once per event (cadence ON_EVENT).
"""

from dataclasses import dataclass, replace
from typing import Callable, Dict, Iterable, Sequence, Tuple

from vehicle_sim.core.sensors.labels import LABELS
from vehicle_sim.core.sensors.params import check_layer, sensor_from_dict
from vehicle_sim.core.sensors.sensor_spec import SensorSpec
from vehicle_sim.core.sensors.sets import mounted
from vehicle_sim.core.specs.errors import InvalidParameterError
from vehicle_sim.core.specs.param_spec import ParamSpec
from vehicle_sim.ros import messages as m
from vehicle_sim.ros import perception_messages as pm
from vehicle_sim.ros.endpoints import converter, EACH_SAMPLE, ON_EVENT, ONCE_LATCHED, Topic
from vehicle_sim.ros.radar_messages import (
    RADAR_SCAN,
    radar_scan_builder,
    RADAR_TRACKS,
    radar_tracks_builder,
)
from vehicle_sim.transport.qos import QOS_LATCHED, QosProfile

# Reliable, volatile, depth 5 (issue: sensor topics); a best-effort sensor_data reader matches.
QOS_SENSOR = QosProfile(depth=5)

COLLISION = Topic(
    'collision', m.COLLISION, QOS_SENSOR, ON_EVENT,
    converter(m.collision_builder, lambda v: (v.event_stamp, v.event),
              lambda w: (w.base_frame,)),
    unit='N',
    doc='the vehicle started touching a body other than the ground: its name, the sum of the '
        'contact normal forces; again only after 0.1 s apart; frame <p>base_link')


def _sample_of(name):
    # ctx -> (stamp, reading) of the sensor ``name``, None when it has no reading in ctx.
    def values(ctx):
        reading = ctx.readings.get(name)
        return None if reading is None else (ctx.sample_stamp, reading)
    return values


def _row(topic, ros_type, builder, spec, doc, optical=False, unit=''):
    def frame(w):
        prefix = w.frame_prefix
        return (spec.optical_frame_id(prefix) if optical else spec.frame_id(prefix),)
    return Topic(topic, ros_type, QOS_SENSOR, EACH_SAMPLE,
                 converter(builder, _sample_of(spec.name), frame), unit=unit, doc=doc)


def _lidar_rows(spec):
    topic, = spec.topics
    if spec.layers == 1:
        return (_row(topic, m.LASER_SCAN, m.laser_scan_builder, spec,
                     'lidar, one layer: ranges counter-clockwise from angle_min, REP 117 '
                     '(+inf no return, -inf too close); intensities with labels: true, else '
                     'empty; frame <p><name>', unit='m, rad'),)
    return (_row(topic, m.POINT_CLOUD2, m.point_cloud2_builder, spec,
                 'lidar, several layers: organized (height = layers, width = rays), x, y, z '
                 'float32, NaN for no return; with labels: true also intensity float32, label '
                 'and instance uint16; frame <p><name>', unit='m'),)


def _imu_rows(spec):
    topic, = spec.topics
    return (_row(topic, m.IMU, m.imu_builder, spec,
                 'orientation in ENU, angular velocity, linear acceleration including gravity '
                 '(+9.81 on z at rest); frame <p><name>', unit='rad/s, m/s^2'),)


def _gnss_rows(spec):
    topic, = spec.topics
    return (_row(topic, m.NAV_SAT_FIX, m.nav_sat_fix_builder, spec,
                 "WGS-84 fix of the antenna (the world's origin); covariance DIAGONAL_KNOWN, "
                 'UNKNOWN without noise; frame <p><name>', unit='deg, m'),)


def _distance_rows(spec):
    topic, = spec.topics
    return (_row(topic, m.RANGE, m.range_builder, spec,
                 'distance sensor: nearest hit, REP 117; topic = its name by default; frame '
                 '<p><name>', unit='m'),)


def _camera_rows(spec):
    image, info = spec.topics[:2]
    rows = (_row(image, m.IMAGE, m.image_builder, spec,
                 'rgb8, rows top to bottom; frame <p><name>_optical', optical=True),
            _row(info, m.CAMERA_INFO, m.camera_info_builder, spec,
                 'ideal pinhole (plumb_bob, no distortion) of the image; frame '
                 '<p><name>_optical', optical=True))
    return rows + _perception_rows(spec, spec.topics[2:])


def _perception_rows(spec, topics):
    # a camera's segmentation images and recognition rows (ros/perception_messages.py)
    rows = ()
    if spec.segmentation:
        semantic, instance, topics = topics[0], topics[1], topics[2:]
        rows += (_row(semantic, m.IMAGE, pm.semantic_image_builder, spec,
                      'segmentation: mono16 label id per pixel (the label table of '
                      'docs/sensors.md); frame <p><name>_optical', optical=True),
                 _row(instance, m.IMAGE, pm.instance_image_builder, spec,
                      'segmentation: mono16 object id per pixel (PredictedObjects ids), 0 = '
                      'none; frame <p><name>_optical', optical=True))
    if spec.recognition:
        detections, labels = topics
        rows += (_row(detections, pm.DETECTION_2D_ARRAY, pm.detection_2d_array_builder, spec,
                      'recognition: the visible objects, id = object id, bbox = the visible '
                      'part [px], class_id = label name, score 1; frame <p><name>_optical',
                      optical=True, unit='px'),
                 Topic(labels, pm.LABEL_INFO, QOS_LATCHED, ONCE_LATCHED,
                       converter(pm.label_info_builder, lambda ctx: (ctx.stamp, LABELS),
                                 lambda w: (spec.optical_frame_id(w.frame_prefix),)),
                       doc='recognition: the label table (class_id = label id, class_name), '
                           'latched'))
    return rows


def _range_finder_rows(spec):
    image, info = spec.topics[:2]
    rows = (_row(image, m.IMAGE, m.image_builder, spec,
                 'range finder: 32FC1 depth along the optical axis, rows top to bottom, '
                 'REP 118 (+inf nothing within max_range, -inf under min_range); frame '
                 '<p><name>_optical', optical=True, unit='m'),
            _row(info, m.CAMERA_INFO, m.camera_info_builder, spec,
                 'ideal pinhole (plumb_bob, no distortion) of the depth image; frame '
                 '<p><name>_optical', optical=True))
    if spec.point_cloud:
        rows += (_row(spec.topics[2], m.POINT_CLOUD2, m.point_cloud2_builder, spec,
                      'range finder with point_cloud: organized as the image (height x '
                      'width), x, y, z float32, NaN where the depth is not finite; frame '
                      '<p><name>_optical', optical=True, unit='m'),)
    return rows


def _radar_rows(spec):
    tracks, scan = spec.topics
    return (_row(tracks, RADAR_TRACKS, radar_tracks_builder, spec,
                 'radar targets as tracks (Autoware): uuid = the instance id, position, '
                 'velocity relative to the radar, size, classification 32000-32007; frame '
                 '<p><name>', unit='m, m/s'),
            _row(scan, RADAR_SCAN, radar_scan_builder, spec,
                 'radar targets as returns: range, azimuth (REP 103), elevation, doppler '
                 'velocity (> 0 away), amplitude = received power [dBm]; frame <p><name>',
                 unit='m, rad, m/s, dBm'))


@dataclass(frozen=True)
class SensorRows:
    """
    The ROS part of a sensor type: its rows, and the configurations the docs table shows.

    :param rows: ``rows(spec)`` -> the Topic rows of one SensorSpec of the type.
    :param doc_examples: the non-default keys of each docs example (``{}``: the defaults).
    """

    rows: Callable
    doc_examples: Tuple[Dict, ...] = ({},)


# The ROS registration: core sensor type -> its SensorRows.
SENSOR_ROWS = {
    'lidar': SensorRows(_lidar_rows, ({}, {'layers': 16, 'vertical_fov': 0.5})),
    'imu': SensorRows(_imu_rows),
    'gnss': SensorRows(_gnss_rows),
    'distance': SensorRows(_distance_rows),
    'camera': SensorRows(_camera_rows, ({'segmentation': True, 'recognition': True},)),
    'range_finder': SensorRows(_range_finder_rows, ({'point_cloud': True},)),
    'radar': SensorRows(_radar_rows),
}
check_layer('ROS SENSOR_ROWS (ros/sensor_interfaces.py)', SENSOR_ROWS)


def sensor_rows(specs: Iterable[SensorSpec]) -> Tuple[Topic, ...]:
    """Return the rows of the mounted sensors, in sensor order."""
    rows = []
    for spec in mounted(specs):
        rows.extend(SENSOR_ROWS[spec.sensor_type].rows(spec))
    return tuple(rows)


def check_names(rows: Sequence[Topic], taken: Dict[str, str], resolve, source):
    """
    Refuse a sensor row whose name another endpoint of the node has; record the new names.

    Two sensors of a vehicle on one topic are refused by its configuration already; this
    check covers the node's whole interface (its own topics and services, other vehicles).

    :param rows: a vehicle's sensor rows.
    :param taken: {fully-qualified name: what has it}, extended with ``rows``.
    :param resolve: ``resolve(row.name)`` -> its fully-qualified name on the node.
    :param source: quoted in the error (the world file, the vehicle).
    :raises InvalidParameterError: naming the sensor topic and what already has that name.
    """
    for row in rows:
        name = resolve(row.name)
        if name in taken:
            raise InvalidParameterError(
                f'{source}: sensor topic {row.name!r} ({name}) is already {taken[name]}; set '
                'another "topic" on the sensor')
        taken[name] = f'a sensor topic ({row.ros_type})'


# ---------------------------------------------------------------------------------------------
# The sensors node parameter (automobile and diff_robot)


def _sensor_names(value):
    names = [v for v in value if v]
    if 'all' in names and len(names) > 1:
        return "'all' must be the only entry"
    return None


SENSORS_PARAMETER = ParamSpec(
    'sensors', kind='str_list', default=('',), empty=True, check=_sensor_names,
    doc="preset sensors to mount (on each vehicle), by name, or ['all']; [''] = none but those "
        'a world file mounts (docs/sensors.md)')


# ---------------------------------------------------------------------------------------------
# Docs


def sensor_topic_rows() -> Tuple[Topic, ...]:
    """Return the rows of one sensor of each type, default topics, named ``<name>`` (docs)."""
    examples = (dict(example, type=sensor_type, name='x')
                for sensor_type, row in SENSOR_ROWS.items() for example in row.doc_examples)
    return sensor_rows(replace(sensor_from_dict(data, 'docs'), name='<name>')
                       for data in examples)
