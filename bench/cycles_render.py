# Blender Cycles render of one cinepath plan sample, for bench/render_vs_cycles.sh:
#   blender -b --factory-startup --python-exit-code 1 -P cycles_render.py -- \
#       scene.glb plan.json SAMPLE WIDTH HEIGHT SPP OUT.exr
# Like for like with `cinepath render --shading flat`: vertex colours as emission, no bounces, a box pixel
# filter of 1 px, no adaptive sampling, no denoising, linear EXR out, a uniform 0.18 grey world (what
# cinepath shows where a ray leaves the mesh below the horizon), the plan's camera and thin lens.
# Prints "render_seconds S" (the render alone, after the import).
import json
import sys
import time

import bpy
import mathutils
import numpy

numpy.bool = bool  # Debian's numpy 1.24 and Blender 3.4's glTF importer

argv = sys.argv[sys.argv.index("--") + 1:]
glb, plan_path, k, width, height, spp, out = argv[0], argv[1], int(argv[2]), int(argv[3]), int(argv[4]), int(argv[5]), argv[6]
plan = json.load(open(plan_path))
sample = plan["samples"][k]
camera_spec = plan["camera"]

bpy.ops.wm.read_factory_settings(use_empty=True)
bpy.ops.import_scene.gltf(filepath=glb)

# Emission of the vertex colour on every mesh.
for obj in bpy.context.scene.objects:
    if obj.type != "MESH":
        continue
    attribute = obj.data.color_attributes[0].name if obj.data.color_attributes else None
    material = bpy.data.materials.new("emission")
    material.use_nodes = True
    nodes, links = material.node_tree.nodes, material.node_tree.links
    nodes.clear()
    output = nodes.new("ShaderNodeOutputMaterial")
    emission = nodes.new("ShaderNodeEmission")
    emission.inputs["Strength"].default_value = 1.0
    if attribute:
        color = nodes.new("ShaderNodeVertexColor")
        color.layer_name = attribute
        links.new(color.outputs["Color"], emission.inputs["Color"])
    links.new(emission.outputs["Emission"], output.inputs["Surface"])
    obj.data.materials.clear()
    obj.data.materials.append(material)

world = bpy.data.worlds.new("grey")
world.use_nodes = True
world.node_tree.nodes["Background"].inputs["Color"].default_value = (0.18, 0.18, 0.18, 1)
world.node_tree.nodes["Background"].inputs["Strength"].default_value = 1.0
scene = bpy.context.scene
scene.world = world

# The camera: Blender's world is ENU (the importer turns glTF's Y-up into Z-up); cinepath's camera looks
# along +z with y down, Blender's along -z with y up: R_blender = R_world_from_camera * diag(1, -1, -1).
w, x, y, z = sample["world_from_camera"]
rotation = mathutils.Quaternion((w, x, y, z)).to_matrix() @ mathutils.Matrix(((1, 0, 0), (0, -1, 0), (0, 0, -1)))
camera_data = bpy.data.cameras.new("cinepath")
camera_data.sensor_fit = "HORIZONTAL"
camera_data.sensor_width = camera_spec["sensor_width_mm"]
camera_data.lens = sample["focal_length_mm"]
camera_data.clip_start = 0.01
camera_data.clip_end = 1e6
focus = sample["focus_distance_m"]
camera_data.dof.use_dof = True
camera_data.dof.focus_distance = focus if focus is not None else 1e9
camera_data.dof.aperture_fstop = sample["f_number"]
camera_data.dof.aperture_blades = 0
camera = bpy.data.objects.new("cinepath", camera_data)
camera.matrix_world = mathutils.Matrix.Translation(sample["position_enu_m"]) @ rotation.to_4x4()
scene.collection.objects.link(camera)
scene.camera = camera

scene.render.engine = "CYCLES"
scene.cycles.device = "CPU"
scene.cycles.samples = spp
scene.cycles.use_adaptive_sampling = False
scene.cycles.use_denoising = False
scene.cycles.max_bounces = 0
scene.cycles.pixel_filter_type = "BOX"
scene.cycles.filter_width = 1.0
scene.cycles.seed = 0
scene.render.use_motion_blur = False
scene.render.threads_mode = "FIXED"
scene.render.threads = 2
scene.render.resolution_x = width
scene.render.resolution_y = height
scene.render.resolution_percentage = 100
scene.view_settings.view_transform = "Standard"
scene.view_settings.look = "None"
scene.render.image_settings.file_format = "OPEN_EXR"
scene.render.image_settings.color_depth = "32"
scene.render.filepath = out
start = time.time()
bpy.ops.render.render(write_still=True)
print("render_seconds %.3f" % (time.time() - start))
