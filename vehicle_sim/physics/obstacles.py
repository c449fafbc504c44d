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
Obstacles in a World: boxes, cylinders and spheres from core ObstacleSpec.

A mass of 0 makes a static obstacle (fixed in the world); otherwise a free rigid body of uniform
density (PyBullet's inertia of the shape). Every obstacle has a visual in its colour, so cameras
see it; the friction is Bullet's default (0.5).
"""

import pybullet


def _cylinder(spec, visual):
    # createCollisionShape calls the cylinder's length 'height', createVisualShape 'length'
    key = 'length' if visual else 'height'
    return {'shapeType': pybullet.GEOM_CYLINDER, 'radius': spec.radius_m, key: spec.height_m}


# obstacle shape (core/world/params.py OBSTACLE_SHAPES) -> geometry(spec, visual) -> the keyword
# arguments of pybullet.createCollisionShape (visual False) or createVisualShape (visual True).
OBSTACLE_GEOMETRY = {
    'box': lambda spec, visual: dict(shapeType=pybullet.GEOM_BOX,
                                     halfExtents=[s / 2.0 for s in spec.size_m]),
    'cylinder': _cylinder,
    'sphere': lambda spec, visual: dict(shapeType=pybullet.GEOM_SPHERE, radius=spec.radius_m),
}


def _shape(spec, visual):
    return OBSTACLE_GEOMETRY[spec.shape](spec, visual)


def create_obstacle(client_id, spec, placed=False):
    """
    Create an obstacle's body.

    :param client_id: the World's PyBullet client.
    :param spec: core.world_params.ObstacleSpec.
    :param placed: a static obstacle moved only by being placed (traffic): a Bullet rigid body
        (maximal coordinates) put to sleep, which the physics step does not visit (an awake
        one costs it about 0.1 us: 250 SUMO vehicles and persons, 25 us a step); otherwise a
        multibody. Asleep, it is still where it was last put for rays, overlap checks and the
        contacts of the bodies that move (PyBullet's reset moves its bounding box at once, and
        leaves it asleep).
    :return: the body id.
    """
    collision = pybullet.createCollisionShape(physicsClientId=client_id, **_shape(spec, False))
    visual = pybullet.createVisualShape(rgbaColor=list(spec.color_rgba),
                                        physicsClientId=client_id, **_shape(spec, True))
    pose = spec.pose
    body_id = pybullet.createMultiBody(spec.mass_kg, collision, visual, list(pose.xyz),
                                       list(pose.quaternion), useMaximalCoordinates=placed,
                                       physicsClientId=client_id)
    if placed:
        pybullet.changeDynamics(body_id, -1, activationState=pybullet.ACTIVATION_STATE_SLEEP,
                                physicsClientId=client_id)
    return body_id
