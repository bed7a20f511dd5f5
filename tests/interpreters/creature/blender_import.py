# Imports a .glb into an empty Blender scene and prints what it holds as one JSON line:
# armatures (with their bone counts), meshes with an armature modifier (skinned), actions
# (with their frame ranges). Usage: blender -b --factory-startup --python blender_import.py -- FILE
import json
import sys

import numpy

# Debian 12's Blender 3.4 glTF importer still uses numpy.bool, which numpy 1.24 removed.
numpy.bool = numpy.bool_

import bpy  # noqa: E402

path = sys.argv[sys.argv.index("--") + 1]
for obj in list(bpy.data.objects):
    bpy.data.objects.remove(obj, do_unlink=True)
bpy.ops.import_scene.gltf(filepath=path)
report = {
    "armatures": [{"name": o.name, "bones": len(o.data.bones)} for o in bpy.data.objects if o.type == "ARMATURE"],
    "skinned": [o.name for o in bpy.data.objects
                if o.type == "MESH" and any(m.type == "ARMATURE" and m.object is not None for m in o.modifiers)],
    "actions": [{"name": a.name, "range": list(a.frame_range), "curves": len(a.fcurves)} for a in bpy.data.actions],
}
print("ONTOGEN-REPORT " + json.dumps(report))
