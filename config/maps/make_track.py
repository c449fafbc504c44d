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
Draw config/maps/race_track.png and race_track.yaml: a small race track in nav2's map format.

Run ``python config/maps/make_track.py`` to redraw them (Pillow). The centreline is a closed
polygon of corner points, smoothed by Chaikin's corner cutting. Cells within TRACK_WIDTH_M / 2
of it are the track (free: white, 254), the next WALL_M on both sides the walls (occupied:
black, 0), the rest unknown (grey, 205), as nav2's map_saver writes them. The YAML's origin
puts the start point, the middle of the first straight, at the map (and world) origin heading
+x; the script prints the start pose the world file config/worlds/race_track.yaml uses.
"""

import math
from pathlib import Path

import numpy as np
from PIL import Image

RESOLUTION_M = 0.1
TRACK_WIDTH_M = 7.0
WALL_M = 0.6
MARGIN_M = 3.0
# Corner points of the centreline [m], counter-clockwise; the first straight runs along +x.
CORNERS_M = [(-20.0, 0.0), (30.0, 0.0), (48.0, 10.0), (44.0, 28.0), (26.0, 26.0),
             (16.0, 38.0), (-6.0, 40.0), (-22.0, 30.0), (-12.0, 18.0), (-30.0, 10.0)]
SMOOTHING_ROUNDS = 5
FOLDER = Path(__file__).resolve().parent
NAME = 'race_track'


def chaikin(points, rounds):
    """Smooth a closed polygon by Chaikin's corner cutting (each round doubles the points)."""
    points = np.asarray(points, dtype=float)
    for _ in range(rounds):
        following = np.roll(points, -1, axis=0)
        points = np.stack([0.75 * points + 0.25 * following,
                           0.25 * points + 0.75 * following], axis=1).reshape(-1, 2)
    return points


def distance_to_polyline(points, low, width, height):
    """Distance [m] of every cell centre (row 0 = bottom) to a closed polyline."""
    distance = np.full((height, width), np.inf)
    reach = TRACK_WIDTH_M / 2 + WALL_M + RESOLUTION_M
    for a, b in zip(points, np.roll(points, -1, axis=0)):
        lo = (np.minimum(a, b) - reach - low) / RESOLUTION_M
        hi = (np.maximum(a, b) + reach - low) / RESOLUTION_M
        c0, r0 = max(int(lo[0]), 0), max(int(lo[1]), 0)
        c1, r1 = min(int(hi[0]) + 1, width), min(int(hi[1]) + 1, height)
        xs = low[0] + (np.arange(c0, c1) + 0.5) * RESOLUTION_M
        ys = low[1] + (np.arange(r0, r1) + 0.5) * RESOLUTION_M
        px, py = np.meshgrid(xs, ys)
        ab = b - a
        t = np.clip(((px - a[0]) * ab[0] + (py - a[1]) * ab[1]) / (ab @ ab), 0.0, 1.0)
        d = np.hypot(px - a[0] - t * ab[0], py - a[1] - t * ab[1])
        window = distance[r0:r1, c0:c1]
        np.minimum(window, d, out=window)
    return distance


def draw():
    """Write the PNG and the YAML; return the start pose (x, y, yaw) in the map frame."""
    centre = chaikin(CORNERS_M, SMOOTHING_ROUNDS)
    # The start: the smoothed point nearest the middle of the first straight.
    start = int(np.argmin(np.hypot(centre[:, 0] - 5.0, centre[:, 1])))
    ahead = centre[(start + 1) % len(centre)] - centre[start]
    start_pose = (0.0, 0.0, math.atan2(ahead[1], ahead[0]))
    centre = centre - centre[start]           # the start point at the origin
    reach = TRACK_WIDTH_M / 2 + WALL_M + MARGIN_M
    low = centre.min(axis=0) - reach
    high = centre.max(axis=0) + reach
    width, height = (int(math.ceil(v)) for v in (high - low) / RESOLUTION_M)
    distance = distance_to_polyline(centre, low, width, height)[::-1]   # top row first
    pixels = np.full((height, width), 205, dtype=np.uint8)
    pixels[distance <= TRACK_WIDTH_M / 2 + WALL_M] = 0
    pixels[distance <= TRACK_WIDTH_M / 2] = 254
    image = Image.fromarray(pixels)
    image.save(FOLDER / f'{NAME}.png', optimize=True)
    (FOLDER / f'{NAME}.yaml').write_text(
        f'# Drawn by make_track.py: {width} x {height} cells of {RESOLUTION_M} m, track '
        f'{TRACK_WIDTH_M} m wide, walls {WALL_M} m.\n'
        f'image: {NAME}.png\n'
        f'resolution: {RESOLUTION_M}\n'
        f'origin: [{low[0]:.3f}, {low[1]:.3f}, 0.0]\n'
        'negate: 0\n'
        'occupied_thresh: 0.65\n'
        'free_thresh: 0.196\n'
        'mode: trinary\n', encoding='utf-8')
    return start_pose


if __name__ == '__main__':
    x, y, yaw = draw()
    print(f'start pose: {{x: {x:.3f}, y: {y:.3f}, yaw: {yaw:.4f}}}')
