# Renders an oblique test scene of known shape with Blender (Cycles, CPU) and writes its exact truth.
#
#   blender -b --factory-startup --python-exit-code 1 -P make_oblique.py -- SCENE OUTDIR [WIDTH HEIGHT]
#
# SCENE: "house" (a gabled house, a shed and a wall on ground with a low mound) or "cliff" (a slope
# rising to an 8 m cliff with a box on its top and a block at its foot). OUTDIR gets:
# - images/view_NN.jpg: two orbits of 16 views each, every camera aimed at the scene's centre;
# - refs_gps.txt: every image's camera centre as WGS84 latitude, longitude and ellipsoidal height
#   (`image_name lat lon alt`, the file `cinepath mesh --refs` reads), about ORIGIN below;
# - truth.ply: the rendered geometry itself, triangles in local ENU metres about ORIGIN (x east, y
#   north, z up: Blender's world frame), so the distance to it is the distance to the true surface;
# - truth.json: the origin, the cameras (centre, look-at point, focal length in pixels) and the scene's
#   parts.
# Materials are emission-only procedural textures (no lights, no shading: the same surface looks the
# same from every view, and there is no render noise to match), sampled in world coordinates.
# Deterministic: a fixed Cycles seed per image, no randomness elsewhere.
import json
import math
import os
import sys

import bpy

argv = sys.argv[sys.argv.index("--") + 1:]
if len(argv) not in (2, 4):
    raise SystemExit("usage: blender -b -P make_oblique.py -- house|cliff OUTDIR [WIDTH HEIGHT]")
SCENE, OUT = argv[0], argv[1]
WIDTH, HEIGHT = (int(argv[2]), int(argv[3])) if len(argv) == 4 else (800, 600)
if SCENE not in ("house", "cliff"):
    raise SystemExit("SCENE must be house or cliff")

ORIGIN = {"house": (47.3769, 8.5417, 420.0), "cliff": (46.8182, 8.2275, 610.0)}[SCENE]  # lat, lon, h (WGS84)
FOCAL_MM, SENSOR_MM = 24.0, 36.0
GROUND_HALF_M, GROUND_STEP_M = 90.0, 2.0

# --- geometry: every part as (name, material, vertices, faces) in ENU metres ---------------------------


def grid(height_of, x0, x1, y0, y1, step):
    nx, ny = int(round((x1 - x0) / step)), int(round((y1 - y0) / step))
    xs = [x0 + (x1 - x0) * i / nx for i in range(nx + 1)]
    ys = [y0 + (y1 - y0) * j / ny for j in range(ny + 1)]
    verts = [(x, y, height_of(x, y)) for y in ys for x in xs]
    faces = []
    for j in range(ny):
        for i in range(nx):
            a = j * (nx + 1) + i
            faces += [(a, a + 1, a + nx + 2), (a, a + nx + 2, a + nx + 1)]
    return verts, faces


def box(x0, y0, z0, x1, y1, z1):
    v = [(x0, y0, z0), (x1, y0, z0), (x1, y1, z0), (x0, y1, z0), (x0, y0, z1), (x1, y0, z1), (x1, y1, z1),
         (x0, y1, z1)]
    f = [(0, 2, 1), (0, 3, 2), (4, 5, 6), (4, 6, 7), (0, 1, 5), (0, 5, 4), (1, 2, 6), (1, 6, 5), (2, 3, 7),
         (2, 7, 6), (3, 0, 4), (3, 4, 7)]
    return v, f


def gabled_house(x0, y0, x1, y1, eave, ridge):  # ridge along x
    ym = 0.5 * (y0 + y1)
    v = [(x0, y0, 0), (x1, y0, 0), (x1, y1, 0), (x0, y1, 0), (x0, y0, eave), (x1, y0, eave), (x1, y1, eave),
         (x0, y1, eave), (x0, ym, ridge), (x1, ym, ridge)]
    f = [(0, 2, 1), (0, 3, 2),  # floor
         (0, 1, 5), (0, 5, 4), (2, 3, 7), (2, 7, 6),  # long walls
         (1, 2, 6), (1, 6, 5), (5, 6, 9), (3, 0, 4), (3, 4, 7), (7, 4, 8),  # gable ends
         (4, 5, 9), (4, 9, 8), (6, 7, 8), (6, 8, 9)]  # roof
    return v, f


def mound(x, y):
    return 1.5 * math.exp(-((x + 22.0)**2 + (y - 18.0)**2) / (2 * 8.0**2))


def cliff_height(x, y):
    # Ground at 0 for y < -10, a 12 % slope up to y = 15 (3 m), then an 8 m cliff (faces added apart) and
    # a plateau at 11 m gently tilted; a low mound on the lower ground.
    if y < -10:
        return mound(x, y)
    if y <= 15:
        return 0.12 * (y + 10) + mound(x, y)
    return 11.0 + 0.03 * x


parts = []
if SCENE == "house":
    parts.append(("ground", "ground", *grid(mound, -GROUND_HALF_M, GROUND_HALF_M, -GROUND_HALF_M, GROUND_HALF_M,
                                             GROUND_STEP_M)))
    parts.append(("house", "house", *gabled_house(-6.0, -4.0, 6.0, 4.0, 5.0, 8.5)))
    parts.append(("shed", "shed", *box(9.0, 5.0, 0.0, 13.0, 8.0, 3.0)))
    parts.append(("wall", "wall", *box(-14.0, -12.0, 0.0, 2.0, -11.6, 1.8)))
else:
    # The lower ground (slope included, y <= 15) and the plateau (y >= 15) as two grids, and the cliff
    # face between them at y = 15.
    H = GROUND_HALF_M
    parts.append(("lower_ground", "ground", *grid(cliff_height, -H, H, -H, 15.0, GROUND_STEP_M)))
    parts.append(("plateau", "rock", *grid(lambda x, y: 11.0 + 0.03 * x, -H, H, 15.0, H, GROUND_STEP_M)))
    n = int(round(2 * H / GROUND_STEP_M))
    cv, cf = [], []
    for i in range(n + 1):
        x = -H + i * GROUND_STEP_M
        cv += [(x, 15.0, cliff_height(x, 15.0)), (x, 15.0, 11.0 + 0.03 * x)]
    for i in range(n):
        a = 2 * i
        cf += [(a, a + 2, a + 3), (a, a + 3, a + 1)]
    parts.append(("cliff_face", "cliff", cv, cf))
    parts.append(("box", "shed", *box(-4.0, 22.0, 11.0 + 0.03 * -4.0 - 0.5, 4.0, 28.0, 15.0)))
    parts.append(("block", "house", *box(8.0, -6.0, 0.0, 14.0, 0.0, 4.0)))

# --- Blender scene ------------------------------------------------------------------------------------
bpy.ops.wm.read_factory_settings(use_empty=True)
scene = bpy.context.scene


def material(name, scale, hue):
    m = bpy.data.materials.new(name)
    m.use_nodes = True
    nodes, links = m.node_tree.nodes, m.node_tree.links
    nodes.clear()
    out = nodes.new("ShaderNodeOutputMaterial")
    emission = nodes.new("ShaderNodeEmission")
    geometry = nodes.new("ShaderNodeNewGeometry")
    noise = nodes.new("ShaderNodeTexNoise")
    noise.inputs["Scale"].default_value = scale
    noise.inputs["Detail"].default_value = 12.0
    noise.inputs["Roughness"].default_value = 0.65
    voronoi = nodes.new("ShaderNodeTexVoronoi")
    voronoi.inputs["Scale"].default_value = scale * 1.7
    ramp = nodes.new("ShaderNodeValToRGB")
    ramp.color_ramp.elements[0].position = 0.3
    ramp.color_ramp.elements[0].color = (0.02, 0.02, 0.02, 1)
    ramp.color_ramp.elements[1].position = 0.7
    ramp.color_ramp.elements[1].color = (0.95, 0.95, 0.95, 1)
    mix = nodes.new("ShaderNodeMixRGB")
    mix.blend_type = "MULTIPLY"
    mix.inputs["Fac"].default_value = 0.6
    tint = nodes.new("ShaderNodeMixRGB")
    tint.blend_type = "MULTIPLY"
    tint.inputs["Fac"].default_value = 1.0
    tint.inputs["Color2"].default_value = (*hue, 1)
    links.new(geometry.outputs["Position"], noise.inputs["Vector"])
    links.new(geometry.outputs["Position"], voronoi.inputs["Vector"])
    links.new(noise.outputs["Fac"], ramp.inputs["Fac"])
    links.new(ramp.outputs["Color"], mix.inputs["Color1"])
    links.new(voronoi.outputs["Color"], mix.inputs["Color2"])
    links.new(mix.outputs["Color"], tint.inputs["Color1"])
    links.new(tint.outputs["Color"], emission.inputs["Color"])
    links.new(emission.outputs["Emission"], out.inputs["Surface"])
    return m


materials = {
    "ground": material("ground", 0.9, (0.75, 0.85, 0.55)),
    "house": material("house", 1.6, (0.95, 0.75, 0.6)),
    "shed": material("shed", 2.0, (0.6, 0.7, 0.95)),
    "wall": material("wall", 2.4, (0.9, 0.9, 0.8)),
    "rock": material("rock", 1.1, (0.85, 0.8, 0.7)),
    "cliff": material("cliff", 1.4, (0.8, 0.7, 0.65)),
}
for name, mat, verts, faces in parts:
    mesh = bpy.data.meshes.new(name)
    mesh.from_pydata(verts, [], faces)
    mesh.update()
    obj = bpy.data.objects.new(name, mesh)
    obj.data.materials.append(materials[mat])
    scene.collection.objects.link(obj)

world = bpy.data.worlds.new("black")
world.use_nodes = True
world.node_tree.nodes["Background"].inputs["Color"].default_value = (0, 0, 0, 1)
scene.world = world
scene.render.engine = "CYCLES"
scene.cycles.device = "CPU"
scene.cycles.samples = 16
scene.cycles.use_denoising = False
scene.cycles.max_bounces = 0
scene.cycles.use_adaptive_sampling = False
scene.render.resolution_x, scene.render.resolution_y = WIDTH, HEIGHT
scene.render.resolution_percentage = 100
scene.render.threads_mode = "FIXED"
scene.render.threads = 2
scene.view_settings.view_transform = "Standard"
scene.render.image_settings.file_format = "JPEG"
scene.render.image_settings.quality = 90

cam_data = bpy.data.cameras.new("camera")
cam_data.lens = FOCAL_MM
cam_data.sensor_fit = "HORIZONTAL"
cam_data.sensor_width = SENSOR_MM
cam_data.clip_end = 1000.0
camera = bpy.data.objects.new("camera", cam_data)
scene.collection.objects.link(camera)
scene.camera = camera

# Two orbits: (radius, height, views, start angle).
ORBITS = [(32.0, 22.0, 16, 0.0), (50.0, 34.0, 16, 11.25)]
TARGET = (0.0, 0.0, 2.0) if SCENE == "house" else (0.0, 8.0, 5.0)
cameras = []
os.makedirs(os.path.join(OUT, "images"), exist_ok=True)
import mathutils  # noqa: E402 (Blender's)

index = 0
for radius, height, count, start in ORBITS:
    for k in range(count):
        a = math.radians(start + 360.0 * k / count)
        c = (TARGET[0] + radius * math.cos(a), TARGET[1] + radius * math.sin(a), height)
        camera.location = c
        direction = mathutils.Vector(TARGET) - mathutils.Vector(c)
        camera.rotation_euler = direction.to_track_quat("-Z", "Y").to_euler()
        scene.cycles.seed = index
        name = "view_%02d.jpg" % index
        scene.render.filepath = os.path.join(OUT, "images", name)
        bpy.ops.render.render(write_still=True)
        cameras.append({"image": name, "centre_enu_m": [round(x, 6) for x in c], "look_at_enu_m": list(TARGET)})
        index += 1

# --- truth and references -----------------------------------------------------------------------------
# The WGS84 conversions of the Blender interop tests (an implementation independent of cinepath's).
sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "..", "interop", "blender"))
from wgs84 import ecef_from_geodetic as ecef, geodetic_from_ecef as geodetic  # noqa: E402


def enu_to_geodetic(e, nn, u):
    lat0, lon0, h0 = ORIGIN
    x0 = ecef(lat0, lon0, h0)
    la, lo = math.radians(lat0), math.radians(lon0)
    dx = -math.sin(lo) * e - math.sin(la) * math.cos(lo) * nn + math.cos(la) * math.cos(lo) * u
    dy = math.cos(lo) * e - math.sin(la) * math.sin(lo) * nn + math.cos(la) * math.sin(lo) * u
    dz = math.cos(la) * nn + math.sin(la) * u
    return geodetic(x0[0] + dx, x0[1] + dy, x0[2] + dz)


with open(os.path.join(OUT, "refs_gps.txt"), "w") as f:
    f.write("# image latitude_deg longitude_deg height_m (WGS84 ellipsoidal): the rendered camera centres\n")
    for cam in cameras:
        lat, lon, h = enu_to_geodetic(*cam["centre_enu_m"])
        f.write("%s %.10f %.10f %.4f\n" % (cam["image"], lat, lon, h))

all_v, all_f = [], []
for name, mat, verts, faces in parts:
    base = len(all_v)
    all_v += verts
    all_f += [(a + base, b + base, c + base) for a, b, c in faces]
with open(os.path.join(OUT, "truth.ply"), "w") as f:
    f.write("ply\nformat ascii 1.0\ncomment local ENU metres about truth.json's origin\n")
    f.write("element vertex %d\nproperty double x\nproperty double y\nproperty double z\n" % len(all_v))
    f.write("element face %d\nproperty list uchar int vertex_indices\nend_header\n" % len(all_f))
    for x, y, z in all_v:
        f.write("%.6f %.6f %.6f\n" % (x, y, z))
    for a, b, c in all_f:
        f.write("3 %d %d %d\n" % (a, b, c))
with open(os.path.join(OUT, "truth.json"), "w") as f:
    json.dump({"scene": SCENE, "origin": {"latitude_deg": ORIGIN[0], "longitude_deg": ORIGIN[1],
                                         "height_m": ORIGIN[2]},
               "focal_length_px": FOCAL_MM / SENSOR_MM * WIDTH, "width_px": WIDTH, "height_px": HEIGHT,
               "parts": [p[0] for p in parts], "cameras": cameras}, f, indent=1)
print("wrote", OUT)
