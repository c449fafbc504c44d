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
The files of a training run: its rows as CSV and its learning curve as a PNG.

The training examples (examples/train_highway.py, train_highway_ray.py, train_crossing_shared.py;
docs/learning.md) write their curve and episodes through :func:`write_rows`, their evaluation's
episodes through :func:`write_evaluation`, and draw the curve with :func:`plot_curve`: the mean
return in the top row, rates (success, collision) in the bottom row, against environment steps
(left) and wall time (right). matplotlib is the ``plot`` extra; without it the PNG is skipped
with a line saying so.
"""

import csv

# (row key, legend label, colour) of the success rate: the rates every example draws.
SUCCESS = ('success_rate', 'success', 'tab:green')
COLLISION = ('collision_rate', 'collision', 'tab:red')


def write_rows(path, rows, fields=None):
    """
    Write dict rows as a CSV file with a header.

    :param fields: the columns in order (None: the first row's keys).
    """
    rows = list(rows)
    if fields is None:
        fields = list(rows[0]) if rows else []
    with open(path, 'w', encoding='utf-8', newline='') as stream:
        writer = csv.DictWriter(stream, fieldnames=list(fields))
        writer.writeheader()
        writer.writerows(rows)


def write_evaluation(path, results):
    """
    Write evaluation episodes as CSV: a row per episode, its policy's name first.

    :param results: {policy name: [episode outcome dicts, each of the same keys]}.
    """
    first = next(iter(results.values()))
    write_rows(path, (dict(o, policy=name) for name, outcomes in results.items()
                      for o in outcomes), ['policy'] + list(first[0]))


def plot_curve(path, rows, title, window, steps_key='env_steps',
               steps_label='environment steps', rates=(SUCCESS,), return_label='mean return'):
    """
    Draw the learning curve as a PNG; return False when matplotlib is missing.

    :param rows: the curve's rows: ``steps_key``, ``wall_s`` [s], ``mean_return`` and the rates'
        keys.
    :param window: the training episodes each row averages (the axes' labels say so).
    :param rates: (row key, legend label, colour) of the rates in the bottom row; more than one
        gets a legend.
    """
    try:
        import matplotlib
    except ImportError:
        print(f"matplotlib is missing (pip install 'vehicle_sim[plot]'): no {path}")
        return False
    matplotlib.use('Agg')
    import matplotlib.pyplot as plt
    figure, axes = plt.subplots(2, 2, figsize=(8, 5), sharey='row')
    steps = [r[steps_key] for r in rows]
    minutes = [r['wall_s'] / 60.0 for r in rows]
    for column, (x, label) in enumerate(((steps, steps_label), (minutes, 'wall time [min]'))):
        axes[0, column].plot(x, [r['mean_return'] for r in rows])
        for key, name, colour in rates:
            axes[1, column].plot(x, [r[key] for r in rows], color=colour, label=name)
        axes[1, column].set_xlabel(label)
        axes[1, column].set_ylim(-0.02, 1.02)
    if len(rates) > 1:
        axes[1, 0].legend(loc='center right', fontsize=8)
    axes[0, 0].set_ylabel(f'{return_label},\nlast {window} episodes')
    rate_label = rates[0][0].replace('_', ' ') if len(rates) == 1 else 'rate'
    axes[1, 0].set_ylabel(f'{rate_label},\nlast {window} episodes')
    figure.suptitle(title, fontsize=10)
    figure.tight_layout()
    figure.savefig(path, dpi=80)
    plt.close(figure)
    return True
