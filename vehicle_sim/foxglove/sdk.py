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


"""The optional ``foxglove-sdk`` package, imported only when a live view is asked for."""

from vehicle_sim.core.specs.errors import VehicleSimError

EXTRA = 'foxglove'
INSTALL_HINT = f"pip install 'vehicle_sim[{EXTRA}]'"


class LiveViewError(VehicleSimError):
    """The live view cannot start (package missing, address refused, port in use)."""


def load_sdk():
    """
    Return the ``foxglove`` module of the ``foxglove-sdk`` package.

    :raises LiveViewError: when it is not installed, naming the extra that installs it.
    """
    try:
        import foxglove
        import foxglove.channels  # noqa: F401 - the typed channels of the scene
        import foxglove.messages  # noqa: F401
        import foxglove.websocket  # noqa: F401
    except ImportError as error:
        raise LiveViewError(
            f'the Foxglove live view needs the foxglove-sdk package ({error}); install it '
            f'with: {INSTALL_HINT}') from None
    return foxglove
