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
PyBullet's window: whether one can open here, and a chase camera driven from the keyboard.

``World(gui=True)`` opens the window (after :func:`check_gui_available`: on Linux PyBullet
ends the whole process when it cannot reach an X server, so the display is checked first and a
clear :class:`GuiUnavailableError` raised instead). :class:`ChaseCamera` then keeps the window's
camera behind and above a vehicle; it is a World hook, so anything that owns a GUI world (the
nodes, a scenario runner, a script) enables it the same way::

    world = World(gui=True)
    car = SimulatedCar(world, load_car('BmwX5'))
    ChaseCamera(world, [car])          # follows the first target; 'n' cycles through them

The camera math lives in :mod:`vehicle_sim.core.geometry.chase_camera`; docs/drive.md lists the
keys.
"""

from contextlib import contextmanager
import ctypes
import ctypes.util
import os
import sys
import time
from typing import Dict, Optional, Sequence, Tuple

import pybullet

from vehicle_sim.core.geometry.angles import yaw_from_quaternion
from vehicle_sim.core.geometry.chase_camera import chase_view, ChaseSettings, follow_heading
from vehicle_sim.core.specs.errors import VehicleSimError

# Our keys (PyBullet's own shortcuts use a c d g i j k l o p s v w and Esc; see docs/drive.md).
KEY_FOLLOW = 'f'
KEY_NEXT = 'n'
KEY_CLOSER = '='
KEY_FARTHER = '-'
# PyBullet's own window size, the smallest we shrink it to, and what is left of the screen for the
# window manager's title bar and a desktop panel [pixels].
DEFAULT_WINDOW_SIZE = (1024, 768)
MIN_WINDOW_SIZE = (320, 240)
WINDOW_MARGIN = (40, 100)
# Simulated time between the window's updates [s]: the camera's moves and key polls, and the
# traffic boxes' placing (physics/traffic_bodies.py). In GUI mode a PyBullet call can wait for
# the window to finish a frame, so nothing is moved for it each 10 ms step; at real time this
# is 33 frames a second.
FRAME_PERIOD_S = 0.03
CAMERA_PERIOD_S = FRAME_PERIOD_S
SHORTCUTS = (
    (KEY_FOLLOW, 'chase camera on/off (off: the mouse moves the camera)'),
    (KEY_NEXT, 'follow the next vehicle'),
    (KEY_CLOSER, 'chase camera closer'),
    (KEY_FARTHER, 'chase camera farther'),
)


class GuiUnavailableError(VehicleSimError):
    """PyBullet's window cannot open here (no display, or one is open in this process)."""


class GuiClosedError(VehicleSimError):
    """The PyBullet window was closed (Esc or the window's close button): the world is gone."""


# How long opening the X display is retried while its server is there but refuses (a reset) [s].
OPEN_RETRY_S = 5.0

def gui_unavailable_reason(environ=None) -> Optional[str]:
    """
    Return why PyBullet's window cannot open here, or None when it can.

    On Linux the window needs an X server (PyBullet has no Wayland back end; XWayland serves):
    ``DISPLAY`` must be set and the server must accept a connection (libX11's XOpenDisplay).
    Elsewhere (macOS, Windows) PyBullet opens a native window and None is returned.

    :param environ: the environment to read DISPLAY from (default ``os.environ``).
    """
    if not sys.platform.startswith('linux'):
        return None
    display = (os.environ if environ is None else environ).get('DISPLAY', '')
    hint = ("PyBullet's window needs an X display; without one, run under a virtual display "
            '(Debian/Ubuntu package xvfb: xvfb-run -a <command>) or leave the GUI off')
    if not display:
        return f'DISPLAY is not set: {hint}'
    with _x_display(display) as (_, _, problem):
        return None if problem is None else f'{problem}: {hint}'


def screen_size(environ=None) -> Optional[Tuple[int, int]]:
    """
    Return the X display's default screen size (width, height) [pixels], or None if unknown.

    :param environ: the environment to read DISPLAY from (default ``os.environ``).
    """
    display = (os.environ if environ is None else environ).get('DISPLAY', '')
    if not display or not sys.platform.startswith('linux'):
        return None
    with _x_display(display) as (x11, handle, problem):
        if problem is not None:
            return None
        screen = x11.XDefaultScreen(handle)
        return int(x11.XDisplayWidth(handle, screen)), int(x11.XDisplayHeight(handle, screen))


@contextmanager
def display_held(environ=None):
    """
    Keep a connection to the X display open for the block (Linux with DISPLAY set).

    An X server started without -noreset (Xvfb, as xvfb-run starts it) resets when its last
    client leaves and refuses connections while it does; PyBullet ends the process when its
    window cannot connect. Holding a connection from the availability check until PyBullet has
    its own keeps the server from resetting in between.

    :param environ: the environment to read DISPLAY from (default ``os.environ``).
    """
    display = (os.environ if environ is None else environ).get('DISPLAY', '')
    if not display or not sys.platform.startswith('linux'):
        yield
        return
    with _x_display(display):
        yield


def _local_socket(display):
    # True when the display is local (':N' or ':N.S') and its server's socket exists.
    if not display.startswith(':'):
        return False
    number = display[1:].split('.')[0]
    return number.isdigit() and os.path.exists(f'/tmp/.X11-unix/X{number}')


@contextmanager
def _x_display(display):
    # (libX11, the open display, None), or (None, None, why it cannot be opened); closed after.
    library = ctypes.util.find_library('X11')
    if library is None:
        yield None, None, 'libX11 is not installed'
        return
    try:
        x11 = ctypes.CDLL(library)
    except OSError as error:
        yield None, None, f'libX11 cannot be loaded ({error})'
        return
    x11.XOpenDisplay.restype = ctypes.c_void_p
    x11.XOpenDisplay.argtypes = [ctypes.c_char_p]
    x11.XCloseDisplay.argtypes = [ctypes.c_void_p]
    x11.XDefaultScreen.argtypes = [ctypes.c_void_p]
    x11.XDisplayWidth.argtypes = x11.XDisplayHeight.argtypes = [ctypes.c_void_p, ctypes.c_int]
    handle = x11.XOpenDisplay(display.encode())
    deadline = time.monotonic() + OPEN_RETRY_S
    while not handle and _local_socket(display) and time.monotonic() < deadline:
        # A server is there but refuses connections for now: one started without -noreset
        # (Xvfb as xvfb-run starts it) resets when its last client leaves, and a loaded
        # machine makes that reset slow.
        time.sleep(0.05)
        handle = x11.XOpenDisplay(display.encode())
    if not handle:
        yield None, None, f'cannot open X display {display!r}'
        return
    try:
        yield x11, handle, None
    finally:
        x11.XCloseDisplay(handle)


def window_size(screen: Optional[Tuple[int, int]]) -> Tuple[int, int]:
    """
    Return PyBullet's window size [pixels]: its usual 1024 × 768, shrunk to fit the screen.

    A margin is left for the window manager's title bar and a desktop panel (a 1024 × 768
    window does not fit a 1280 × 720 laptop screen).

    :param screen: (width, height) of the screen [pixels], or None (unknown: the usual size).
    """
    width, height = DEFAULT_WINDOW_SIZE
    if screen is None:
        return width, height
    return (max(MIN_WINDOW_SIZE[0], min(width, screen[0] - WINDOW_MARGIN[0])),
            max(MIN_WINDOW_SIZE[1], min(height, screen[1] - WINDOW_MARGIN[1])))


def check_gui_available(environ=None) -> None:
    """Raise :class:`GuiUnavailableError` when PyBullet's window cannot open here."""
    reason = gui_unavailable_reason(environ)
    if reason is not None:
        raise GuiUnavailableError(reason)


def shortcuts_text() -> str:
    """Return the chase camera's keys as one line (logged when a node opens the window)."""
    return '; '.join(f"'{key}' {what}" for key, what in SHORTCUTS)


def _body_id(target) -> int:
    # A body id, a body (CarBody, DiffRobotBody: .body_id) or a vehicle holding one (.body).
    if isinstance(target, int):
        return target
    body = getattr(target, 'body', target)
    return body.body_id


class ChaseCamera:
    """
    World hook: PyBullet's window camera behind and above a vehicle, yaw following its heading.

    After a world step, every ``period_s`` of simulated time, it reads the window's key presses
    (:data:`SHORTCUTS`) and, while following, moves the camera (``resetDebugVisualizerCamera``;
    PyBullet applies it at the window's next frame). In a DIRECT world nothing is shown but
    :attr:`view` is still computed.

    :param world: the World (it registers itself with ``world.add_body``).
    :param targets: what can be followed, first one first: body ids, bodies with ``body_id``
        or vehicles with ``body`` (SimulatedCar).
    :param settings: distance, pitch, target height, heading lag (core ChaseSettings).
    :param period_s: simulated time between updates [s]; 0 = after every step.
    :raises ValueError: for an empty target list or a negative period.
    """

    def __init__(self, world, targets: Sequence, settings: Optional[ChaseSettings] = None,
                 period_s: float = CAMERA_PERIOD_S):
        if not targets:
            raise ValueError('ChaseCamera needs at least one target to follow')
        if not period_s >= 0.0:
            raise ValueError(f'period_s = {period_s!r}: must be >= 0')
        self.period_s = float(period_s)
        self._last_s = world.time_s
        self.world = world
        self._targets = list(targets)   # their ids are read each time: a reset may reload a body
        self.settings = settings or ChaseSettings()
        self.index = 0
        self.following = True
        self.view = None          # the last ChaseView sent to the window
        self._heading = None      # the lagged camera heading [rad]
        self._keys = {ord(key): action for key, action in (
            (KEY_FOLLOW, self._toggle_follow), (KEY_NEXT, self._next_target),
            (KEY_CLOSER, lambda: self._zoom(-1)), (KEY_FARTHER, lambda: self._zoom(1)))}
        world.add_body(self)
        self.update(None)

    @property
    def target_id(self) -> int:
        """Body id of the vehicle followed."""
        return _body_id(self._targets[self.index])

    def post_step(self):
        """World hook, after each step: keys, then the camera, once per period."""
        now = self.world.time_s
        if now - self._last_s < self.period_s - 1e-9:
            return
        dt_s, self._last_s = now - self._last_s, now
        events = pybullet.getKeyboardEvents(physicsClientId=self.world.client_id)
        if events:
            self.handle_keys(events)
        if self.following:
            self.update(dt_s)

    def handle_keys(self, events: Dict[int, int]) -> None:
        """Act on the keys pressed since the last call (``getKeyboardEvents`` form)."""
        for key, state in events.items():
            action = self._keys.get(key)
            if action is not None and state & pybullet.KEY_WAS_TRIGGERED:
                action()

    def update(self, dt_s: Optional[float]) -> None:
        """
        Move the camera to the followed vehicle's current pose.

        :param dt_s: time since the last update [s] for the heading lag; None = snap to the
            vehicle's heading (first view, after switching vehicles).
        """
        cid = self.world.client_id
        try:
            position, orientation = pybullet.getBasePositionAndOrientation(
                self.target_id, physicsClientId=cid)
        except pybullet.error:   # the body was removed: nothing to follow this step
            return
        heading = yaw_from_quaternion(*orientation)
        if dt_s is None or self._heading is None:
            self._heading = heading
        else:
            self._heading = follow_heading(self._heading, heading, dt_s,
                                           self.settings.heading_lag_s)
        view = self.view = chase_view(position, self._heading, self.settings)
        pybullet.resetDebugVisualizerCamera(view.distance_m, view.yaw_deg, view.pitch_deg,
                                            view.target_m, physicsClientId=cid)

    def _toggle_follow(self):
        self.following = not self.following
        if self.following:
            self.update(None)

    def _next_target(self):
        self.index = (self.index + 1) % len(self._targets)
        self.update(None)

    def _zoom(self, steps):
        self.settings = self.settings.zoomed(steps)
        if self.following:
            self.update(0.0)
