#!/usr/bin/env python3
"""Writes the sample meshes of this folder (run it here; the files are committed).

l-prism.obj      an L-shaped prism (concave): the L of [0,2]x[0,1] and [0,1]x[1,2] in x-y,
                 extruded over z in [0,1]; volume 3. Quads, vertices shared.
tetrahedron.off  the corner tetrahedron (0,0,0), (1,0,0), (0,1,0), (0,0,1); volume 1/6.
box.stl          the unit cube centred at the origin, ascii STL (every facet has its own
                 three vertices, as STL always does).
open-box.ply     the same cube without its top face (+y): an open mesh.
mug.obj          a mug without a handle (concave): a 32-sided prism of radius 0.05 m and
                 height 0.1 m standing on y = 0, with a hole of radius 0.04 m and depth 0.09 m;
                 for "collision": "convex-parts" (mug-on-board.json).
All faces run counter-clockwise seen from outside.
"""

# L cross-section, boundary counter-clockwise, with the points where the caps' quads meet.
ring = [(0, 0), (1, 0), (2, 0), (2, 1), (1, 1), (1, 2), (0, 2), (0, 1)]
caps = [[(0, 0), (1, 0), (1, 1), (0, 1)], [(1, 0), (2, 0), (2, 1), (1, 1)], [(0, 1), (1, 1), (1, 2), (0, 2)]]


def l_prism():
    verts = [(x, y, z) for z in (0, 1) for (x, y) in ring]
    index = {v: i + 1 for i, v in enumerate(verts)}
    faces = []
    for quad in caps:
        faces.append([index[(x, y, 0)] for (x, y) in reversed(quad)])  # bottom looks down
        faces.append([index[(x, y, 1)] for (x, y) in quad])
    for k in range(len(ring)):
        (ax, ay), (bx, by) = ring[k], ring[(k + 1) % len(ring)]
        faces.append([index[(ax, ay, 0)], index[(bx, by, 0)], index[(bx, by, 1)], index[(ax, ay, 1)]])
    with open("l-prism.obj", "w") as f:
        f.write("# L-shaped prism, volume 3 (make_meshes.py)\no l-prism\n")
        for v in verts:
            f.write("v %g %g %g\n" % v)
        for face in faces:
            f.write("f " + " ".join(map(str, face)) + "\n")


def tetrahedron():
    with open("tetrahedron.off", "w") as f:
        f.write("OFF\n4 4 6\n0 0 0\n1 0 0\n0 1 0\n0 0 1\n")
        f.write("3 0 2 1\n3 0 1 3\n3 0 3 2\n3 1 2 3\n")


def cube_faces():
    """The unit cube's 6 faces as 4 corners each, counter-clockwise seen from outside."""
    faces = []
    for axis in range(3):
        for sign in (-0.5, 0.5):
            u, w = (axis + 1) % 3, (axis + 2) % 3
            corners = []
            for a, b in [(-0.5, -0.5), (0.5, -0.5), (0.5, 0.5), (-0.5, 0.5)]:
                p = [0.0, 0.0, 0.0]
                p[axis], p[u], p[w] = sign, a, b
                corners.append(tuple(p))
            if sign < 0:
                corners.reverse()
            normal = [0, 0, 0]
            normal[axis] = 1 if sign > 0 else -1
            faces.append((tuple(normal), corners))
    return faces


def box_stl():
    with open("box.stl", "w") as f:
        f.write("solid box\n")
        for n, c in cube_faces():
            for tri in ([c[0], c[1], c[2]], [c[0], c[2], c[3]]):
                f.write("  facet normal %g %g %g\n    outer loop\n" % n)
                for v in tri:
                    f.write("      vertex %g %g %g\n" % v)
                f.write("    endloop\n  endfacet\n")
        f.write("endsolid box\n")


def open_box_ply():
    faces = [c for n, c in cube_faces() if n != (0, 1, 0)]
    verts = sorted({v for c in faces for v in c})
    with open("open-box.ply", "w") as f:
        f.write("ply\nformat ascii 1.0\ncomment unit cube without its top face (make_meshes.py)\n")
        f.write("element vertex %d\nproperty float x\nproperty float y\nproperty float z\n" % len(verts))
        f.write("element face %d\nproperty list uchar int vertex_indices\nend_header\n" % len(faces))
        for v in verts:
            f.write("%g %g %g\n" % v)
        for c in faces:
            f.write("4 " + " ".join(str(verts.index(v)) for v in c) + "\n")


def mug(R=0.05, H=0.1, r=0.04, D=0.09, segments=32):
    """A revolved profile (radius, height) from the axis at the bottom round to the axis at
    the hole's floor, counter-clockwise seen from outside (as tests/engine/test_meshes.h)."""
    import math
    profile = [(0, 0), (R, 0), (R, H), (r, H), (r, H - D), (0, H - D)]
    verts = [(0.0, 0.0, 0.0)]
    for rad, y in profile[1:-1]:
        for k in range(segments):
            a = 2 * math.pi * k / segments
            verts.append((rad * math.cos(a), y, -rad * math.sin(a)))
    verts.append((0.0, H - D, 0.0))
    last = len(verts) - 1

    def ring(i, k):
        return 1 + (i - 1) * segments + (k % segments)

    tris = [(0, ring(1, k + 1), ring(1, k)) for k in range(segments)]
    for i in range(1, len(profile) - 2):
        for k in range(segments):
            tris.append((ring(i, k), ring(i, k + 1), ring(i + 1, k + 1)))
            tris.append((ring(i, k), ring(i + 1, k + 1), ring(i + 1, k)))
    tris += [(last, ring(len(profile) - 2, k), ring(len(profile) - 2, k + 1)) for k in range(segments)]
    with open("mug.obj", "w") as f:
        f.write("# a mug without a handle (make_meshes.py)\no mug\n")
        for v in verts:
            f.write("v %.9g %.9g %.9g\n" % v)
        for t in tris:
            f.write("f %d %d %d\n" % (t[0] + 1, t[1] + 1, t[2] + 1))


if __name__ == "__main__":
    mug()
    l_prism()
    tetrahedron()
    box_stl()
    open_box_ply()
