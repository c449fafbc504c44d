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
Test peer: one embedded-transport node run in a subprocess by the transport tests.

Usage: ``python transport_peer.py [--reply-timeout S] --ros-args -r __node:=peer -r __ns:=/tp``.
It offers ``echo_in`` -> ``echo_out`` (std_msgs/String, prefix 'echo: '), the service
``set_int`` (vehicle_msgs/SetInt, success = value is even), a double parameter ``gain`` in
[0, 10], logs 'peer ready' and prints one JSON line describing its GUIDs, then spins until
SIGTERM/SIGINT.
"""

import json
import math
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.dirname(os.path.abspath(__file__))))

from vehicle_sim.transport import dds  # noqa: E402
from vehicle_sim.transport.selection import create_node, run_node  # noqa: E402


def _gain_validator(value):
    if not math.isfinite(value) or not 0.0 <= value <= 10.0:
        return f'gain {value} outside [0, 10]'
    return None


class Peer:
    """The peer node: wiring only, as a vehicle_sim node would be."""

    def __init__(self, args):
        reply_timeout_s = 1.0
        if '--reply-timeout' in args:
            reply_timeout_s = float(args[args.index('--reply-timeout') + 1])
        self.node = create_node('peer', '', args=args, transport='dds',
                                reply_match_timeout_s=reply_timeout_s)
        self._string = self.node.msg('std_msgs/msg/String')
        self._pub = self.node.create_publisher('std_msgs/msg/String', 'echo_out')
        self._sub = self.node.create_subscription(
            'std_msgs/msg/String', 'echo_in', self._on_echo_in)
        self._srv = self.node.create_service(
            'vehicle_msgs/srv/SetInt', 'set_int', self._handle_set_int)
        self.node.declare_parameter('gain', 1.0, description='test gain [1]',
                                    validator=_gain_validator)
        self.node.get_logger().info('peer ready')
        print(json.dumps({
            'participant': dds.participant_guid().hex(),
            'node': self.node.get_fully_qualified_name(),
            'echo_out_writer': self._pub.gid.hex(),
            'echo_in_reader': self._sub.gid.hex(),
            'set_int_reader': self._srv._reader.guid.bytes.hex(),
            'set_int_writer': self._srv._writer.guid.bytes.hex(),
        }), flush=True)

    def _on_echo_in(self, msg):
        self._pub.publish(self._string(data='echo: ' + msg.data))

    def _handle_set_int(self, request, response):
        response.success = request.value % 2 == 0
        return response


if __name__ == '__main__':
    sys.exit(run_node(Peer, sys.argv[1:], transport='dds'))
