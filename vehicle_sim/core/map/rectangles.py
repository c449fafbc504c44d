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
Merging the wall cells of a grid into few rectangles, so that a large map stays cheap.

:func:`merge_rectangles` covers every True cell of a mask exactly once with axis-aligned
rectangles: each row's runs of consecutive cells, then runs of equal columns in consecutive rows
joined into one rectangle. A straight wall, horizontal or vertical, is one rectangle; a filled
block is one; a diagonal or curved wall costs about one rectangle per row it crosses. Vectorised
(no Python loop per cell or per run): a 3000 x 2250 mask merges in tens of milliseconds.
"""

import numpy as np

# Columns of the array merge_rectangles returns.
ROW, COLUMN, ROWS, COLUMNS = range(4)


def merge_rectangles(mask: np.ndarray) -> np.ndarray:
    """
    Cover the True cells of a 2-D bool mask with disjoint axis-aligned rectangles.

    :param mask: bool (height, width).
    :return: int64 (n, 4): first row, first column, number of rows, number of columns of each
        rectangle (indices :data:`ROW`, :data:`COLUMN`, :data:`ROWS`, :data:`COLUMNS`), sorted
        by column span, then row.
    """
    height, width = mask.shape
    if not mask.any():
        return np.zeros((0, 4), dtype=np.int64)
    padded = np.zeros((height, width + 2), dtype=np.int8)
    padded[:, 1:-1] = mask
    edges = np.diff(padded, axis=1)
    run_rows, run_starts = np.nonzero(edges == 1)     # row-major, so starts and ends pair up
    _, run_ends = np.nonzero(edges == -1)
    # Join runs of the same columns in consecutive rows: sort by (columns, row), then a new
    # rectangle starts where the columns change or a row is skipped.
    span = run_starts.astype(np.int64) * (width + 1) + run_ends
    order = np.lexsort((run_rows, span))
    span, rows = span[order], run_rows[order].astype(np.int64)
    starts, ends = run_starts[order].astype(np.int64), run_ends[order].astype(np.int64)
    new = np.ones(len(span), dtype=bool)
    new[1:] = (span[1:] != span[:-1]) | (rows[1:] != rows[:-1] + 1)
    first = np.flatnonzero(new)
    last = np.append(first[1:], len(span)) - 1
    result = np.empty((len(first), 4), dtype=np.int64)
    result[:, ROW] = rows[first]
    result[:, COLUMN] = starts[first]
    result[:, ROWS] = rows[last] - rows[first] + 1
    result[:, COLUMNS] = ends[first] - starts[first]
    return result


def rectangles_mask(rectangles: np.ndarray, shape) -> np.ndarray:
    """Return the bool mask the rectangles cover (the inverse of :func:`merge_rectangles`)."""
    mask = np.zeros(shape, dtype=bool)
    for row, column, rows, columns in rectangles:
        mask[row:row + rows, column:column + columns] = True
    return mask
