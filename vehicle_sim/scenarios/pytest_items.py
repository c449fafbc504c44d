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
Scenario files as pytest tests: ``scenario_*.yaml`` files are collected, one test per criterion.

The pytest plugin (vehicle_sim.testing) hands matching files to :class:`ScenarioFile`. The
scenario runs once, when its first test runs; each criterion's test then passes or fails with
the measured value. An invalid file is a collection error naming ``file:line``.
"""

import pytest

PATTERN = 'scenario_*.yaml'


class ScenarioRunFailed(Exception):
    """A criterion failed, or the run itself failed (reported without a traceback)."""


class ScenarioFile(pytest.File):
    """A ``scenario_*.yaml`` file: one :class:`CriterionItem` per criterion."""

    _result = None

    def collect(self):
        from vehicle_sim.scenarios.schema import load_scenario
        from vehicle_sim.scenarios.yaml_lines import ScenarioError
        try:
            self.spec = load_scenario(self.path)
        except ScenarioError as error:
            raise self.CollectError(str(error)) from None
        for criterion in self.spec.criteria:
            yield CriterionItem.from_parent(self, name=criterion.name, criterion=criterion)

    def result(self):
        """Run the scenario once; return its ScenarioResult."""
        if self._result is None:
            from vehicle_sim.scenarios.runner import run_scenario
            self._result = run_scenario(self.spec)
        return self._result


class CriterionItem(pytest.Item):
    """One criterion of a scenario file."""

    def __init__(self, *, criterion, **kwargs):
        super().__init__(**kwargs)
        self.criterion = criterion

    def runtest(self):
        result = self.parent.result()
        measured = result.criterion(self.criterion.name)
        self.user_properties.append(('value', measured.value))
        if result.error:
            raise ScenarioRunFailed(f'the scenario run failed: {result.error}')
        if not measured.passed:
            raise ScenarioRunFailed(f'{measured.kind}: {measured.detail}')

    def repr_failure(self, excinfo):
        if isinstance(excinfo.value, ScenarioRunFailed):
            return str(excinfo.value)
        return super().repr_failure(excinfo)

    def reportinfo(self):
        return self.path, self.criterion.line, f'{self.parent.spec.name}: {self.name}'
