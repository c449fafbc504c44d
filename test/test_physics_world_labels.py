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
Every body of a composed world carries its label and instance id where it is made.

A hand-made signalised crossing (test/lane_helpers.py) with a walkway, a curb, a crosswalk, a
stop line and a parking area, a traffic light, an obstacle, our car and two traffic vehicles:
what a camera looking straight down sees at known points, and what rays hit, read through
``World.labels`` as the label table says (physics/body_labels.py).
"""

from dataclasses import replace

from lane_helpers import (
    CROSSWALK,
    LIGHT_XY,
    PARKING,
    signal_crossing,
    StandInSignals,
    straight,
)
import numpy as np
import pybullet
import pytest

from vehicle_sim.config import world_from_data
from vehicle_sim.core.map.lane_graph import Boundary, Lane, LaneGraph
from vehicle_sim.core.map.lane_rules import MapArea
from vehicle_sim.core.sensors.labels import LABEL_IDS, LABELS
from vehicle_sim.physics.lane_layer import build_lane_bodies
from vehicle_sim.physics.scene import build_scene, mount_suite
from vehicle_sim.physics.sensors.render import View
from vehicle_sim.physics.signal_lamps import SignalLampsPart

WALKWAY = ((-20.0, 3.0), (0.0, 3.0), (0.0, 6.0), (-20.0, 6.0))
CONE_XY = (-15.0, -12.0)
CAR_XY = (-14.0, 0.0)
# a labelled lidar looking down around the car: its rays meet the ground within 3 .. 12 m
LIDAR = {'type': 'lidar', 'name': 'lidar', 'fov': 6.28, 'horizontal_resolution': 360,
         'layers': 8, 'vertical_fov': 0.4, 'pose': {'x': 1.0, 'z': 1.8, 'pitch': 0.45},
         'max_range': 40.0, 'labels': True}
DOWN = np.array([[0.0, 0.0, -1.0], [0.0, 1.0, 0.0], [1.0, 0.0, 0.0]]).T   # columns x, y, z


def crossing():
    """Return the signal crossing with a walkway north of lane 1 and a curb along lane 2."""
    graph = signal_crossing()
    lanes = [lane for lane in graph.lanes.values() if lane.id != 2]
    curbed = Lane(2, [(0.0, 0.0), (20.0, 0.0)], Boundary(4, [(0.0, 1.75), (20.0, 1.75)], 'solid'),
                  Boundary(5, [(0.0, -1.75), (20.0, -1.75)], 'curbstone'), 10.0)
    assert straight(2, 0, 0, 20, 0).centerline.tolist() == curbed.centerline.tolist()
    found = LaneGraph(lanes + [curbed])
    rules = graph.rules
    found.set_rules(replace(rules, areas=rules.areas + (MapArea(503, 'walkway', WALKWAY),)))
    return found


class LaneBodies:
    """The ``roads`` part of the spec's lanes (a ``roads:`` key's lanes would be built)."""

    name = 'roads'

    def build(self, world, spec):
        return build_lane_bodies(world, spec.lanes)


@pytest.fixture(scope='module')
def scene():
    spec = world_from_data({
        'vehicles': [{'name': 'ego', 'model': 'Car', 'sensors': [LIDAR],
                      'pose': {'x': CAR_XY[0], 'y': CAR_XY[1], 'yaw': 0.0}}],
        'obstacles': [{'name': 'cone', 'shape': 'cylinder', 'radius': 0.3, 'height': 0.8,
                       'position': [CONE_XY[0], CONE_XY[1], 0.4]}],
        'traffic': {'vehicles': 2, 'seed': 3, 'spawn': {'lanes': [3, 4], 'spacing': 8.0}}},
        'labels.yaml')
    built = build_scene(replace(spec, lanes=crossing()), mount=mount_suite,
                        parts=(LaneBodies(), StandInSignals(), SignalLampsPart()))
    yield built
    built.world.close()


def seen_below(world, x, y, height_m=30.0):
    """Return (label name, instance id) of what a camera straight above (x, y) sees."""
    frame = world.renderer.render(View(9, 9, 0.02, 0.1, 100.0), (x, y, height_m), DOWN,
                                  mask=True)
    body, link = int(frame.bodies[4, 4]), int(frame.links[4, 4])
    if body < 0:
        return 'none', 0
    label, instance = world.labels.of(body, link)
    return LABELS[label].name, instance


def test_the_road_its_paint_and_areas_are_labelled_where_they_are_drawn(scene):
    world = scene.world
    assert seen_below(world, -6.0, -1.0) == ('road', 0)                   # lane 1
    assert seen_below(world, 10.0, 0.0) == ('road', 0)                    # the junction
    assert seen_below(world, -10.0, 1.75) == ('lane_marking', 0)         # a solid line
    assert seen_below(world, -2.0, 0.0) == ('lane_marking', 0)            # the stop line
    crosswalk_x = 0.5 * (CROSSWALK[0][0] + CROSSWALK[1][0])
    assert seen_below(world, crosswalk_x, 1.5) == ('crosswalk', 0)       # a zebra stripe's middle
    assert seen_below(world, -10.0, 4.5) == ('sidewalk', 0)               # the walkway
    parking = np.mean(PARKING, axis=0)
    assert seen_below(world, *parking) == ('road', 0)
    assert seen_below(world, 15.0, -1.75) == ('wall', 0)                 # the curb's top
    assert seen_below(world, -30.0, 30.0) == ('ground', 0)                # off the map


def test_the_light_obstacle_and_vehicles_are_labelled_with_their_instances(scene):
    world = scene.world
    labels = world.labels
    assert seen_below(world, *LIGHT_XY) == ('traffic_light', 0)
    assert seen_below(world, *CONE_XY) == ('obstacle', labels.instance('cone'))
    assert seen_below(world, CAR_XY[0] + 0.5, CAR_XY[1]) == ('car', labels.instance('ego'))
    traffic = scene.parts['traffic']
    assert len(traffic.objects()) == 2
    for o in traffic.objects():
        assert o.instance_id == labels.instance(o.name) > 0
        assert seen_below(world, o.x_m, o.y_m) == ('car', o.instance_id)
    ids = [labels.instance(name) for name in ('cone', 'ego', 'traffic_0', 'traffic_1')]
    assert len(set(ids)) == 4


def test_rays_hit_bodies_whose_labels_are_what_they_are(scene):
    world = scene.world
    world.sync_bodies()
    pole = scene.parts['signal_lamps'].poles[0]
    targets = [(CONE_XY[0], CONE_XY[1], 0.4), (CAR_XY[0], CAR_XY[1], 0.7),
               (10.0, -1.755, 0.1), (pole.x_m, pole.y_m, 1.0)]
    starts = [(x, y + 3.0, z) if index != 2 else (x, y - 3.0, z)
              for index, (x, y, z) in enumerate(targets)]
    ends = [(x, y - (3.0 if index != 2 else -3.0), z)
            for index, (x, y, z) in enumerate(targets)]
    hits = pybullet.rayTestBatch(starts, ends, physicsClientId=world.client_id)
    bodies = np.array([hit[0] for hit in hits])
    links = np.array([hit[1] for hit in hits])
    got, instances = world.labels.lookup(bodies, links)
    assert got.tolist() == [LABEL_IDS[name] for name in
                            ('obstacle', 'car', 'wall', 'traffic_light')]
    assert instances.tolist() == [world.labels.instance('cone'), world.labels.instance('ego'),
                                  0, 0]


def test_lidar_points_on_the_ground_read_what_is_drawn_there(scene):
    """The rays pass the drawn meshes; where they meet the ground the raster of them answers."""
    reading = scene.vehicles['ego'].sensors.sample('lidar')
    mount = scene.vehicles['ego'].sensors.sensors['lidar'].mount
    origin, rotation, _ = mount.world_frame()
    finite = np.isfinite(reading.ranges_m)
    points = reading.points()[finite].astype(float) @ rotation.T + origin
    labels = reading.labels[finite]
    x, y = points[:, 0], points[:, 1]
    on_ground = np.abs(points[:, 2]) < 0.05
    names = np.array([LABELS[label].name for label in labels])

    def read(where):
        return set(names[where & on_ground].tolist())
    lane = (np.abs(y) < 1.5) & (x > -19.8) & (x < -2.4)          # lane 1 before its stop line
    assert lane.sum() > 20 and read(lane) == {'road'}
    line = (np.abs(y - 1.75) < 0.03) & (x > -19.5) & (x < -2.5)    # lane 1's left line
    assert read(line) == {'lane_marking'}
    walk = (y > 3.2) & (y < 5.8) & (x > -19.8) & (x < -0.2)
    assert walk.sum() > 5 and read(walk) == {'sidewalk'}
    off = (x < -21.0) | (y > 6.5) | (y < -14.0)
    assert off.sum() > 20 and read(off) == {'ground'}
    # intensities: each label's reflectivity times the cosine on the flat ground
    ground = on_ground & (names == 'road')
    directions = (points[ground] - origin)
    cosine = np.abs(directions[:, 2]) / np.linalg.norm(directions, axis=1)
    assert reading.intensities[finite][ground] == pytest.approx(
        LABELS[LABEL_IDS['road']].reflectivity * cosine, rel=1e-3)
