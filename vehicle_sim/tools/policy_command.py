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
``vehicle-sim policy run|evaluate``: a trained policy drives the automobile node.

``run MODEL.zip`` loads the model and its card, checks the model against the card's environment
and runs the policy driver node (ros/policy_node.py) on a running automobile node's car.
``evaluate MODEL.zip`` runs a scenario (default: scenarios/highway_policy.yaml) for N seeds
twice: in process (the Gym environment with the scenario) and over the wire (the scenario
runner serving the world, ``policy run`` as its process, in lockstep), with the same traffic per
seed on both paths, and prints both success rates.
"""

from dataclasses import replace
import os
import sys
import time

from vehicle_sim.core.specs.errors import InvalidParameterError
from vehicle_sim.core.traffic.params import OBJECTS_RATE
from vehicle_sim.tools.command import CliError, EXIT_FAILURE, EXIT_OK, EXIT_USAGE

DEFAULT_SCENARIO = 'highway_policy.yaml'
ACTION_TOPIC_TYPE = 'std_msgs/msg/Float64MultiArray'


def add_arguments(parser):
    """Add the ``policy`` sub-commands to its sub-parser."""
    sub = parser.add_subparsers(dest='policy_command', metavar='ACTION')
    sub.required = True
    run = sub.add_parser('run', help="drive a running automobile node's car with a policy",
                         description='Drive a car of a running automobile node with a trained '
                                     'policy (its card beside it: MODEL.card.json), at the '
                                     "policy's rate on /clock. Arguments after -- are ROS "
                                     'arguments.')
    _model_arguments(run)
    run.add_argument('--namespace', default='', metavar='NS',
                     help="the car's namespace (default: the default car, none)")
    run.add_argument('--rate', type=float, metavar='HZ',
                     help="act at this rate instead of the card's (1 / (action_repeat x "
                          'time_step)); a whole number of basic steps per action')
    run.add_argument('--objects-rate', type=float, metavar='HZ',
                     help="the rate the automobile node publishes the objects at (its "
                          "objects_rate, or the world's traffic: objects_rate; default "
                          f'{OBJECTS_RATE.default:g} Hz)')
    run.add_argument('--timeout', type=float, default=30.0, metavar='S',
                     help='wall-clock bound on the services and on the topics of each tick '
                          '(default 30 s)')
    run.add_argument('ros_args', nargs='*', help='ROS arguments after --')
    run.set_defaults(func=cmd_policy_run)
    evaluate = sub.add_parser(
        'evaluate', help='success rates in process and over ROS on the same seeds',
        description='Run a scenario for N seeds in process (the Gym environment) and over the '
                    'wire (vehicle-sim scenario with policy run as its process, lockstep), the '
                    'same traffic per seed on both; print both success rates.')
    _model_arguments(evaluate)
    evaluate.add_argument('--scenario', metavar='FILE',
                          help='the evaluation (default: scenarios/highway_policy.yaml)')
    evaluate.add_argument('--episodes', type=int, default=10, metavar='N',
                          help='episodes per path (default 10)')
    evaluate.add_argument('--first-seed', type=int, default=1000, metavar='S',
                          help='seeds S .. S+N-1 (default 1000: not training seeds)')
    evaluate.add_argument('--only', choices=('in-process', 'wire'),
                          help='run one path only')
    evaluate.set_defaults(func=cmd_policy_evaluate)


def _model_arguments(parser):
    parser.add_argument('model', metavar='MODEL.zip',
                        help='a stable-baselines3 model file or an RLlib checkpoint folder, '
                             'its card beside it')
    parser.add_argument('--algorithm', default='PPO', metavar='ALGO',
                        help="a model file's stable-baselines3 class (default PPO; an RLlib "
                             'checkpoint says its own)')


def load_policy(path, algorithm='PPO', rate_hz=None):
    """
    Return (card, model, DriveSetup) of a model file.

    :raises CliError: (exit 2) a missing or malformed card or model, a model of another space.
    """
    from vehicle_sim.gym.policy_card import load_card
    from vehicle_sim.tools.policy_loader import drive_setup, load_model
    try:
        card = load_card(path)
        model = load_model(path, algorithm)
        return card, model, drive_setup(card, model, rate_hz, source=str(path))
    except InvalidParameterError as error:
        raise CliError(str(error), EXIT_USAGE) from None


def make_driver(model, setup, namespace='', timeout_s=None, args=None, transport=None,
                objects_rate_hz=None):
    """Return the PolicyNode of a policy and its DriveSetup (built, services found)."""
    from vehicle_sim.ros.policy_actions import ActionWriter
    from vehicle_sim.ros.policy_node import PolicyNode
    from vehicle_sim.ros.policy_observation import ObservationBuilder
    builder = ObservationBuilder(setup.keys, setup.objects_spec)
    writer = ActionWriter(setup.control, setup.low, setup.high, setup.action_range,
                          setup.steering_bounds, setup.objects_spec)
    return PolicyNode(model, builder, writer, setup.period_s, namespace, timeout_s, args=args,
                      transport=transport, objects_rate_hz=objects_rate_hz or
                      OBJECTS_RATE.default)


def cmd_policy_run(args) -> int:
    """Run ``vehicle-sim policy run``."""
    from vehicle_sim.transport import run_node
    if not args.timeout > 0.0:
        raise CliError(f'--timeout {args.timeout!r}: must be > 0 [s]', EXIT_USAGE)
    _, model, setup = load_policy(args.model, args.algorithm, args.rate)
    holder = {}

    def factory(argv):
        holder['driver'] = make_driver(model, setup, args.namespace, args.timeout, argv,
                                       objects_rate_hz=args.objects_rate)
        return holder['driver'].node

    try:
        status = run_node(factory, ['vehicle-sim'] + list(args.ros_args))
    except InvalidParameterError as error:
        raise CliError(str(error), EXIT_FAILURE) from None
    driver = holder.get('driver')
    if driver is not None and driver.error is not None:
        raise CliError(driver.error, EXIT_FAILURE)
    return status


# ------------------------------------------------------------------------------ evaluate
def scenario_path(path=None):
    """Return the evaluation scenario's path (default: the shipped highway_policy.yaml)."""
    if path:
        return path
    here = os.path.dirname(os.path.abspath(__file__))
    for folder in (os.path.join(here, '..', '..', 'scenarios'),
                   os.path.join(sys.prefix, 'share', 'vehicle_sim', 'scenarios')):
        candidate = os.path.normpath(os.path.join(folder, DEFAULT_SCENARIO))
        if os.path.isfile(candidate):
            return candidate
    raise CliError(f'{DEFAULT_SCENARIO}: not found; give --scenario FILE', EXIT_USAGE)


def in_process_episode(card, model, scenario, seed):
    """
    Run one episode of ``scenario`` in process; return (passed, detail).

    The card's environment with the scenario instead of its world, reset with ``seed``.
    """
    from vehicle_sim.gym.policy_card import make_env
    env = make_env(card, world=None, scenario=scenario, max_episode_s=None)
    try:
        obs, _ = env.reset(seed=seed)
        terminated = truncated = False
        while not (terminated or truncated):
            action, _ = model.predict(obs, deterministic=True)
            obs, _, terminated, truncated, _ = env.step(action)
        results = list(env.unwrapped.sim.criteria_results().values())
    finally:
        env.close()
    return _verdict(results)


def _verdict(results):
    failed = [r for r in results if not r.passed]
    detail = '; '.join(f'{r.name}: {r.detail}' for r in failed) or 'every criterion passed'
    return bool(results) and not failed, detail


def wire_spec(spec, model_path, seed, setup, timeout_s=30.0):
    """
    Return the scenario ``spec`` driven over ROS by ``policy run`` with seed ``seed``'s traffic.

    The driver becomes the policy process (lockstep on its ``policy/action``, on the node's
    answer grid: ros/policy_node.py ``answer_period_s``);
    the world's ``traffic: seed`` becomes the traffic seed of the Gym environment's
    ``reset(seed=seed)``, so both paths start the same traffic.
    """
    from vehicle_sim.config import read_yaml
    from vehicle_sim.gym.drive_sim import episode_traffic_seed
    from vehicle_sim.ros.policy_node import answer_period_s
    from vehicle_sim.ros.policy_observation import OBJECTS
    from vehicle_sim.scenarios.driver_schema import DriverSpec
    world = spec.world
    if world.traffic is None:
        traffic_seed = None
        data = spec.world_data
    else:
        traffic_seed = episode_traffic_seed(seed)
        data = dict(spec.world_data if spec.world_data is not None
                    else read_yaml(spec.world_file))
        data['traffic'] = dict(data['traffic'], seed=traffic_seed)
        world = replace(world, traffic=replace(world.traffic, seed=traffic_seed))
    command = ('python', '-m', 'vehicle_sim', 'policy', 'run', os.path.abspath(model_path),
               '--timeout', f'{timeout_s:g}')
    rate = getattr(world.traffic, 'objects_rate_hz', None)
    if rate is not None:
        command += ('--objects-rate', f'{rate!r}')
    grid_s = answer_period_s(setup.period_s, rate or OBJECTS_RATE.default,
                             OBJECTS in setup.keys)
    driver = DriverSpec('processes', processes=(command,), real_time_factor=0.0,
                        clock_subscribers=1, startup_timeout_s=900.0,
                        sync=(('/policy/action', ACTION_TOPIC_TYPE, 1),), sync_period_s=grid_s,
                        sync_timeout_s=timeout_s)
    return replace(spec, world=world, world_file=None if data is not None else spec.world_file,
                   world_data=data, driver=driver, seed=int(seed))


def wire_episode(spec, model_path, seed, setup):
    """Run one episode of ``spec`` over the wire; return (passed, detail)."""
    from vehicle_sim.scenarios.runner import run_scenario
    result = run_scenario(wire_spec(spec, model_path, seed, setup))
    if result.error:
        return False, f'run error: {result.error.splitlines()[0]}'
    return _verdict(result.criteria)


def cmd_policy_evaluate(args) -> int:
    """Run ``vehicle-sim policy evaluate``: both success rates on the same seeds."""
    from vehicle_sim.scenarios.schema import load_scenario
    from vehicle_sim.scenarios.yaml_lines import ScenarioError
    if not 1 <= args.episodes <= 10000:
        raise CliError(f'--episodes {args.episodes}: must be 1 .. 10000', EXIT_USAGE)
    if args.first_seed < 0:
        raise CliError(f'--first-seed {args.first_seed}: must be >= 0', EXIT_USAGE)
    path = scenario_path(args.scenario)
    try:
        spec = load_scenario(path)
    except ScenarioError as error:
        raise CliError(str(error), EXIT_USAGE) from None
    card, model, setup = load_policy(args.model, args.algorithm)
    seeds = range(args.first_seed, args.first_seed + args.episodes)
    paths = [('in-process', lambda s: in_process_episode(card, model, spec, s)),
             ('wire', lambda s: wire_episode(spec, args.model, s, setup))]
    paths = [(name, run) for name, run in paths if not args.only or args.only == name]
    passed = {name: 0 for name, _ in paths}
    start = time.monotonic()
    # seed by seed, both paths: a run cut short still compares the same seeds
    for index, seed in enumerate(seeds):
        for name, run in paths:
            ok, detail = run(seed)
            passed[name] += ok
            print(f'{name} seed {seed}: {"PASS" if ok else "FAIL"} ({detail})', flush=True)
        print(f'after {index + 1} seeds ({time.monotonic() - start:.0f} s): ' + ', '.join(
            f'{name} {passed[name]}/{index + 1}' for name, _ in paths), flush=True)
    rates = {name: count / len(seeds) for name, count in passed.items()}
    print(f'model {args.model}, scenario {path}, seeds {seeds.start}..{seeds.stop - 1} '
          f'(N = {len(seeds)})')
    for name, rate in rates.items():
        print(f'  {name:10s} success rate {100.0 * rate:5.1f} %')
    if len(rates) == 2:
        gap = 100.0 * abs(rates['in-process'] - rates['wire'])
        print(f'  difference {gap:.1f} points')
    return EXIT_OK if rates else EXIT_FAILURE
