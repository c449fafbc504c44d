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

from vehicle_sim.foxglove.scene import Entity, Transform

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
    return messages.SceneEntity(timestamp=stamp, frame_id=entity.frame_id, id=entity.id,
                                **shapes)


def scene_update(messages, entities: Iterable[Entity], time_s: float):
    """Return a ``foxglove.SceneUpdate`` replacing every entity given (same ids replace)."""
    stamp = timestamp(messages, time_s)
    return messages.SceneUpdate(entities=[scene_entity(messages, entity, stamp)
                                          for entity in entities])


def frame_transforms(messages, transforms: Iterable[Transform], time_s: float):
    """Return a ``foxglove.FrameTransforms`` of the transforms given."""
    stamp = timestamp(messages, time_s)
    return messages.FrameTransforms(transforms=[messages.FrameTransform(
        timestamp=stamp, parent_frame_id=t.parent, child_frame_id=t.child,
        translation=_vector(messages, t.translation_m),
        rotation=_quaternion(messages, t.rotation)) for t in transforms])
