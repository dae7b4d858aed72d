#!/usr/bin/env python3
"""Writes the animated-body sample scenes of this folder (run it here; the files are committed).

paddle-dominoes.json  a paddle keyed to swing in at 1.5 m/s and back knocks over the first of
                      a row of 12 dominoes; the row falls one by one.
lift.json             a lift keyed to rise 2 m (smooth: eased in and out, at most 1.5 m/s²
                      each way) carries a stack of three boxes up and stops; they ride it
                      without sinking or hopping.
turntable.json        a turntable keyed to spin up to 2.5 rad/s (smooth keys every half second)
                      with four boxes (mu 0.5) at radii 0.3, 0.6, 0.9 and 1.2 m: those inside
                      r* = mu g / w^2 = 0.785 m turn with it, the others slide off.

`python3 make_animated_samples.py NAME ...` writes only those (paddle-dominoes, lift, turntable).
"""

import json
import math
import sys

from make_compound_samples import quat_axis, write


def floor():
    return {"name": "floor", "motion": "static", "shape": {"type": "plane", "normal": [0, 1, 0], "distance": 0},
            "friction": 0.5, "restitution": 0.2}


def key(time, position, orientation=None):
    return {"time": time, "position": position, "orientation": orientation or [1, 0, 0, 0]}


def animated(name, shape, keys, interpolation="linear", **extra):
    body = {"name": name, "motion": "animated", "shape": shape, "position": keys[0]["position"],
            "orientation": keys[0]["orientation"], "interpolation": interpolation, "keys": keys}
    body.update(extra)
    return body


def box(name, half, position, density=600, **extra):
    body = {"name": name, "shape": {"type": "box", "half_extents": half}, "density": density,
            "position": position, "friction": 0.5, "restitution": 0.1}
    body.update(extra)
    return body


def scene(duration, bodies, **settings):
    s = {"duration": duration, "frame_rate": 60}
    s.update(settings)
    return {"settings": s, "bodies": bodies}


def paddle_dominoes():
    # Dominoes 0.1 x 0.8 x 0.4 m, 0.45 m apart from x = 0.5; the paddle, 0.1 x 0.4 x 0.8 m at
    # 0.65 m up, comes in from x = -1.2 at 1.5 m/s, meets the first domino's face near its
    # top at about t = 0.97 s, pushes it 0.15 m and goes back.
    bodies = [floor()]
    for n in range(12):
        bodies.append(box("domino-%d" % n, [0.05, 0.4, 0.2], [0.5 + 0.45 * n, 0.4, 0]))
    bodies.append(animated("paddle", {"type": "box", "half_extents": [0.05, 0.2, 0.4]},
                           [key(0, [-1.2, 0.65, 0]), key(1.2, [0.6, 0.65, 0]), key(2.4, [-1.2, 0.65, 0])],
                           friction=0.3, restitution=0.1))
    return scene(6, bodies)


def lift():
    # A platform 1.6 x 0.1 x 1.6 m resting on the floor rises 2 m from t = 1 s to t = 4 s
    # (smooth: a peak acceleration of 6 x 2 / 3^2 = 1.33 m/s^2); three 0.4 m boxes on it.
    bodies = [floor(),
              animated("lift", {"type": "box", "half_extents": [0.8, 0.05, 0.8]},
                       [key(1, [0, 0.05, 0]), key(4, [0, 2.05, 0])], "smooth", friction=0.6, restitution=0.0)]
    for n in range(3):
        bodies.append(box("box-%d" % n, [0.2, 0.2, 0.2], [0, 0.3 + 0.4 * n, 0], restitution=0.0))
    return scene(6, bodies)


def turntable():
    # Spun up at 1.25 rad/s^2 for 2 s (theta = 0.625 t^2), then 2.5 rad/s: keys every 0.5 s
    # on that curve, smooth (C1); the last one eases out at 8 s.
    keys = []
    for n in range(17):
        t = 0.5 * n
        theta = 0.625 * t * t if t <= 2 else 2.5 + 2.5 * (t - 2)
        keys.append(key(t, [0, 0.05, 0], quat_axis([0, 1, 0], theta)))
    bodies = [floor(),
              animated("turntable", {"type": "cylinder", "radius": 1.5, "half_height": 0.05}, keys, "smooth",
                       friction=0.5, restitution=0.0)]
    for n, r in enumerate([0.3, 0.6, 0.9, 1.2]):
        angle = n * math.pi / 2
        bodies.append(box("box-r%.1f" % r, [0.08, 0.08, 0.08], [r * math.cos(angle), 0.18, r * math.sin(angle)],
                          friction=0.5, restitution=0.0))
    return scene(8, bodies)


SAMPLES = {"paddle-dominoes": paddle_dominoes, "lift": lift, "turntable": turntable}

if __name__ == "__main__":
    for name in sys.argv[1:] or SAMPLES:
        s = SAMPLES[name]()
        s["format"] = "tumble-scene"
        s["version"] = 1
        write(name + ".json", s)
