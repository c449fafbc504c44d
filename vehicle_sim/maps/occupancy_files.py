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
Reading the files of a world's map: an occupancy grid's YAML and its image.

The reader of occupancy-grid map files (kept outside ``core``, which reads none). The YAML goes
through ``yaml_files.py`` and core's table (core/map/occupancy.py); the image through Pillow (the
``maps`` extra: ``pip install 'vehicle_sim[maps]'``), imported only when a world has a map.
Images: PGM, PNG and whatever else Pillow opens, 8 bits per channel: grey, grey + alpha, RGB,
RGBA, palette (as RGB, with its transparency as alpha) and 1-bit (as grey). Every refusal names
the file and the field: the world file's ``map`` field ``file`` for a map YAML that cannot be
read, the map YAML's field ``image`` for an image that cannot.
"""

from pathlib import Path
from typing import Optional, Tuple

import numpy as np

from vehicle_sim.core.map.kinds import OccupancyMapSpec
from vehicle_sim.core.map.occupancy import (
    check_size,
    map_yaml_from_dict,
    MapYaml,
    occupancy_values,
    OccupancyGrid,
)
from vehicle_sim.core.specs.errors import InvalidParameterError
from vehicle_sim.core.specs.value_text import brief
from vehicle_sim.yaml_files import load_file

__all__ = ['load_occupancy_grid', 'read_image', 'read_map_yaml']

# Pillow modes -> what they become: grey ('L'), grey + alpha ('LA'), 'RGB', 'RGBA'.
_AS_IS = {'L': 'L', 'LA': 'LA', 'RGB': 'RGB', 'RGBA': 'RGBA'}
_CONVERTED = {'1': 'L', 'PA': 'RGBA', 'La': 'LA', 'RGBa': 'RGBA', 'RGBX': 'RGB', 'CMYK': 'RGB',
              'YCbCr': 'RGB', 'LAB': 'RGB', 'HSV': 'RGB'}


def _pillow():
    try:
        from PIL import Image
    except ImportError:
        raise InvalidParameterError(
            "reading an occupancy-grid map's image needs Pillow: pip install "
            "'vehicle_sim[maps]'") from None
    return Image


def read_map_yaml(spec: OccupancyMapSpec) -> MapYaml:
    """
    Read and validate the map YAML a world's ``map:`` names.

    :raises InvalidParameterError: naming the world file's field ``file`` when the YAML cannot
        be read, or the YAML file and its field when a value is wrong.
    """
    path = Path(spec.file)
    if not path.is_file():
        reason = 'is a folder, not a file' if path.is_dir() else 'does not exist'
        raise InvalidParameterError(f"{spec.source}: field 'file' = {brief(spec.file)}: "
                                    f'{reason}')
    try:
        data = load_file(path)
    except InvalidParameterError as error:
        raise InvalidParameterError(f"{spec.source}: field 'file': {error}") from None
    return map_yaml_from_dict(data, str(path), str(path.parent))


def read_image(map_yaml: MapYaml) -> Tuple[np.ndarray, Optional[np.ndarray]]:
    """
    Read a map's image as uint8 arrays, top row first.

    :return: (colour: (h, w) grey or (h, w, 3) RGB, alpha: (h, w) or None).
    :raises InvalidParameterError: naming the map YAML's field ``image``: a missing or
        unreadable file, a mode of more than 8 bits per channel, more than MAX_CELLS cells.
    """
    Image = _pillow()
    where = f"{map_yaml.source}: field 'image' = {brief(map_yaml.image)}"
    try:
        with Image.open(map_yaml.image) as image:
            check_size(image.width, image.height, where)
            mode = _AS_IS.get(image.mode)
            if mode is None:
                if image.mode == 'P':
                    mode = 'RGBA' if 'transparency' in image.info else 'RGB'
                else:
                    mode = _CONVERTED.get(image.mode)
                if mode is None:
                    raise InvalidParameterError(
                        f'{where}: pixel mode {image.mode!r} is not supported; save it with 8 '
                        'bits per channel (grey, grey + alpha, RGB or RGBA)')
                image = image.convert(mode)
            pixels = np.asarray(image)
    except InvalidParameterError:
        raise
    except FileNotFoundError:
        raise InvalidParameterError(f'{where}: does not exist') from None
    except Image.DecompressionBombError as error:
        raise InvalidParameterError(f'{where}: too large: {error}') from None
    except (OSError, ValueError, SyntaxError) as error:
        # Pillow: UnidentifiedImageError (an OSError) for what is no image, OSError for a
        # truncated file, SyntaxError for a malformed header.
        raise InvalidParameterError(f'{where}: cannot read it as an image: {error}') from None
    if mode in ('LA', 'RGBA'):
        return pixels[:, :, :-1].squeeze(axis=2) if mode == 'LA' else pixels[:, :, :3], \
            pixels[:, :, -1]
    return pixels, None


def load_occupancy_grid(spec: OccupancyMapSpec) -> Tuple[MapYaml, OccupancyGrid]:
    """
    Read an occupancy-grid map: its YAML, its image, its cell values as map_server has them.

    :raises InvalidParameterError: naming the file and field (see :func:`read_map_yaml`,
        :func:`read_image`).
    """
    map_yaml = read_map_yaml(spec)
    color, alpha = read_image(map_yaml)
    data = occupancy_values(color, alpha, map_yaml)
    return map_yaml, OccupancyGrid(data, map_yaml.resolution_m, map_yaml.origin)
