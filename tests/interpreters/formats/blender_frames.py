# Imports a skinned, animated .glb into an empty Blender scene and writes, for each time
# its action keys (the run's frames, in order), where Blender's armature puts every vertex
# of the skinned mesh, in the file's own axes (glTF's y up), with the bone that carries
# it: one JSON line per frame, {"frame", "time", "bones": {name: [x, y, z, ...]}}, so that
# a test can compare the animated positions with what ontogen drew in that frame.
# Usage: blender -b --factory-startup --python blender_frames.py -- FILE
import json
import sys

import numpy

# Debian 12's Blender 3.4 glTF importer still uses numpy.bool, which numpy 1.24 removed.
numpy.bool = numpy.bool_

import bpy  # noqa: E402

path = sys.argv[sys.argv.index("--") + 1]
bpy.ops.wm.read_factory_settings(use_empty=True)
bpy.ops.import_scene.gltf(filepath=path)
scene = bpy.context.scene
meshes = [o for o in bpy.data.objects
          if o.type == "MESH" and any(m.type == "ARMATURE" and m.object is not None for m in o.modifiers)]
if len(meshes) != 1:
    print("ONTOGEN-ERROR skinned meshes: %d" % len(meshes))
    sys.exit(0)
mesh = meshes[0]
# The vertex's bone: the one group that weighs it (ontogen skins each vertex to one joint).
groups = {g.index: g.name for g in mesh.vertex_groups}
bone_of = []
for v in mesh.data.vertices:
    weighed = [groups[g.group] for g in v.groups if g.weight > 0]
    bone_of.append(weighed[0] if len(weighed) == 1 else "")
keys = sorted({k.co[0] for a in bpy.data.actions for c in a.fcurves for k in c.keyframe_points})
for n, key in enumerate(keys):
    whole = int(numpy.floor(key))
    scene.frame_set(whole, subframe=key - whole)
    evaluated = mesh.evaluated_get(bpy.context.evaluated_depsgraph_get())
    shown = evaluated.to_mesh()
    world = evaluated.matrix_world
    bones = {}
    for i, v in enumerate(shown.vertices):
        p = world @ v.co
        # Blender's z up back to the file's y up: (x, y, z) -> (x, z, -y).
        bones.setdefault(bone_of[i], []).extend([p.x, p.z, -p.y])
    evaluated.to_mesh_clear()
    print("ONTOGEN-FRAME " + json.dumps({"frame": n, "time": key / scene.render.fps, "bones": bones}))
