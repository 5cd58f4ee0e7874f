#!/usr/bin/env python3
"""Subset a COLMAP 3.8 binary sparse model to a few images: keeps the named images, only their keypoints
that observe a kept 3D point, and the 3D points seen by >= MIN_TRACK kept images (tracks restricted to them).
Usage: subset_colmap.py IN_DIR OUT_DIR MIN_TRACK NAME [NAME...]"""
import struct, sys, os

def rd(f, fmt):
    n = struct.calcsize(fmt)
    return struct.unpack('<' + fmt, f.read(n))

src, dst, min_track, names = sys.argv[1], sys.argv[2], int(sys.argv[3]), set(sys.argv[4:])
os.makedirs(dst, exist_ok=True)
cams = open(os.path.join(src, 'cameras.bin'), 'rb').read()
images = {}
with open(os.path.join(src, 'images.bin'), 'rb') as f:
    (n,) = rd(f, 'Q')
    for _ in range(n):
        image_id, = rd(f, 'I'); q = rd(f, '4d'); t = rd(f, '3d'); cam, = rd(f, 'I')
        name = b''
        while True:
            c = f.read(1)
            if c == b'\0': break
            name += c
        (np2,) = rd(f, 'Q')
        pts = [rd(f, 'ddQ') for _ in range(np2)]
        images[image_id] = (q, t, cam, name.decode(), pts)
keep = {i for i, v in images.items() if v[3] in names}
points = {}
with open(os.path.join(src, 'points3D.bin'), 'rb') as f:
    (n,) = rd(f, 'Q')
    for _ in range(n):
        pid, = rd(f, 'Q'); xyz = rd(f, '3d'); rgb = rd(f, '3B'); err, = rd(f, 'd'); (tl,) = rd(f, 'Q')
        track = [rd(f, 'II') for _ in range(tl)]
        track = [(i, k) for i, k in track if i in keep]
        if len({i for i, _ in track}) >= min_track:
            points[pid] = (xyz, rgb, err, track)
# Re-index keypoints: keep only observations of kept points.
new_idx = {}
out_images = {}
for i in sorted(keep):
    q, t, cam, name, pts = images[i]
    kept = []
    for k, (x, y, pid) in enumerate(pts):
        if pid != 0xFFFFFFFFFFFFFFFF and pid in points and any(ii == i and kk == k for ii, kk in points[pid][3]):
            new_idx[(i, k)] = len(kept)
            kept.append((x, y, pid))
    out_images[i] = (q, t, cam, name, kept)
with open(os.path.join(dst, 'cameras.bin'), 'wb') as f:
    f.write(cams)
with open(os.path.join(dst, 'images.bin'), 'wb') as f:
    f.write(struct.pack('<Q', len(out_images)))
    for i, (q, t, cam, name, pts) in sorted(out_images.items()):
        f.write(struct.pack('<I4d3dI', i, *q, *t, cam)); f.write(name.encode() + b'\0')
        f.write(struct.pack('<Q', len(pts)))
        for x, y, pid in pts: f.write(struct.pack('<ddQ', x, y, pid))
with open(os.path.join(dst, 'points3D.bin'), 'wb') as f:
    f.write(struct.pack('<Q', len(points)))
    for pid, (xyz, rgb, err, track) in sorted(points.items()):
        f.write(struct.pack('<Q3d3Bd', pid, *xyz, *rgb, err)); f.write(struct.pack('<Q', len(track)))
        for i, k in track: f.write(struct.pack('<II', i, new_idx[(i, k)]))
print(len(out_images), 'images', len(points), 'points')
