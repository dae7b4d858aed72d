// Triangle meshes with known geometry for the engine tests.
#pragma once

#include <tumble/mass.h>

#include <cmath>
#include <numbers>
#include <utility>

namespace tumble::test {

/// Closed UV sphere of radius r: rings between the poles, counter-clockwise from outside.
inline TriangleMesh uvSphere(double r, int rings, int segments) {
    using std::numbers::pi;
    TriangleMesh m;
    m.vertices.emplace_back(0, -r, 0);
    for (int i = 1; i < rings; ++i) {
        const double phi = pi * i / rings - pi / 2;
        for (int s = 0; s < segments; ++s) {
            const double a = 2 * pi * s / segments;
            m.vertices.emplace_back(r * std::cos(phi) * std::cos(a), r * std::sin(phi),
                                    -r * std::cos(phi) * std::sin(a));
        }
    }
    m.vertices.emplace_back(0, r, 0);
    const int top = static_cast<int>(m.vertices.size()) - 1;
    auto id = [&](int ring, int s) { return 1 + (ring - 1) * segments + (s % segments); };
    for (int s = 0; s < segments; ++s) {
        m.triangles.push_back({0, id(1, s + 1), id(1, s)});
        m.triangles.push_back({top, id(rings - 1, s), id(rings - 1, s + 1)});
    }
    for (int i = 1; i + 1 < rings; ++i) {
        for (int s = 0; s < segments; ++s) {
            m.triangles.push_back({id(i, s), id(i, s + 1), id(i + 1, s + 1)});
            m.triangles.push_back({id(i, s), id(i + 1, s + 1), id(i + 1, s)});
        }
    }
    return m;
}

/// The lower half (and a little more) of a UV sphere of radius r about the origin, its
/// triangles facing the centre: the inside of a bowl, an open mesh.
inline TriangleMesh hemisphereBowl(double r, int rings, int segments) {
    TriangleMesh sphere = uvSphere(r, rings, segments);
    TriangleMesh bowl;
    bowl.vertices = sphere.vertices;
    for (auto t : sphere.triangles) {
        const Vec3 c = (sphere.vertices[t[0]] + sphere.vertices[t[1]] + sphere.vertices[t[2]]) / 3.0;
        if (c.y() > 0.1 * r) continue;  // the lower half and a little more
        std::swap(t[1], t[2]);          // seen from inside
        bowl.triangles.push_back(t);
    }
    return bowl;
}

}  // namespace tumble::test
