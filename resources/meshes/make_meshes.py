#!/usr/bin/env python3
"""Writes the sample meshes of this folder (run it here; the files are committed).

l-prism.obj      an L-shaped prism (concave): the L of [0,2]x[0,1] and [0,1]x[1,2] in x-y,
                 extruded over z in [0,1]; volume 3. Quads, vertices shared.
tetrahedron.off  the corner tetrahedron (0,0,0), (1,0,0), (0,1,0), (0,0,1); volume 1/6.
box.stl          the unit cube centred at the origin, ascii STL (every facet has its own
                 three vertices, as STL always does).
open-box.ply     the same cube without its top face (+y): an open mesh.
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


if __name__ == "__main__":
    l_prism()
    tetrahedron()
    box_stl()
    open_box_ply()
