#!/usr/bin/env python3
"""Writes the compound-body sample scenes of this folder (run it here; the files are committed).

table.json          a table (a top on four legs) on the floor, a ball dropped on one corner
                    of the top: the table rocks and settles on its four legs.
chair.json          a chair (seat, back, four legs) dropped tilted onto the floor.
hammer.json         a hammer (a wooden handle, a steel head) thrown spinning about its centre
                    of mass: the head circles the centre while the centre flies a parabola.
cart.json           a cart (a deck with a push handle, one compound body) on four wheels, each
                    a cylinder on a hinge under a corner of the deck, pushed at 1 m/s: it rolls
                    on, the wheels turning at v / r (10 rad/s).
mug-on-board.json   a mug (mesh, split into convex parts) with a ball in it, on a board that a
                    kinematic turn tilts: the mug slides and tips, the ball stays in until the
                    mug falls over. Its parts are kept in mug-on-board.convex-parts.json.
chair-pile.json     200 chairs in eight layers of 5 x 5, each turned about the vertical,
                    dropped in a heap onto the floor (tumble-bench's chair-pile); impacts at
                    the end of the step, as the peers take them.

`python3 make_compound_samples.py NAME ...` writes only those (table, chair, hammer, cart,
mug-on-board, chair-pile).

The chair: a seat 0.44 x 0.04 x 0.44 m at
0.45 m, a back 0.44 x 0.5 x 0.04 m on its rear edge, legs 0.04 x 0.45 x 0.04 m under its
corners; pine, 500 kg/m³ (4.9 kg).
"""

import json
import math


def quat_axis(axis, angle):
    n = math.sqrt(sum(a * a for a in axis))
    s = math.sin(angle / 2) / n
    return [math.cos(angle / 2), axis[0] * s, axis[1] * s, axis[2] * s]


def box_part(name, half, position, **extra):
    part = {"name": name, "shape": {"type": "box", "half_extents": half}, "position": position}
    part.update(extra)
    return part


def floor(friction=0.6, restitution=0.1):
    return {"name": "floor", "motion": "static", "shape": {"type": "plane", "normal": [0, 1, 0], "distance": 0},
            "friction": friction, "restitution": restitution}


def scene(duration, bodies, joints=None, frame_rate=60):
    s = {"format": "tumble-scene", "version": 1, "settings": {"duration": duration, "frame_rate": frame_rate},
         "bodies": bodies}
    if joints:
        s["joints"] = joints
    return s


def write(path, s):
    """One body, one joint a line."""
    def line(x):
        return json.dumps(x, separators=(", ", ": "))
    with open(path, "w") as f:
        f.write('{\n "format": "tumble-scene",\n "version": 1,\n "settings": %s,\n "bodies": [\n' % line(s["settings"]))
        f.write(",\n".join("  " + line(b) for b in s["bodies"]))
        f.write("\n ]")
        if "joints" in s:
            f.write(',\n "joints": [\n' + ",\n".join("  " + line(j) for j in s["joints"]) + "\n ]")
        f.write("\n}\n")


def table_parts():
    leg = [0.03, 0.36, 0.03]
    parts = [box_part("top", [0.6, 0.03, 0.4], [0, 0.75, 0])]
    for x, z, n in [(0.55, 0.35, "front right"), (-0.55, 0.35, "front left"), (0.55, -0.35, "back right"),
                    (-0.55, -0.35, "back left")]:
        parts.append(box_part("leg " + n, leg, [x, 0.36, z]))
    return parts


def chair(name, position, orientation=None, velocity=None):
    leg = [0.02, 0.225, 0.02]
    parts = [box_part("seat", [0.22, 0.02, 0.22], [0, 0.47, 0]),
             box_part("back", [0.22, 0.25, 0.02], [0, 0.74, -0.2])]
    for x, z in [(0.2, 0.2), (-0.2, 0.2), (0.2, -0.2), (-0.2, -0.2)]:
        parts.append(box_part("leg", leg, [x, 0.225, z]))
    body = {"name": name, "shape": {"type": "compound", "parts": parts}, "density": 500, "position": position,
            "friction": 0.5, "restitution": 0.2}
    if orientation:
        body["orientation"] = orientation
    if velocity:
        body["velocity"] = velocity
    return body


def table():
    t = {"name": "table", "shape": {"type": "compound", "parts": table_parts()}, "density": 600,
         "friction": 0.6, "restitution": 0.1}
    ball = {"name": "ball", "shape": {"type": "sphere", "radius": 0.1}, "density": 2000,
            "position": [0.45, 1.6, 0.3], "restitution": 0.3}
    write("table.json", scene(3, [floor(), t, ball]))


def chair_sample():
    write("chair.json", scene(3, [floor(), chair("chair", [0, 0.6, 0], quat_axis([1, 0, 1], 0.5))]))


def hammer():
    h = {"name": "hammer",
         "shape": {"type": "compound", "parts": [
             {"name": "handle", "shape": {"type": "cylinder", "radius": 0.015, "half_height": 0.15},
              "density": 700},
             box_part("head", [0.05, 0.015, 0.015], [0, 0.165, 0], density=7800, friction=0.3)]},
         "position": [0, 1, 0], "velocity": [3, 4, 0], "angular_velocity": [0, 0, 12]}
    s = scene(1.2, [h])
    s["settings"]["gravity"] = [0, -9.81, 0]
    write("hammer.json", s)


def cart():
    v, r = 1.0, 0.1
    deck = {"name": "cart", "density": 600, "position": [0, 0.2, 0], "velocity": [v, 0, 0], "friction": 0.6,
            "shape": {"type": "compound", "parts": [
                box_part("deck", [0.35, 0.015, 0.2], [0, 0, 0]),
                box_part("post left", [0.015, 0.25, 0.015], [-0.33, 0.26, -0.18]),
                box_part("post right", [0.015, 0.25, 0.015], [-0.33, 0.26, 0.18]),
                {"name": "bar", "shape": {"type": "cylinder", "radius": 0.015, "half_height": 0.2},
                 "position": [-0.33, 0.52, 0], "orientation": quat_axis([1, 0, 0], math.pi / 2)}]}}
    bodies, joints = [floor(), deck], []
    for k, (x, z) in enumerate([(-0.25, -0.24), (-0.25, 0.24), (0.25, -0.24), (0.25, 0.24)]):
        wheel = "wheel %d" % (k + 1)
        # The wheel's axis (its y) along z: turned a quarter about x.
        bodies.append({"name": wheel, "density": 900, "position": [x, r, z], "friction": 0.8,
                       "orientation": quat_axis([1, 0, 0], math.pi / 2),
                       "velocity": [v, 0, 0], "angular_velocity": [0, 0, -v / r],
                       "shape": {"type": "cylinder", "radius": r, "half_height": 0.02}})
        joints.append({"name": "axle %d" % (k + 1), "type": "hinge", "body_a": wheel, "anchor_a": [0, 0, 0],
                       "axis_a": [0, 1, 0], "body_b": "cart", "anchor_b": [x, r - 0.2, z], "axis_b": [0, 0, 1]})
    write("cart.json", scene(3, bodies, joints))


def mug_on_board():
    board = {"name": "board", "motion": "kinematic", "shape": {"type": "box", "half_extents": [0.4, 0.01, 0.2]},
             "position": [0, 0.3, 0], "angular_velocity": [0, 0, 0.15], "friction": 0.4, "restitution": 0.1}
    mug = {"name": "mug", "shape": {"type": "mesh", "file": "../meshes/mug.obj", "collision": "convex-parts",
                                    "max_parts": 16},
           "density": 2300, "position": [0.1, 0.31, 0], "friction": 0.4, "restitution": 0.1}
    ball = {"name": "ball", "shape": {"type": "sphere", "radius": 0.015}, "density": 1200,
            "position": [0.1, 0.45, 0], "restitution": 0.2}
    write("mug-on-board.json", scene(6, [floor(), board, mug, ball]))


def chair_pile():
    chairs = []
    for k in range(200):
        layer, i, j = k // 25, (k % 25) // 5, k % 5
        turn = k + 0.3 * ((k * 7) % 11 - 5) / 5.0
        chairs.append(chair("chair-%d" % k, [round((i - 2) * 0.7, 6), round(0.1 + 1.1 * layer, 6),
                                              round((j - 2) * 0.7, 6)], quat_axis([0, 1, 0], turn)))
    s = scene(8, [floor()] + chairs)
    s["settings"]["impacts"] = "end-of-step"
    write("chair-pile.json", s)


if __name__ == "__main__":
    import sys
    samples = {"table": table, "chair": chair_sample, "hammer": hammer, "cart": cart,
               "mug-on-board": mug_on_board, "chair-pile": chair_pile}
    for name in sys.argv[1:] or samples:
        samples[name]()
