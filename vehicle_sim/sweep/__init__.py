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
Scenario sweeps: a scenario run over a grid of values and seeds, merged (docs/sweeps.md).

Every combination of values (``--set key=v1,v2``) and seeds runs in parallel worker processes
or as Ray tasks, with one merged report.

Modules: :mod:`.grid` (the variants: ``--set``, ``--seeds``, dotted keys, validation),
:mod:`.worker` (running one case in a process), :mod:`.local` (the local worker processes),
:mod:`.ray_tasks` (the Ray backend), :mod:`.results` (the results folder, table, JUnit XML),
:mod:`.plot` (the summary plot), :mod:`.progress` (the progress display), :mod:`.run`
(:func:`run_sweep`, which the ``vehicle-sim sweep`` command wraps).

May import: core, config, scenarios, vehicle_sim.
"""

from vehicle_sim.sweep.grid import SweepError
from vehicle_sim.sweep.run import run_sweep, SweepResult

__all__ = ['run_sweep', 'SweepError', 'SweepResult']
