# Blender Cycles render of samples of a cinepath plan.json, for bench/render_vs_cycles.sh and
# bench/render_sequence_vs_cycles.sh:
#   blender -b --factory-startup --python-exit-code 1 -P bench/cycles_render.py -- \
#       scene.glb plan.json SAMPLE WIDTH HEIGHT SPP OUT.exr [THREADS]
# SAMPLE may be a range A-B: then every sample from A to B is rendered in turn in the one Blender process,
# with persistent data (the scene synced and its BVH built once; each frame only moves the camera and
# changes the lens), each to OUT with "#" replaced by the sample index (6 digits).
# Like for like with `cinepath render --shading flat --exposure fixed` (docs/render.md):
# - every material replaced by the mesh's first colour attribute (glTF COLOR_0, linear) into an Emission
#   shader of strength 1; no bounces, so the pixel value is the vertex colour, unlit;
# - the world is cinepath's sky: horizon (0.75, 0.80, 0.88) to zenith (0.25, 0.40, 0.75) by sqrt(up),
#   0.18 grey below the horizon (preview/preview_scene.cc, PreviewScene::Sky);
# - the plan sample's camera: position, world_from_camera, focal length, filmback width (sensor fit
#   HORIZONTAL), thin lens focused at focus_distance_m (null = infinity) with aperture f/f_number, round
#   (no blades);
# - box pixel filter 1 px wide, no adaptive sampling, no denoising, no motion blur, 'Standard' view
#   transform; linear float EXR out; CPU, THREADS threads (default 2).
# Prints "import_seconds S" and "render_seconds S" (the render alone: scene sync, BVH and sampling), one
# "render_seconds S" line per sample of a range.
#
# Frames: Blender's world is ENU. The glTF importer turns glTF's Y-up into Blender's Z-up, (x, y, z) ->
# (x, -z, y), and cinepath GLBs store ENU (e, n, u) as glTF (e, u, -n), so the mesh lands at (e, n, u).
# cinepath's camera frame is x right, y down, z forward; Blender's camera looks along -z with y up:
# R_blender = R_world_from_camera * diag(1, -1, -1). plan.json quaternions are [w, x, y, z].
import json
import math
import sys
import time

import bpy
import mathutils
import numpy

if not hasattr(numpy, "bool"):
    numpy.bool = bool  # Blender 3.4's glTF importer uses numpy.bool, removed in numpy 1.24 (Debian 12)

argv = sys.argv[sys.argv.index("--") + 1:]
if len(argv) not in (7, 8):
    raise SystemExit("usage: blender -b -P cycles_render.py -- scene.glb plan.json SAMPLE W H SPP OUT.exr [THREADS]")
glb, plan_path, width, height, spp, out = argv[0], argv[1], int(argv[3]), int(argv[4]), int(argv[5]), argv[6]
first, _, last = argv[2].partition("-")
samples_to_render = list(range(int(first), int(last or first) + 1))
threads = int(argv[7]) if len(argv) > 7 else 2

plan = json.load(open(plan_path))
camera_spec = plan["camera"]

start = time.time()
bpy.ops.wm.read_factory_settings(use_empty=True)
bpy.ops.import_scene.gltf(filepath=glb)
print("import_seconds %.3f" % (time.time() - start))
scene = bpy.context.scene

# Emission of the first colour attribute on every mesh.
meshes = [obj for obj in scene.objects if obj.type == "MESH"]
if not meshes:
    raise SystemExit("no mesh in " + glb)
for obj in meshes:
    attributes = obj.data.color_attributes
    material = bpy.data.materials.new("cinepath_flat")
    material.use_nodes = True
    nodes, links = material.node_tree.nodes, material.node_tree.links
    nodes.clear()
    output = nodes.new("ShaderNodeOutputMaterial")
    emission = nodes.new("ShaderNodeEmission")
    emission.inputs["Strength"].default_value = 1.0
    if len(attributes):
        color = nodes.new("ShaderNodeVertexColor")  # "Color Attribute" node
        color.layer_name = attributes[0].name
        links.new(color.outputs["Color"], emission.inputs["Color"])
    else:
        emission.inputs["Color"].default_value = (0.5, 0.5, 0.5, 1)  # cinepath's colour of an uncoloured mesh
    links.new(emission.outputs["Emission"], output.inputs["Surface"])
    obj.data.materials.clear()
    obj.data.materials.append(material)
    for polygon in obj.data.polygons:
        polygon.material_index = 0


# cinepath's sky. In a world shader, Texture Coordinate "Generated" is the ray direction (world frame).
def sky_world():
    world = bpy.data.worlds.new("cinepath_sky")
    world.use_nodes = True
    nodes, links = world.node_tree.nodes, world.node_tree.links
    nodes.clear()
    output = nodes.new("ShaderNodeOutputWorld")
    background = nodes.new("ShaderNodeBackground")
    background.inputs["Strength"].default_value = 1.0
    coords = nodes.new("ShaderNodeTexCoord")
    split = nodes.new("ShaderNodeSeparateXYZ")
    links.new(coords.outputs["Generated"], split.inputs["Vector"])
    up = nodes.new("ShaderNodeMath")  # max(z, 0)
    up.operation = "MAXIMUM"
    up.inputs[1].default_value = 0.0
    links.new(split.outputs["Z"], up.inputs[0])
    root = nodes.new("ShaderNodeMath")  # sqrt(up)
    root.operation = "SQRT"
    links.new(up.outputs[0], root.inputs[0])
    gradient = nodes.new("ShaderNodeMixRGB")  # horizon + sqrt(up) (zenith - horizon)
    gradient.blend_type = "MIX"
    gradient.inputs["Color1"].default_value = (0.75, 0.80, 0.88, 1)
    gradient.inputs["Color2"].default_value = (0.25, 0.40, 0.75, 1)
    links.new(root.outputs[0], gradient.inputs["Fac"])
    below = nodes.new("ShaderNodeMath")  # 1 when z < 0
    below.operation = "LESS_THAN"
    below.inputs[1].default_value = 0.0
    links.new(split.outputs["Z"], below.inputs[0])
    ground = nodes.new("ShaderNodeMixRGB")
    ground.blend_type = "MIX"
    ground.inputs["Color2"].default_value = (0.18, 0.18, 0.18, 1)
    links.new(gradient.outputs["Color"], ground.inputs["Color1"])
    links.new(below.outputs[0], ground.inputs["Fac"])
    links.new(ground.outputs["Color"], background.inputs["Color"])
    links.new(background.outputs["Background"], output.inputs["Surface"])
    return world


scene.world = sky_world()

# The camera, placed and focused for each sample.
camera_data = bpy.data.cameras.new("cinepath")
camera = bpy.data.objects.new("cinepath", camera_data)
scene.collection.objects.link(camera)
scene.camera = camera


def place_camera(sample):
    w, x, y, z = sample["world_from_camera"]
    rotation = mathutils.Quaternion((w, x, y, z)).normalized().to_matrix() @ mathutils.Matrix(
        ((1, 0, 0), (0, -1, 0), (0, 0, -1)))
    camera_data.type = "PERSP"
    camera_data.sensor_fit = "HORIZONTAL"
    camera_data.sensor_width = camera_spec["sensor_width_mm"]
    camera_data.lens_unit = "MILLIMETERS"
    camera_data.lens = sample["focal_length_mm"]
    camera_data.shift_x = camera_data.shift_y = 0.0
    camera_data.clip_start = 0.001
    camera_data.clip_end = 1e7
    focus = sample["focus_distance_m"]
    camera_data.dof.use_dof = True
    camera_data.dof.focus_object = None
    camera_data.dof.focus_distance = focus if focus is not None else 1e9  # null = infinity
    camera_data.dof.aperture_fstop = sample["f_number"]
    camera_data.dof.aperture_blades = 0
    camera_data.dof.aperture_rotation = 0.0
    camera_data.dof.aperture_ratio = 1.0
    camera.matrix_world = mathutils.Matrix.Translation(sample["position_enu_m"]) @ rotation.to_4x4()


scene.render.engine = "CYCLES"
scene.cycles.device = "CPU"
scene.cycles.samples = spp
scene.cycles.use_adaptive_sampling = False
scene.cycles.use_denoising = False
scene.cycles.max_bounces = 0
scene.cycles.diffuse_bounces = scene.cycles.glossy_bounces = scene.cycles.transmission_bounces = 0
scene.cycles.volume_bounces = scene.cycles.transparent_max_bounces = 0
scene.cycles.caustics_reflective = scene.cycles.caustics_refractive = False
scene.cycles.pixel_filter_type = "BOX"
scene.cycles.filter_width = 1.0
scene.cycles.seed = 0
scene.cycles.film_exposure = 1.0
scene.cycles.use_auto_tile = False
scene.render.film_transparent = False
scene.render.use_motion_blur = False
scene.render.threads_mode = "FIXED"
scene.render.threads = threads
scene.render.resolution_x = width
scene.render.resolution_y = height
scene.render.resolution_percentage = 100
scene.render.pixel_aspect_x = scene.render.pixel_aspect_y = 1.0
scene.render.use_border = False
scene.display_settings.display_device = "sRGB"
scene.view_settings.view_transform = "Standard"
scene.view_settings.look = "None"
scene.view_settings.exposure = 0.0
scene.view_settings.gamma = 1.0
scene.render.image_settings.file_format = "OPEN_EXR"
scene.render.image_settings.color_mode = "RGB"
scene.render.image_settings.color_depth = "32"
scene.render.image_settings.exr_codec = "ZIP"
scene.render.use_compositing = False
scene.render.use_sequencer = False
scene.render.use_persistent_data = True  # a range: the scene synced once, only the camera changes
for k in samples_to_render:
    place_camera(plan["samples"][k])
    scene.render.filepath = out.replace("#", "%06d" % k)
    start = time.time()
    bpy.ops.render.render(write_still=True)
    print("render_seconds %.3f" % (time.time() - start))
