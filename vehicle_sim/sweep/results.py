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
A sweep's results folder: each case's record as it finishes, and the merged reports.

Layout of ``DIR``::

    sweep.json          what was swept (scenario file and its SHA-256, the --set axes, seeds)
    cases/<id>.json     one record per finished case, written as it finishes (atomically)
    logs/<id>.log       each case's output
    results.csv         one row per case, in grid order: its values, status, every criterion's
                        measured value and verdict (results.parquet too when pyarrow imports)
    junit.xml           a testcase per (case, criterion); an errored case adds a testcase 'run'
    summary.png         pass/fail over the grid (matplotlib; see :mod:`.plot`)

The merged files are made from the records alone and hold no wall-clock times (but the JUnit
``time`` attributes), so they are the same whichever backend and however many workers ran the
cases.
"""

import csv
from datetime import datetime, timezone
import json
import os
import socket
from xml.etree import ElementTree

from vehicle_sim.sweep.grid import SweepError

MANIFEST = 'sweep.json'
CASES = 'cases'
LOGS = 'logs'
TABLE = 'results.csv'
PARQUET = 'results.parquet'
JUNIT = 'junit.xml'


def prepare(out_dir, manifest, resume):
    """
    Make ``out_dir`` ready; return the records already there (``resume``) as {case_id: record}.

    :raises SweepError: the folder holds another sweep, or this sweep's results without
        ``resume``, or cannot be written.
    """
    path = os.path.join(out_dir, MANIFEST)
    try:
        os.makedirs(os.path.join(out_dir, CASES), exist_ok=True)
        os.makedirs(os.path.join(out_dir, LOGS), exist_ok=True)
    except OSError as error:
        raise SweepError(f'--out {out_dir}: cannot create it: {error.strerror}') from None
    if not os.access(out_dir, os.W_OK | os.X_OK):
        raise SweepError(f'--out {out_dir}: not writable')
    existing = load_records(out_dir)
    if os.path.exists(path):
        with open(path, encoding='utf-8') as file:
            old = json.load(file)
        if old != manifest:
            raise SweepError(f'--out {out_dir}: holds the results of another sweep (its '
                             f'{MANIFEST} differs: scenario, --set or --seeds); give another '
                             'folder')
    if existing and not resume:
        raise SweepError(f'--out {out_dir}: holds {len(existing)} finished case(s) of this '
                         'sweep; --resume runs the others, or give another folder')
    _write_json(path, manifest)
    return existing


def _write_json(path, data):
    temporary = f'{path}.tmp{os.getpid()}'
    with open(temporary, 'w', encoding='utf-8') as file:
        json.dump(data, file, indent=1, sort_keys=True)
        file.write('\n')
    os.replace(temporary, path)


def save_record(out_dir, record):
    """Write one case's record (atomically: a reader never sees half a file)."""
    _write_json(os.path.join(out_dir, CASES, f'{record["case_id"]}.json'), record)


def load_records(out_dir):
    """Return the records in ``out_dir/cases`` as {case_id: record} (skipping unreadable ones)."""
    folder = os.path.join(out_dir, CASES)
    records = {}
    if not os.path.isdir(folder):
        return records
    for name in sorted(os.listdir(folder)):
        if not name.endswith('.json'):
            continue
        try:
            with open(os.path.join(folder, name), encoding='utf-8') as file:
                record = json.load(file)
        except (OSError, ValueError):
            continue
        records[record['case_id']] = record
    return records


def log_path(out_dir, case_id):
    return os.path.join(out_dir, LOGS, f'{case_id}.log')


def criterion_names(records):
    """Every criterion's name, in the order of the first record that has it."""
    names = []
    for record in records:
        for criterion in record['criteria']:
            if criterion['name'] not in names:
                names.append(criterion['name'])
    return names


def _cell(value):
    if value is None:
        return ''
    if isinstance(value, bool):
        return 'true' if value else 'false'
    if isinstance(value, float):
        return repr(value)
    return str(value)


def table_rows(records, keys):
    """
    Return the results table: a header, then one row per record (in the order given).

    Columns: case, each swept key, seed, status, for each criterion ``<name>`` (the measured
    value) and ``<name>.passed``, error (its first line), odometry_sha256.
    """
    names = criterion_names(records)
    header = ['case'] + list(keys) + ['seed', 'status']
    for name in names:
        header += [name, f'{name}.passed']
    header += ['error', 'odometry_sha256']
    rows = [header]
    for record in records:
        overrides = dict((k, v) for k, v in record['overrides'])
        row = [record['case_id']] + [_cell(overrides.get(k)) for k in keys]
        row += [str(record['seed']), record['status']]
        by_name = {c['name']: c for c in record['criteria']}
        for name in names:
            criterion = by_name.get(name)
            row += (['', ''] if criterion is None else
                    [_cell(criterion['value']), _cell(criterion['passed'])])
        error = record['error'] or ''
        row += [error.strip().splitlines()[0] if error.strip() else '',
                record['odometry_sha256']]
        rows.append(row)
    return rows


def write_table(out_dir, records, keys):
    """Write results.csv (and results.parquet when pyarrow imports); return the paths."""
    rows = table_rows(records, keys)
    path = os.path.join(out_dir, TABLE)
    temporary = f'{path}.tmp{os.getpid()}'
    with open(temporary, 'w', encoding='utf-8', newline='') as file:
        csv.writer(file, lineterminator='\n').writerows(rows)
    os.replace(temporary, path)
    written = [path]
    try:
        import pyarrow
        import pyarrow.parquet
    except ImportError:
        return written
    parquet = os.path.join(out_dir, PARQUET)
    pyarrow.parquet.write_table(pyarrow.table(table_columns(records, keys)), parquet)
    written.append(parquet)
    return written


def table_columns(records, keys):
    """
    Return the table's columns, typed, as {name: values} (for Parquet).

    The CSV's columns: a swept key's values keep their type when all have the same one (text
    otherwise), measured values are floats (None where none), verdicts booleans.
    """
    columns = {'case': [r['case_id'] for r in records]}
    for key in keys:
        values = [dict((k, v) for k, v in r['overrides'])[key] for r in records]
        kinds = {type(v) for v in values if v is not None}
        if len(kinds) > 1:
            values = [None if v is None else _cell(v) for v in values]
        columns[key] = values
    columns['seed'] = [r['seed'] for r in records]
    columns['status'] = [r['status'] for r in records]
    for name in criterion_names(records):
        found = [next((c for c in r['criteria'] if c['name'] == name), None) for r in records]
        columns[name] = [None if c is None or c['value'] is None else float(c['value'])
                         for c in found]
        columns[f'{name}.passed'] = [None if c is None else c['passed'] for c in found]
    columns['error'] = [(r['error'] or '').strip().split('\n')[0] for r in records]
    columns['odometry_sha256'] = [r['odometry_sha256'] for r in records]
    return columns


def write_junit(out_dir, records, scenario_name, source):
    """Write junit.xml: one testsuite, a testcase per (case, criterion); return its path."""
    failures = sum(not c['passed'] for r in records for c in r['criteria'])
    errors = sum(1 for r in records if r['error'])
    tests = sum(len(r['criteria']) for r in records) + errors
    total_s = sum(r['wall_time_s'] for r in records)
    suites = ElementTree.Element('testsuites', name='vehicle_sim sweeps')
    suite = ElementTree.SubElement(suites, 'testsuite', {
        'name': f'sweep.{scenario_name}', 'errors': str(errors), 'failures': str(failures),
        'skipped': '0', 'tests': str(tests), 'time': f'{total_s:.3f}',
        'timestamp': datetime.now(timezone.utc).isoformat(),
        'hostname': socket.gethostname()})
    properties = ElementTree.SubElement(suite, 'properties')
    for name, value in (('file', source), ('cases', len(records))):
        ElementTree.SubElement(properties, 'property', name=name, value=str(value))
    for record in records:
        classname = f'sweep.{scenario_name}[{record["label"]}]'
        share = record['wall_time_s'] / max(1, len(record['criteria']))
        for criterion in record['criteria']:
            case = ElementTree.SubElement(suite, 'testcase', classname=classname,
                                          name=criterion['name'], time=f'{share:.3f}')
            if not criterion['passed']:
                failure = ElementTree.SubElement(case, 'failure', message=criterion['detail'])
                failure.text = f'{criterion["kind"]}: {criterion["detail"]}'
            out = ElementTree.SubElement(case, 'system-out')
            value = criterion['value']
            out.text = (f'{criterion["kind"]}: '
                        + ('no value measured' if value is None else
                           f'{value} {criterion["unit"]}'.strip())
                        + f'; {criterion["detail"]}')
        if record['error']:
            case = ElementTree.SubElement(suite, 'testcase', classname=classname, name='run',
                                          time=f'{record["wall_time_s"]:.3f}')
            error = ElementTree.SubElement(case, 'error',
                                           message=record['error'].strip().splitlines()[0][:200]
                                           if record['error'].strip() else 'error')
            error.text = record['error']
    tree = ElementTree.ElementTree(suites)
    ElementTree.indent(tree)
    path = os.path.join(out_dir, JUNIT)
    tree.write(path, encoding='utf-8', xml_declaration=True)
    return path
