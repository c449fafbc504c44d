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

"""Whether a publisher's message can reach a subscriber now: the gate a publishing loop reads."""


class ReaderGate:
    """
    Whether a message published now can reach a subscriber (``open``).

    ``open`` is False only while the transport knows that no subscriber would receive it: a
    volatile publisher of the embedded transport with no matched subscription (the message
    would go nowhere; a subscriber matching later does not get it either). A node's publishing
    loop reads it before building a message and skips the message when it is closed. Kept up to
    date by the transport, read as a plain attribute.
    """

    __slots__ = ('open',)

    def __init__(self, open_: bool = True):
        self.open = open_


# The gate of publishers whose transport does not track their subscribers: always open.
ALWAYS_OPEN = ReaderGate(True)
