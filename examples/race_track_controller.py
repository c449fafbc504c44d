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
A Webots-style controller that laps the race track with its lidar: F1TENTH's "follow the gap".

Runs unchanged in Webots apart from its import (``from vehicle import Driver``) on a car with a
lidar named 'Sick LMS 291' (its front slot). On vehicle_sim::

    VEHICLE_SIM_WORLD=race_track python examples/race_track_controller.py
    vehicle-sim scenario scenarios/race_track_lap.yaml      # the same, judged: a lap, no contact

config/worlds/race_track.yaml puts a CitroenCZero on the start straight of the 7 m wide track
with F1TENTH's lidar (270 degrees, 1080 rays, 30 m) on its front bumper. Each scan the
controller (as the F1TENTH course's follow-the-gap examples do):

1. limits the ranges to LOOK_AHEAD_M and averages each with its neighbours;
2. blanks a bubble of CAR_RADIUS_M around the nearest point (there is no gap there);
3. aims at the middle of the widest run of rays that see farther than GAP_M;
4. steers towards it (Webots: + = right), slower the sharper it steers.

It prints a line per second and stops after LAPS_S seconds (or VEHICLE_SIM_DURATION, sooner).
"""

import math

from vehicle_sim.webots import Driver

LIDAR = 'Sick LMS 291'        # the Webots car's front lidar slot (race_track: F1TENTH's)
LOOK_AHEAD_M = 12.0           # ranges beyond this count as this far
SMOOTHING_RAYS = 9            # moving average over this many neighbouring rays
CAR_RADIUS_M = 1.2            # bubble blanked round the nearest point
GAP_M = 4.0                   # a ray seeing farther than this is part of a gap
FIELD_RAD = math.radians(100.0)   # gaps are looked for within +-this of straight ahead
STEERING_GAIN = 0.9           # steering angle per radian of aim
FAST_KMH = 24.0               # on a straight
SLOW_KMH = 12.0               # at full lock
CONTROL_STEPS = 3             # a scan and a steering command every 3 basic steps (30 ms)
LAPS_S = 60.0                 # stop after this long (VEHICLE_SIM_DURATION may stop it sooner)


def smoothed(ranges, limit_m, window):
    """Return the ranges limited to ``limit_m`` [m] and averaged over ``window`` rays."""
    clipped = [min(r, limit_m) if math.isfinite(r) else limit_m for r in ranges]
    half = window // 2
    out = []
    total = sum(clipped[:half])
    for i in range(len(clipped)):
        if i + half < len(clipped):
            total += clipped[i + half]
        if i - half - 1 >= 0:
            total -= clipped[i - half - 1]
        count = min(len(clipped), i + half + 1) - max(0, i - half)
        out.append(total / count)
    return out


def aim(ranges, angles):
    """
    Return the angle [rad, + = left] of the middle of the widest gap, or 0 when there is none.

    :param ranges: one scan [m], left to right (Webots' order).
    :param angles: each ray's angle [rad, + = left].
    """
    ranges = smoothed(ranges, LOOK_AHEAD_M, SMOOTHING_RAYS)
    nearest = min(range(len(ranges)), key=ranges.__getitem__)
    if ranges[nearest] > 0.0:
        blank = math.atan2(CAR_RADIUS_M, ranges[nearest])
        ranges = [0.0 if abs(a - angles[nearest]) < blank else r
                  for r, a in zip(ranges, angles)]
    best, run_start = None, None
    for i, (r, a) in enumerate(zip(ranges + [0.0], angles + [0.0])):
        open_ray = r > GAP_M and abs(a) <= FIELD_RAD
        if open_ray and run_start is None:
            run_start = i
        elif not open_ray and run_start is not None:
            if best is None or i - run_start > best[1] - best[0]:
                best = (run_start, i)
            run_start = None
    if best is None:
        return 0.0
    return angles[(best[0] + best[1] - 1) // 2]


def main():
    """Drive until the time is up."""
    driver = Driver()
    time_step = int(driver.getBasicTimeStep())
    lidar = driver.getDevice(LIDAR)
    lidar.enable(CONTROL_STEPS * time_step)
    count, fov = lidar.getHorizontalResolution(), lidar.getFov()
    angles = [fov / 2.0 - i * fov / (count - 1) for i in range(count)]   # left to right
    max_steering = 0.6             # rad, within the CitroenCZero's 0.631
    printed = -1
    step = 0
    while driver.step() != -1 and driver.getTime() < LAPS_S:
        step += 1
        ranges = lidar.getRangeImage()
        if ranges is None or step % CONTROL_STEPS:     # no scan yet, or no new one
            continue
        left = max(-max_steering, min(max_steering, STEERING_GAIN * aim(list(ranges), angles)))
        driver.setSteeringAngle(-left)                 # Webots: + = right
        lock = abs(left) / max_steering
        driver.setCruisingSpeed(FAST_KMH + (SLOW_KMH - FAST_KMH) * lock)
        if int(driver.getTime()) != printed:
            printed = int(driver.getTime())
            print(f't={driver.getTime():5.2f} s  speed={driver.getCurrentSpeed():5.2f} km/h  '
                  f'steering={-left:+.3f} rad')


if __name__ == '__main__':
    main()
