#!/usr/bin/env python3
"""Writes the stacking sample scenes of this folder (run it here; the files are committed).

tower-20.json    20 boxes of 1 m (half extents 0.5) in a column on the ground, exactly
                 touching: box k has its centre at y = 0.5 + k. Runs 60 s.
pyramid-15.json  a 15-layer pyramid of the same boxes: layer k (k = 0 at the bottom) holds
                 15 - k boxes side by side, exactly touching, each layer shifted by half a box
                 so every box rests on two below it; 120 boxes. Runs 20 s.

Every coordinate is a multiple of 0.5, so "exactly touching" is exact in binary too.
Boxes are 10 kg, restitution 0.1, friction 0.6 (wooden crates); the ground plane has
restitution 0.1, friction 0.6, so every contact uses e = 0.1, mu = 0.6.
"""

HALF = 0.5


def header(duration):
    return (
        '{\n  "format": "tumble-scene",\n  "version": 1,\n'
        '  "settings": { "duration": %g, "frame_rate": 30 },\n'
        '  "bodies": [\n'
        '    { "name": "ground", "motion": "static", '
        '"shape": { "type": "plane", "normal": [0, 1, 0], "distance": 0 }, '
        '"restitution": 0.1, "friction": 0.6 }' % duration
    )


def box(name, x, y):
    return (
        '    { "name": "%s", "shape": { "type": "box", "half_extents": [%g, %g, %g] }, "mass": 10, '
        '"position": [%g, %g, 0], "restitution": 0.1, "friction": 0.6 }' % (name, HALF, HALF, HALF, x, y)
    )


def write(path, duration, boxes):
    with open(path, "w") as f:
        f.write(",\n".join([header(duration)] + boxes) + "\n  ]\n}\n")


def tower(levels=20):
    write("tower-%d.json" % levels, 60, [box("box-%02d" % k, 0, HALF + 2 * HALF * k) for k in range(levels)])


def pyramid(layers=15):
    boxes = []
    for k in range(layers):
        n = layers - k
        for i in range(n):
            x = (i - (n - 1) / 2) * 2 * HALF
            boxes.append(box("layer-%02d-box-%02d" % (k, i), x, HALF + 2 * HALF * k))
    write("pyramid-%d.json" % layers, 20, boxes)


if __name__ == "__main__":
    tower()
    pyramid()
