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
What each scene update of the live view carries: :class:`SceneStream`, SDK-free.

Static sources (a map, lanes) are built once per scene and sent in full updates only: the first
one, and the one after a client subscribes (a SceneUpdate goes to every subscriber of the
channel; the others receive the same entities again, which replaces them with themselves).
Moving sources (vehicles, movable obstacles, traffic) are sent in every update; an id one of
them gave in the previous update and no longer gives (a traffic car gone) is deleted. The
entities of on-change sources (traffic lights) are sent in full updates and when they differ
from the ones sent last (a light changed colour); gone ones are deleted as moving ones are.
"""

from dataclasses import dataclass
from typing import List, Tuple

from vehicle_sim.foxglove import scene as scene_sources
from vehicle_sim.foxglove.entities import Entity


@dataclass(frozen=True)
class SceneFrame:
    """One update: the entities to add or replace, then the ids to delete."""

    entities: Tuple[Entity, ...]
    deleted_ids: Tuple[str, ...]


class SceneStream:
    """The updates of one live view, from the registered entity sources."""

    def __init__(self):
        self._scene = None
        self._static: List[Entity] = []
        self._moving_ids = set()
        self._sent = {}               # id -> the entity of an on-change source sent last

    def frame(self, scene, full: bool) -> SceneFrame:
        """
        Return the update of ``scene`` now.

        :param full: a client subscribed since the last update: the static entities too.
        :raises ValueError: an id given twice (within or across sources), an unknown source.
        """
        static_names = [n for n in scene_sources.ENTITY_SOURCES
                        if n in scene_sources.STATIC_SOURCES]
        changing_names = [n for n in scene_sources.ENTITY_SOURCES
                          if n in scene_sources.CHANGING_SOURCES]
        moving_names = [n for n in scene_sources.ENTITY_SOURCES
                        if n not in scene_sources.STATIC_SOURCES
                        and n not in scene_sources.CHANGING_SOURCES]
        deleted = set()
        if scene is not self._scene:
            previous = {entity.id for entity in self._static} | self._moving_ids
            self._static = scene_sources.scene_entities(scene, static_names)
            self._scene, full = scene, True
            deleted = previous - {entity.id for entity in self._static}
        moving = scene_sources.scene_entities(scene, moving_names)
        changing = scene_sources.scene_entities(scene, changing_names)
        changed = [entity for entity in changing
                   if full or self._sent.get(entity.id) != entity]
        self._sent = {entity.id: entity for entity in changing}
        moving_ids = {entity.id for entity in moving}
        twice = moving_ids & set(self._sent)
        if twice:
            raise ValueError(f'entity id {sorted(twice)[0]!r} given by a moving and an '
                             'on-change source')
        moving_ids |= set(self._sent)
        static_ids = {entity.id for entity in self._static}
        both = moving_ids & static_ids
        if both:
            raise ValueError(f'entity id {sorted(both)[0]!r} given by a static and a moving '
                             'source')
        deleted |= self._moving_ids - moving_ids
        deleted -= moving_ids | static_ids
        self._moving_ids = moving_ids
        moving = tuple(moving) + tuple(changed)
        entities = tuple(self._static) + moving if full else moving
        return SceneFrame(entities, tuple(sorted(deleted)))
