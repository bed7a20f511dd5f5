# Imports each .glb given into an empty Blender scene and prints, per file, one JSON line:
# its objects by type, its actions with their frame ranges, the bones' custom properties
# of the first bone, the mesh's UV maps, the scene's custom properties; and, when a picture
# size is given, renders it through the file's camera with Workbench (flat lighting,
# material colours, no anti-aliasing, the Standard view transform) and counts the pixels
# of each colour, so that a test can compare them with the palette in sRGB.
# Usage: blender -b --factory-startup --python blender_glb.py -- SIZE FRAME FILE... (SIZE 0:
# no picture; FRAME: the scene frame to render, -1: the last frame of the action).
import collections
import json
import os
import sys
import tempfile
import time

import numpy

# Debian 12's Blender 3.4 glTF importer still uses numpy.bool, which numpy 1.24 removed.
numpy.bool = numpy.bool_

import bpy  # noqa: E402

args = sys.argv[sys.argv.index("--") + 1:]
size = int(args[0])
frame = int(args[1])
for path in args[2:]:
    bpy.ops.wm.read_factory_settings(use_empty=True)
    started = time.time()
    bpy.ops.import_scene.gltf(filepath=path)
    imported = time.time() - started
    scene = bpy.context.scene
    objects = collections.Counter(o.type for o in bpy.data.objects)
    report = {
        "file": os.path.basename(path),
        "import_seconds": round(imported, 2),
        "objects": dict(objects),
        "actions": [{"name": a.name, "range": list(a.frame_range), "curves": len(a.fcurves)} for a in bpy.data.actions],
        "scene_frames": [scene.frame_start, scene.frame_end, scene.render.fps],
        "scene_props": {k: (list(v) if hasattr(v, "__len__") and not isinstance(v, str) else v)
                        for k, v in scene.items() if k.startswith("ontogen")},
    }
    armatures = [o for o in bpy.data.objects if o.type == "ARMATURE"]
    if armatures:
        bones = armatures[0].pose.bones
        report["bones"] = len(bones)
        if len(bones) > 0:
            report["bone"] = {"name": bones[0].name,
                              "props": {k: v for k, v in bones[0].items() if isinstance(v, (int, float, str))}}
    meshes = [o for o in bpy.data.objects if o.type == "MESH"]
    if meshes:
        mesh = meshes[0].data
        report["uv_maps"] = [uv.name for uv in mesh.uv_layers]
        report["vertices"] = len(mesh.vertices)
        report["skinned"] = any(m.type == "ARMATURE" and m.object is not None for m in meshes[0].modifiers)
    if size > 0:
        cameras = [o for o in bpy.data.objects if o.type == "CAMERA"]
        if cameras:
            scene.camera = cameras[0]
        if frame >= 0:
            scene.frame_set(frame)
        elif bpy.data.actions:
            scene.frame_set(int(round(max(a.frame_range[1] for a in bpy.data.actions))))
        scene.render.engine = "BLENDER_WORKBENCH"
        scene.display.shading.light = "FLAT"
        scene.display.shading.color_type = "MATERIAL"
        scene.display.render_aa = "OFF"
        scene.view_settings.view_transform = "Standard"
        scene.view_settings.look = "None"
        scene.render.resolution_x = size
        scene.render.resolution_y = size
        scene.render.resolution_percentage = 100
        scene.render.film_transparent = False
        scene.render.dither_intensity = 0
        world = bpy.data.worlds.new("ontogen test") if scene.world is None else scene.world
        scene.world = world
        world.color = (0, 0, 0)
        picture = os.path.join(tempfile.mkdtemp(), "render.png")
        scene.render.filepath = picture
        bpy.ops.render.render(write_still=True)
        image = bpy.data.images.load(picture)
        pixels = numpy.array(image.pixels[:]).reshape(-1, 4)[:, :3]
        counts = collections.Counter(tuple(int(round(c * 255)) for c in p) for p in pixels)
        report["colours"] = [[list(c), n] for c, n in counts.most_common(8)]
        rows = numpy.nonzero(pixels.reshape(size, size, 3).sum(axis=2) > 0)
        report["drawn_box"] = [int(rows[1].min()), int(rows[0].min()), int(rows[1].max()), int(rows[0].max())] \
            if len(rows[0]) else []
    print("ONTOGEN-REPORT " + json.dumps(report))
