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
SUMO's traffic over the wire: its objects with their classes, its signals on our topic.

The automobile node runs the signalised SUMO city of test/test_physics_sumo_city.py (SUMO's
vehicles and pedestrians, our car in a lane) in this process (synchronous, embedded DDS) for 60
simulated seconds; a client node reads /perception/object_recognition/objects (CAR objects of
SUMO's passenger cars with their type's box, PEDESTRIAN objects as upright CYLINDERs of a person's
width and height, one per SUMO body) and /perception/traffic_light_recognition/traffic_signals
(each group's colour SUMO's state of its link at the message's stamp, read from SUMO at every
step). Its own module: the topics are global.
"""

from automobile_helpers import client_node, wait_for
import pytest
import yaml

pytest.importorskip('libsumo', reason="needs the 'sumo' extra")

from test_physics_sumo_city import city_net, DEMAND, EGO_LANE, EGO_S  # noqa: E402

from vehicle_sim.core.map.signal_programs import SUMO_STATES  # noqa: E402
from vehicle_sim.core.sensors.labels import label_of_class  # noqa: E402
from vehicle_sim.physics.body_labels import instance_uuid  # noqa: E402
from vehicle_sim.physics.sumo_pool import instance_name  # noqa: E402
from vehicle_sim.ros.traffic_interfaces import (  # noqa: E402
    PREDICTED_OBJECTS_TOPIC,
    TRAFFIC_SIGNALS,
)
from vehicle_sim.ros.traffic_messages import ELEMENT_COLOR  # noqa: E402
from vehicle_sim.transport.qos import QosProfile, TRANSIENT_LOCAL  # noqa: E402

pytestmark = pytest.mark.transport

# subscriptions keeping every message of the run (the signals' writer is transient-local)
KEEP = {PREDICTED_OBJECTS_TOPIC.name: QosProfile(depth=1000),
        TRAFFIC_SIGNALS.name: QosProfile(depth=1000, durability=TRANSIENT_LOCAL)}
SECONDS = 60.0
CAR, PEDESTRIAN, BOUNDING_BOX, CYLINDER = 1, 7, 0, 1


class SumoStates:
    """A world step hook: SUMO's state string of every traffic light after each step."""

    def __init__(self, world, api, tls_ids):
        self.world, self.api, self.tls_ids = world, api, tls_ids
        self.at = {}            # {time [ms]: {tls id: state string}}
        self.post_step()        # now

    def post_step(self):
        self.at[round(self.world.time_s * 1000)] = {
            tls: self.api.trafficlight.getRedYellowGreenState(tls) for tls in self.tls_ids}


def run_city_node(folder):
    """
    Run the city's node SECONDS with a client node listening; return what the run saw.

    :return: (bodies, programs, SumoStates, {topic: messages}, the end time [ms]); the node
        closed (its SUMO with it): the bodies' last state is the end's.
    """
    from vehicle_sim.ros.automobile_node import AutomobileNode
    world = folder / 'city.yaml'
    world.write_text(yaml.safe_dump({
        'vehicles': [{'name': 'ego', 'model': 'Car', 'pose': {'lane': EGO_LANE, 's': EGO_S}}],
        'map': {'type': 'sumo', 'net': city_net(folder)},
        'traffic': {'engine': 'sumo', 'demand': DEMAND, 'seed': 1}}), encoding='utf-8')
    node = AutomobileNode(['x', '--ros-args', '-r', '__ns:=/sumo_city'], transport='dds',
                          parameter_overrides={'synchronous': True, 'world': str(world)})
    try:
        bodies = node.scene.parts['traffic']
        programs = node.scene.lanes.rules.programs
        states = SumoStates(node.world, bodies.session.api, [p.tls_id for p in programs])
        node.world.add_body(states)
        received = {PREDICTED_OBJECTS_TOPIC.name: [], TRAFFIC_SIGNALS.name: []}
        with client_node('sumo_city_listener') as client:
            subs = [client.create_subscription(row.ros_type, row.name, received[row.name].append,
                                               KEEP[row.name])
                    for row in (PREDICTED_OBJECTS_TOPIC, TRAFFIC_SIGNALS)]
            assert wait_for(lambda: all(s.get_publisher_count() for s in subs), spin=client)
            node.step(int(round(SECONDS * 100)))
            end_ms = round(node.world.time_s * 1000)
            assert wait_for(lambda: any(round(seconds(m.header.stamp) * 1000) == end_ms
                                        for m in received[PREDICTED_OBJECTS_TOPIC.name]),
                            spin=client)
            client.spin_once(0.2)
        return bodies, programs, states, received, end_ms, _truth(bodies)
    finally:
        node.close()


def _truth(bodies):
    """Return each SUMO body now: {uuid: (object, SUMO id, person?, (length, width, height))}."""
    api = bodies.session.api
    persons = set(api.person.getIDList())
    found = {}
    for o in bodies.objects():
        sumo_id = bodies.sumo_id(o.name)
        person = sumo_id in persons
        kind = (api.person if person else api.vehicle).getTypeID(sumo_id)
        vclass = None if person else api.vehicle.getVehicleClass(sumo_id)
        # the UUID of the instance id of its body's SUMO vehicle or person
        label, instance = bodies.world.labels.of(bodies.body_of(o.name))
        assert instance == bodies.world.labels.instance(instance_name(person, sumo_id))
        assert label == label_of_class(o.object_class)
        found[instance_uuid(instance)] = (o, person, vclass, (
            api.vehicletype.getLength(kind), api.vehicletype.getWidth(kind),
            api.vehicletype.getHeight(kind)))
    return found


def seconds(stamp):
    return stamp.sec + stamp.nanosec * 1e-9


def test_sumos_objects_and_signals_over_the_wire(tmp_path):
    _, programs, states, received, end_ms, truth = run_city_node(tmp_path)
    check_objects(received, end_ms, truth)
    check_signals(programs, states, received)


def check_objects(received, end_ms, truth):
    """SUMO's passenger cars are CAR boxes of their type, its persons PEDESTRIAN cylinders."""
    last, = [m for m in received[PREDICTED_OBJECTS_TOPIC.name]
             if round(seconds(m.header.stamp) * 1000) == end_ms]
    assert len(last.objects) == len(truth) > 10
    labels = []
    for item in last.objects:
        o, person, vclass, (length, width, height) = truth[bytes(item.object_id.uuid)]
        label = item.classification[0].label
        labels.append(label)
        dimensions = item.shape.dimensions
        if label == PEDESTRIAN:
            assert person and item.shape.type == CYLINDER
            assert (dimensions.x, dimensions.y, dimensions.z) == \
                pytest.approx((width, width, height))
        else:
            assert label == CAR and vclass == 'passenger' and item.shape.type == BOUNDING_BOX
            assert (dimensions.x, dimensions.y, dimensions.z) == \
                pytest.approx((length, width, height))
        position = item.kinematics.initial_pose_with_covariance.pose.position
        assert (position.x, position.y) == pytest.approx((o.x_m, o.y_m), abs=1e-6)
    assert labels.count(PEDESTRIAN) >= 3 and labels.count(CAR) >= 3


def check_signals(programs, states, received):
    """Each group's colour is SUMO's state of its link at the message's stamp."""
    messages = received[TRAFFIC_SIGNALS.name]
    assert len(messages) >= SECONDS * 10
    link_of = {g: (p.tls_id, k) for p in programs for k, g in enumerate(p.links)
               if g is not None}
    colours, compared = set(), 0
    for message in messages:
        shown = states.at[round(seconds(message.stamp) * 1000)]
        for group in message.traffic_light_groups:
            tls, link = link_of[group.traffic_light_group_id]
            element, = group.elements
            assert element.color == ELEMENT_COLOR[SUMO_STATES[shown[tls][link]]], \
                (seconds(message.stamp), tls, link)
            colours.add(element.color)
            compared += 1
    assert compared == len(messages) * len(link_of)
    assert colours == {1, 2, 3}                             # red, amber and green seen
