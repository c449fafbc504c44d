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
A traffic engine the tests register: the builtin bodies, each vehicle of its own object class.

``classes`` (the engine's world-file key, a list) gives the class of each vehicle by index,
cycled; a pedestrian is a :data:`WALKER_M` (diameter, height) upright cylinder in its objects
and bodies' shapes (its physics body stays the builtin box: what reads the contract never sees
it). :func:`register_classes_engine` adds it under ``'classes'`` for one test (monkeypatch).
"""

from dataclasses import replace

from vehicle_sim.core.traffic import engines as traffic_engines
from vehicle_sim.core.traffic.objects import CLASS_SHAPES
from vehicle_sim.core.traffic.params import traffic_from_dict, traffic_markdown
from vehicle_sim.physics import traffic_bodies

ENGINE = 'classes'
WALKER_M = (0.5, 1.7)        # a pedestrian's diameter and height [m]


def _parse(data, source, check_model, base_dir=None):
    rest = {k: v for k, v in data.items() if k not in ('engine', 'classes')}
    spec = replace(traffic_from_dict(rest, source, check_model), engine=ENGINE)
    object.__setattr__(spec, 'classes', tuple(data.get('classes', ('car',))))
    return spec


class ClassedBodies:
    """The builtin bodies (every other call goes to them); vehicle ``i`` of ``classes[i % n]``."""

    def __init__(self, builtin, classes):
        self.builtin = builtin
        self.classes = classes

    def __getattr__(self, name):
        return getattr(self.builtin, name)

    def class_of(self, index):
        return self.classes[index % len(self.classes)]

    def objects(self):
        found = []
        for o in self.builtin.objects():
            object_class = self.class_of(o.index)
            if object_class == 'pedestrian':
                diameter, height = WALKER_M
                o = replace(o, length_m=diameter, width_m=diameter, height_m=height)
            found.append(replace(o, object_class=object_class))
        return tuple(found)

    def boxes(self):
        found = []
        indices = {v.name: v.index for v in self.builtin.manager.vehicles}
        for name, body_id, size, colour, _ in self.builtin.boxes():
            object_class = self.class_of(indices[name])
            if object_class == 'pedestrian':
                diameter, height = WALKER_M
                size = (diameter, diameter, height)
            found.append((name, body_id, size, colour, CLASS_SHAPES[object_class]))
        return found


def _build(part, world, spec, parts):
    return ClassedBodies(traffic_bodies.TrafficPart.build_builtin(part, world, spec, parts),
                         spec.traffic.classes)


def register_classes_engine(monkeypatch):
    """Register the engine ``'classes'`` (core and physics) for this test."""
    monkeypatch.setitem(traffic_engines.TRAFFIC_ENGINES, ENGINE, traffic_engines.TrafficEngine(
        ENGINE, _parse, traffic_markdown, 'builtin bodies of given object classes'))
    monkeypatch.setitem(traffic_bodies.TRAFFIC_BUILDERS, ENGINE, _build)
