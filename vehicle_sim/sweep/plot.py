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
The summary plot of a sweep (summary.png): the share of passing cases over the grid.

The keys given more than one value span the plot (a key with one value is named in the title).
Two or more such keys: a grid of cells, the first key across and the second up, each cell
coloured by the share of its cases that passed (red 0 .. green 1) and labelled ``passed/cases``
(the seeds and any further keys pooled in a cell); errors are counted as not passing and shown
as ``E``. One key: a row of cells over its values. No key: a row over the seeds. matplotlib is
optional (the ``plot`` extra): without it no plot is written and the sweep says so.
"""

import os
import warnings

from vehicle_sim.scenarios.plot import PlotUnavailable, require

PLOT = 'summary.png'
LABEL_CHARS = 24

__all__ = ['plot_summary', 'PlotUnavailable', 'PLOT']


def _label(value):
    if isinstance(value, float):
        return f'{value:g}'
    text = str(value)
    if isinstance(value, str) and '/' in text:
        text = text.rsplit('/', 1)[-1]          # a file: its name
    return text if len(text) <= LABEL_CHARS else text[:LABEL_CHARS - 1] + '…'


def _axis_values(records, key):
    values = []
    for record in records:
        value = dict((k, v) for k, v in record['overrides'])[key] if key else record['seed']
        if not any(type(v) is type(value) and v == value for v in values):
            values.append(value)
    return values


def grid_counts(records, keys):
    """
    Return the cells of the plot: (x values, y values, {(i, j): (passed, errors, cases)}).

    x is the first key (the seeds when there is none), y the second (a single row when there is
    none).
    """
    x_key = keys[0] if keys else None
    y_key = keys[1] if len(keys) > 1 else None
    xs = _axis_values(records, x_key)
    ys = _axis_values(records, y_key) if y_key else [None]
    cells = {}
    for record in records:
        overrides = dict((k, v) for k, v in record['overrides'])
        x = overrides[x_key] if x_key else record['seed']
        y = overrides[y_key] if y_key else None
        i = next(n for n, v in enumerate(xs) if type(v) is type(x) and v == x)
        j = next(n for n, v in enumerate(ys) if type(v) is type(y) and v == y)
        passed, errors, total = cells.get((i, j), (0, 0, 0))
        cells[(i, j)] = (passed + (record['status'] == 'pass'),
                         errors + (record['status'] == 'error'), total + 1)
    return xs, ys, cells


def plot_summary(out_dir, records, keys, name):
    """Write summary.png into ``out_dir`` and return its path (PlotUnavailable without it)."""
    require()
    from matplotlib import pyplot
    from matplotlib.colors import LinearSegmentedColormap
    fixed = [k for k in keys if len(_axis_values(records, k)) == 1]
    keys = [k for k in keys if k not in fixed]
    xs, ys, cells = grid_counts(records, keys)
    colours = LinearSegmentedColormap.from_list('pass_share', ['#d73027', '#fee08b', '#1a9850'])
    width = min(16.0, max(6.5, 2.5 + 0.7 * len(xs)))
    height = min(12.0, max(3.5, 2.0 + 0.6 * len(ys)))
    figure, axes = pyplot.subplots(figsize=(width, height))
    for (i, j), (passed, errors, total) in cells.items():
        share = passed / total
        axes.add_patch(pyplot.Rectangle((i - 0.5, j - 0.5), 1, 1, color=colours(share)))
        text = f'{passed}/{total}' + (f'\nE{errors}' if errors else '')
        axes.text(i, j, text, ha='center', va='center', fontsize=8)
    axes.set_xlim(-0.5, len(xs) - 0.5)
    axes.set_ylim(-0.5, len(ys) - 0.5)
    axes.set_xticks(range(len(xs)), [_label(v) for v in xs], rotation=45 if len(xs) > 8 else 0)
    axes.set_xlabel(keys[0] if keys else 'seed')
    if len(keys) > 1:
        axes.set_yticks(range(len(ys)), [_label(v) for v in ys])
        axes.set_ylabel(keys[1])
    else:
        axes.set_yticks([])
    passed = sum(r['status'] == 'pass' for r in records)
    seeds = {r['seed'] for r in records}
    pooled = (['seeds'] if keys and len(seeds) > 1 else []) + list(keys[2:])
    title = f'{name}: {passed}/{len(records)} cases passed'
    if pooled:
        title += f'\ncells pool {", ".join(pooled)}'
    if fixed:
        overrides = dict((k, v) for k, v in records[0]['overrides'])
        title += '\n' + ', '.join(f'{k}={_label(overrides[k])}' for k in fixed)
    axes.set_title(title, fontsize=10)
    figure.colorbar(pyplot.cm.ScalarMappable(cmap=colours), ax=axes,
                    label='share of cases passed')
    with warnings.catch_warnings():     # long labels: the layout does what it can
        warnings.simplefilter('ignore')
        figure.tight_layout()
    path = os.path.join(out_dir, PLOT)
    figure.savefig(path, dpi=100)
    pyplot.close(figure)
    return path
