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
The training examples' files (vehicle_sim/gym/learning_curve.py): CSV rows and the curve's PNG.

The rows read back as written, in the columns asked for; the evaluation's rows carry their
policy first; the PNG is a picture of the curve (matplotlib is in ``test``, through ``plot``).
"""

import csv

import pytest

from vehicle_sim.gym import learning_curve as lc


def _read(path):
    with open(path, encoding='utf-8') as stream:
        reader = csv.DictReader(stream)
        return reader.fieldnames, list(reader)


def test_rows_read_back_in_the_columns_asked_for(tmp_path):
    rows = [{'wall_s': 1.5, 'env_steps': 2048, 'mean_return': -0.25},
            {'wall_s': 3.0, 'env_steps': 4096, 'mean_return': 1.75}]
    lc.write_rows(tmp_path / 'curve.csv', rows, ['env_steps', 'wall_s', 'mean_return'])
    fields, back = _read(tmp_path / 'curve.csv')
    assert fields == ['env_steps', 'wall_s', 'mean_return']
    assert [(int(r['env_steps']), float(r['wall_s']), float(r['mean_return'])) for r in back] \
        == [(2048, 1.5, -0.25), (4096, 3.0, 1.75)]
    # without columns: the first row's keys, in its order
    lc.write_rows(tmp_path / 'episodes.csv', rows)
    assert _read(tmp_path / 'episodes.csv')[0] == ['wall_s', 'env_steps', 'mean_return']
    # a column the rows do not have is refused (csv's own error), nothing silently dropped
    with pytest.raises(ValueError, match='fields not in fieldnames'):
        lc.write_rows(tmp_path / 'bad.csv', rows, ['env_steps'])


def test_the_evaluation_rows_name_their_policy_first(tmp_path):
    results = {'trained': [{'seed': 1, 'success': True}, {'seed': 2, 'success': False}],
               'random': [{'seed': 1, 'success': False}]}
    lc.write_evaluation(tmp_path / 'evaluation.csv', results)
    fields, back = _read(tmp_path / 'evaluation.csv')
    assert fields == ['policy', 'seed', 'success']
    assert [(r['policy'], r['seed'], r['success']) for r in back] == [
        ('trained', '1', 'True'), ('trained', '2', 'False'), ('random', '1', 'False')]


def test_the_curve_is_drawn_as_a_png(tmp_path):
    pytest.importorskip('matplotlib', reason="the PNG needs the 'plot' extra (matplotlib)")
    rows = [{'agent_steps': 100 * k, 'wall_s': 30.0 * k, 'mean_return': k / 2.0,
             'success_rate': k / 10.0, 'collision_rate': 1.0 - k / 10.0} for k in range(1, 8)]
    path = tmp_path / 'learning_curve.png'
    assert lc.plot_curve(path, rows, 'a curve', 50, steps_key='agent_steps',
                         rates=(lc.SUCCESS, lc.COLLISION))
    data = path.read_bytes()
    assert data[:8] == b'\x89PNG\r\n\x1a\n'
    # 8 x 5 inches at 80 dpi: 640 x 400 pixels (the IHDR chunk's width and height)
    assert (int.from_bytes(data[16:20], 'big'), int.from_bytes(data[20:24], 'big')) == (640, 400)
