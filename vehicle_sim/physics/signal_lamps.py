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
Traffic lights in the physics world: lamps the cameras see in their group's state.

The scene part ``signal_lamps`` (physics/scene.py) of a world whose lane map has traffic light
groups with bulbs (``graph.rules``) draws what core/map/signal_lamps.py lays out:

- each bulb a lamp, a visual-only sphere body of its own (its colour changes alone);
- the housings, one visual-only mesh (a box behind each bulb);
- the poles of the lights that stand off every lane, solid: static triangle meshes named
  ``signal_lamps`` (``World.add_static``), so that lidars and distance sensors see them,
  collisions name them and a vehicle that starts inside one is refused. Housings and lamps
  are visual only (nothing hits a light's head; a light over a lane gets no pole).

The lamps show the state of the world's SignalController (``scene.parts['signals']
.controller``): a lamp is lit in its bulb's colour when the state is that colour, dark grey
otherwise. Their colours change only when a state changes (PyBullet's changeVisualShape, some
3 us a lamp): after each step (the GUI window) and before anything reads the world between
steps (``World.sync_bodies``: a camera image after a scenario forced a state). A world without
a controller shows every lamp dark ('off').
"""

from typing import Dict, Optional, Tuple

import pybullet

from vehicle_sim.core.map.signal_lamps import (
    box_mesh,
    HOUSING_COLOR,
    housing_corners,
    lamp_color,
    LAMP_RADIUS_M,
    lamps,
    POLE_COLOR,
    pole_corners,
    poles,
)
from vehicle_sim.physics.lane_layer import inside_boxes, solid_box_bodies, visual_bodies

LAMPS_BODY_NAME = 'signal_lamps'


class SignalLamps:
    """
    The lamps of a world's traffic lights, lit as its SignalController says (a world body).

    :param world: the World.
    :param graph: the lane map (a core LaneGraph with rules).
    :param controller: the world's SignalController, or None (every lamp dark).
    """

    def __init__(self, world, graph, controller=None):
        self.world = world
        self.controller = controller
        self.lamps = lamps(graph)
        self.poles = poles(graph, self.lamps)
        cid = self._cid = world.client_id
        self.housing_ids = visual_bodies(world, box_mesh(housing_corners(self.lamps)),
                                         HOUSING_COLOR)
        standing = pole_corners(self.poles)
        self.pole_ids = solid_box_bodies(world, standing, POLE_COLOR)
        if self.pole_ids:
            world.add_static(LAMPS_BODY_NAME, self.pole_ids, inside_boxes(standing))
        sphere = pybullet.createVisualShape(pybullet.GEOM_SPHERE, radius=LAMP_RADIUS_M,
                                            rgbaColor=list(lamp_color('red', 'off')),
                                            physicsClientId=cid)
        self.lamp_ids = tuple(pybullet.createMultiBody(
            0.0, -1, sphere, basePosition=[lamp.bulb.x_m, lamp.bulb.y_m, lamp.bulb.z_m],
            physicsClientId=cid) for lamp in self.lamps)
        self._by_group: Dict[int, Tuple[int, ...]] = {}
        for index, lamp in enumerate(self.lamps):
            self._by_group[lamp.group_id] = self._by_group.get(lamp.group_id, ()) + (index,)
        self.shown: Dict[int, str] = {group: 'off' for group in self._by_group}
        self.changes = 0            # lamp colours changed so far (changeVisualShape calls)
        self.refresh()
        if controller is not None:
            world.add_body(self)

    @property
    def visual_shape_count(self) -> int:
        """The bodies it added: one per lamp, the housings' and the poles' meshes."""
        return len(self.lamp_ids) + len(self.housing_ids) + len(self.pole_ids)

    def refresh(self) -> int:
        """Recolour the lamps of the groups whose state changed; return how many lamps."""
        if self.controller is None:
            return 0
        states = self.controller.states()
        shown = self.shown
        changed = 0
        for group, indices in self._by_group.items():
            state = states.get(group, 'off')
            if shown[group] == state:
                continue
            shown[group] = state
            for index in indices:
                pybullet.changeVisualShape(
                    self.lamp_ids[index], -1,
                    rgbaColor=list(lamp_color(self.lamps[index].bulb.color, state)),
                    physicsClientId=self._cid)
            changed += len(indices)
        self.changes += changed
        return changed

    def post_step(self):
        """World hook: the lamps follow the controller after each step (the GUI window)."""
        self.refresh()

    def before_query(self):
        """World hook (``World.sync_bodies``): the lamps as the controller says now."""
        self.refresh()

    def lamp_colors(self):
        """Return [(Lamp, RGBA now)] of every lamp, as drawn."""
        return [(lamp, lamp_color(lamp.bulb.color, self.shown[lamp.group_id]))
                for lamp in self.lamps]


class SignalLampsPart:
    """
    The scene part ``signal_lamps``: the lamps of the lane map's traffic light groups.

    :param controller: the SignalController to show; None = the world's (``parts['signals']``,
        the parts built before it).
    """

    name = 'signal_lamps'
    reads_parts = True          # build() takes the parts built before it

    def __init__(self, controller=None):
        self.controller = controller

    def build(self, world, spec, parts=None) -> Optional[SignalLamps]:
        if not wants_lamps(spec):
            return None
        controller = self.controller
        if controller is None:
            controller = getattr((parts or {}).get('signals'), 'controller', None)
        return SignalLamps(world, spec.lanes, controller)


def wants_lamps(spec) -> bool:
    """Return whether a WorldSpec's lane map has bulbs to draw."""
    graph = getattr(spec, 'lanes', None)
    return graph is not None and any(group.bulbs for group in graph.rules.groups)
