#!/usr/bin/env python3
"""refs_gps.txt for the banana photos: each registered image's camera centre, from the COLMAP model in
sparse/, placed on WGS84 about ORIGIN, so that georeferencing is exact by construction.

The photos carry no GPS. COLMAP's frame has an arbitrary orientation and scale, so the centres are first
turned so that the cameras' mean "up" (the opposite of their image y axis) is the local vertical, then
scaled by SCALE (COLMAP units to metres). Run from this folder, after `colmap model_converter
--input_path sparse --output_path TXT --output_type TXT`:

    python3 make_refs.py TXT/images.txt > refs_gps.txt
"""
import math
import os
import sys

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "..", "interop", "blender"))
from wgs84 import ecef_from_enu, geodetic_from_ecef  # noqa: E402

ORIGIN = {"lat_deg": 46.8426, "lon_deg": -91.9939, "height_m": 160.0}
SCALE = 1.0  # COLMAP units to metres (the model's units are arbitrary; the photos were taken ~0.5 m away)


def quat_to_matrix(w, x, y, z):
    return [[1 - 2 * (y * y + z * z), 2 * (x * y - w * z), 2 * (x * z + w * y)],
            [2 * (x * y + w * z), 1 - 2 * (x * x + z * z), 2 * (y * z - w * x)],
            [2 * (x * z - w * y), 2 * (y * z + w * x), 1 - 2 * (x * x + y * y)]]


def main(path):
    cams = []
    with open(path) as f:
        lines = [line for line in f if not line.startswith("#")]
    for line in lines[0::2]:
        v = line.split()
        if len(v) < 10:
            continue
        w, x, y, z, tx, ty, tz = map(float, v[1:8])
        r = quat_to_matrix(w, x, y, z)  # cam_from_world
        c = [-sum(r[k][i] * (tx, ty, tz)[k] for k in range(3)) for i in range(3)]
        up = [-r[1][i] for i in range(3)]  # world direction of the image's -y
        cams.append((v[9], c, up))
    cams.sort()
    # A rotation taking the mean up to +z (Rodrigues), about the centres' mean.
    u = [sum(cam[2][i] for cam in cams) for i in range(3)]
    n = math.sqrt(sum(a * a for a in u))
    u = [a / n for a in u]
    axis = [u[1], -u[0], 0.0]  # u x z
    s = math.sqrt(axis[0] ** 2 + axis[1] ** 2)
    cos = u[2]
    mean = [sum(cam[1][i] for cam in cams) / len(cams) for i in range(3)]
    print("# image latitude_deg longitude_deg height_m (WGS84 ellipsoidal): COLMAP's camera centres (make_refs.py)")
    for name, c, _ in cams:
        p = [c[i] - mean[i] for i in range(3)]
        if s > 1e-12:
            k = [a / s for a in axis]
            kxp = [k[1] * p[2] - k[2] * p[1], k[2] * p[0] - k[0] * p[2], k[0] * p[1] - k[1] * p[0]]
            kdp = sum(k[i] * p[i] for i in range(3))
            p = [p[i] * cos + kxp[i] * s + k[i] * kdp * (1 - cos) for i in range(3)]
        enu = [SCALE * a for a in p]
        lat, lon, h = geodetic_from_ecef(*ecef_from_enu(ORIGIN, enu))
        print("%s %.10f %.10f %.4f" % (name, lat, lon, h))


if __name__ == "__main__":
    main(sys.argv[1])
