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


"""The scene's entities and transforms (:mod:`.scene`) as Foxglove's own messages."""

from typing import Iterable

from vehicle_sim.foxglove.entities import Entity, Lines, Transform, Triangles

# Entity primitive kind -> the SceneEntity field listing it.
_FIELD_OF_KIND = {'cube': 'cubes', 'cylinder': 'cylinders', 'sphere': 'spheres'}


def timestamp(messages, time_s: float):
    """Return a ``foxglove.Timestamp`` of a simulated time [s] (whole nanoseconds)."""
    total_ns = int(round(time_s * 1e9))
    return messages.Timestamp(sec=total_ns // 1_000_000_000, nsec=total_ns % 1_000_000_000)


def _vector(messages, xyz):
    return messages.Vector3(x=float(xyz[0]), y=float(xyz[1]), z=float(xyz[2]))


def _quaternion(messages, q):
    return messages.Quaternion(x=float(q[0]), y=float(q[1]), z=float(q[2]), w=float(q[3]))


def _color(messages, rgba):
    r, g, b, a = rgba
    return messages.Color(r=float(r), g=float(g), b=float(b), a=float(a))


def _points(messages, points):
    point = messages.Point3
    return [point(x=x, y=y, z=z) for x, y, z in points.tolist()]


def _identity_pose(messages):
    return messages.Pose(position=messages.Vector3(x=0.0, y=0.0, z=0.0),
                         orientation=messages.Quaternion(x=0.0, y=0.0, z=0.0, w=1.0))


def line_primitive(messages, lines: Lines):
    """Return a ``foxglove.LinePrimitive`` of :class:`~.entities.Lines` (world-size thickness)."""
    kind = {'line_strip': messages.LinePrimitiveLineType.LineStrip,
            'line_list': messages.LinePrimitiveLineType.LineList}[lines.kind]
    return messages.LinePrimitive(
        type=kind, pose=_identity_pose(messages), thickness=float(lines.thickness_m),
        scale_invariant=False, points=_points(messages, lines.points_m),
        color=_color(messages, lines.color_rgba))


def triangle_primitive(messages, triangles: Triangles):
    """Return a ``foxglove.TriangleListPrimitive`` (indexed) of :class:`~.entities.Triangles`."""
    return messages.TriangleListPrimitive(
        pose=_identity_pose(messages), points=_points(messages, triangles.points_m),
        color=_color(messages, triangles.color_rgba),
        indices=[int(i) for i in triangles.indices.reshape(-1).tolist()])


def scene_entity(messages, entity: Entity, stamp):
    """Return a ``foxglove.SceneEntity`` of an :class:`~.scene.Entity`."""
    shapes = {field: [] for field in _FIELD_OF_KIND.values()}
    for primitive in entity.primitives:
        kind = getattr(messages, {'cube': 'CubePrimitive', 'cylinder': 'CylinderPrimitive',
                                  'sphere': 'SpherePrimitive'}[primitive.kind])
        r, g, b, a = primitive.color_rgba
        extra = {'bottom_scale': 1.0, 'top_scale': 1.0} if primitive.kind == 'cylinder' else {}
        shapes[_FIELD_OF_KIND[primitive.kind]].append(kind(
            pose=messages.Pose(position=_vector(messages, primitive.position_m),
                               orientation=_quaternion(messages, primitive.orientation)),
            size=_vector(messages, primitive.size_m),
            color=messages.Color(r=float(r), g=float(g), b=float(b), a=float(a)), **extra))
    return messages.SceneEntity(
        timestamp=stamp, frame_id=entity.frame_id, id=entity.id, **shapes,
        lines=[line_primitive(messages, lines) for lines in entity.lines],
        triangles=[triangle_primitive(messages, tri) for tri in entity.triangles])


def scene_update(messages, entities: Iterable[Entity], time_s: float,
                 deleted_ids: Iterable[str] = ()):
    """
    Return a ``foxglove.SceneUpdate`` replacing every entity given (same ids replace).

    :param deleted_ids: ids of entities to remove (applied before the entities).
    """
    stamp = timestamp(messages, time_s)
    deletions = [messages.SceneEntityDeletion(
        timestamp=stamp, type=messages.SceneEntityDeletionType.MatchingId, id=entity_id)
        for entity_id in deleted_ids]
    return messages.SceneUpdate(deletions=deletions,
                                entities=[scene_entity(messages, entity, stamp)
                                          for entity in entities])


def frame_transforms(messages, transforms: Iterable[Transform], time_s: float):
    """Return a ``foxglove.FrameTransforms`` of the transforms given."""
    stamp = timestamp(messages, time_s)
    return messages.FrameTransforms(transforms=[messages.FrameTransform(
        timestamp=stamp, parent_frame_id=t.parent, child_frame_id=t.child,
        translation=_vector(messages, t.translation_m),
        rotation=_quaternion(messages, t.rotation)) for t in transforms])
