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
A camera's segmentation and recognition: label and instance images, the visible objects.

The body mask of the camera's frame (physics/sensors/render.py) becomes, through the world's
body labels (physics/body_labels.py ``World.labels``), a semantic image (label id per pixel:
nothing drawn is ``none``, the camera's own vehicle ``ego``) and an instance image (object id
per pixel; 0 for stuff, nothing and the camera's own vehicle, which is no object of its own
camera).

Recognition (Webots' Recognition node): each instance id of the image whose label is one of the
camera's classes and which shows at least ``recognition_min_pixels`` pixels is an object; its
image box is that of its visible pixels (so a box half hidden behind another gets the box of
its visible half: Webots' occlusion from the rendered image). Its 3D box is that of its body:
the box, cylinder or sphere visual of a one-link body exactly (obstacles, traffic, persons),
otherwise (a vehicle of several links) the world-aligned box around its links. An object whose
centre is farther than ``recognition_max_range`` is dropped; of the rest,
``recognition_max_objects`` (-1: all) with the most pixels are kept, in id order.
"""

import math
from typing import Tuple

import numpy as np
import pybullet

from vehicle_sim.core.sensors.labels import LABEL_IDS, LABELS
from vehicle_sim.core.sensors.recognition import RecognitionObject

EGO = LABEL_IDS['ego']


def segment(world, frame, own_body_id) -> Tuple[np.ndarray, np.ndarray]:
    """
    Return the semantic (uint8) and instance (uint16) images of a frame rendered with its mask.

    :param world: the World (its body labels).
    :param frame: a physics Frame with ``bodies`` and ``links``.
    :param own_body_id: the camera's vehicle body: ``ego``, instance 0.
    """
    semantic, instance = world.labels.lookup(frame.bodies, frame.links)
    own = frame.bodies == own_body_id
    if own.any():
        semantic[own] = EGO
        instance[own] = 0
    return semantic, instance


def _image_boxes(instance):
    # {id: (u_min, v_min, u_max, v_max, pixels, first flat index)} of each id > 0, vectorised:
    # the object pixels sorted by id, then min / max per run of one id.
    flat = instance.ravel()
    at = np.flatnonzero(flat)
    if at.size == 0:
        return {}
    ids = flat[at]
    order = np.argsort(ids, kind='stable')
    ids, at = ids[order], at[order]
    starts = np.flatnonzero(np.r_[True, ids[1:] != ids[:-1]])
    width = instance.shape[1]
    rows, cols = at // width, at % width
    counts = np.diff(np.r_[starts, ids.size])
    boxes = zip(ids[starts].tolist(), np.minimum.reduceat(cols, starts).tolist(),
                np.minimum.reduceat(rows, starts).tolist(),
                np.maximum.reduceat(cols, starts).tolist(),
                np.maximum.reduceat(rows, starts).tolist(), counts.tolist(),
                at[starts].tolist())
    return {box[0]: box[1:] for box in boxes}


def body_box(client_id, body_id):
    """
    Return the 3D box of a body in the world: (centre (3,), rotation (3, 3), dimensions (3,)).

    One link with one box, cylinder or sphere visual (what the camera sees): that shape's box in
    its pose; otherwise the world-aligned box around every link's bounding box. (The visual,
    not the collision shape: Bullet does not report a placed body's collision shape.)
    """
    if pybullet.getNumJoints(body_id, physicsClientId=client_id) == 0:
        shapes = pybullet.getVisualShapeData(body_id, physicsClientId=client_id)
        if len(shapes) == 1:
            _, _, geometry, size, _, local_xyz, local_xyzw = shapes[0][:7]
            dimensions = _shape_dimensions(geometry, size)
            if dimensions is not None:
                xyz, xyzw = pybullet.getBasePositionAndOrientation(body_id,
                                                                   physicsClientId=client_id)
                centre, orientation = pybullet.multiplyTransforms(xyz, xyzw, local_xyz,
                                                                  local_xyzw)
                rotation = np.array(pybullet.getMatrixFromQuaternion(orientation)).reshape(3, 3)
                return np.array(centre), rotation, np.array(dimensions)
    links = range(-1, pybullet.getNumJoints(body_id, physicsClientId=client_id))
    boxes = np.array([pybullet.getAABB(body_id, link, physicsClientId=client_id)
                      for link in links])
    low, high = boxes[:, 0].min(axis=0), boxes[:, 1].max(axis=0)
    return (low + high) / 2.0, np.eye(3), high - low


def _shape_dimensions(geometry, size):
    # getVisualShapeData's dimensions: a box's full sizes, a cylinder's (length, radius), a
    # sphere's (radius, ...).
    if geometry == pybullet.GEOM_BOX:
        return size[:3]
    if geometry in (pybullet.GEOM_CYLINDER, pybullet.GEOM_CAPSULE):
        return (2.0 * size[1], 2.0 * size[1], size[0])
    if geometry == pybullet.GEOM_SPHERE:
        return (2.0 * size[0],) * 3
    return None


_CORNERS = np.array([[x, y, z] for x in (-0.5, 0.5) for y in (-0.5, 0.5) for z in (-0.5, 0.5)])


def _quaternion(rotation):
    # (x, y, z, w) of a rotation matrix
    w = math.sqrt(max(0.0, 1.0 + rotation[0, 0] + rotation[1, 1] + rotation[2, 2])) / 2.0
    x = math.copysign(math.sqrt(max(0.0, 1.0 + rotation[0, 0] - rotation[1, 1]
                                    - rotation[2, 2])) / 2.0, rotation[2, 1] - rotation[1, 2])
    y = math.copysign(math.sqrt(max(0.0, 1.0 - rotation[0, 0] + rotation[1, 1]
                                    - rotation[2, 2])) / 2.0, rotation[0, 2] - rotation[2, 0])
    z = math.copysign(math.sqrt(max(0.0, 1.0 - rotation[0, 0] - rotation[1, 1]
                                    + rotation[2, 2])) / 2.0, rotation[1, 0] - rotation[0, 1])
    return (x, y, z, w)


def recognise(world, spec, frame, semantic, instance, position, rotation):
    """
    Return the recognised objects of a segmented frame (RecognitionObject, in id order).

    :param world: the World.
    :param spec: the core CameraSpec (its recognition keys).
    :param frame: the physics Frame (its body mask).
    :param semantic: the frame's label image; ``instance``: its object image.
    :param position: the camera's position in the world; ``rotation``: its axes (columns).
    """
    classes = {LABEL_IDS[name] for name in spec.recognition_classes}
    bodies = frame.bodies.ravel()
    labels = semantic.ravel()
    found = []
    for object_id, (u0, v0, u1, v1, pixels, first) in _image_boxes(instance).items():
        label = int(labels[first])
        if pixels < spec.recognition_min_pixels or label not in classes:
            continue
        centre, axes, dimensions = body_box(world.client_id, int(bodies[first]))
        local = rotation.T @ (centre - position)
        if float(np.linalg.norm(local)) > spec.recognition_max_range_m:
            continue
        in_camera = rotation.T @ axes
        corners = (_CORNERS * dimensions) @ in_camera.T
        size = corners.max(axis=0) - corners.min(axis=0)
        found.append(RecognitionObject(
            object_id, label, LABELS[label].name, tuple(local.tolist()),
            _quaternion(in_camera), tuple(float(d) for d in dimensions),
            (float(size[1]), float(size[2])), (u0, v0, u1, v1), pixels,
            tuple(c / 255.0 for c in LABELS[label].colour)))
    limit = spec.recognition_max_objects
    if 0 <= limit < len(found):
        found = sorted(found, key=lambda o: -o.pixels)[:limit]
    return tuple(sorted(found, key=lambda o: o.id))
