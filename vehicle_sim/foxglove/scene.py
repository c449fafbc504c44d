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
The 3D scene of a running world as Foxglove scene entities, from a registry of entity sources.

What is drawn is described with plain values (:mod:`.entities`: :class:`Entity` and its
cubes, cylinders, spheres, lines and triangles), SDK-free so that the geometry is tested on its
own; :mod:`.scene_messages` turns them into ``foxglove.SceneUpdate`` and
``foxglove.FrameTransforms``.

Every entity is in the ``world`` frame and posed from the ground truth of the physics, so the
scene does not depend on the transforms. An entity source is a function ``source(scene)`` ->
entities of the scene builder's ``Scene``; :func:`register_entity_source` adds one (a new kind
of thing plugs in there, under its own name), either *static* (built once per scene, sent when
a client subscribes) or moving (called at every update; :func:`boxes_entity` draws a body as
posed boxes).
A source may also be *on change*: called at every update, its entities sent only when they
differ from the ones sent last.
Built in: ``'vehicles'`` (each vehicle's chassis boxes, posed at each update), ``'obstacles'``
(the world's cubes, cylinders and spheres), ``'traffic'`` (the traffic's boxes and cylinders), the
static ``'map'`` (an occupancy map's walls) and ``'lanes'`` (road surface, markings, barriers,
centrelines, the rules' areas, stop lines, crosswalks and traffic light poles), and the on-change
``'signals'`` (the traffic lights' heads in their colours) of :mod:`.map_scene`, and
``'radar_targets'`` (each mounted radar's last targets, :mod:`.radar_scene`).
"""

from typing import Callable, Dict, Iterable, List, Optional, Sequence, Tuple

from vehicle_sim.core.geometry.frames import pose_from_frame, quaternion_from_rpy
from vehicle_sim.foxglove import map_scene, radar_scene
from vehicle_sim.foxglove.entities import (  # noqa: F401 - the values sources build, here too
    Color,
    Entity,
    IDENTITY,
    Lines,
    Primitive,
    Quaternion,
    Transform,
    Triangles,
    Vector,
    WORLD_FRAME,
)

# The colour of vehicle boxes (RGBA): a translucent blue, so that sensors inside show.
VEHICLE_COLOR = (0.2, 0.45, 0.85, 0.8)
# The height of a vehicle drawn from its footprint alone (a body with no boxes of its own) [m].
FOOTPRINT_BOX_HEIGHT_M = 1.0
# obstacle shape (core/world/params.py OBSTACLE_SHAPES) -> the Foxglove primitive drawing it
# (its size_m the primitive's size).
PRIMITIVE_OF_SHAPE = {'box': 'cube', 'cylinder': 'cylinder', 'sphere': 'sphere'}

Box = Tuple[Vector, Quaternion, Vector]


# ------------------------------------------------------------------------------ vehicles

def vehicle_boxes(params, outline) -> List[Box]:
    """
    Return a vehicle's body boxes in its base_link: (centre [m], orientation, size [m]).

    A car: its chassis collision boxes (preset ``collisionBoxes``: size, position, pitch). A
    differential robot: its body box, centred on the axle height. Anything else: its footprint
    rectangle, :data:`FOOTPRINT_BOX_HEIGHT_M` high, on the ground.
    """
    boxes = getattr(params, 'collision_boxes', None)
    if boxes:
        return [(tuple(box.position_m), quaternion_from_rpy(0.0, box.pitch_rad, 0.0),
                 tuple(box.size_m)) for box in boxes]
    body = getattr(params, 'body_size_m', None)
    if body is not None:
        return [((0.0, 0.0, params.wheel_radius_m), IDENTITY, tuple(body))]
    return [(((outline.x_min_m + outline.x_max_m) / 2.0, (outline.y_min_m + outline.y_max_m) / 2.0,
              FOOTPRINT_BOX_HEIGHT_M / 2.0), IDENTITY,
             (outline.length_m, outline.width_m, FOOTPRINT_BOX_HEIGHT_M))]


def boxes_entity(entity_id: str, pose, boxes: Sequence[Box], color_rgba: Color) -> Entity:
    """
    Return a body drawn as boxes, posed now, in the world frame (vehicles, traffic).

    :param entity_id: the entity's id; the same id each frame moves the entity.
    :param pose: the body's frame in the world: (x, y, z [m], qx, qy, qz, qw).
    :param boxes: (centre [m], orientation, size [m]) of each box in the body's frame.
    """
    xyz, q = tuple(pose[:3]), tuple(pose[3:])
    primitives = []
    for centre, orientation, size in boxes:
        position, rotation = pose_from_frame(xyz, q, centre, orientation)
        primitives.append(Primitive('cube', position, rotation, tuple(size), tuple(color_rgba)))
    return Entity(entity_id, WORLD_FRAME, tuple(primitives))


def vehicle_entity(name: str, pose, boxes, color_rgba=VEHICLE_COLOR) -> Entity:
    """
    Return a vehicle's entity in the world frame.

    :param pose: base_link in the world: (x, y, z [m], qx, qy, qz, qw).
    :param boxes: :func:`vehicle_boxes`.
    """
    return boxes_entity(f'vehicle/{name}', pose, boxes, color_rgba)


def vehicle_entities(scene) -> List[Entity]:
    """Return every vehicle of the scene, posed now (the entity source ``'vehicles'``)."""
    found = []
    for name, vehicle in scene.vehicles.items():
        body = vehicle.body
        found.append(vehicle_entity(name, body.pose(), vehicle_boxes(body.params, body.outline)))
    return found


# ------------------------------------------------------------------------------ obstacles

def obstacle_entity(spec, position_m: Optional[Vector] = None,
                    orientation: Optional[Quaternion] = None) -> Entity:
    """
    Return an obstacle's entity from its world-file spec (ObstacleSpec).

    :param position_m: where it is now (a movable obstacle); None: its spec's position.
    :param orientation: its orientation now; None: the spec's roll, pitch and yaw.
    """
    kind = PRIMITIVE_OF_SHAPE.get(spec.shape)
    if kind is None:
        raise ValueError(f'obstacle {spec.name!r}: shape {spec.shape!r} has no Foxglove '
                         f'primitive; known: {", ".join(PRIMITIVE_OF_SHAPE)}')
    if position_m is None:
        position_m = tuple(spec.position_m)
    if orientation is None:
        orientation = quaternion_from_rpy(spec.roll_rad, spec.pitch_rad, spec.yaw_rad)
    primitive = Primitive(kind, tuple(position_m), tuple(orientation), tuple(spec.size_m),
                          tuple(spec.color_rgba))
    return Entity(f'obstacle/{spec.name}', WORLD_FRAME, (primitive,))


def obstacle_entities(scene) -> List[Entity]:
    """
    Return the obstacles of the scene (the entity source ``'obstacles'``).

    Static ones where the world file put them, movable ones (``mass`` > 0) where the physics
    has them now.
    """
    found = []
    for spec in scene.spec.obstacles:
        if spec.mass_kg > 0.0 and spec.name in scene.obstacles:
            (position, orientation), *_ = scene.world.body_state(scene.obstacles[spec.name])
            found.append(obstacle_entity(spec, tuple(position), tuple(orientation)))
        else:
            found.append(obstacle_entity(spec))
    return found


# ------------------------------------------------------------------------------ traffic

def traffic_entities(scene) -> List[Entity]:
    """
    Return the traffic bodies on the map (the entity source ``'traffic'``), each its shape.

    The traffic scene part (``scene.parts['traffic']``, the traffic-body contract of
    physics/traffic_bodies.py) gives each body's shape (a box, a pedestrian's upright
    cylinder), size and colour; its pose is where the physics has the body now. A body that
    leaves the map is not returned (so it is deleted from the view).
    """
    traffic = getattr(scene, 'parts', {}).get('traffic')
    if traffic is None:
        return []
    found = []
    for name, body_id, size, colour, shape in traffic.boxes():
        (position, orientation), *_ = scene.world.body_state(body_id)
        found.append(Entity(f'traffic/{name}', WORLD_FRAME, (Primitive(
            PRIMITIVE_OF_SHAPE[shape], tuple(position), tuple(orientation), tuple(size),
            tuple(colour)),)))
    return found


# ------------------------------------------------------------------------------ the registry

EntitySource = Callable[[object], Iterable[Entity]]
ENTITY_SOURCES: Dict[str, EntitySource] = {}
# The names of the sources whose entities never change for one scene (drawn once per
# subscriber, not at every update).
STATIC_SOURCES: set = set()
# The names of the sources whose entities change now and then (traffic lights): called at every
# update, an entity is sent when it differs from what was sent last.
CHANGING_SOURCES: set = set()


def register_entity_source(name: str, source: EntitySource, *, static: bool = False,
                           on_change: bool = False) -> None:
    """
    Add an entity source under ``name`` (a map layer, lanes, traffic).

    :param source: ``source(scene)`` -> the entities now; a source whose scene has nothing of
        its kind returns none.
    :param static: True: its entities never change for one scene (a map, lanes): they are
        built once and sent when a client subscribes. False: called at every update (moving
        bodies); an id it gave before and no longer gives is deleted from the view.
    :param on_change: (not static) its entities are sent only when they differ from those sent
        last (and in full updates): lights that change colour now and then.
    :raises ValueError: for a name already registered, or static and on_change both.
    """
    if name in ENTITY_SOURCES:
        raise ValueError(f'entity source {name!r} is already registered; registered: '
                         f'{", ".join(ENTITY_SOURCES)}')
    if static and on_change:
        raise ValueError(f'entity source {name!r}: static or on_change, not both')
    ENTITY_SOURCES[name] = source
    if static:
        STATIC_SOURCES.add(name)
    if on_change:
        CHANGING_SOURCES.add(name)


def scene_entities(scene, sources: Optional[Iterable[str]] = None) -> List[Entity]:
    """
    Return the entities of every registered source (or of ``sources``), in registry order.

    :raises ValueError: for an unknown source name, or two entities of one id.
    """
    names = list(ENTITY_SOURCES) if sources is None else list(sources)
    found, seen = [], set()
    for name in names:
        if name not in ENTITY_SOURCES:
            raise ValueError(f'unknown entity source {name!r}; registered: '
                             f'{", ".join(ENTITY_SOURCES)}')
        for entity in ENTITY_SOURCES[name](scene):
            if entity.id in seen:
                raise ValueError(f'entity id {entity.id!r} given twice (source {name!r})')
            seen.add(entity.id)
            found.append(entity)
    return found


register_entity_source('vehicles', vehicle_entities)
register_entity_source('obstacles', obstacle_entities)
register_entity_source('traffic', traffic_entities)
register_entity_source('map', map_scene.wall_entities, static=True)
register_entity_source('lanes', map_scene.lane_entities, static=True)
register_entity_source('signals', map_scene.lamp_entities, on_change=True)
register_entity_source('radar_targets', radar_scene.radar_entities)
