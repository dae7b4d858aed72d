# Run by Blender (blender -b --factory-startup --python import_gltf.py -- FILE FPS FRAMES OUT):
# imports a glTF or GLB with Blender's own importer and writes, for each of the FRAMES
# (comma-separated), every object's world location and rotation (w, x, y, z) to OUT as JSON,
# with the frame range of the imported animation.
import json
import sys

try:
    import numpy as np
except ImportError:
    # Debian's python3-numpy, where Blender's Python does not look when the python3 first on
    # the PATH is another one (pyenv's shims on the CI machines).
    sys.path.append("/usr/lib/python3/dist-packages")
    import numpy as np

np.bool = bool  # Blender 3.4's glTF importer still uses numpy.bool, which numpy 1.24 removed

import bpy

args = sys.argv[sys.argv.index("--") + 1:]
path, fps, frames, out = args[0], int(args[1]), [int(f) for f in args[2].split(",")], args[3]

bpy.ops.wm.read_factory_settings(use_empty=True)
scene = bpy.context.scene
scene.render.fps = fps  # so that the file's key times land on whole frames
bpy.ops.import_scene.gltf(filepath=path)

ranges = [list(action.frame_range) for action in bpy.data.actions]
result = {
    "actions": len(bpy.data.actions),
    "first_key": min((r[0] for r in ranges), default=None),
    "last_key": max((r[1] for r in ranges), default=None),
    "objects": {},
    # Each mesh object's vertices in its own axes: least and greatest x, y, z.
    "bounds": {
        ob.name: [min(v.co[k] for v in ob.data.vertices) for k in range(3)] +
                 [max(v.co[k] for v in ob.data.vertices) for k in range(3)]
        for ob in scene.objects if ob.type == "MESH" and len(ob.data.vertices) > 0
    },
}
for frame in frames:
    scene.frame_set(frame)
    for ob in scene.objects:
        m = ob.matrix_world
        t, q = m.to_translation(), m.to_quaternion()
        result["objects"].setdefault(ob.name, {})[str(frame)] = [t.x, t.y, t.z, q.w, q.x, q.y, q.z]
with open(out, "w") as f:
    json.dump(result, f)
