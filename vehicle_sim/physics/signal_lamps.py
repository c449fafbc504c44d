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

- each bulb a lamp, a visual-only sphere body of its own (its colour changes alone; a sleeping
  rigid body), made the first time the world is drawn (``World.prepare_render``: a camera, the
  chase image) or at once with a GUI window. Rays pass the lamps, so a world that is never
  drawn needs none, and Bullet's step still walks over every body it has, asleep or not: about
  20 ns a body, 150 us a step for the 6 912 lamps of a city of 144 signalised junctions;
- the housings, one visual-only mesh (a box behind each bulb);
- the poles of the lights that stand off every lane, solid: a static box each, named
  ``signal_lamps`` (``World.add_static``), so that lidars and distance sensors see them,
  collisions name them and a vehicle that starts inside one is refused. Housings and lamps
  are visual only (nothing hits a light's head; a light over a lane gets no pole).

The lamps show the state of the world's SignalController (``scene.parts['signals']
.controller``): a lamp is lit in its bulb's colour when the state is that colour, dark grey
otherwise. Their colours change only when a state changes (PyBullet's changeVisualShape, some
1.5 us a lamp), when something looks: before anything reads the world (``World.sync_bodies``:
a camera image, also one right after a scenario forced a state) and, with a GUI window, after
each step; a step without a window pays nothing for them. A world without a controller shows
every lamp dark ('off').
"""

from typing import Dict, Optional, Tuple

import pybullet

from vehicle_sim.core.map.signal_lamps import (
    box_mesh,
    HOUSING_COLOR,
    housing_corners,
    lamp_color,
    lamp_mesh,
    lamps,
    lit,
    POLE_COLOR,
    pole_corners,
    POLE_WIDTH_M,
    poles,
)
from vehicle_sim.physics.lane_layer import (
    inside_boxes,
    visual_bodies,
    visual_body,
)

LAMPS_BODY_NAME = 'signal_lamps'


class SignalLamps:
    """
    The lamps of a world's traffic lights, lit as its SignalController says (a world body).

    :param world: the World.
    :param graph: the lane map (a core LaneGraph with rules).
    :param controller: the world's SignalController, or None: the one of ``parts``.
    :param parts: the scene's parts by name (``Scene.parts``, filled as they are built): the
        controller is ``parts['signals'].controller``, looked up when the lamps are first
        coloured after the build (a caller's own 'signals' part is built after the rows).
        Neither: every lamp stays dark ('off').
    """

    def __init__(self, world, graph, controller=None, parts=None):
        self.world = world
        self.controller = controller
        self._parts = parts
        self.lamps = lamps(graph)
        self.poles = poles(graph, self.lamps)
        self._cid = world.client_id
        self.housing_ids = visual_bodies(world, box_mesh(housing_corners(self.lamps)),
                                         HOUSING_COLOR)
        self.pole_ids = tuple(self._pole_body(pole) for pole in self.poles)
        if self.pole_ids:
            world.add_static(LAMPS_BODY_NAME, self.pole_ids, inside_boxes(
                pole_corners(self.poles)))
        for body_id in self.housing_ids + self.pole_ids:
            world.labels.set(body_id, 'traffic_light')
        self.lamp_ids: Tuple[int, ...] = ()     # made when first drawn (make_lamp_bodies)
        self._by_group: Dict[int, Tuple[int, ...]] = {}
        for index, lamp in enumerate(self.lamps):
            self._by_group[lamp.group_id] = self._by_group.get(lamp.group_id, ()) + (index,)
        self.shown: Dict[int, str] = {group: 'off' for group in self._by_group}
        self.changes = 0            # lamp colours changed so far (as the states changed)
        self._states = None         # every group's state when the lamps were last coloured
        self.refresh()
        world.add_body(self)        # before_render; the hooks below with a controller
        if world.gui:       # the window draws every frame: the lamps follow after each step
            self.make_lamp_bodies()
            if controller is not None or parts is not None:
                world.add_body(_AfterEachStep(self.refresh))

    def make_lamp_bodies(self) -> Tuple[int, ...]:
        """
        Make the lamps' bodies, in the colours shown now, if they are not made yet; return them.

        Only images show the lamps (rays pass them), so they are made the first time the world
        is drawn (``World.prepare_render``) or at once with a GUI window: a world that is never
        drawn does not pay Bullet's pass over each of them at every step (about 20 ns a body,
        150 us a step for a city of 144 signalised junctions).
        """
        if self.lamp_ids or not self.lamps:
            return self.lamp_ids
        world, cid = self.world, self._cid
        sphere = lamp_mesh()
        sphere = pybullet.createVisualShape(
            pybullet.GEOM_MESH, vertices=sphere.vertices.tolist(),
            indices=sphere.triangles.reshape(-1).tolist(),
            rgbaColor=list(lamp_color('red', 'off')), physicsClientId=cid)
        self.lamp_ids = tuple(visual_body(world, sphere, (lamp.bulb.x_m, lamp.bulb.y_m,
                                                          lamp.bulb.z_m)) for lamp in self.lamps)
        # a group's lamps are one object (recognition, instance images): its signal
        for lamp, body_id in zip(self.lamps, self.lamp_ids):
            world.labels.set(body_id, 'traffic_light',
                             world.labels.instance(f'traffic_light_{lamp.group_id}'))
        for group, indices in self._by_group.items():     # made dark: the lit ones lit
            state = self.shown[group]
            self._colour([i for i in indices if lit(self.lamps[i].bulb.color, state)], state)
        world.mark_redrawn()
        return self.lamp_ids

    def before_render(self):
        """World hook (``World.prepare_render``): the lamps made, in the states of now."""
        self.make_lamp_bodies()
        self.refresh()

    def _colour(self, indices, state):
        # The lamps ``indices`` in a group state's colours (nothing before they are made).
        if not self.lamp_ids:
            return
        for index in indices:
            pybullet.changeVisualShape(
                self.lamp_ids[index], -1,
                rgbaColor=list(lamp_color(self.lamps[index].bulb.color, state)),
                physicsClientId=self._cid)

    def _pole_body(self, pole) -> int:
        # A static box of its own (a small bounding box: a vehicle is near few poles), a
        # sleeping rigid body as the lamps (static: it still stops what drives into it).
        cid = self._cid
        half = [0.5 * POLE_WIDTH_M, 0.5 * POLE_WIDTH_M, 0.5 * pole.height_m]
        collision = pybullet.createCollisionShape(pybullet.GEOM_BOX, halfExtents=half,
                                                  physicsClientId=cid)
        visual = pybullet.createVisualShape(pybullet.GEOM_BOX, halfExtents=half,
                                            rgbaColor=list(POLE_COLOR), physicsClientId=cid)
        body_id = pybullet.createMultiBody(0.0, collision, visual,
                                           [pole.x_m, pole.y_m, 0.5 * pole.height_m],
                                           useMaximalCoordinates=True, physicsClientId=cid)
        pybullet.changeDynamics(body_id, -1, activationState=pybullet.ACTIVATION_STATE_SLEEP,
                                physicsClientId=cid)
        return body_id

    @property
    def visual_shape_count(self) -> int:
        """The bodies it added: one per lamp (once drawn) and per pole, the housings' mesh."""
        return len(self.lamp_ids) + len(self.housing_ids) + len(self.pole_ids)

    def refresh(self) -> int:
        """Recolour the lamps of the groups whose state changed; return how many lamps."""
        controller = self.controller
        if controller is None:
            if self._parts is None:
                return 0
            controller = self.controller = getattr(self._parts.get('signals'), 'controller',
                                                   None)
            if controller is None:
                return 0
        states = controller.states()
        if states == self._states:  # what nearly every step finds
            return 0
        self._states = states
        shown = self.shown
        changed = 0
        for group, indices in self._by_group.items():
            state = states.get(group, 'off')
            if shown[group] == state:
                continue
            shown[group] = state
            self._colour(indices, state)
            changed += len(indices)
        self.changes += changed
        if changed:
            self.world.mark_redrawn()      # renders of this step show the new colours
        return changed

    def before_query(self):
        """World hook (``World.sync_bodies``): the lamps as the controller says now."""
        self.refresh()

    def lamp_colors(self):
        """Return [(Lamp, RGBA now)] of every lamp, as drawn."""
        return [(lamp, lamp_color(lamp.bulb.color, self.shown[lamp.group_id]))
                for lamp in self.lamps]


class _AfterEachStep:
    """A world hook that calls ``call()`` after each step (``post_step``)."""

    def __init__(self, call):
        self.post_step = call


class SignalLampsPart:
    """
    The scene part ``signal_lamps``: the lamps of the lane map's traffic light groups.

    :param controller: the SignalController to show; None = the world's (``parts['signals']
        .controller`` of the scene's parts).
    """

    name = 'signal_lamps'
    reads_parts = True          # build() takes the scene's parts

    def __init__(self, controller=None):
        self.controller = controller

    def build(self, world, spec, parts=None) -> Optional[SignalLamps]:
        if not wants_lamps(spec):
            return None
        return SignalLamps(world, spec.lanes, self.controller,
                           None if self.controller is not None or parts is None else parts)


def wants_lamps(spec) -> bool:
    """Return whether a WorldSpec's lane map has bulbs to draw."""
    graph = getattr(spec, 'lanes', None)
    return graph is not None and any(group.bulbs for group in graph.rules.groups)
