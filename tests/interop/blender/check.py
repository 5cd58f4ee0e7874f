"""Imports what `cinepath export --format gltf-camera|nuke-chan` wrote with Blender's own importers
(headless) and compares Blender's cameras with plan.json's samples at five frames spread over each
flight. Run by CTest (CMakeLists.txt here):

  blender -b --factory-startup --python-exit-code 1 -P check.py -- gltf|chan OUT_DIR PLAN_JSON
          [--scene SCENE_JSON]

- gltf: OUT_DIR/previs.glb through the bundled glTF importer (io_scene_gltf2); one camera object per
  drone, named after it. Checks position within 1 mm, viewing direction and roll within 0.05 deg, the
  frame rate (the scene's extras) and range (the camera's action), yfov, the lens in the extras, and with
  --scene (a mesh) the mesh's vertex count and bounding box against the scene's GLB and scene.json, and
  its texture (the image bytes Blender packed are the scene GLB's).
- chan: OUT_DIR/<drone>.chan through the bundled "Nuke Animation Format (.chan)" add-on
  (io_anim_nuke_chan, rotation order ZXY, Y-up converted to Blender's Z-up, the filmback given as the
  sensor) onto a new camera per drone. Checks the same pose tolerances, the frame range, and the vertical
  field of view within 0.01 deg.

The expected values come from plan.json alone: ENU position and world_from_camera (camera x right,
y down, z forward), moved into the scene's ENU frame through ECEF (wgs84.py) when --scene has another
origin. Blender's world is ENU for both importers (x east, y north, z up); its camera looks along -Z
with +Y up.
"""
import json
import math
import os
import struct
import sys

import addon_utils
import bpy
from mathutils import Matrix, Quaternion, Vector

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import wgs84  # noqa: E402

POSITION_TOLERANCE_M = 0.001
ANGLE_TOLERANCE_DEG = 0.05
FOV_TOLERANCE_DEG = 0.01

failures = []


def fail(message):
    failures.append(message)
    print("FAIL " + message)


def flights_of(plan):
    if "flights" in plan:
        return [(f["name"], f) for f in plan["flights"]]
    return [(plan["drone"]["name"], plan)]


def expected_pose(sample, plan_origin, scene_origin):
    """Position (ENU, the output frame), forward and up (unit, ENU) of a plan sample."""
    w, x, y, z = sample["world_from_camera"]
    q = Quaternion((w, x, y, z)).normalized()
    forward = q @ Vector((0, 0, 1))
    up = q @ Vector((0, -1, 0))
    # plain Python floats (doubles): mathutils vectors are float32 and would round the truth as Blender does
    position = tuple(sample["position_enu_m"])
    if scene_origin is not None and plan_origin is not None:
        position = wgs84.enu_from_ecef(scene_origin, wgs84.ecef_from_enu(plan_origin, position))
        forward = Vector(wgs84.rotate_between_frames(plan_origin, scene_origin, tuple(forward)))
        up = Vector(wgs84.rotate_between_frames(plan_origin, scene_origin, tuple(up)))
    return position, forward.normalized(), up.normalized()


def angle_deg(a, b):
    return math.degrees(math.atan2(a.cross(b).length, a.dot(b)))


def roll_error_deg(forward, up_blender, up_expected):
    """The angle between two up vectors about the viewing direction."""
    a = (up_blender - forward * up_blender.dot(forward)).normalized()
    b = (up_expected - forward * up_expected.dot(forward)).normalized()
    return angle_deg(a, b)


def five_indices(n):
    return sorted({round(k * (n - 1) / 4) for k in range(5)})


def vertical_fov_deg(camera_spec, focal_mm):
    # the image's height on the sensor: the filmback's width times height_px / width_px (sensor fit)
    height_mm = camera_spec["sensor_width_mm"] * camera_spec["height_px"] / camera_spec["width_px"]
    return math.degrees(2 * math.atan(height_mm / (2 * focal_mm)))


def compare_pose(label, obj, frame, sample, plan_origin, scene_origin):
    bpy.context.scene.frame_set(frame)
    m = obj.matrix_world
    position, forward, up = expected_pose(sample, plan_origin, scene_origin)
    got_position = m.to_translation()
    rotation = m.to_3x3().normalized()
    got_forward = (rotation @ Vector((0, 0, -1))).normalized()
    got_up = (rotation @ Vector((0, 1, 0))).normalized()
    d = math.sqrt(sum((float(got_position[i]) - position[i]) ** 2 for i in range(3)))
    view = angle_deg(got_forward, forward)
    roll = roll_error_deg(got_forward, got_up, up)
    print(f"  {label} frame {frame}: position {d * 1000:.3f} mm, view {view:.5f} deg, roll {roll:.5f} deg")
    if d > POSITION_TOLERANCE_M:
        fail(f"{label} frame {frame}: position {tuple(got_position)} is {d * 1000:.3f} mm from {tuple(position)}")
    if view > ANGLE_TOLERANCE_DEG:
        fail(f"{label} frame {frame}: viewing direction off by {view:.4f} deg")
    if roll > ANGLE_TOLERANCE_DEG:
        fail(f"{label} frame {frame}: roll off by {roll:.4f} deg")
    return d, view, roll


def frame_of(sample, rate):
    return round(sample["time_s"] * rate)


def check_action_range(label, obj, samples, rate):
    action = obj.animation_data.action if obj.animation_data else None
    if action is None:
        fail(f"{label}: no animation")
        return
    want = (frame_of(samples[0], rate), frame_of(samples[-1], rate))
    got = tuple(round(f, 6) for f in action.frame_range)
    if len(samples) == 1:
        # Blender gives a one-key action the range (key, key + 1)
        got = (got[0], got[0])
    print(f"  {label}: frames {got[0]:g}-{got[1]:g} (plan {want[0]}-{want[1]})")
    if got != (float(want[0]), float(want[1])):
        fail(f"{label}: frame range {got}, plan {want}")
    # glTF keeps times as float32 seconds, so a key lands within a thousandth of its frame
    keys = sorted({round(k.co.x, 3) for fc in action.fcurves for k in fc.keyframe_points})
    want_keys = [float(frame_of(s, rate)) for s in samples]
    if keys != want_keys:
        fail(f"{label}: {len(keys)} key frames, not the plan's {len(want_keys)} frames at {rate} fps")


def glb_scene_stats(path):
    """POSITION accessor count and bounds (glTF frame), and the bytes of image 0, of a GLB."""
    data = open(path, "rb").read()
    json_length = struct.unpack_from("<I", data, 12)[0]
    doc = json.loads(data[20:20 + json_length])
    bin_chunk = data[20 + json_length + 8:]
    count = 0
    lo = [math.inf] * 3
    hi = [-math.inf] * 3
    for mesh in doc["meshes"]:
        for prim in mesh["primitives"]:
            acc = doc["accessors"][prim["attributes"]["POSITION"]]
            count += acc["count"]
            lo = [min(a, b) for a, b in zip(lo, acc["min"])]
            hi = [max(a, b) for a, b in zip(hi, acc["max"])]
    image = None
    if doc.get("images"):
        view = doc["bufferViews"][doc["images"][0]["bufferView"]]
        image = bin_chunk[view.get("byteOffset", 0):view.get("byteOffset", 0) + view["byteLength"]]
    return count, lo, hi, image


def check_mesh(scene_json_path, scene):
    folder = os.path.dirname(os.path.abspath(scene_json_path))
    glb_path = os.path.join(folder, scene["mesh"])
    count, lo, hi, image = glb_scene_stats(glb_path)
    meshes = [o for o in bpy.data.objects if o.type == "MESH"]
    if not meshes:
        fail("no mesh imported")
        return
    vertices = sum(len(o.data.vertices) for o in meshes)
    print(f"  mesh: {vertices} vertices in Blender, {count} in {scene['mesh']}")
    if vertices != count:
        fail(f"mesh: {vertices} vertices, {scene['mesh']} has {count}")
    points = [o.matrix_world @ v.co for o in meshes for v in o.data.vertices]
    got_lo = [min(p[i] for p in points) for i in range(3)]
    got_hi = [max(p[i] for p in points) for i in range(3)]
    # glTF (e, u, -n) bounds as ENU
    want_lo = [lo[0], -hi[2], lo[1]]
    want_hi = [hi[0], -lo[2], hi[1]]
    worst = max(max(abs(a - b) for a, b in zip(got_lo, want_lo)), max(abs(a - b) for a, b in zip(got_hi, want_hi)))
    print(f"  mesh: bounding box within {worst * 1000:.3f} mm of the GLB's accessor bounds")
    if worst > POSITION_TOLERANCE_M:
        fail(f"mesh: bounding box {got_lo} .. {got_hi}, the GLB says {want_lo} .. {want_hi}")
    output = scene.get("surface", {}).get("output", {})
    if "bbox_min_m" in output:
        # scene.json rounds to 0.1 mm
        worst = max(max(abs(a - b) for a, b in zip(got_lo, output["bbox_min_m"])),
                    max(abs(a - b) for a, b in zip(got_hi, output["bbox_max_m"])))
        print(f"  mesh: bounding box within {worst * 1000:.3f} mm of scene.json's")
        if worst > POSITION_TOLERANCE_M:
            fail(f"mesh: bounding box {got_lo} .. {got_hi}, scene.json says {output['bbox_min_m']} .. "
                 f"{output['bbox_max_m']}")
    if image is not None:
        images = [i for i in bpy.data.images if i.packed_file is not None]
        if not images:
            fail("mesh: the texture was not imported")
            return
        img = images[0]
        atlas = scene.get("texture", {}).get("atlas", {})
        print(f"  texture: {img.size[0]}x{img.size[1]}, {len(img.packed_file.data)} bytes packed")
        if bytes(img.packed_file.data) != image:
            fail("texture: Blender's image is not the scene GLB's")
        if atlas and (img.size[0], img.size[1]) != (atlas["width_px"], atlas["height_px"]):
            fail(f"texture: {tuple(img.size)}, scene.json says {atlas['width_px']}x{atlas['height_px']}")
        uses = [o for o in meshes if o.data.uv_layers and any(
            n.type == "TEX_IMAGE" and n.image == img for s in o.material_slots if s.material and s.material.node_tree
            for n in s.material.node_tree.nodes)]
        if not uses:
            fail("texture: no mesh has UVs and a material using the image")


def main():
    args = sys.argv[sys.argv.index("--") + 1:]
    kind, out_dir, plan_path = args[:3]
    scene_path = args[args.index("--scene") + 1] if "--scene" in args else None
    plan = json.load(open(plan_path))
    scene = json.load(open(scene_path)) if scene_path else None
    plan_origin = plan.get("origin")
    scene_origin = scene.get("origin") if scene else None
    rate = plan["frame_rate_hz"]
    if rate != round(rate):
        raise SystemExit("the test needs a whole frame rate (Blender's render.fps is an integer)")

    bpy.ops.wm.read_factory_settings(use_empty=True)
    bpy.context.scene.render.fps = int(rate)
    bpy.context.scene.render.fps_base = 1.0
    flights = flights_of(plan)
    worst = [0.0, 0.0, 0.0, 0.0]

    if kind == "gltf":
        # Debian 12's Blender 3.4 glTF importer calls numpy.bool, which Debian's numpy 1.24 no longer has: a
        # mesh without normals (every cinepath scene.glb) fails to import without this alias
        # (docs/camera-tracks.md, "Debian's Blender").
        import numpy
        if not hasattr(numpy, "bool"):
            numpy.bool = bool
        bpy.ops.import_scene.gltf(filepath=os.path.join(out_dir, "previs.glb"))
        got_rate = bpy.context.scene.get("frame_rate_hz")
        print(f"  scene: frame_rate_hz {got_rate}, frames {bpy.context.scene.get('frame_start')}-"
              f"{bpy.context.scene.get('frame_end')}")
        if got_rate != rate:
            fail(f"scene extras: frame_rate_hz {got_rate}, plan {rate}")
        cameras = [o for o in bpy.data.objects if o.type == "CAMERA"]
        if len(cameras) != len(flights):
            fail(f"{len(cameras)} cameras, the plan has {len(flights)} drones")
        for name, flight in flights:
            obj = bpy.data.objects.get(name)
            if obj is None or obj.type != "CAMERA":
                fail(f"no camera named {name}")
                continue
            samples = flight["samples"]
            check_action_range(name, obj, samples, rate)
            for i in five_indices(len(samples)):
                d, view, roll = compare_pose(name, obj, frame_of(samples[i], rate), samples[i], plan_origin,
                                             scene_origin)
                worst[:3] = [max(worst[0], d), max(worst[1], view), max(worst[2], roll)]
            yfov = math.degrees(obj.data.angle_y)
            want = vertical_fov_deg(flight["camera"], samples[0]["focal_length_mm"])
            print(f"  {name}: yfov {yfov:.5f} deg (plan {want:.5f})")
            if abs(yfov - want) > FOV_TOLERANCE_DEG:
                fail(f"{name}: yfov {yfov} deg, plan {want}")
            focal = list(obj.get("focal_length_mm", []))
            if [round(f, 6) for f in focal] != [round(s["focal_length_mm"], 6) for s in samples]:
                fail(f"{name}: extras focal_length_mm is not the plan's per sample")
        if scene is not None and scene.get("mesh"):
            check_mesh(scene_path, scene)
    elif kind == "chan":
        addon_utils.enable("io_anim_nuke_chan", default_set=True)
        for name, flight in flights:
            camera = flight["camera"]
            data = bpy.data.cameras.new(name)
            obj = bpy.data.objects.new(name, data)
            bpy.context.scene.collection.objects.link(obj)
            bpy.context.view_layer.objects.active = obj
            image_height_mm = camera["sensor_width_mm"] * camera["height_px"] / camera["width_px"]
            result = bpy.ops.import_scene.import_chan(filepath=os.path.join(out_dir, name + ".chan"),
                                                      rotation_order="ZXY", z_up=True,
                                                      sensor_width=camera["sensor_width_mm"],
                                                      sensor_height=image_height_mm)
            if result != {"FINISHED"}:
                fail(f"{name}.chan: the importer returned {result}")
                continue
            samples = flight["samples"]
            check_action_range(name, obj, samples, rate)
            for i in five_indices(len(samples)):
                frame = frame_of(samples[i], rate)
                d, view, roll = compare_pose(name, obj, frame, samples[i], plan_origin, scene_origin)
                worst[:3] = [max(worst[0], d), max(worst[1], view), max(worst[2], roll)]
                fov = math.degrees(obj.data.angle_y)
                want = vertical_fov_deg(camera, samples[i]["focal_length_mm"])
                worst[3] = max(worst[3], abs(fov - want))
                print(f"  {name} frame {frame}: vertical fov {fov:.5f} deg (plan {want:.5f}), lens "
                      f"{obj.data.lens:.4f} mm (plan {samples[i]['focal_length_mm']})")
                if abs(fov - want) > FOV_TOLERANCE_DEG:
                    fail(f"{name} frame {frame}: vertical field of view {fov} deg, plan {want}")
    else:
        raise SystemExit("kind must be gltf or chan")

    print(f"worst: position {worst[0] * 1000:.3f} mm, view {worst[1]:.5f} deg, roll {worst[2]:.5f} deg" +
          (f", vertical fov {worst[3]:.6f} deg" if kind == "chan" else ""))
    if failures:
        print(f"{len(failures)} check(s) failed")
        sys.exit(1)
    print("ok")


main()
