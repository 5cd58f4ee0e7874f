#!/usr/bin/env python3
"""Writes the extremes table's inputs (tests/extremes/cases.txt): shot lists at the poles, on the
antimeridian, 9 km up, with a 4-1200 mm zoom, straight down to straight up, one frame, a zero-length shot
and a 21 M-sample plan; and tiny GLB scenes (no faces, one triangle, degenerate triangles, a triangle
10 km from the origin) with their scene.json. Python's standard library only. The two plan.json files
are `cinepath plan` outputs:
  cinepath plan one_frame_shots.json --scene one_triangle.json -o one_frame_plan.json
  cinepath plan antimeridian_shots.json -o antimeridian_plan.json
"""
import json
import struct

CAMERA = {"filmback": "super35", "width_px": 1920, "height_px": 1080, "min_focal_length_mm": 4,
          "max_focal_length_mm": 1200, "min_f_number": 0.95, "max_f_number": 64, "min_focus_distance_m": 0.1}
ORBIT = {"name": "orbit", "type": "ORBIT", "subject": "keeper", "duration_s": 4, "radius_m": 20, "height_m": 5,
         "turns": 0.1}


def shots(origin, shot_list, rate=30):
    d = {"schema": "cinepath.shots/1", "frame_rate_hz": rate, "camera": CAMERA, "drone": "px4-multirotor",
         "actors": [{"name": "keeper", "height_m": 1.8, "position_enu_m": [0, 0, 0]}], "shots": shot_list}
    if origin:
        d["origin"] = origin
    return d


def keys(pitches_and_headings):
    return [{"name": "keys", "type": "KEYFRAMES", "duration_s": 4, "keys": [
        {"time_s": 2 * i, "position_enu_m": [0, 5 * i, 20], "heading_deg": h, "pitch_deg": p}
        for i, (p, h) in enumerate(pitches_and_headings)]}]


FILES = {
    "north_pole_shots.json": shots({"lat_deg": 90, "lon_deg": 0, "height_m": 2800}, [ORBIT]),
    "south_pole_shots.json": shots({"lat_deg": -90, "lon_deg": 0, "height_m": 2800}, [ORBIT]),
    "antimeridian_shots.json": shots({"lat_deg": -16.5, "lon_deg": 179.9999, "height_m": 10},
                                     [dict(ORBIT, radius_m=60, turns=0.5, duration_s=40, direction="cw",
                                           start_bearing_deg=0)], rate=5),
    "altitude_9km_shots.json": shots({"lat_deg": 27.9881, "lon_deg": 86.925, "height_m": 9000}, [ORBIT]),
    "one_frame_shots.json": shots(None, [dict(ORBIT, duration_s=0)]),
    "zero_length_shot_shots.json": shots(None, [dict(ORBIT, duration_s=0, name="hold"), dict(ORBIT, name="go")]),
    "twenty_million_samples_shots.json": shots(None, [dict(ORBIT, duration_s=700000)]),
    "straight_down_then_up_shots.json": shots(None, keys([(-90, 0), (0, 0), (90, 0)])),
    "slerp_0_and_180_shots.json": shots(None, keys([(-10, 0), (-10, 0), (-10, 180)])),
    "lens_4mm_to_1200mm_shots.json": shots(None, [dict(ORBIT, lens={
        "focal_length_mm": 4, "focal_length_end_mm": 1200, "focus": "infinity",
        "f_number": [{"time_s": 0, "f_number": 0.95}, {"time_s": 4, "f_number": 64}]})]),
}


def glb(positions_enu, triangles):
    """glTF 2.0 binary; ENU (e, n, u) stored as glTF (e, u, -n), as cinepath writes it."""
    gltf = [(e, u, -n) for e, n, u in positions_enu]
    pos = b"".join(struct.pack("<3f", *p) for p in gltf)
    idx = b"".join(struct.pack("<3I", *t) for t in triangles)
    accessors = [{"bufferView": 0, "componentType": 5126, "count": len(gltf), "type": "VEC3",
                  "min": [min(p[i] for p in gltf) for i in range(3)],
                  "max": [max(p[i] for p in gltf) for i in range(3)]}]
    views = [{"buffer": 0, "byteOffset": 0, "byteLength": len(pos)}]
    primitive = {"attributes": {"POSITION": 0}}
    if triangles:
        accessors.append({"bufferView": 1, "componentType": 5125, "count": 3 * len(triangles), "type": "SCALAR"})
        views.append({"buffer": 0, "byteOffset": len(pos), "byteLength": len(idx)})
        primitive["indices"] = 1
    else:
        primitive["mode"] = 0  # points: a mesh with no triangles
        idx = b""
    binary = pos + idx
    doc = {"asset": {"version": "2.0"}, "scenes": [{"nodes": [0]}], "scene": 0, "nodes": [{"mesh": 0}],
           "buffers": [{"byteLength": len(binary)}], "bufferViews": views, "accessors": accessors,
           "meshes": [{"primitives": [primitive]}]}
    js = json.dumps(doc, separators=(",", ":")).encode()
    js += b" " * (-len(js) % 4)
    total = 12 + 8 + len(js) + 8 + len(binary)
    return (b"glTF" + struct.pack("<II", 2, total) + struct.pack("<I", len(js)) + b"JSON" + js +
            struct.pack("<I", len(binary)) + b"BIN\0" + binary)


def scene(name, positions, triangles):
    open(name + ".glb", "wb").write(glb(positions, triangles))
    json.dump({"format": "cinepath.scene", "version": 1,
               "origin": {"lat_deg": 46.84265, "lon_deg": -91.99445, "height_m": 153.0}, "mesh": name + ".glb"},
              open(name + ".json", "w"), indent=1)


if __name__ == "__main__":
    for name, d in FILES.items():
        json.dump(d, open(name, "w"), indent=1)
    scene("no_faces", [(0, 0, 0), (1, 0, 0), (0, 1, 0)], [])
    scene("one_triangle", [(-50, -50, -1), (50, -50, -1), (0, 60, -1)], [(0, 1, 2)])
    scene("degenerate", [(-50, -50, -1), (50, -50, -1), (0, -50, -1), (5, 5, -1), (5, 5, -1), (6, 6, -1)],
          [(0, 1, 2), (3, 4, 5), (0, 0, 0)])
    scene("ten_km_away", [(9950, 9950, -1), (10050, 9950, -1), (10000, 10060, -1)], [(0, 1, 2)])
