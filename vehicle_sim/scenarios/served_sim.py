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
The simulation a scenario runs in, served over ROS in the runner's process.

:class:`ServedSim` steps synchronously: the automobile node (cars; it owns the world and publishes
/clock) and a robot node per robot sharing that world (the first robot owns it when there is no
car). External controllers (subprocesses) and topic criteria need it. Its vehicles are
:class:`~vehicle_sim.scenarios.sim.VehicleHandle` as those of the plain
:class:`~vehicle_sim.scenarios.sim.LocalSim`.
"""

import os
import tempfile

import yaml

from vehicle_sim.physics.scene import build_scene
from vehicle_sim.scenarios.scene import map_walls
from vehicle_sim.scenarios.sim import VehicleHandle
from vehicle_sim.scenarios.yaml_lines import ScenarioError


class ServedSim:
    """
    The scenario's world served over ROS (synchronous, /clock each step).

    :param spec: ScenarioSpec.
    :param director: registered with the world once it exists (after the served vehicles: their
        commands of a step are those set before it).
    :param transport: the nodes' transport (None = VEHICLE_SIM_TRANSPORT).
    :param foxglove: (host, port) of the automobile node's live Foxglove view, or None.
    :param recorder: a Recorder (vehicle_sim.recording) tapping every node's publishers from
        its creation on, or None.
    """

    served = True

    def __init__(self, spec, director, seed, gui=False, transport=None, foxglove=None,
                 recorder=None):
        from vehicle_sim.ros.diff_robot_node import DiffRobotNode
        self.automobile = None
        self.robot_nodes = []
        self._temp = None
        self.vehicles = {}
        self.lanes = None               # the lane criteria's lane map (None: none)
        self.walls = ()                 # an occupancy map's walls (Footprints)
        step_ms = spec.time_step_ms

        def tapped(name, overrides):
            # The node, its publishers recorded before the node object wires them.
            if recorder is None:
                return None
            from vehicle_sim.transport import create_node
            node = create_node(name, parameter_overrides=overrides, transport=transport)
            try:
                node.tap_publishers(recorder.tap)
            except BaseException:
                node.shutdown()
                raise
            return node

        try:
            if foxglove is not None and not spec.world.vehicles:
                raise ScenarioError('--foxglove shows the automobile node: this scenario has '
                                    'no car')
            if spec.world.vehicles:
                from vehicle_sim.ros.automobile_node import AutomobileNode, NODE_NAME
                live_view = {} if foxglove is None else {
                    'foxglove_host': foxglove[0], 'foxglove': foxglove[1]}
                overrides = {'world': self._world_file(spec), 'synchronous': True,
                             'time_step_ms': step_ms, 'gui': gui, **live_view}
                self.automobile = AutomobileNode(transport=transport,
                                                 parameter_overrides=overrides,
                                                 node=tapped(NODE_NAME, overrides))
                world = self.automobile.world
                self.lanes = self.automobile.scene.lanes
                self.walls = map_walls(self.automobile.scene)
                for vehicle in spec.world.vehicles:
                    built = self.automobile.scene.vehicles[vehicle.name]
                    self.vehicles[vehicle.name] = VehicleHandle(
                        vehicle.name, built.body, built.car, sensors=vehicle.sensors)
            else:
                world = None
            for robot in spec.robots:
                overrides = {'robot': robot.model, 'x': robot.x_m, 'y': robot.y_m,
                             'yaw': robot.yaw_rad, 'synchronous': True,
                             'time_step_ms': step_ms, 'gui': gui and world is None,
                             'sensors': list(robot.sensors) or ['']}
                node = DiffRobotNode(world=world, transport=transport, node_name=robot.name,
                                     parameter_overrides=overrides,
                                     node=tapped(robot.name, overrides))
                self.robot_nodes.append(node)
                if world is None:
                    world = node.world
                    # the obstacles (no car: no vehicles) and the lane map
                    built_scene = build_scene(spec.world, world)
                    self.lanes, self.walls = built_scene.lanes, map_walls(built_scene)
                self.vehicles[robot.name] = VehicleHandle(robot.name, node.robot)
            self.world = world
            world.add_body(director)
        except BaseException:
            self.close()
            raise

    def _world_file(self, spec):
        if spec.world_file:
            return spec.world_file
        handle, path = tempfile.mkstemp(prefix='vehicle_sim_world_', suffix='.yaml')
        with os.fdopen(handle, 'w', encoding='utf-8') as stream:
            yaml.safe_dump(spec.world_data, stream)
        self._temp = path
        return path

    @property
    def traffic(self):
        """The world's traffic (physics TrafficBodies), or None."""
        if self.automobile is None:
            return None
        return self.automobile.scene.parts.get('traffic')

    @property
    def signals(self):
        """The world's signals (physics WorldSignals: ``controller``), or None."""
        if self.automobile is None:
            return None
        return self.automobile.scene.parts.get('signals')

    @property
    def live_view(self):
        """The automobile node's Foxglove LiveView (``foxglove``), or None."""
        return None if self.automobile is None else self.automobile.live_view

    @property
    def nodes(self):
        """The transport nodes to spin."""
        nodes = [self.automobile.node] if self.automobile is not None else []
        return nodes + [robot.node for robot in self.robot_nodes]

    def step(self):
        """Advance one basic step and publish (/clock, the vehicles' topics)."""
        if self.automobile is not None:
            time_s = self.automobile.step_once()
            for robot in self.robot_nodes:
                robot.publish_state()
            return time_s
        owner, *others = self.robot_nodes
        owner.step()          # owns the world: steps it and publishes /clock
        for robot in others:
            robot.publish_state()
        return self.world.time_s

    def spin(self):
        """Serve pending requests and messages of every node (non-blocking)."""
        for node in self.nodes:
            node.spin_once(0.0)

    def close(self):
        for robot in reversed(self.robot_nodes):
            robot.destroy()
        self.robot_nodes = []
        if self.automobile is not None:
            self.automobile.close()
            self.automobile = None
        if self._temp is not None:
            os.unlink(self._temp)
            self._temp = None
