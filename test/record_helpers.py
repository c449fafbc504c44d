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
Helpers of the recording tests: the automobile node recorded in process, read back by rosbags.

Import it after ``pytest.importorskip('mcap', ...)``: recording needs the 'record' extra.
"""

from rosbags.typesys import get_types_from_msg, get_typestore, Stores

from vehicle_sim.recording.recorder import record_node
from vehicle_sim.ros.automobile_node import AutomobileNode, NODE_NAME
from vehicle_sim.transport import create_node


def record_automobile(path, namespace, drive, tap=None, parameters=(), **recorder_options):
    """
    Record the automobile node (synchronous, under ``namespace``) in process while it is driven.

    :param path: the .mcap file.
    :param drive: ``drive(app)``: sets the car going and steps the AutomobileNode ``app``;
        what it returns is handed back.
    :param tap: ``tap(topic, ros_type, qos)`` for each publisher the node creates.
    :param parameters: more node parameters, ``'name:=value'`` each (``'world:=<file>'``).
    :param recorder_options: passed on to ``record_node`` (``opener``, ``chunk_size``).
    :return: (what ``drive`` returned, the recorder, its ``close()``: None when all was written).
    """
    extra = [arg for parameter in parameters for arg in ('-p', parameter)]
    node = create_node(NODE_NAME, args=['rt', '--ros-args', '-r', f'__ns:={namespace}',
                                        '-p', 'synchronous:=true', *extra], transport='dds')
    recorder = record_node(node, path, **recorder_options)
    if tap is not None:
        node.tap_publishers(tap)
    app = AutomobileNode(node=node)
    try:
        result = drive(app)
    finally:
        error = recorder.close()
        app.close()
    return result, recorder, error


def typestore(connections):
    """Return a rosbags typestore of the file's own schemas (each a type and its dependencies)."""
    store = get_typestore(Stores.EMPTY)
    for connection in connections:
        store.register(get_types_from_msg(connection.msgdef.data, connection.msgtype))
    return store
