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

from glob import glob
import os

from setuptools import find_namespace_packages, setup

package_name = 'vehicle_sim'


def _data(pattern):
    return [path for path in glob(pattern) if os.path.isfile(path)]


# Optional parts, each an extra that its error names when the package is missing. `test`
# installs all of them, so that every test runs on a fresh machine.
EXTRAS = {
    'plot': ['matplotlib'],                        # `vehicle-sim demo` and `scenario --plot`
    'maps': ['Pillow'],                            # occupancy-grid images (vehicle_sim/maps)
    'lanelet2': ['lanelet2'],                      # Lanelet2 .osm lane maps
    'ray': ['ray'],                                # sweeps on a Ray cluster (vehicle_sim/sweep)
    'foxglove': ['foxglove-sdk>=0.30,<0.31'],      # the live view (docs/foxglove.md)
    'gym': ['gymnasium>=1.0'],                     # vehicle_sim.gym (docs/gym.md)
    'multi': ['gymnasium>=1.0', 'pettingzoo>=1.24'],  # vehicle_sim.gym.multi (docs/gym.md)
    'record': ['mcap', 'zstandard', 'lz4'],        # MCAP recordings and their compressors
    # SUMO networks, netconvert (OpenDRIVE, OSM) and the SUMO traffic engine (docs/sumo.md):
    # libsumo in process, traci where libsumo cannot load.
    'sumo': ['eclipse-sumo>=1.20', 'libsumo>=1.20', 'sumolib>=1.20', 'traci>=1.20'],
    # the occupancy grid's ray march compiled (vehicle_sim/core/map/grid_rays_jit.py): used
    # when numba imports (docs/maps.md, "Walls"); 0.60 is its first release for NumPy 2
    'fast': ['numba>=0.60'],
}
# pyarrow: a sweep writes results.parquet when it imports. protobuf: the Foxglove scene tests
# decode a SceneUpdate with the schema its channel advertises.
EXTRAS['test'] = (['pytest', 'pytest-timeout', 'ruff', 'pyarrow', 'protobuf']
                  + sorted({req for reqs in EXTRAS.values() for req in reqs}))
# Learning (examples/train_highway.py, vehicle_sim/gym/scaled_inputs.py), not in `test`: PyTorch
# is large; `make learn` installs it from PyTorch's CPU wheel index (docs/learning.md). SuperSuit
# and PettingZoo: the crossing's 4 agents as one vector env (examples/train_crossing_shared.py).
EXTRAS['learn'] = ['gymnasium>=1.0', 'stable-baselines3>=2.3', 'torch>=2.3', 'matplotlib',
                   'pettingzoo>=1.24', 'supersuit>=3.11']
# Training on Ray (examples/train_highway_ray.py, docs/learning.md), not in `test`: RLlib
# (which pins its Gymnasium release) and PyTorch (a CPU build: docs/learning.md).
EXTRAS['learn-ray'] = ['ray[rllib]', 'torch>=2.3']
# Benchmark only, not in `test`: bench_gym.py and bench_traffic.py compare with highway-env.
EXTRAS['bench'] = ['gymnasium>=1.0', 'highway-env']


setup(
    name=package_name,
    version='0.1.0',
    # The interface definitions (vehicle_msgs_py/definitions/<package>/<msg|srv>/) are data
    # directories with importable names; listing them as namespace packages is how setuptools
    # wants such data shipped (no SetuptoolsDeprecationWarning 'Installing ... as data').
    packages=find_namespace_packages(
        include=['vehicle_sim', 'vehicle_sim.*', 'vehicle_msgs_py', 'vehicle_msgs_py.*'],
        exclude=['*.__pycache__']),
    package_data={'vehicle_msgs_py.definitions': ['*/msg/*.msg', '*/srv/*.srv']},
    data_files=[
        ('share/ament_index/resource_index/packages', ['resource/' + package_name]),
        ('share/' + package_name, ['package.xml']),
        ('share/' + package_name + '/launch', _data('launch/*.launch.py')),
        ('share/' + package_name + '/config', _data('config/*.yaml')),
        ('share/' + package_name + '/config/cars', _data('config/cars/*.yaml')),
        ('share/' + package_name + '/config/robots', _data('config/robots/*.yaml')),
        ('share/' + package_name + '/config/worlds', _data('config/worlds/*.yaml')),
        ('share/' + package_name + '/config/maps',
         _data('config/maps/*.yaml') + _data('config/maps/*.png')
         + _data('config/maps/*.osm') + _data('config/maps/*.net.xml')),
        ('share/' + package_name + '/config/rviz', _data('config/rviz/*.rviz')),
        ('share/' + package_name + '/config/foxglove', _data('config/foxglove/*.json')),
    ],
    install_requires=['setuptools', 'numpy', 'pybullet', 'PyYAML', 'cyclonedds==11.0.1',
                      'rosbags>=0.10'],
    extras_require=EXTRAS,
    zip_safe=True,
    maintainer='vehicle_sim maintainers',
    maintainer_email='maintainers@vehicle-sim.example.org',
    description='PyBullet car simulator with the Webots automobile API and ROS 2 nodes.',
    license='Apache-2.0',
    tests_require=['pytest'],
    entry_points={
        'console_scripts': [
            'vehicle-sim = vehicle_sim.tools.cli:main',
            'automobile = vehicle_sim.ros.automobile_node:main',
            'ackermann_to_differential = vehicle_sim.ros.bridge_node:main',
            'diff_robot = vehicle_sim.ros.diff_robot_node:main',
            'autoware_automobile = vehicle_sim.ros.autoware_automobile_node:main',
            'teleop = vehicle_sim.tools.cli:teleop_main',
        ],
        # Named after the module, so that '-p vehicle_sim.testing' and pytest_plugins =
        # ['vehicle_sim.testing'] find the installed plugin instead of registering it twice.
        'pytest11': ['vehicle_sim.testing = vehicle_sim.testing'],
        # Gymnasium releases that load environment plugins call this; importing
        # vehicle_sim.gym registers the same ids (vehicle_sim/gym/registration.py).
        'gymnasium.envs': ['vehicle_sim = vehicle_sim.gym.registration:register_envs'],
    },
)
