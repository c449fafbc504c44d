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
Rendering of the Gymnasium environment.

'rgb_array' (the chase camera by the CPU renderer) and 'human' (PyBullet's window, on a virtual
X display), and Gymnasium's checker with its render checks on: with a display and without one
(docs/gym.md's check, run as written).
"""

import json
import re
import subprocess
import sys

from conftest import peer_env, REPO_ROOT
import numpy as np
import pytest

gymnasium = pytest.importorskip('gymnasium', reason="needs the 'gym' extra (gymnasium)")

from xvfb_helpers import require_xvfb, xvfb_run  # noqa: E402

from vehicle_sim.gym import DriveEnv, DriveVectorEnv  # noqa: E402

HUMAN = r"""
import json, warnings
import numpy as np
import gymnasium
from gymnasium.utils.env_checker import check_env
import vehicle_sim.gym
warnings.simplefilter('ignore')
out = {}
env = gymnasium.make('vehicle_sim/Drive-v0')
check_env(env.unwrapped)            # with the render checks: 'human' and 'rgb_array'
out['render_modes'] = env.unwrapped.metadata['render_modes']
env.close()
out['check_env'] = 'passed'
env = gymnasium.make('vehicle_sim/Drive-v0', render_mode='human')
env.reset(seed=0)
for _ in range(100):
    obs, *_ = env.step(np.array([0.2, 5.0], dtype=np.float32))
out['render'] = repr(env.render())
out['gui'] = env.unwrapped.sim.world.gui
out['x'] = float(obs['pose'][0])
view = env.unwrapped._chase.view
out['target_x'] = view.target_m[0]
env.close()
print('RESULT ' + json.dumps(out))
"""


def test_rgb_array_pictures_follow_the_car():
    env = DriveEnv(render_mode='rgb_array', render_width=96, render_height=72)
    try:
        env.reset(seed=0)
        first = env.render()
        for _ in range(250):        # 2.5 s at up to 8 m/s: about 13 m towards the wall
            env.step(np.array([0.0, 8.0], dtype=np.float32))
        later = env.render()
    finally:
        env.close()
    assert first.shape == later.shape == (72, 96, 3) and first.dtype == np.uint8
    # the camera moved with the car: the (red-brown) wall ahead grew in the picture
    def wall_pixels(picture):
        rgb = picture.astype(int)
        return int(((rgb[..., 0] > rgb[..., 1] + 40) & (rgb[..., 0] > rgb[..., 2] + 40)).sum())

    assert wall_pixels(first) > 20
    assert wall_pixels(later) > 2.0 * wall_pixels(first)


def test_the_vector_env_renders_one_picture_per_world():
    env = DriveVectorEnv(2, render_mode='rgb_array', render_width=32, render_height=24)
    try:
        env.reset(seed=0)
        pictures = env.render()
    finally:
        env.close()
    assert len(pictures) == 2 and all(p.shape == (24, 32, 3) for p in pictures)
    assert np.array_equal(pictures[0], pictures[1])       # same world, same start


def test_human_mode_opens_the_window_and_check_env_passes_with_render_checks(tmp_path):
    require_xvfb()
    result = xvfb_run([sys.executable, '-c', HUMAN], 240, tmp_path)
    lines = [line for line in result.stdout.splitlines() if line.startswith('RESULT ')]
    assert result.returncode == 0 and lines, result.stdout[-2000:] + result.stderr[-2000:]
    seen = json.loads(lines[-1][len('RESULT '):])
    assert seen['check_env'] == 'passed'
    assert seen['render_modes'] == ['human', 'rgb_array']
    assert seen['gui'] is True and seen['render'] == 'None'
    assert seen['x'] > 1.0
    assert abs(seen['target_x'] - seen['x']) < 3.0        # the window's camera follows it


HEADLESS = r"""
import json
from vehicle_sim.physics.gui import GuiUnavailableError
{check}
out = {{'render_modes': env.unwrapped.metadata['render_modes']}}
try:
    gymnasium.make('vehicle_sim/Drive-v0', render_mode='human')
except GuiUnavailableError as error:
    out['human'] = str(error)
print('RESULT ' + json.dumps(out))
"""


def test_the_documented_check_env_passes_without_a_display():
    # docs/gym.md's check, as written, in a process without DISPLAY: Gymnasium's checker opens
    # every declared render mode; 'human' is declared only where PyBullet's window can open.
    text = open(f'{REPO_ROOT}/docs/gym.md', encoding='utf-8').read()
    check = [block for block in re.findall(r'```python\n(.*?)```', text, re.S)
             if 'check_env(' in block][0]
    env = peer_env()
    env.pop('DISPLAY', None)
    result = subprocess.run([sys.executable, '-c', HEADLESS.format(check=check)], env=env,
                            capture_output=True, text=True, timeout=240)
    lines = [line for line in result.stdout.splitlines() if line.startswith('RESULT ')]
    assert result.returncode == 0 and lines, result.stdout[-2000:] + result.stderr[-2000:]
    seen = json.loads(lines[-1][len('RESULT '):])
    assert seen['render_modes'] == ['rgb_array']
    assert seen['human'].startswith('DISPLAY is not set')     # asked for, still refused
