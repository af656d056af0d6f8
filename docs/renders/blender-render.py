# Renders a GLB in Blender (3.4, headless) with Cycles on the CPU, no denoising: the
# README's Blender picture. Usage: blender -b --python docs/renders/blender-render.py --
# HEAD.glb OUT.png [YAW_DEG [SAMPLES [SUN_Z_DEG]]]. Prints each object, its material and
# what feeds its Principled BSDF (base colour, roughness, metallic, normal).
import bpy, sys, math, numpy
numpy.bool = bool
argv = sys.argv[sys.argv.index("--") + 1:]
glb, out = argv[0], argv[1]
yaw = float(argv[2]) if len(argv) > 2 else 0.0
bpy.ops.wm.read_factory_settings(use_empty=True)
bpy.ops.import_scene.gltf(filepath=glb)
objs = [o for o in bpy.context.scene.objects if o.type == 'MESH']
for o in objs:
    m = o.active_material
    info = ""
    if m and m.use_nodes:
        bsdf = next((n for n in m.node_tree.nodes if n.type == 'BSDF_PRINCIPLED'), None)
        if bsdf:
            links = {k: [l.from_node.type + ":" + (l.from_node.image.name if getattr(l.from_node, 'image', None) else l.from_socket.name) for l in bsdf.inputs[k].links] for k in ("Base Color", "Roughness", "Metallic", "Normal")}
            info = str(links)
    print("OBJECT", o.name, len(o.data.polygons), "faces", "material", m.name if m else None, info, "attrs", [a.name for a in o.data.color_attributes] if hasattr(o.data, 'color_attributes') else "")
# bounds
from mathutils import Vector
pts = [o.matrix_world @ Vector(c) for o in objs for c in o.bound_box]
lo = Vector((min(p.x for p in pts), min(p.y for p in pts), min(p.z for p in pts)))
hi = Vector((max(p.x for p in pts), max(p.y for p in pts), max(p.z for p in pts)))
c = (lo + hi) / 2
size = (hi - lo).length
scene = bpy.context.scene
cam = bpy.data.objects.new("cam", bpy.data.cameras.new("cam"))
scene.collection.objects.link(cam)
cam.data.lens = 85
d = size * 2.2
a = math.radians(yaw)
cam.location = (c.x + d * math.sin(a), c.y - d * math.cos(a), c.z + size * 0.08)
direction = c - cam.location
cam.rotation_euler = direction.to_track_quat('-Z', 'Y').to_euler()
scene.camera = cam
sun = bpy.data.objects.new("sun", bpy.data.lights.new("sun", 'SUN'))
sun.data.energy = 3.0
sun.rotation_euler = (math.radians(60), 0, math.radians(float(argv[4]) if len(argv) > 4 else -25))
scene.collection.objects.link(sun)
world = bpy.data.worlds.new("w"); world.use_nodes = True
world.node_tree.nodes["Background"].inputs[1].default_value = 0.5
scene.world = world
scene.render.engine = 'CYCLES'
scene.cycles.device = 'CPU'
scene.cycles.samples = int(argv[3]) if len(argv) > 3 else 24
scene.cycles.use_denoising = False
scene.render.resolution_x = 640
scene.render.resolution_y = 640
scene.render.filepath = out
bpy.ops.render.render(write_still=True)
