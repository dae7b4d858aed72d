# Writes chain.json, ragdoll.json and hinged-door.json (run it in the repository root with
# Debian's python3 and python3-numpy). The files are committed; this is how they were made.
import json, math
import numpy as np

def quat_about(axis, angle):
    axis = np.array(axis, float); axis /= np.linalg.norm(axis)
    s = math.sin(angle/2); return [math.cos(angle/2), *(axis*s)]

def qmul(a, b):
    w1,x1,y1,z1 = a; w2,x2,y2,z2 = b
    return [w1*w2-x1*x2-y1*y2-z1*z2, w1*x2+x1*w2+y1*z2-z1*y2, w1*y2-x1*z2+y1*w2+z1*x2, w1*z2+x1*y2-y1*x2+z1*w2]

def rot(q, v):
    w,x,y,z = q
    R = np.array([[1-2*(y*y+z*z), 2*(x*y-w*z), 2*(x*z+w*y)],[2*(x*y+w*z), 1-2*(x*x+z*z), 2*(y*z-w*x)],[2*(x*z-w*y), 2*(y*z+w*x), 1-2*(x*x+y*y)]])
    return R @ np.array(v, float)

def r(v, n=12): return [round(float(c), n) + 0.0 for c in v]

# Ragdoll: A-pose, y up, feet at y = 0.
parts = [
  # name, shape, mass, centre
  ("torso", {"type": "box", "half_extents": [0.18, 0.3, 0.1]}, 30, [0, 1.26, 0]),
  ("head", {"type": "sphere", "radius": 0.11}, 5, [0, 1.70, 0]),
  ("upper-arm-left", {"type": "capsule", "radius": 0.05, "half_height": 0.11}, 2.5, [-0.25, 1.38, 0]),
  ("upper-arm-right", {"type": "capsule", "radius": 0.05, "half_height": 0.11}, 2.5, [0.25, 1.38, 0]),
  ("forearm-left", {"type": "capsule", "radius": 0.045, "half_height": 0.1}, 1.5, [-0.25, 1.075, 0]),
  ("forearm-right", {"type": "capsule", "radius": 0.045, "half_height": 0.1}, 1.5, [0.25, 1.075, 0]),
  ("thigh-left", {"type": "capsule", "radius": 0.07, "half_height": 0.17}, 8, [-0.1, 0.72, 0]),
  ("thigh-right", {"type": "capsule", "radius": 0.07, "half_height": 0.17}, 8, [0.1, 0.72, 0]),
  ("shin-left", {"type": "capsule", "radius": 0.06, "half_height": 0.17}, 4, [-0.1, 0.25, 0]),
  ("shin-right", {"type": "capsule", "radius": 0.06, "half_height": 0.17}, 4, [0.1, 0.25, 0]),
]
centre = {p[0]: np.array(p[3], float) for p in parts}
joints_spec = [
  ("neck", "ball", "head", "torso", [0, 1.575, 0], None, None),
  ("shoulder-left", "ball", "upper-arm-left", "torso", [-0.25, 1.54, 0], None, None),
  ("shoulder-right", "ball", "upper-arm-right", "torso", [0.25, 1.54, 0], None, None),
  ("elbow-left", "hinge", "forearm-left", "upper-arm-left", [-0.25, 1.22, 0], [1, 0, 0], [-2.5, 0]),
  ("elbow-right", "hinge", "forearm-right", "upper-arm-right", [0.25, 1.22, 0], [1, 0, 0], [-2.5, 0]),
  ("hip-left", "ball", "thigh-left", "torso", [-0.1, 0.96, 0], None, None),
  ("hip-right", "ball", "thigh-right", "torso", [0.1, 0.96, 0], None, None),
  ("knee-left", "hinge", "shin-left", "thigh-left", [-0.1, 0.48, 0], [1, 0, 0], [0, 2.5]),
  ("knee-right", "hinge", "shin-right", "thigh-right", [0.1, 0.48, 0], [1, 0, 0], [0, 2.5]),
]
# Falling sideways and a little forward, from 1 m up.
q = qmul(quat_about([0, 0, 1], math.radians(70)), quat_about([1, 0, 0], math.radians(20)))
lift = np.array([0, 1.0, 0])
bodies = [{"name": "ground", "motion": "static", "shape": {"type": "plane", "normal": [0, 1, 0], "distance": 0}, "friction": 0.8}]
for name, shape, mass, c in parts:
    p = rot(q, c) + lift
    bodies.append({"name": name, "shape": shape, "mass": mass, "position": r(p), "orientation": r(q, 12), "friction": 0.8, "restitution": 0.1,
                   # a little damping of turns, as a body's joints have: else the head can
                   # spin for ever about the line from its neck to its point on the ground
                   "angular_damping": 1.0})
# keep the lowest point above the ground: measured by the spheres' centres is enough for a rough lift
joints = []
for name, kind, a, b, P, axis, limits in joints_spec:
    P = np.array(P, float)
    j = {"name": name, "type": kind, "body_a": a, "anchor_a": r(P - centre[a]), "body_b": b, "anchor_b": r(P - centre[b])}
    if axis: j["axis_a"] = axis
    if limits: j["limits"] = limits
    joints.append(j)
scene = {"format": "tumble-scene", "version": 1,
         "settings": {"gravity": [0, -9.81, 0], "dt": 1/240, "duration": 5, "frame_rate": 60},
         "bodies": bodies, "joints": joints}

def dump(scene, path):
    lines = ['{', '  "format": "tumble-scene",', '  "version": 1,', '  "settings": ' + json.dumps(scene["settings"]) + ',', '  "bodies": [']
    lines += [',\n'.join('    ' + json.dumps(b) for b in scene["bodies"])]
    lines += ['  ],', '  "joints": [']
    lines += [',\n'.join('    ' + json.dumps(j) for j in scene["joints"])]
    lines += ['  ]', '}']
    open(path, 'w').write('\n'.join(lines) + '\n')

dump(scene, 'resources/scenes/ragdoll.json')

# Chain: 20 links (capsules r 0.03, pitch 0.15 m) on ball joints, hung from the world at
# (0, 3.5, 0) and held out horizontally at the start.
links, joints = [{"name": "ground", "motion": "static", "shape": {"type": "plane", "normal": [0, 1, 0], "distance": 0}}], []
pitch = 0.15
rz = quat_about([0, 0, 1], math.radians(90))  # capsule axis y turned to -x (towards the hook)
for i in range(20):
    c = [pitch * (i + 0.5), 3.5, 0]
    links.append({"name": f"link-{i+1:02d}", "shape": {"type": "capsule", "radius": 0.03, "half_height": 0.045}, "mass": 0.2,
                  "position": r(c), "orientation": r(rz, 12)})
    # each link's own ends are (0, ±0.075, 0) in its frame: +y is towards the hook
    if i == 0:
        joints.append({"name": "hook", "type": "ball", "body_a": "link-01", "anchor_a": [0, 0.075, 0], "anchor_b": [0, 3.5, 0]})
    else:
        joints.append({"name": f"joint-{i:02d}-{i+1:02d}", "type": "ball", "body_a": f"link-{i+1:02d}", "anchor_a": [0, 0.075, 0],
                       "body_b": f"link-{i:02d}", "anchor_b": [0, -0.075, 0]})
dump({"settings": {"gravity": [0, -9.81, 0], "dt": 1/240, "duration": 6, "frame_rate": 60}, "bodies": links, "joints": joints}, 'resources/scenes/chain.json')

# Door: a 20 kg door (0.8 x 2 x 0.04 m) on a hinge at its edge to a static post, opened by a
# motor (1 rad/s, at most 20 N m) until its limit at 1.5 rad.
door = [
  {"name": "ground", "motion": "static", "shape": {"type": "plane", "normal": [0, 1, 0], "distance": 0}},
  {"name": "post", "motion": "static", "shape": {"type": "box", "half_extents": [0.03, 1.05, 0.03]}, "position": [-0.03, 1.05, 0]},
  {"name": "door", "shape": {"type": "box", "half_extents": [0.4, 1, 0.02]}, "mass": 20, "position": [0.4, 1.02, 0]},
]
dj = [{"name": "hinge", "type": "hinge", "body_a": "door", "anchor_a": [-0.4, 0, 0], "axis_a": [0, 1, 0],
       "body_b": "post", "anchor_b": [0.03, -0.03, 0], "limits": [0, 1.5], "motor": {"speed": 1, "max_torque": 20}}]
dump({"settings": {"gravity": [0, -9.81, 0], "dt": 1/240, "duration": 3, "frame_rate": 60}, "bodies": door, "joints": dj}, 'resources/scenes/hinged-door.json')
