#!/usr/bin/python3
"""Open3D's quadric decimation on the bench mesh, for the comparison in bench/RESULTS.md.

Run with Debian's python3 (python3-open3d 0.16):
  build/bench/mesh_decimate_bench --faces 2500000 --methods meshoptimizer --export-raw /tmp/terrain.raw
  /usr/bin/python3 bench/open3d_decimate.py /tmp/terrain.raw 250000 /tmp/terrain_open3d.raw
  build/bench/mesh_decimate_bench --faces 2500000 --import-raw /tmp/terrain_open3d.raw --label open3d
The raw format (mesh_decimate_bench): uint64 vertex count, uint64 face count, float64 xyz per
vertex, uint32 × 3 per face.
"""
import struct
import sys
import time

import numpy as np
import open3d as o3d


def read_raw(path):
    with open(path, "rb") as f:
        nv, nf = struct.unpack("<QQ", f.read(16))
        v = np.frombuffer(f.read(24 * nv), dtype="<f8").reshape(nv, 3)
        t = np.frombuffer(f.read(12 * nf), dtype="<u4").reshape(nf, 3)
    return v, t


def write_raw(path, v, t):
    with open(path, "wb") as f:
        f.write(struct.pack("<QQ", len(v), len(t)))
        f.write(np.ascontiguousarray(v, dtype="<f8").tobytes())
        f.write(np.ascontiguousarray(t, dtype="<u4").tobytes())


def main():
    src, target, dst = sys.argv[1], int(sys.argv[2]), sys.argv[3]
    v, t = read_raw(src)
    mesh = o3d.geometry.TriangleMesh(o3d.utility.Vector3dVector(np.array(v, dtype=np.float64)),
                                     o3d.utility.Vector3iVector(np.array(t, dtype=np.int32)))
    start = time.perf_counter()
    out = mesh.simplify_quadric_decimation(target_number_of_triangles=target)
    seconds = time.perf_counter() - start
    write_raw(dst, np.asarray(out.vertices), np.asarray(out.triangles))
    print(f'{{"open3d": "{o3d.__version__}", "faces_in": {len(t)}, "faces_out": {len(out.triangles)}, '
          f'"seconds": {seconds:.3f}, "input_faces_per_s": {len(t) / seconds:.0f}}}')


if __name__ == "__main__":
    main()
