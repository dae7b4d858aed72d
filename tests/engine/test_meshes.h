// Triangle meshes with known geometry for the engine tests.
#pragma once

#include <tumble/mass.h>

#include <array>
#include <cmath>
#include <numbers>
#include <utility>
#include <vector>

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

/// The closed surface swept by turning `profile` (points (radius, height), from the axis
/// back to the axis, the solid on the left going up the outside) about the y axis in
/// `segments` steps; its first and last points are on the axis (radius 0).
inline TriangleMesh revolved(const std::vector<std::pair<double, double>>& profile, int segments) {
    TriangleMesh m;
    const int n = static_cast<int>(profile.size());
    m.vertices.emplace_back(0, profile.front().second, 0);  // the first pole
    for (int i = 1; i + 1 < n; ++i)
        for (int k = 0; k < segments; ++k) {
            const double a = 2 * std::numbers::pi * k / segments;
            m.vertices.emplace_back(profile[i].first * std::cos(a), profile[i].second,
                                    -profile[i].first * std::sin(a));
        }
    m.vertices.emplace_back(0, profile.back().second, 0);  // the last pole
    const int last = static_cast<int>(m.vertices.size()) - 1;
    auto ring = [&](int i, int k) { return 1 + (i - 1) * segments + (k % segments); };
    for (int k = 0; k < segments; ++k) m.triangles.push_back({0, ring(1, k + 1), ring(1, k)});
    for (int i = 1; i + 2 < n; ++i)
        for (int k = 0; k < segments; ++k) {
            m.triangles.push_back({ring(i, k), ring(i, k + 1), ring(i + 1, k + 1)});
            m.triangles.push_back({ring(i, k), ring(i + 1, k + 1), ring(i + 1, k)});
        }
    for (int k = 0; k < segments; ++k) m.triangles.push_back({last, ring(n - 2, k), ring(n - 2, k + 1)});
    return m;
}

/// A mug without a handle: a cylinder of radius R and height H standing on y = 0, with a
/// round hole of radius r and depth D from its top. Exact solid volume (of the polygons):
/// see mugVolume.
inline TriangleMesh mug(double R, double H, double r, double D, int segments) {
    return revolved({{0, 0}, {R, 0}, {R, H}, {r, H}, {r, H - D}, {0, H - D}}, segments);
}

/// The volume of mug(): prisms of regular polygons (not circles) of `segments` sides.
inline double mugVolume(double R, double H, double r, double D, int segments) {
    const double polygon = 0.5 * segments * std::sin(2 * std::numbers::pi / segments);  // area / radius^2
    return polygon * (R * R * H - r * r * D);
}

/// A torus about the y axis: tube radius r around a circle of radius R; nu steps around the
/// axis, nv around the tube. Closed, counter-clockwise from outside.
inline TriangleMesh torus(double R, double r, int nu, int nv) {
    TriangleMesh m;
    for (int i = 0; i < nu; ++i)
        for (int j = 0; j < nv; ++j) {
            const double u = 2 * std::numbers::pi * i / nu, v = 2 * std::numbers::pi * j / nv;
            const double rho = R + r * std::cos(v);
            m.vertices.emplace_back(rho * std::cos(u), r * std::sin(v), -rho * std::sin(u));
        }
    auto at = [&](int i, int j) { return (i % nu) * nv + (j % nv); };
    for (int i = 0; i < nu; ++i)
        for (int j = 0; j < nv; ++j) {
            m.triangles.push_back({at(i, j), at(i + 1, j), at(i + 1, j + 1)});
            m.triangles.push_back({at(i, j), at(i + 1, j + 1), at(i, j + 1)});
        }
    return m;
}

/// A U-shaped bracket: a base w x t (x by y) with two arms of width t rising h above it,
/// depth d along z, extruded from its outline; standing on y = 0, centred on x = 0 and z = 0.
/// Its volume is d (w t + 2 t h).
inline TriangleMesh uBracket(double w, double t, double h, double d) {
    const double x0 = -w / 2, x1 = w / 2;
    // The outline, counter-clockwise seen from +z, and its triangles (three rectangles).
    const std::vector<std::pair<double, double>> outline = {{x0, 0},         {x1, 0},     {x1, t + h},
                                                            {x1 - t, t + h}, {x1 - t, t}, {x0 + t, t},
                                                            {x0 + t, t + h}, {x0, t + h}};
    const std::vector<std::array<int, 3>> cap = {{0, 1, 4}, {0, 4, 5}, {1, 2, 3},
                                                 {1, 3, 4}, {0, 5, 6}, {0, 6, 7}};
    TriangleMesh m;
    const int n = static_cast<int>(outline.size());
    for (double z : {d / 2, -d / 2})
        for (const auto& [x, y] : outline) m.vertices.emplace_back(x, y, z);
    for (const auto& c : cap) {
        m.triangles.push_back({c[0], c[1], c[2]});              // front (+z), counter-clockwise
        m.triangles.push_back({n + c[0], n + c[2], n + c[1]});  // back (-z)
    }
    for (int i = 0; i < n; ++i) {
        const int j = (i + 1) % n;
        m.triangles.push_back({i, n + i, n + j});
        m.triangles.push_back({i, n + j, j});
    }
    return m;
}

/// Closed box of half extents `half` about `at`, counter-clockwise from outside.
inline TriangleMesh boxMesh(const Vec3& half, const Vec3& at = Vec3::Zero()) {
    TriangleMesh m;
    for (int i = 0; i < 8; ++i)
        m.vertices.push_back(
            at + Vec3((i & 1 ? 1 : -1) * half.x(), (i & 2 ? 1 : -1) * half.y(), (i & 4 ? 1 : -1) * half.z()));
    m.triangles = {{0, 2, 1}, {1, 2, 3}, {4, 5, 6}, {5, 7, 6}, {0, 1, 4}, {1, 5, 4},
                   {2, 6, 3}, {3, 6, 7}, {0, 4, 2}, {2, 4, 6}, {1, 3, 5}, {3, 7, 5}};
    return m;
}

/// The signed volume a closed surface bounds (each triangle's tetrahedron with the origin).
inline double signedVolume(const TriangleMesh& m) {
    double v = 0.0;
    for (const auto& t : m.triangles)
        v += m.vertices[t[0]].dot(m.vertices[t[1]].cross(m.vertices[t[2]])) / 6.0;
    return v;
}

}  // namespace tumble::test
