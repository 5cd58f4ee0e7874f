#!/usr/bin/python3
"""Builds the small Brighton Beach fixtures in this folder from the prepared dataset (PROVENANCE.md).

Run with Debian's python3 (needs numpy):  /usr/bin/python3 make_brighton_fixtures.py <brighton_beach source dir>

1. brighton_sparse_default/ and brighton_sparse_exif_focal/: the COLMAP binary models with every keypoint
   that has no 3D point dropped (keypoint indices renumbered in images and tracks). Same cameras, poses,
   points and observations as the originals; 1.2 MB instead of 5.3 MB.
2. odm_reference_2m.txt: the OpenDroneMap reference cloud (EPSG:32615 UTM 15N, z ellipsoidal) reduced to
   the median easting, northing and height of the points in each 2 m x 2 m cell that holds >= 3 points.
"""
import os
import struct
import sys

import numpy as np

src = sys.argv[1]
here = os.path.dirname(os.path.abspath(__file__))


def reduce_model(name):
    d = os.path.join(src, "colmap", name)
    out = os.path.join(here, "brighton_" + name)
    os.makedirs(out, exist_ok=True)
    with open(os.path.join(d, "cameras.bin"), "rb") as f:
        cams = f.read()
    with open(os.path.join(out, "cameras.bin"), "wb") as f:
        f.write(cams)
    data = open(os.path.join(d, "images.bin"), "rb").read()
    pos = 0
    (n,) = struct.unpack_from("<Q", data, pos)
    pos += 8
    remap = {}
    images_out = [struct.pack("<Q", n)]
    for _ in range(n):
        head = data[pos:pos + 4 + 56 + 4]
        (image_id,) = struct.unpack_from("<I", data, pos)
        pos += 64
        end = data.index(b"\0", pos)
        name_bytes = data[pos:end + 1]
        pos = end + 1
        (npts,) = struct.unpack_from("<Q", data, pos)
        pos += 8
        kept = []
        for k in range(npts):
            x, y, pid = struct.unpack_from("<ddQ", data, pos)
            pos += 24
            if pid != 0xFFFFFFFFFFFFFFFF:
                remap[(image_id, k)] = len(kept)
                kept.append(struct.pack("<ddQ", x, y, pid))
        images_out.append(head + name_bytes + struct.pack("<Q", len(kept)) + b"".join(kept))
    assert pos == len(data)
    with open(os.path.join(out, "images.bin"), "wb") as f:
        f.write(b"".join(images_out))
    data = open(os.path.join(d, "points3D.bin"), "rb").read()
    pos = 0
    (n,) = struct.unpack_from("<Q", data, pos)
    pos += 8
    pts_out = [struct.pack("<Q", n)]
    for _ in range(n):
        head = data[pos:pos + 8 + 24 + 3 + 8]
        pos += 43
        (tl,) = struct.unpack_from("<Q", data, pos)
        pos += 8
        track = []
        for _ in range(tl):
            iid, idx = struct.unpack_from("<II", data, pos)
            pos += 8
            track.append(struct.pack("<II", iid, remap[(iid, idx)]))
        pts_out.append(head + struct.pack("<Q", tl) + b"".join(track))
    assert pos == len(data)
    with open(os.path.join(out, "points3D.bin"), "wb") as f:
        f.write(b"".join(pts_out))


def reduce_reference():
    path = os.path.join(src, "odm_reference.ply")
    raw = open(path, "rb").read()
    end = raw.index(b"end_header\n") + len(b"end_header\n")
    dt = np.dtype([("x", "<f8"), ("y", "<f8"), ("z", "<f8"), ("r", "u1"), ("g", "u1"), ("b", "u1")])
    pts = np.frombuffer(raw[end:], dtype=dt)
    cell = 2.0
    ix = np.floor(pts["x"] / cell).astype(np.int64)
    iy = np.floor(pts["y"] / cell).astype(np.int64)
    key = ix * 1000003 + iy
    order = np.argsort(key, kind="stable")
    key_sorted = key[order]
    bounds = np.flatnonzero(np.diff(key_sorted)) + 1
    starts = np.concatenate(([0], bounds))
    ends = np.concatenate((bounds, [len(key_sorted)]))
    lines = ["# OpenDroneMap reference (brighton_beach/odm_reference.ply) reduced to 2 m cells: median of each",
             "# cell with >= 3 points. Columns: easting_m northing_m height_m, EPSG:32615 (UTM 15N), height",
             "# WGS84 ellipsoidal. Made by make_brighton_fixtures.py."]
    for s, e in zip(starts, ends):
        if e - s < 3:
            continue
        sel = order[s:e]
        lines.append("%.2f %.2f %.3f" % (np.median(pts["x"][sel]), np.median(pts["y"][sel]), np.median(pts["z"][sel])))
    with open(os.path.join(here, "odm_reference_2m.txt"), "w") as f:
        f.write("\n".join(lines) + "\n")


reduce_model("sparse_default")
reduce_model("sparse_exif_focal")
reduce_reference()
