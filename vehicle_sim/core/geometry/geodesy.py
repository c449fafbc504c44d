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
WGS-84 geodesy: the local east-north-up (ENU) plane of a world and latitude/longitude/altitude.

A world's geodetic ``origin`` is the point of the ellipsoid-referred WGS-84 frame where the world
frame sits: world x points east, y north, z up, in the plane tangent to the ellipsoid there
(local tangent plane). A world position converts exactly: ENU -> ECEF (a rotation and the
origin's ECEF position) -> geodetic latitude, longitude and ellipsoidal altitude, with Bowring's
iteration, which converges to the last bit in a few steps (about 1e-15 rad).

Constants: WGS-84 (NIMA TR8350.2): a = 6378137 m, 1/f = 298.257223563.
"""

from dataclasses import dataclass
import math

WGS84_A_M = 6378137.0
WGS84_F = 1.0 / 298.257223563
WGS84_B_M = WGS84_A_M * (1.0 - WGS84_F)
WGS84_E2 = WGS84_F * (2.0 - WGS84_F)              # first eccentricity squared
WGS84_EP2 = WGS84_E2 / (1.0 - WGS84_E2)           # second eccentricity squared

_MAX_ITERATIONS = 10
_TOLERANCE_RAD = 1e-15


@dataclass(frozen=True)
class GeodeticOrigin:
    """WGS-84 position of a world frame origin: latitude, longitude [deg], altitude [m]."""

    latitude_deg: float = 0.0
    longitude_deg: float = 0.0
    altitude_m: float = 0.0


def geodetic_to_ecef(latitude_deg, longitude_deg, altitude_m):
    """
    Convert WGS-84 geodetic coordinates to Earth-centred, Earth-fixed (ECEF) ones.

    :param latitude_deg: geodetic latitude [deg].
    :param longitude_deg: longitude [deg].
    :param altitude_m: height above the ellipsoid [m].
    :return: (x, y, z) [m].
    """
    lat = math.radians(latitude_deg)
    lon = math.radians(longitude_deg)
    sin_lat = math.sin(lat)
    n = WGS84_A_M / math.sqrt(1.0 - WGS84_E2 * sin_lat * sin_lat)
    r = (n + altitude_m) * math.cos(lat)
    return (r * math.cos(lon), r * math.sin(lon), (n * (1.0 - WGS84_E2) + altitude_m) * sin_lat)


def ecef_to_geodetic(x_m, y_m, z_m):
    """
    Convert ECEF coordinates to WGS-84 geodetic ones (Bowring's iteration).

    The latitude is iterated on the reduced latitude until it no longer changes (about
    1e-15 rad: two or three passes near the Earth's surface); the height uses
    h = p cos(lat) + z sin(lat) - a sqrt(1 - e^2 sin^2(lat)), which holds at the poles too.

    :param x_m: ECEF x [m].
    :param y_m: ECEF y [m].
    :param z_m: ECEF z [m].
    :return: (latitude [deg], longitude [deg], ellipsoidal altitude [m]).
    """
    p = math.hypot(x_m, y_m)
    lon = math.atan2(y_m, x_m)
    beta = math.atan2(z_m, p * (1.0 - WGS84_F))
    lat = beta
    for _ in range(_MAX_ITERATIONS):
        sin_b, cos_b = math.sin(beta), math.cos(beta)
        lat = math.atan2(z_m + WGS84_EP2 * WGS84_B_M * sin_b ** 3,
                         p - WGS84_E2 * WGS84_A_M * cos_b ** 3)
        new_beta = math.atan2((1.0 - WGS84_F) * math.sin(lat), math.cos(lat))
        done = abs(new_beta - beta) <= _TOLERANCE_RAD
        beta = new_beta
        if done:
            break
    sin_lat = math.sin(lat)
    height = (p * math.cos(lat) + z_m * sin_lat
              - WGS84_A_M * math.sqrt(1.0 - WGS84_E2 * sin_lat * sin_lat))
    return math.degrees(lat), math.degrees(lon), height


class LocalTangentPlane:
    """
    The east-north-up plane of a world at its geodetic origin.

    :param origin: GeodeticOrigin of the world frame.
    """

    def __init__(self, origin=GeodeticOrigin()):
        self.origin = origin
        self._ecef0 = geodetic_to_ecef(origin.latitude_deg, origin.longitude_deg,
                                       origin.altitude_m)
        lat = math.radians(origin.latitude_deg)
        lon = math.radians(origin.longitude_deg)
        sl, cl, so, co = math.sin(lat), math.cos(lat), math.sin(lon), math.cos(lon)
        # rows: the east, north and up unit vectors in ECEF
        self._east = (-so, co, 0.0)
        self._north = (-sl * co, -sl * so, cl)
        self._up = (cl * co, cl * so, sl)

    def enu_to_ecef(self, east_m, north_m, up_m):
        """Return the ECEF position (x, y, z) [m] of a world position (x east, y north, z up)."""
        e, n, u = self._east, self._north, self._up
        x0, y0, z0 = self._ecef0
        return (x0 + e[0] * east_m + n[0] * north_m + u[0] * up_m,
                y0 + e[1] * east_m + n[1] * north_m + u[1] * up_m,
                z0 + e[2] * east_m + n[2] * north_m + u[2] * up_m)

    def ecef_to_enu(self, x_m, y_m, z_m):
        """Return the world position (east, north, up) [m] of an ECEF position."""
        x0, y0, z0 = self._ecef0
        d = (x_m - x0, y_m - y0, z_m - z0)
        return tuple(sum(a * b for a, b in zip(axis, d))
                     for axis in (self._east, self._north, self._up))

    def to_geodetic(self, east_m, north_m, up_m):
        """
        Convert a world position to WGS-84 coordinates.

        :param east_m: world x [m].
        :param north_m: world y [m].
        :param up_m: world z [m].
        :return: (latitude [deg], longitude [deg], ellipsoidal altitude [m]).
        """
        return ecef_to_geodetic(*self.enu_to_ecef(east_m, north_m, up_m))

    def from_geodetic(self, latitude_deg, longitude_deg, altitude_m):
        """Convert WGS-84 coordinates to a world position (east, north, up) [m]."""
        return self.ecef_to_enu(*geodetic_to_ecef(latitude_deg, longitude_deg, altitude_m))
