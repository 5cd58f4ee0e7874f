#!/usr/bin/env python3
"""Writes the synthetic plans the Blender interop tests export (plain Python, no cinepath code):

  antimeridian/plan.json + scene.json  a 3 km flight east across the 180th meridian (Taveuni, Fiji),
                                       its scene's origin on the other side (lon -179.995)
  ten_km/plan.json                     a 10.2 km straight flight at 40 m/s, 10 fps
  one_sample/plan.json                 a plan of one sample
  straight_down/plan.json              a locked-off camera turning while it looks straight down, then
                                       tilting up with roll (the ZXY Euler angles' gimbal lock)

Every camera turns, tilts and rolls, so that a wrong axis or sign shows at any frame.

  python3 make_plans.py TEMPLATE_PLAN_JSON OUT_DIR
"""
import copy
import json
import math
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import wgs84  # noqa: E402


def quaternion_from_matrix(m):
    """Hamilton (w, x, y, z) of a rotation matrix given as three columns."""
    (m00, m10, m20), (m01, m11, m21), (m02, m12, m22) = m
    trace = m00 + m11 + m22
    if trace > 0:
        s = 2 * math.sqrt(trace + 1)
        q = (s / 4, (m21 - m12) / s, (m02 - m20) / s, (m10 - m01) / s)
    elif m00 > m11 and m00 > m22:
        s = 2 * math.sqrt(1 + m00 - m11 - m22)
        q = ((m21 - m12) / s, s / 4, (m01 + m10) / s, (m02 + m20) / s)
    elif m11 > m22:
        s = 2 * math.sqrt(1 + m11 - m00 - m22)
        q = ((m02 - m20) / s, (m01 + m10) / s, s / 4, (m12 + m21) / s)
    else:
        s = 2 * math.sqrt(1 + m22 - m00 - m11)
        q = ((m10 - m01) / s, (m02 + m20) / s, (m12 + m21) / s, s / 4)
    if q[0] < 0:
        q = tuple(-c for c in q)
    return [round(c, 9) for c in q]


def world_from_camera(heading_deg, pitch_deg, roll_deg):
    """Camera x right, y down, z forward in ENU: looking along the compass heading, pitched up by
    pitch_deg, rolled clockwise (as seen from behind) by roll_deg."""
    h, p, r = (math.radians(a) for a in (heading_deg, pitch_deg, roll_deg))
    forward = (math.sin(h) * math.cos(p), math.cos(h) * math.cos(p), math.sin(p))
    # level right (perpendicular to forward and up), well defined at pitch ±90 through the heading
    right0 = (math.cos(h), -math.sin(h), 0.0)
    down0 = cross(forward, right0)
    right = tuple(math.cos(r) * a + math.sin(r) * b for a, b in zip(right0, down0))
    down = cross(forward, right)
    return quaternion_from_matrix((right, down, forward))


def cross(a, b):
    return (a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0])


def sample(template, t, position, heading, pitch, roll, focal_mm, focus_m, shot):
    s = copy.deepcopy(template)
    s.update({"time_s": round(t, 9), "position_enu_m": [round(c, 6) for c in position],
              "world_from_camera": world_from_camera(heading, pitch, roll),
              "drone_heading_deg": round(heading % 360, 6), "gimbal_pitch_deg": round(pitch, 6),
              "gimbal_roll_deg": round(roll, 6), "gimbal_yaw_deg": 0.0, "focal_length_mm": focal_mm,
              "focus_distance_m": None if math.isinf(focus_m) else focus_m, "shot": shot, "subjects_in_frame": []})
    return s


def plan(template, origin, rate, samples, shot):
    for s in samples:
        lat, lon, h = wgs84.geodetic_from_ecef(*wgs84.ecef_from_enu(origin, s["position_enu_m"]))
        s["lat_deg"], s["lon_deg"], s["height_m"] = round(lat, 9), round(lon, 9), round(h, 6)
    p = copy.deepcopy(template)
    p["origin"] = origin
    p["frame_rate_hz"] = rate
    p["shots"] = [{"name": shot, "type": "FLYBY", "subject": "", "transition": "continuous", "start_time_s": 0.0,
                   "end_time_s": samples[-1]["time_s"]}]
    p["subjects"] = []
    p["keyframes"] = []
    p["samples"] = samples
    p["feasibility"] = {"feasible": True, "violations": [], "skipped": []}
    return p


def write(path, document):
    os.makedirs(os.path.dirname(path), exist_ok=True)
    with open(path, "w") as f:
        json.dump(document, f, indent=2)
        f.write("\n")


def main():
    template_path, out = sys.argv[1:3]
    template = json.load(open(template_path))
    s0 = template["samples"][0]
    template["camera"]["max_focal_length_mm"] = 120.0

    # Across the antimeridian: the plan's origin at lon 179.99, the flight 3 km east (180 at ~1.07 km).
    rate = 30
    origin = {"lat_deg": -16.8, "lon_deg": 179.99, "height_m": 40.0}
    samples = []
    n = 151
    for k in range(n):
        t = k / rate
        u = k / (n - 1)
        samples.append(sample(s0, t, (-500 + 3000 * u, 200 * math.sin(3 * u), 120 + 30 * u), 60 + 200 * u,
                              -35 + 50 * u, -20 + 40 * u, 24 + 60 * u, 50 + 100 * u, "across"))
    write(f"{out}/antimeridian/plan.json", plan(template, origin, rate, samples, "across"))
    write(f"{out}/antimeridian/scene.json",
          {"format": "cinepath.scene", "version": 1, "origin": {"lat_deg": -16.79, "lon_deg": -179.995,
                                                                  "height_m": 10.0}})

    # 10.2 km at 40 m/s, 10 fps (Blender's .chan importer sets the frame for every line: ~10 ms each).
    rate = 10
    origin = {"lat_deg": 46.8, "lon_deg": -92.0, "height_m": 200.0}
    samples = []
    n = 255 * rate + 1
    for k in range(n):
        t = k / rate
        u = k / (n - 1)
        samples.append(sample(s0, t, (10000 * u, 2000 * u, 80 + 40 * u), 78.7 + 30 * math.sin(7 * u),
                              -15 + 10 * math.cos(5 * u), 5 * math.sin(11 * u), 35.0, math.inf if k % 2 else 300.0,
                              "long"))
    document = plan(template, origin, rate, samples, "long")
    write(f"{out}/ten_km/plan.json", document)

    # One sample.
    write(f"{out}/one_sample/plan.json",
          plan(template, origin, 30, [sample(s0, 0.0, (3, -4, 25), 200, -30, 10, 50.0, 20.0, "still")], "still"))

    # Straight down, turning, then tilting up and rolling.
    rate = 24
    samples = []
    n = 97
    for k in range(n):
        t = k / rate
        u = k / (n - 1)
        pitch = -90.0 if u < 0.5 else -90 + 120 * (u - 0.5)
        roll = 0.0 if u < 0.5 else 30 * (u - 0.5)
        samples.append(sample(s0, t, (5 * u, -3 * u, 60), 350 + 60 * u, pitch, roll, 28.0, 60.0, "down"))
    write(f"{out}/straight_down/plan.json", plan(template, origin, rate, samples, "down"))


if __name__ == "__main__":
    main()
