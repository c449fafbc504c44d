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
What each Bullet body is, for perception ground truth: a label and an instance id per body.

Every place that creates a body the sensors can see registers it here (``World.labels``): the
ground, the map's walls, the lane layer's road, markings, sidewalks and crosswalks, signal
poles and lamps, obstacles, vehicle bodies and traffic bodies. A body never registered reads as
``obstacle`` with instance 0 (a sensor never shows an unlabelled body as nothing).

Instance ids are the objects' ids everywhere: the pixel value of the instance image, a
labelled lidar point's ``instance``, a recognition object's id, a radar target's, and the
PredictedObjects object id (its UUID is the instance id as a 128-bit big-endian integer:
:func:`instance_uuid`). They are integers 1..65535 (0 = no object: stuff like road and walls),
handed out per world by :meth:`BodyLabels.instance` in the order objects first appear, one per
name for the world's life, so a world built and run twice with the same seed gives the same
ids. After 65535 names they start again from 1 (documented wrap; a SUMO city of hours).

A camera's segmentation mask and Bullet's ray tests give a body id (and a link index for a
multi-link body); :meth:`BodyLabels.lookup` turns arrays of them into label and instance arrays.
What is drawn flat on the ground (the lane layer's visual meshes, which rays pass) is looked up
by position: :meth:`BodyLabels.ground_labels` (a ray that met the ground plane on a road reads
``road``).
"""

from typing import Dict, Optional, Tuple
import uuid

import numpy as np

from vehicle_sim.core.sensors.labels import LABEL_IDS

MAX_INSTANCE = 65535
UNLABELLED = LABEL_IDS['obstacle']


def instance_uuid(instance_id: int) -> bytes:
    """Return the 16 bytes of an object's UUID (unique_identifier_msgs/UUID) from its id."""
    return uuid.UUID(int=int(instance_id)).bytes


class BodyLabels:
    """The label and instance id of every labelled body of one world."""

    def __init__(self):
        self._bodies: Dict[int, Tuple[int, int]] = {}          # body -> (label, instance)
        self._links: Dict[Tuple[int, int], Tuple[int, int]] = {}   # (body, link) -> ...
        self._instances: Dict[str, int] = {}
        self._next_instance = 1
        self._table: Optional[np.ndarray] = None               # body id -> (label, instance)
        self._surfaces = []                                    # drawn on the ground (rasters)

    def instance(self, name: str) -> int:
        """Return the instance id of the object ``name``, handing out the next on first use."""
        found = self._instances.get(name)
        if found is None:
            found = self._instances[name] = self._next_instance
            self._next_instance = self._next_instance % MAX_INSTANCE + 1
        return found

    def set(self, body_id: int, label: str, instance_id: int = 0, link: Optional[int] = None):
        """
        Label a body (or one link of it: ``link`` >= 0; -1 is the base).

        :raises ValueError: for a label not in core/sensors/labels.py LABELS, or an instance id
            outside 0..65535.
        """
        if label not in LABEL_IDS:
            raise ValueError(f'label {label!r} is not in the label table; valid: '
                             + ', '.join(LABEL_IDS))
        if not 0 <= int(instance_id) <= MAX_INSTANCE:
            raise ValueError(f'instance id {instance_id!r}: must be in 0..{MAX_INSTANCE}')
        value = (LABEL_IDS[label], int(instance_id))
        if link is None:
            self._bodies[int(body_id)] = value
        else:
            self._links[(int(body_id), int(link))] = value
        self._table = None

    def forget(self, body_id: int):
        """Drop a removed body's labels."""
        self._bodies.pop(int(body_id), None)
        for key in [key for key in self._links if key[0] == int(body_id)]:
            del self._links[key]
        self._table = None

    def add_surface(self, surface):
        """
        Add what is drawn on the ground plane (the lane layer's road, paint and areas).

        :param surface: an object with ``labels_at(x, y)`` -> label ids (0: nothing drawn),
            core/map/surface_raster.py's SurfaceRaster.
        """
        self._surfaces.append(surface)

    @property
    def has_surfaces(self) -> bool:
        """Whether something is drawn on the ground (:meth:`ground_labels` differ)."""
        return bool(self._surfaces)

    def ground_labels(self, x_m, y_m) -> np.ndarray:
        """
        Return the label ids (uint8) of the ground plane at points: what is drawn there.

        The last surface added that draws something at a point wins; ``ground`` where none does
        (a ray passes the drawn meshes and meets the ground plane under them).
        """
        found = np.full(np.shape(x_m), LABEL_IDS['ground'], dtype=np.uint8)
        for surface in self._surfaces:
            drawn = surface.labels_at(x_m, y_m)
            found = np.where(drawn > 0, drawn, found)
        return found

    @property
    def has_links(self) -> bool:
        """Whether any link has a label of its own (else a body's links read as the body)."""
        return bool(self._links)

    def of(self, body_id: int, link: int = -1) -> Tuple[int, int]:
        """Return (label id, instance id) of a body's link; unlabelled: (obstacle, 0)."""
        found = self._links.get((int(body_id), int(link)))
        if found is None:
            found = self._bodies.get(int(body_id), (UNLABELLED, 0))
        return found

    def lookup(self, body_ids, links=None) -> Tuple[np.ndarray, np.ndarray]:
        """
        Return the label ids (uint8) and instance ids (uint16) of arrays of body ids.

        :param body_ids: int array; negative = nothing hit (label none, instance 0).
        :param links: the link indices beside them (-1 = base), or None: the bodies' labels.
        """
        body_ids = np.asarray(body_ids, dtype=np.int64)
        table = self._lookup_table()
        hit = (body_ids >= 0) & (body_ids < len(table))
        index = np.where(hit, body_ids, 0)
        labels = np.where(hit, table[index, 0], 0).astype(np.uint8)
        instances = np.where(hit, table[index, 1], 0).astype(np.uint16)
        labels[(body_ids >= len(table))] = UNLABELLED
        if links is not None and self._links:
            links = np.asarray(links, dtype=np.int64)
            for (body, link), (label, instance) in self._links.items():
                at = (body_ids == body) & (links == link)
                labels[at] = label
                instances[at] = instance
        return labels, instances

    def _lookup_table(self) -> np.ndarray:
        if self._table is None:
            size = max(self._bodies, default=-1) + 1
            table = np.zeros((size, 2), dtype=np.int64)
            table[:, 0] = UNLABELLED
            for body, value in self._bodies.items():
                table[body] = value
            self._table = table
        return self._table
