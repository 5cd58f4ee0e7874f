"""WGS84 geodetic <-> ECEF <-> local ENU in plain Python (doubles), for the Blender interop tests: an
implementation independent of cinepath's (core/geodesy.h uses GeographicLib).

ECEF from geodetic: the closed form on the ellipsoid (a = 6378137 m, f = 1/298.257223563). Geodetic
from ECEF: Bowring's iteration, run to convergence (sub-micrometre).
"""
import math

A = 6378137.0
F = 1 / 298.257223563
E2 = F * (2 - F)


def ecef_from_geodetic(lat_deg, lon_deg, h):
    lat, lon = math.radians(lat_deg), math.radians(lon_deg)
    n = A / math.sqrt(1 - E2 * math.sin(lat) ** 2)
    return ((n + h) * math.cos(lat) * math.cos(lon), (n + h) * math.cos(lat) * math.sin(lon),
            (n * (1 - E2) + h) * math.sin(lat))


def geodetic_from_ecef(x, y, z):
    lon = math.atan2(y, x)
    p = math.hypot(x, y)
    lat = math.atan2(z, p * (1 - E2))
    for _ in range(10):
        n = A / math.sqrt(1 - E2 * math.sin(lat) ** 2)
        h = p / math.cos(lat) - n
        lat = math.atan2(z, p * (1 - E2 * n / (n + h)))
    n = A / math.sqrt(1 - E2 * math.sin(lat) ** 2)
    h = p / math.cos(lat) - n
    return math.degrees(lat), math.degrees(lon), h


def enu_axes(lat_deg, lon_deg):
    """Rows: east, north, up as ECEF unit vectors."""
    lat, lon = math.radians(lat_deg), math.radians(lon_deg)
    return ((-math.sin(lon), math.cos(lon), 0.0),
            (-math.sin(lat) * math.cos(lon), -math.sin(lat) * math.sin(lon), math.cos(lat)),
            (math.cos(lat) * math.cos(lon), math.cos(lat) * math.sin(lon), math.sin(lat)))


def ecef_from_enu(origin, enu):
    o = ecef_from_geodetic(origin["lat_deg"], origin["lon_deg"], origin["height_m"])
    axes = enu_axes(origin["lat_deg"], origin["lon_deg"])
    return tuple(o[i] + sum(enu[k] * axes[k][i] for k in range(3)) for i in range(3))


def enu_from_ecef(origin, ecef):
    o = ecef_from_geodetic(origin["lat_deg"], origin["lon_deg"], origin["height_m"])
    axes = enu_axes(origin["lat_deg"], origin["lon_deg"])
    d = [ecef[i] - o[i] for i in range(3)]
    return tuple(sum(axes[k][i] * d[i] for i in range(3)) for k in range(3))


def rotate_between_frames(from_origin, to_origin, v):
    """A direction in from_origin's ENU frame, in to_origin's."""
    a = enu_axes(from_origin["lat_deg"], from_origin["lon_deg"])
    b = enu_axes(to_origin["lat_deg"], to_origin["lon_deg"])
    ecef = [sum(v[k] * a[k][i] for k in range(3)) for i in range(3)]
    return tuple(sum(b[k][i] * ecef[i] for i in range(3)) for k in range(3))
