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
The label table of perception ground truth: what a pixel, a lidar point or a radar target is.

One row per class: its id (the value of a semantic image pixel and of a labelled point's
``label``), its name, its colour (the semantic image drawn in colour, the Foxglove view; the
Cityscapes palette where Cityscapes has the class) and its reflectivity (a labelled lidar point's
intensity before the incidence angle, a radar target's radar cross-section per square metre of
frontal area: typical values for asphalt, road paint, concrete, painted metal, skin and
clothing, not measurements). Id 0 is nothing: the sky, a ray without a return.

Physics bodies get their label and instance id from ``physics/body_labels.py``; traffic object
classes (core/traffic/objects.py) map to labels by :func:`label_of_class`. The camera's own
vehicle reads as ``ego`` in its images; other vehicles of the world as ``car``.
"""

from dataclasses import dataclass
from typing import Dict, Iterable, Tuple


@dataclass(frozen=True)
class Label:
    """One class of the label table."""

    id: int
    name: str
    colour: Tuple[int, int, int]
    reflectivity: float


LABELS: Tuple[Label, ...] = (
    Label(0, 'none', (0, 0, 0), 0.0),
    Label(1, 'road', (128, 64, 128), 0.10),
    Label(2, 'lane_marking', (157, 234, 50), 0.60),
    Label(3, 'sidewalk', (244, 35, 232), 0.20),
    Label(4, 'crosswalk', (200, 200, 240), 0.60),
    Label(5, 'wall', (70, 70, 70), 0.30),
    Label(6, 'obstacle', (190, 153, 153), 0.30),
    Label(7, 'car', (0, 0, 142), 0.50),
    Label(8, 'truck', (0, 0, 70), 0.50),
    Label(9, 'bus', (0, 60, 100), 0.50),
    Label(10, 'motorcycle', (0, 0, 230), 0.50),
    Label(11, 'bicycle', (119, 11, 32), 0.40),
    Label(12, 'pedestrian', (220, 20, 60), 0.25),
    Label(13, 'traffic_light', (250, 170, 30), 0.70),
    Label(14, 'ego', (255, 255, 255), 0.50),
    Label(15, 'ground', (81, 0, 81), 0.15),
)
LABEL_IDS: Dict[str, int] = {label.name: label.id for label in LABELS}
NONE = 0
assert [label.id for label in LABELS] == list(range(len(LABELS)))

# traffic object classes (core/traffic/objects.py OBJECT_CLASSES) -> their label
_CLASS_LABELS = {'car': 'car', 'truck': 'truck', 'bus': 'bus', 'trailer': 'truck',
                 'motorcycle': 'motorcycle', 'bicycle': 'bicycle', 'pedestrian': 'pedestrian'}


def label_of_class(object_class: str) -> int:
    """Return the label id of a traffic object class; 'obstacle' for a class it does not know."""
    return LABEL_IDS[_CLASS_LABELS.get(object_class, 'obstacle')]


def check_label_names(names: Iterable[str], source: str) -> Tuple[str, ...]:
    """
    Return ``names`` as a tuple when every one is a label of :data:`LABELS`.

    :param names: label names (a configuration's class list).
    :param source: what named them (a file and key), for the error.
    :raises ValueError: naming the first unknown name and the valid ones.
    """
    names = tuple(names)
    for name in names:
        if name not in LABEL_IDS:
            raise ValueError(f'{source}: {name!r} is not a label; valid: '
                             + ', '.join(LABEL_IDS))
    return names


def labels_markdown() -> str:
    """Return the label table as a markdown table (docs/sensors.md)."""
    rows = ['| id | label | colour (r, g, b) | reflectivity |', '|---|---|---|---|']
    rows += [f'| {label.id} | `{label.name}` | {label.colour} | {label.reflectivity:.2f} |'
             for label in LABELS]
    return '\n'.join(rows)
