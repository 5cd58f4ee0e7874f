#!/usr/bin/env python3
"""`cinepath plan --scene` with a shot list made about its own origin (a surveyed point on the ground, or the
origin of an earlier reconstruction), through the real binary.

The same shots are planned three ways on the six-photo Brighton scene: about the scene's origin (no "origin"
in the list), about an origin 37 m straight below it (on the ground), and about one 420 m east, 310 m south
and 20 m lower, with every position of the list re-expressed in that frame (tests/interop/blender/wgs84.py,
an implementation independent of cinepath's). The plans must put every sample at the same place on earth
(its lat/lon/height) and give the same heading and gimbal pitch (taken where the drone is): the mesh is
moved into the list's frame, not the list onto the mesh. Before, such a list was refused (exit 2).

usage: plan_own_origin.py CINEPATH SOURCE_DIR WORK_DIR
"""
import json
import math
import os
import subprocess
import sys

cinepath, source, work = sys.argv[1:4]
sys.path.insert(0, os.path.join(source, "tests", "interop", "blender"))
import wgs84  # noqa: E402

scene = os.path.join(source, "tests", "golden", "mesh", "brighton6_binary", "expected", "scene.json")
scene_origin = json.load(open(scene))["origin"]
os.makedirs(work, exist_ok=True)

# Actors on the ground ([e, n]), a moving one, and shots placed by bearings and by the subject's travel.
shots = {
    "schema": "cinepath.shots/1",
    "frame_rate_hz": 10,
    "camera": {"filmback": "super35", "width_px": 1920, "height_px": 1080, "min_focal_length_mm": 24,
               "max_focal_length_mm": 120, "min_f_number": 2.8, "max_f_number": 16},
    "drone": "px4-multirotor",
    "actors": [
        {"name": "keeper", "height_m": 1.8, "position_enu_m": [12.0, -12.0], "above_ground_m": 0},
        {"name": "walker", "height_m": 1.75, "keyframes": [
            {"time_s": 0, "position_enu_m": [8.0, -20.0], "above_ground_m": 0},
            {"time_s": 20, "position_enu_m": [20.0, -4.0], "above_ground_m": 0}]},
    ],
    "shots": [
        {"name": "orbit", "type": "ORBIT", "subject": "keeper", "duration_s": 6, "radius_m": 10, "height_m": 6,
         "turns": 0.25, "direction": "ccw", "start_bearing_deg": 200, "easing": "smootherstep",
         "lens": {"frame_height_fraction": 0.3, "f_number": 2.8}},
        {"name": "chase", "type": "CHASE", "subject": "walker", "duration_s": 6, "distance_m": 8, "height_m": 4,
         "blend_s": 3, "lens": {"focal_length_mm": 35, "f_number": 4}},
        {"name": "reveal", "type": "REVEAL", "subject": "keeper", "duration_s": 6, "distance_m": 8,
         "distance_end_m": 20, "height_m": 3, "height_end_m": 15, "bearing_deg": 220, "tilt_start_deg": -5,
         "transition": "cut", "lens": {"focal_length_mm": 24, "f_number": 5.6}},
    ],
}


def fail(message):
    print("plan_own_origin: FAIL: " + message)
    sys.exit(1)


def plan(name, shot_list):
    shots_path = os.path.join(work, name + "_shots.json")
    out = os.path.join(work, name + "_plan.json")
    json.dump(shot_list, open(shots_path, "w"), indent=1)
    run = subprocess.run([cinepath, "plan", shots_path, "--scene", scene, "-o", out], capture_output=True, text=True)
    if run.returncode != 0:
        fail(f"{name}: exit {run.returncode}: {run.stderr.strip()}")
    return json.load(open(out))


def moved(shot_list, origin):
    """The list about `origin`: each [e, n] (a point on the scene's ground; its height, unknown here, is taken
    37 m below the scene's origin, where that ground lies) re-expressed in the new frame."""
    def move(en):
        e, n, _ = wgs84.enu_from_ecef(origin, wgs84.ecef_from_enu(scene_origin, (en[0], en[1], -37.0)))
        return [e, n]
    out = json.loads(json.dumps(shot_list))
    out["origin"] = origin
    for actor in out["actors"]:
        if "position_enu_m" in actor:
            actor["position_enu_m"] = move(actor["position_enu_m"])
        for key in actor.get("keyframes", []):
            key["position_enu_m"] = move(key["position_enu_m"])
    return out


def compare(name, got, want, metres, degrees):
    if got["origin"]["lat_deg"] == want["origin"]["lat_deg"] and got["origin"]["height_m"] == want["origin"]["height_m"]:
        fail(f"{name}: the plan is about the scene's origin, not the list's")
    a, b = got["samples"], want["samples"]
    if len(a) != len(b):
        fail(f"{name}: {len(a)} samples, expected {len(b)}")
    worst_m, worst_deg = 0.0, 0.0
    for s, t in zip(a, b):
        ps = wgs84.ecef_from_geodetic(s["lat_deg"], s["lon_deg"], s["height_m"])
        pt = wgs84.ecef_from_geodetic(t["lat_deg"], t["lon_deg"], t["height_m"])
        worst_m = max(worst_m, math.dist(ps, pt))
        for key in ("drone_heading_deg", "gimbal_pitch_deg"):
            d = (s[key] - t[key] + 180) % 360 - 180
            worst_deg = max(worst_deg, abs(d))
    if worst_m > metres or worst_deg > degrees:
        fail(f"{name}: samples {worst_m:.4f} m and {worst_deg:.5f} deg from the plan about the scene's origin "
             f"(allowed {metres} m, {degrees} deg)")
    print(f"plan_own_origin: {name}: every sample within {worst_m:.5f} m and {worst_deg:.6f} deg")


reference = plan("scene", shots)
if reference["origin"]["height_m"] != scene_origin["height_m"]:
    fail("the list without an origin is not planned about the scene's")

# 37 m straight down: the same tangent plane, so the same numbers to rounding.
below = {"lat_deg": scene_origin["lat_deg"], "lon_deg": scene_origin["lon_deg"], "height_m": scene_origin["height_m"] - 37}
compare("below", plan("below", dict(shots, origin=below)), reference, 0.001, 1e-5)

# 420 m east, 310 m south, 20 m lower: bearings are the list's (the frames turn by 0.004 deg here, a few mm at
# these distances), and each [e, n] is re-expressed at an assumed height; 2 cm and 0.02 deg.
lat, lon, h = wgs84.geodetic_from_ecef(*wgs84.ecef_from_enu(scene_origin, (420.0, -310.0, -20.0)))
away = {"lat_deg": round(lat, 9), "lon_deg": round(lon, 9), "height_m": round(h, 4)}
compare("away", plan("away", moved(shots, away)), reference, 0.02, 0.02)
print("plan_own_origin: ok")
