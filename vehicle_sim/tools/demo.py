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
``vehicle-sim demo``: run the end-to-end scenario and plot it (docs/end_to_end.md).

Writes a PNG (matplotlib, Agg backend): the robots' and the car's ground-truth paths with their
bicycle references, and their wheel speeds over time; prints where it wrote it and the path
errors. The nodes are real DDS nodes driven in-process; the demo keeps them off the network
(``ROS_AUTOMATIC_DISCOVERY_RANGE=OFF``) unless the variable is already set.
"""

import argparse
import os
import sys

DEFAULT_OUT = 'vehicle_sim_demo.png'
_COLOURS = {'caster_robot': 'tab:blue', 'skid_steer_robot': 'tab:orange'}


def plot(result, out_path):
    """
    Write the figure of an EndToEndResult to ``out_path`` (PNG).

    :return: out_path.
    """
    import matplotlib
    matplotlib.use('Agg')
    from matplotlib import pyplot as plt

    fig, axes = plt.subplots(2, 2, figsize=(14, 10))
    (ax_robot_path, ax_car_path), (ax_robot_wheels, ax_car_wheels) = axes
    for name, track in result.robots.items():
        colour = _COLOURS.get(name, None)
        x0, y0, _ = track.pose[0]
        ax_robot_path.plot([p[0] - x0 for p in track.pose], [p[1] - y0 for p in track.pose],
                           color=colour, label=f'{name} (ground truth)')
        ax_robot_path.plot([p[0] - x0 for p in track.reference],
                           [p[1] - y0 for p in track.reference], '--', color=colour,
                           label=f'{name} bicycle reference (L = {track.wheel_base_m:g} m)')
        # L = tread for both robots, so their wheel commands coincide: the first robot is drawn
        # wide and pale underneath so both stay visible
        width, alpha = (4.0, 0.4) if name == next(iter(result.robots)) else (1.5, 1.0)
        for side, style in ((0, '-'), (1, ':')):
            ax_robot_wheels.plot(track.wheel_time_s, [w[side] for w in track.wheel_speeds],
                                 style, color=colour, linewidth=width, alpha=alpha,
                                 label=f'{name} {track.wheel_labels[side]}')
    ax_robot_path.set_title('Robots through the Ackermann→differential bridge '
                            '(start at origin)')
    ax_robot_wheels.set_title('Robot wheel speeds (measured, tyre surface)')
    ax_robot_wheels.set_ylabel('m/s')
    car = result.car
    if car is not None:
        x0, y0, _ = car.pose[0]
        ax_car_path.plot([p[0] - x0 for p in car.pose], [p[1] - y0 for p in car.pose],
                         color='tab:green', label=f'{car.name} (ground truth)')
        ax_car_path.plot([p[0] - x0 for p in car.reference], [p[1] - y0 for p in car.reference],
                         '--', color='black',
                         label=f'bicycle reference (L = {car.wheel_base_m:g} m)')
        for index, label in enumerate(car.wheel_labels):
            ax_car_wheels.plot(car.wheel_time_s, [w[index] for w in car.wheel_speeds],
                               label=label)
        ax_car_path.set_title(f'{car.name} through autoware_automobile (start at origin)')
        ax_car_wheels.set_title(f'{car.name} wheel speeds (Webots wheel speed)')
        ax_car_wheels.set_ylabel('rad/s')
    for ax in (ax_robot_path, ax_car_path):
        ax.set_xlabel('x [m]')
        ax.set_ylabel('y [m]')
        ax.set_aspect('equal', adjustable='datalim')
    stream = result.robot_stream
    for ax in (ax_robot_wheels, ax_car_wheels):
        ax.set_xlabel('simulated time [s]')
        start = 0.0
        for segment in stream.segments:
            ax.axvline(start, color='grey', linewidth=0.5)
            ax.text(start + 0.1, 0.98, segment.name, transform=ax.get_xaxis_transform(),
                    va='top', fontsize=8, color='grey')
            start += segment.duration_s
    for ax in axes.flat:
        ax.grid(True, alpha=0.3)
        ax.legend(fontsize=8, loc='lower center' if ax in (ax_robot_wheels, ax_car_wheels)
                  else 'best')
    fig.suptitle('vehicle_sim end to end: Autoware command stream (straight, arc, S-curve, '
                 'silence, stop)')
    fig.tight_layout()
    fig.savefig(out_path, dpi=100)
    plt.close(fig)
    return out_path


def run_demo(out_path=DEFAULT_OUT, car_model=None, short=False, stream=None):
    """
    Run the scenario, write the PNG and print the errors.

    :param out_path: PNG path.
    :param car_model: car preset (default: end_to_end.DEFAULT_CAR).
    :param short: run the short variant (half-length segments).
    :return: (EndToEndResult, out_path).
    """
    stream = sys.stdout if stream is None else stream   # the stdout of the call, not of import
    os.environ.setdefault('ROS_AUTOMATIC_DISCOVERY_RANGE', 'OFF')
    from vehicle_sim.tools import end_to_end
    result = end_to_end.run_scenario(car_model=car_model or end_to_end.DEFAULT_CAR,
                                     scale=0.5 if short else 1.0)
    plot(result, out_path)
    for line in end_to_end.summary(result):
        print(line, file=stream)
    print(f'wrote {os.path.abspath(out_path)}', file=stream)
    return result, out_path


def main(argv=None):
    """Command line: ``vehicle-sim demo [--out FILE.png] [--car MODEL] [--short]``."""
    parser = argparse.ArgumentParser(prog='vehicle-sim demo', description=__doc__.split('\n')[1])
    add_arguments(parser)
    args = parser.parse_args(argv)
    run_demo(args.out, args.car, args.short)
    return 0


def add_arguments(parser):
    """Add the demo's options to an argparse parser (shared with ``vehicle-sim demo``)."""
    parser.add_argument('--out', default=DEFAULT_OUT, help=f'PNG to write ({DEFAULT_OUT})')
    parser.add_argument('--car', default=None, help='car preset (default ToyotaPrius)')
    parser.add_argument('--short', action='store_true', help='half-length scenario')


if __name__ == '__main__':
    sys.exit(main())
