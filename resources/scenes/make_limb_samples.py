# Writes ragdoll-stairs.json, robot-arm.json and suspension-cart.json (issue 51: cones and
# twist limits, servos, slider springs). Run it in the repository root with Debian's python3
# and python3-numpy; the files are committed, this is how they were made.
import json, math
import numpy as np

from make_joint_samples import quat_about, qmul, rot, r, parts, centre, dump

deg = math.pi / 180

# Ragdoll down stairs: the ragdoll of ragdoll.json with a cone and a twist range at every ball
# joint (about the limb as it hangs: an axis from the joint towards the limb's centre), its
# elbows and knees hinges with limits, tipped forwards off the top of six steps.
def limb(a, P):
    d = centre[a] - np.array(P, float)
    return r(d / np.linalg.norm(d))

joints_spec = [
    # name, type, A, B, anchor, hinge axis, hinge limits, cone [towards x, towards -z], twist
    ("neck", "ball", "head", "torso", [0, 1.575, 0], None, None, [40 * deg, 40 * deg], [-50 * deg, 50 * deg]),
    ("shoulder-left", "ball", "upper-arm-left", "torso", [-0.25, 1.54, 0], None, None, [80 * deg, 80 * deg], [-60 * deg, 60 * deg]),
    ("shoulder-right", "ball", "upper-arm-right", "torso", [0.25, 1.54, 0], None, None, [80 * deg, 80 * deg], [-60 * deg, 60 * deg]),
    ("elbow-left", "hinge", "forearm-left", "upper-arm-left", [-0.25, 1.22, 0], [1, 0, 0], [-2.5, 0], None, None),
    ("elbow-right", "hinge", "forearm-right", "upper-arm-right", [0.25, 1.22, 0], [1, 0, 0], [-2.5, 0], None, None),
    # hips: 25° sideways, 60° forwards and back, 30° of twist
    ("hip-left", "ball", "thigh-left", "torso", [-0.1, 0.96, 0], None, None, [25 * deg, 60 * deg], [-30 * deg, 30 * deg]),
    ("hip-right", "ball", "thigh-right", "torso", [0.1, 0.96, 0], None, None, [25 * deg, 60 * deg], [-30 * deg, 30 * deg]),
    ("knee-left", "hinge", "shin-left", "thigh-left", [-0.1, 0.48, 0], [1, 0, 0], [0, 2.5], None, None),
    ("knee-right", "hinge", "shin-right", "thigh-right", [0.1, 0.48, 0], [1, 0, 0], [0, 2.5], None, None),
]
steps, rise, run = 6, 0.2, 0.35
bodies = [{"name": "ground", "motion": "static", "shape": {"type": "plane", "normal": [0, 1, 0], "distance": 0}, "friction": 0.8}]
for i in range(steps):  # step i (from the bottom) reaches up to (i + 1) rise, running back along -z
    h = (i + 1) * rise
    bodies.append({"name": f"step-{i + 1}", "motion": "static", "shape": {"type": "box", "half_extents": [1.0, h / 2, run / 2]},
                   "position": r([0, h / 2, -(i + 0.5) * run]), "friction": 0.8})
top = steps * rise
# Standing at the top step's edge, leaning forwards (towards +z, down the stairs) by 25°.
q = quat_about([1, 0, 0], 25 * deg)
base = np.array([0, top + 0.01, -(steps - 0.5) * run])
for name, shape, mass, c in parts:
    p = rot(q, c) + base
    bodies.append({"name": name, "shape": shape, "mass": mass, "position": r(p), "orientation": r(q), "friction": 0.8,
                   "restitution": 0.1, "angular_damping": 1.0, "velocity": [0, 0, 1.0]})
joints = []
for name, kind, a, b, P, axis, limits, cone, twist in joints_spec:
    P = np.array(P, float)
    j = {"name": name, "type": kind, "body_a": a, "anchor_a": r(P - centre[a]), "body_b": b, "anchor_b": r(P - centre[b])}
    if axis: j["axis_a"] = axis
    if limits: j["limits"] = limits
    if cone:
        j["axis_a"] = limb(a, P)
        j["swing_limit"] = r(cone, 15) if cone[0] != cone[1] else round(cone[0], 15)
        j["twist_limits"] = r(twist, 15)
    joints.append(j)
dump({"settings": {"gravity": [0, -9.81, 0], "dt": 1 / 240, "duration": 5, "frame_rate": 60}, "bodies": bodies, "joints": joints},
     'resources/scenes/ragdoll-stairs.json')

# Robot arm: two links turning about the vertical (a SCARA arm, so gravity does not load its
# servos) on a post, each driven by a servo (time constant 0.1 s, at most 60 and 30 N m)
# through a keyed program: the elbow bends to −70° by 0.8 s and the shoulder swings to 100°
# by 1.2 s, both hold, then swing back to 20° and −20° from 2.5 to 3.5 s; its hand sweeps
# three blocks aside on the way.
arm = [
    {"name": "ground", "motion": "static", "shape": {"type": "plane", "normal": [0, 1, 0], "distance": 0}},
    {"name": "table", "motion": "static", "shape": {"type": "box", "half_extents": [1.2, 0.4, 1.2]}, "position": [0, 0.4, 0], "friction": 0.4},
    {"name": "post", "motion": "static", "shape": {"type": "cylinder", "radius": 0.08, "half_height": 0.25}, "position": [0, 1.05, 0]},
    {"name": "upper-link", "shape": {"type": "box", "half_extents": [0.3, 0.04, 0.05]}, "mass": 4, "position": [0.3, 1.34, 0]},
    {"name": "lower-link", "shape": {"type": "box", "half_extents": [0.25, 0.04, 0.04]}, "mass": 2, "position": [0.85, 1.26, 0]},
    {"name": "hand", "shape": {"type": "box", "half_extents": [0.04, 0.2, 0.04]}, "mass": 1, "position": [1.06, 1.02, 0]},
]
for i, angle in enumerate([25, 45, 62]):  # blocks on the table in the hand's way
    a = angle * deg
    arm.append({"name": f"block-{i + 1}", "shape": {"type": "box", "half_extents": [0.05, 0.05, 0.05]}, "mass": 0.5,
                "position": r([0.92 * math.cos(a), 0.85, -0.92 * math.sin(a)]), "orientation": r(quat_about([0, 1, 0], a)),
                "friction": 0.4})
def program(keys):  # (time in s, angle in degrees) -> the servo's keys
    return [{"time": t, "target": round(a * deg, 15)} for t, a in keys]

arm_joints = [
    {"name": "shoulder", "type": "hinge", "body_a": "upper-link", "anchor_a": [-0.3, -0.04, 0], "axis_a": [0, 1, 0],
     "body_b": "post", "anchor_b": [0, 0.25, 0],
     "servo": {"keys": program([(0, 0), (1.2, 100), (2.5, 100), (3.5, 20)]), "max_torque": 60, "time_constant": 0.1}},
    {"name": "elbow", "type": "hinge", "body_a": "lower-link", "anchor_a": [-0.25, 0, 0], "axis_a": [0, 1, 0],
     "body_b": "upper-link", "anchor_b": [0.3, -0.08, 0],
     "servo": {"keys": program([(0, 0), (0.8, -70), (2.5, -70), (3.5, -20)]), "max_torque": 30, "time_constant": 0.1}},
    {"name": "wrist", "type": "fixed", "body_a": "hand", "anchor_a": [0, 0.2, 0], "body_b": "lower-link", "anchor_b": [0.21, -0.04, 0]},
]
dump({"settings": {"gravity": [0, -9.81, 0], "dt": 1 / 240, "duration": 5, "frame_rate": 60}, "bodies": arm, "joints": arm_joints},
     'resources/scenes/robot-arm.json')

# Suspension cart: a 40 kg chassis on four struts, each a slider along the chassis' y with a
# spring (4000 N/m, 250 N s/m: a 2.5 cm sag, damping ratio 0.6 for a quarter of the chassis)
# and limits of ±8 cm; a wheel on a hinge at each strut, driven at 8 rad/s with at most 25 N m;
# it drives along +x over three bumps.
cart = [
    {"name": "ground", "motion": "static", "shape": {"type": "plane", "normal": [0, 1, 0], "distance": 0}, "friction": 0.9},
    {"name": "chassis", "shape": {"type": "box", "half_extents": [0.6, 0.08, 0.3]}, "mass": 40, "position": [0, 0.5, 0]},
]
for i, x in enumerate([2.0, 3.5, 5.0]):
    cart.append({"name": f"bump-{i + 1}", "motion": "static", "shape": {"type": "cylinder", "radius": 0.08, "half_height": 1.0},
                 "position": [x, 0, 0], "orientation": r(quat_about([1, 0, 0], 90 * deg)), "friction": 0.9})
wheel_q = r(quat_about([1, 0, 0], 90 * deg))  # a cylinder's y turned to z: the axle
cart_joints = []
for name, x, z in [("front-left", 0.45, 0.38), ("front-right", 0.45, -0.38), ("rear-left", -0.45, 0.38), ("rear-right", -0.45, -0.38)]:
    cart.append({"name": f"strut-{name}", "shape": {"type": "box", "half_extents": [0.03, 0.1, 0.03]}, "mass": 1,
                 "position": [x, 0.32, z]})
    cart.append({"name": f"wheel-{name}", "shape": {"type": "cylinder", "radius": 0.18, "half_height": 0.04}, "mass": 3,
                 "position": [x, 0.22, z + (0.07 if z > 0 else -0.07)], "orientation": wheel_q, "friction": 0.9})
    cart_joints.append({"name": f"suspension-{name}", "type": "slider", "body_a": f"strut-{name}", "anchor_a": [0, 0.1, 0],
                        "axis_a": [0, 1, 0], "body_b": "chassis", "anchor_b": [x, -0.08, z], "limits": [-0.08, 0.08],
                        "spring": {"stiffness": 4000, "damping": 250}})
    cart_joints.append({"name": f"axle-{name}", "type": "hinge", "body_a": f"wheel-{name}", "anchor_a": [0, 0, 0],
                        "axis_a": [0, -1, 0], "body_b": f"strut-{name}",
                        "anchor_b": [0, -0.1, 0.07 if z > 0 else -0.07], "motor": {"speed": 8, "max_torque": 25}})
dump({"settings": {"gravity": [0, -9.81, 0], "dt": 1 / 240, "duration": 5, "frame_rate": 60}, "bodies": cart, "joints": cart_joints},
     'resources/scenes/suspension-cart.json')
