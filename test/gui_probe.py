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
Open PyBullet's window with a chase camera, look at it, and print what was seen (JSON).

Run by test/test_physics_gui_xvfb.py under ``xvfb-run`` (one GUI per process, so in a process
of its own). A car drives a few metres in a world of its own with the chase camera following;
the probe then waits until the window's camera reports the chase view and takes two pictures of the
window's view: one render through the window camera's own view and projection matrices
(``getCameraImage`` with ``ER_BULLET_HARDWARE_OPENGL``, in the window's OpenGL context, with the
segmentation mask) and, when ``xwd`` is installed, a screenshot of the X display. Both are taken
again with the car teleported 200 m away. Last, the window's client is disconnected (what Esc
does) and one more step is tried. Usage: ``gui_probe.py OUT_DIR``.
"""

import json
import os
import shutil
import struct
import subprocess
import sys
import time

import numpy as np

from vehicle_sim.config import load_car
from vehicle_sim.core.geometry.angles import yaw_from_quaternion
from vehicle_sim.physics import SimulatedCar, World
from vehicle_sim.physics._pybullet import pybullet
from vehicle_sim.physics.gui import ChaseCamera

IMAGE_SIZE = (320, 240)
SYNC_TIMEOUT_S = 60.0
# How far from the image centre the car is looked for (fraction of width and height).
CENTRE_BOX = 0.2


def wait_for_view(camera, timeout_s):
    """Wait until the window's camera reports the chase view; return the report."""
    view = camera.view
    deadline = time.monotonic() + timeout_s
    while True:
        info = pybullet.getDebugVisualizerCamera(physicsClientId=camera.world.client_id)
        yaw, pitch, distance, target = info[8], info[9], info[10], info[11]
        if (abs(yaw - view.yaw_deg) < 1e-3 and abs(pitch - view.pitch_deg) < 1e-3
                and abs(distance - view.distance_m) < 1e-3
                and max(abs(a - b) for a, b in zip(target, view.target_m)) < 1e-3):
            return info
        if time.monotonic() > deadline:
            raise RuntimeError(f'window camera {info[8:12]} never reported the view {view}')
        time.sleep(0.01)


def render(info, client_id):
    """Render the window camera's view; return (rgb, segmentation) arrays."""
    width, height = IMAGE_SIZE
    _, _, rgba, _, seg = pybullet.getCameraImage(
        width, height, viewMatrix=info[2], projectionMatrix=info[3],
        renderer=pybullet.ER_BULLET_HARDWARE_OPENGL, physicsClientId=client_id)
    rgb = np.asarray(rgba, dtype=np.uint8).reshape(height, width, 4)[:, :, :3]
    return rgb, np.asarray(seg).reshape(height, width)


def screenshot():
    """Return the X display as an RGB array (xwd's ZPixmap, 24 or 32 bits per pixel)."""
    data = subprocess.run(['xwd', '-root', '-silent'], check=True, capture_output=True,
                          timeout=60).stdout
    header = struct.unpack('>25I', data[:100])
    header_size, width, height = header[0], header[4], header[5]
    byte_order, bits_per_pixel, bytes_per_line, ncolors = (header[7], header[11], header[12],
                                                            header[19])
    pixels = np.frombuffer(data, np.uint8, bytes_per_line * height, header_size + 12 * ncolors)
    step = bits_per_pixel // 8
    rows = pixels.reshape(height, bytes_per_line)[:, :width * step].reshape(height, width, step)
    # LSBFirst (0): blue, green, red in memory order; MSBFirst: the reverse.
    return rows[:, :, 2::-1] if byte_order == 0 else rows[:, :, step - 3:step]


def centre_box(array):
    height, width = array.shape[:2]
    dy, dx = int(height * CENTRE_BOX), int(width * CENTRE_BOX)
    return array[height // 2 - dy:height // 2 + dy, width // 2 - dx:width // 2 + dx]


def main(out_dir):
    world = World(gui=True)
    car = SimulatedCar(world, load_car('Car'), (3.0, -2.0, 0.7))
    camera = ChaseCamera(world, [car])
    car.logic.set_cruising_speed_kmh(20.0)
    for _ in range(150):
        world.step()
    pose = car.body.pose()
    camera.update(None)   # the view of the car where it stopped, heading not lagged
    info = wait_for_view(camera, SYNC_TIMEOUT_S)
    time.sleep(1.0)       # let the window draw a few frames with that view
    shot_with = screenshot() if shutil.which('xwd') else None
    rgb_with, seg_with = render(info, world.client_id)
    position, orientation = pybullet.getBasePositionAndOrientation(car.body.body_id,
                                                                   physicsClientId=world.client_id)
    pybullet.resetBasePositionAndOrientation(car.body.body_id, (position[0] + 200.0,
                                                                position[1], position[2]),
                                             orientation, physicsClientId=world.client_id)
    time.sleep(1.0)
    shot_without = screenshot() if shutil.which('xwd') else None
    rgb_without, seg_without = render(info, world.client_id)
    body = car.body.body_id
    result = {
        'car_xy': pose[:2],
        'car_yaw': yaw_from_quaternion(*pose[3:7]),
        'view': {'yaw_deg': camera.view.yaw_deg, 'pitch_deg': camera.view.pitch_deg,
                 'distance_m': camera.view.distance_m, 'target_m': camera.view.target_m},
        'window_camera': {'yaw_deg': info[8], 'pitch_deg': info[9], 'distance_m': info[10],
                          'target_m': info[11]},
        'car_pixels_centre': int(np.sum((centre_box(seg_with) & ((1 << 24) - 1)) == body)),
        'car_pixels_centre_away': int(np.sum((centre_box(seg_without) & ((1 << 24) - 1))
                                             == body)),
        'centre_pixels': int(centre_box(seg_with).size),
        'render_centre_change': float(np.mean(np.abs(
            centre_box(rgb_with).astype(float) - centre_box(rgb_without)))),
        'render_border_change': float(np.mean(np.abs(
            rgb_with[:10].astype(float) - rgb_without[:10]))),
        'screenshot': None,
    }
    from PIL import Image
    Image.fromarray(rgb_with).save(os.path.join(out_dir, 'render_with_car.png'))
    Image.fromarray(rgb_without).save(os.path.join(out_dir, 'render_without_car.png'))
    if shot_with is not None:
        # The window is in the top-left corner of the display (no window manager).
        width, height = (int(v) for v in info[:2])
        window_with = shot_with[:height, :width]
        window_without = shot_without[:height, :width]
        Image.fromarray(np.ascontiguousarray(window_with)).save(
            os.path.join(out_dir, 'screenshot_with_car.png'))
        Image.fromarray(np.ascontiguousarray(window_without)).save(
            os.path.join(out_dir, 'screenshot_without_car.png'))
        changed = np.any(np.abs(window_with.astype(int) - window_without) > 30, axis=2)
        result['screenshot'] = {
            'window_size': [width, height],
            'centre_changed_fraction': float(np.mean(centre_box(changed))),
            'top_rows_changed_fraction': float(np.mean(changed[:height // 10])),
        }
    # Closing the window (Esc) disconnects the client: the next step says so.
    pybullet.disconnect(physicsClientId=world.client_id)
    try:
        world.step()
    except Exception as error:   # noqa: BLE001 - reported to the test
        result['step_after_close'] = f'{type(error).__name__}: {error}'
    world.close()
    print(json.dumps(result), flush=True)


if __name__ == '__main__':
    main(sys.argv[1])
