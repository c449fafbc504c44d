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


"""Node mains freeze what start-up built, so a full collection never scans it (issue 10)."""

import gc

from vehicle_sim.ros.node_support import freezing_start_up


def test_the_node_factory_is_followed_by_a_gc_freeze():
    built = []
    factory = freezing_start_up(lambda args: built.append(args) or 'app')
    gc.unfreeze()
    try:
        assert gc.get_freeze_count() == 0
        assert factory(['node', '--ros-args']) == 'app'
        assert built == [['node', '--ros-args']]
        assert gc.get_freeze_count() > 0
    finally:
        gc.unfreeze()
