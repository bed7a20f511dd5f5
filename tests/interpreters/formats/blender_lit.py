# Imports a .glb into Blender's own startup scene (its light and world kept, its cube
# removed), as a user would, and renders it through the file's camera with Cycles at the
# last frame of its action; prints one JSON line: the lights in the scene, and of the
# model's pixels (those not transparent) how many there are, how many are black and how
# many white, so that a test can see the model lit, neither dark nor washed out.
# Usage: blender -b --factory-startup --python blender_lit.py -- SIZE FILE
import json
import os
import sys
import tempfile

import numpy

# Debian 12's Blender 3.4 glTF importer still uses numpy.bool, which numpy 1.24 removed.
numpy.bool = numpy.bool_

import bpy  # noqa: E402

args = sys.argv[sys.argv.index("--") + 1:]
size = int(args[0])
path = args[1]
startup = {o.name for o in bpy.data.objects}
for o in list(bpy.data.objects):
    if o.type == "MESH":
        bpy.data.objects.remove(o)
bpy.ops.import_scene.gltf(filepath=path)
scene = bpy.context.scene
cameras = [o for o in bpy.data.objects if o.type == "CAMERA" and o.name not in startup]
if cameras:
    scene.camera = cameras[0]
if bpy.data.actions:
    scene.frame_set(int(round(max(a.frame_range[1] for a in bpy.data.actions))))
scene.render.engine = "CYCLES"
scene.cycles.device = "CPU"
scene.cycles.samples = 8
scene.cycles.use_denoising = False
scene.render.resolution_x = size
scene.render.resolution_y = size
scene.render.resolution_percentage = 100
scene.render.film_transparent = True
picture = os.path.join(tempfile.mkdtemp(), "render.png")
scene.render.filepath = picture
bpy.ops.render.render(write_still=True)
pixels = numpy.array(bpy.data.images.load(picture).pixels[:]).reshape(-1, 4)
model = pixels[pixels[:, 3] > 0.99][:, :3]
report = {
    "file": os.path.basename(path),
    "lights": sorted(o.name for o in bpy.data.objects if o.type == "LIGHT"),
    "from_file": sorted(o.name for o in bpy.data.objects if o.type == "LIGHT" and o.name not in startup),
    "model": int(len(model)),
    "black": int((model.max(axis=1) < 8 / 255).sum()),
    "white": int((model.min(axis=1) > 247 / 255).sum()),
    "mean": float(model.mean()) if len(model) else 0.0,
}
print("ONTOGEN-REPORT " + json.dumps(report))
