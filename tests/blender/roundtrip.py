#!/usr/bin/env python3
"""Blender round trip (ctest blender/roundtrip, issues 19 and 49): a scene is exported by
`tumble --headless` as .glb and as .gltf, and as the trajectory CSV; Blender's own glTF
importer reads each file (import_gltf.py, headless), and every body's location and rotation
at several frames must be the CSV's, within 1e-5 m and 1e-5 rad, with the objects named as
the bodies and the animation's keys from frame 0 to the last frame. A compound body's parts
are child objects ("BODY PART" or "BODY part J"), each where its body's pose puts it.

usage: roundtrip.py TUMBLE SCENE [SCENE ...]   (needs `blender` on the PATH: ./dev.sh installs it)
"""
import csv
import json
import math
import os
import shutil
import subprocess
import sys
import tempfile

HERE = os.path.dirname(os.path.abspath(__file__))
TOLERANCE = 1e-5  # m and rad; the file stores 32-bit floats (about 6e-8 relative)


def fail(message):
    print("FAIL: " + message)
    sys.exit(1)


def read_csv(path):
    """{body: {frame: (x, y, z, qw, qx, qy, qz)}}, frames counted from the rows' times."""
    poses, times = {}, []
    with open(path) as f:
        for row in csv.DictReader(f):
            t = float(row["time"])
            if t not in times:
                times.append(t)
            poses.setdefault(row["body"], {})[times.index(t)] = tuple(
                float(row[k]) for k in ("x", "y", "z", "qw", "qx", "qy", "qz"))
    return poses, times


def mesh_bounds(path, scale):
    """The least and greatest x, y, z of an OBJ's or an ASCII STL's vertices, scaled, in
    Blender's axes: what the body's mesh must be in Blender, read from the file itself."""
    points = []
    with open(path) as f:
        for line in f:
            words = line.split()
            if words[:1] == ["v"] or words[:1] == ["vertex"]:
                x, y, z = (float(w) * s for w, s in zip(words[1:4], scale))
                points.append((x, -z, y))
    return [min(p[k] for p in points) for k in range(3)] + [max(p[k] for p in points) for k in range(3)]


def to_blender(pose):
    """glTF (and Tumble) is +Y up, Blender +Z up: the importer maps (x, y, z) to (x, -z, y),
    positions and the axes of rotations alike."""
    x, y, z, qw, qx, qy, qz = pose
    return (x, -z, y), (qw, qx, -qz, qy)


def qmul(a, b):
    aw, ax, ay, az = a
    bw, bx, by, bz = b
    return (aw * bw - ax * bx - ay * by - az * bz, aw * bx + ax * bw + ay * bz - az * by,
            aw * by - ax * bz + ay * bw + az * bx, aw * bz + ax * by - ay * bx + az * bw)


def rotate(q, v):
    w, x, y, z = qmul(qmul(q, (0.0,) + tuple(v)), (q[0], -q[1], -q[2], -q[3]))
    return (x, y, z)


def unit(q):
    n = math.sqrt(sum(c * c for c in q))
    return tuple(c / n for c in q)


def part_poses(scene):
    """{child object name: (body name, part position, part orientation)} of the compounds."""
    with open(scene) as f:
        bodies = json.load(f)["bodies"]
    out = {}
    for body in bodies:
        if body["shape"]["type"] != "compound":
            continue
        for j, part in enumerate(body["shape"]["parts"]):
            name = body["name"] + (" " + part["name"] if part.get("name") else " part %d" % j)
            out[name] = (body["name"], part.get("position", [0, 0, 0]), unit(part.get("orientation", [1, 0, 0, 0])))
    return out


def angle_between(q1, q2):
    dot = abs(sum(a * b for a, b in zip(q1, q2)))
    n1 = math.sqrt(sum(a * a for a in q1))
    n2 = math.sqrt(sum(a * a for a in q2))
    return 2.0 * math.acos(min(1.0, dot / (n1 * n2)))


def check(tumble, scene, fmt, work):
    name = os.path.splitext(os.path.basename(scene))[0]
    exported = os.path.join(work, name + "." + fmt)
    table = os.path.join(work, name + ".csv")
    for out in (exported, table):
        subprocess.run([tumble, "--headless", scene, "--out", out, "--quiet"], check=True)
    poses, times = read_csv(table)
    rate = round(1.0 / (times[1] - times[0]))
    last = len(times) - 1
    frames = sorted({0, 1, last // 3, last // 2, last - 1, last})
    report = os.path.join(work, name + "." + fmt + ".blender.json")
    run = subprocess.run(
        ["blender", "-b", "--factory-startup", "--python", os.path.join(HERE, "import_gltf.py"), "--",
         exported, str(rate), ",".join(map(str, frames)), report],
        capture_output=True, text=True, timeout=600)
    if run.returncode != 0 or not os.path.exists(report):
        fail(f"{name}.{fmt}: Blender did not import it (exit {run.returncode}):\n{run.stdout[-2000:]}{run.stderr[-2000:]}")
    with open(report) as f:
        got = json.load(f)
    # The objects are the bodies, named as in the scene, the scene's root node above them and
    # the compounds' parts below theirs.
    parts = part_poses(scene)
    extra = set(got["objects"]) - set(poses)
    root = name
    while root in poses:  # the root is never named as a body
        root += " scene"
    if not set(poses) <= set(got["objects"]) or extra != {root} | set(parts):
        fail(f"{name}.{fmt}: Blender's objects {sorted(got['objects'])} are not the bodies {sorted(poses)}, "
             f"one root and the parts {sorted(parts)}")
    # Each part where its body puts it: the body's pose times the part's.
    for part, (body, offset, turn) in parts.items():
        for frame in frames:
            x, y, z, qw, qx, qy, qz = poses[body][frame]
            q = (qw, qx, qy, qz)
            p = tuple(a + b for a, b in zip(rotate(q, offset), (x, y, z)))
            position, rotation = to_blender(p + qmul(q, turn))
            seen = got["objects"][part][str(frame)]
            if math.dist(position, seen[:3]) > TOLERANCE or angle_between(rotation, seen[3:]) > TOLERANCE:
                fail(f"{name}.{fmt}: part {part} at frame {frame}: Blender has {seen}, the body's pose and "
                     f"the part's give {position + rotation}")
    if parts:
        print(f"{name}.{fmt}: {len(parts)} parts where their bodies put them")
    moving = [b for b in poses if any(poses[b][k] != poses[b][0] for k in poses[b])]
    if moving and (got["first_key"] != 0 or got["last_key"] != last):
        fail(f"{name}.{fmt}: the animation's keys run from frame {got['first_key']} to {got['last_key']}, "
             f"not 0 to {last}")
    worst_move, worst_turn = 0.0, 0.0
    for body, by_frame in poses.items():
        for frame in frames:
            position, rotation = to_blender(by_frame[frame])
            seen = got["objects"][body][str(frame)]
            move = math.dist(position, seen[:3])
            turn = angle_between(rotation, seen[3:])
            worst_move, worst_turn = max(worst_move, move), max(worst_turn, turn)
            if move > TOLERANCE or turn > TOLERANCE:
                fail(f"{name}.{fmt}: {body} at frame {frame} (t = {times[frame]} s): Blender has "
                     f"{seen}, the CSV {by_frame[frame]} ({move:.2e} m, {turn:.2e} rad apart)")
    # The meshes read from OBJ and STL files (through assimp) come out with their own
    # vertices, scaled, in the body's axes.
    with open(scene) as f:
        bodies = json.load(f)["bodies"]
    for body in bodies:
        shape = body["shape"]
        if shape["type"] != "mesh" or not shape["file"].endswith((".obj", ".stl")):
            continue
        source = os.path.join(os.path.dirname(os.path.abspath(scene)), shape["file"])
        want = mesh_bounds(source, shape.get("scale", [1, 1, 1]))
        have = got["bounds"].get(body["name"])
        if have is None or max(abs(a - b) for a, b in zip(want, have)) > TOLERANCE:
            fail(f"{name}.{fmt}: {body['name']}'s mesh in Blender spans {have}, its file {want}")
        print(f"{name}.{fmt}: {body['name']}'s mesh ({os.path.basename(source)}) spans its file's box")
    print(f"{name}.{fmt}: {len(poses)} objects ({len(moving)} moving), frames {frames} of 0..{last} at "
          f"{rate}/s: at most {worst_move:.1e} m and {worst_turn:.1e} rad from the CSV")


def main():
    if len(sys.argv) < 3:
        fail(__doc__)
    if shutil.which("blender") is None:
        fail("blender is not installed (./dev.sh test installs it: apt-get install blender python3-numpy)")
    tumble, scenes = sys.argv[1], sys.argv[2:]
    with tempfile.TemporaryDirectory() as work:
        # An STL too: the sample cube, stretched, thrown spinning.
        stl = os.path.join(os.path.dirname(os.path.abspath(scenes[0])), "..", "meshes", "box.stl")
        thrown = os.path.join(work, "thrown-stl.json")
        with open(thrown, "w") as f:
            json.dump({"format": "tumble-scene", "version": 1,
                       "settings": {"duration": 1, "frame_rate": 30},
                       "bodies": [{"name": "stl-box", "mass": 1, "position": [0, 2, 0],
                                   "velocity": [1, 2, 0.5], "angular_velocity": [3, 1, 2],
                                   "shape": {"type": "mesh", "file": os.path.abspath(stl),
                                             "scale": [0.5, 0.25, 0.75], "collision": "convex-hull"}}]},
                      f)
        for scene in scenes + [thrown]:
            for fmt in ("glb", "gltf"):
                check(tumble, scene, fmt, work)
    print("PASS")


if __name__ == "__main__":
    main()
