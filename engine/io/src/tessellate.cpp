#include <tumble/io/tessellate.h>

#include <tumble/mass.h>

#include <algorithm>
#include <cmath>
#include <numbers>

namespace tumble::io {

namespace {

using Index = std::uint32_t;

Index add(RenderMesh& m, const Vec3& p, const Vec3& n) {
    m.positions.push_back(p);
    m.normals.push_back(n);
    return static_cast<Index>(m.positions.size() - 1);
}

void triangle(RenderMesh& m, Index a, Index b, Index c) {
    m.indices.insert(m.indices.end(), {a, b, c});
}

// Two triangles a-b-c, a-c-d (counter-clockwise as given).
void quad(RenderMesh& m, Index a, Index b, Index c, Index d) {
    triangle(m, a, b, c);
    triangle(m, a, c, d);
}

// A grid of rings about the y axis, ring r at the point profile(r) = (radius, y) with the
// normal normal(r) = (nr, ny) in the radial plane; the first and last rings may be points.
template <class Profile>
void lathe(RenderMesh& m, int rings, int segments, Profile profile) {
    const Index base = static_cast<Index>(m.positions.size());
    std::vector<bool> pole(rings);
    for (int r = 0; r < rings; ++r) {
        double radius, y, nr, ny;
        profile(r, radius, y, nr, ny);
        pole[r] = radius == 0.0;
        for (int s = 0; s <= segments; ++s) {
            const double phi = 2.0 * std::numbers::pi * s / segments;
            const double c = std::cos(phi), sn = std::sin(phi);
            add(m, Vec3(radius * c, y, -radius * sn), Vec3(nr * c, ny, -nr * sn));
        }
    }
    const Index row = static_cast<Index>(segments + 1);
    // Rings run from top (r = 0) to bottom; with the angle growing towards -z, the quad
    // (r, s), (r+1, s), (r+1, s+1), (r, s+1) is counter-clockwise seen from outside.
    for (int r = 0; r + 1 < rings; ++r) {
        for (int s = 0; s < segments; ++s) {
            const Index a = base + r * row + s, b = base + (r + 1) * row + s;
            // At a pole one half of the quad has no area: left out.
            if (!pole[r + 1]) triangle(m, a, b, b + 1);
            if (!pole[r]) triangle(m, a, b + 1, a + 1);
        }
    }
}

// A flat disc at height y facing +y (up) or -y.
void disc(RenderMesh& m, double radius, double y, bool up, int segments) {
    const Vec3 n(0, up ? 1 : -1, 0);
    const Index centre = add(m, Vec3(0, y, 0), n);
    const Index first = static_cast<Index>(m.positions.size());
    for (int s = 0; s < segments; ++s) {
        const double phi = 2.0 * std::numbers::pi * s / segments;
        add(m, Vec3(radius * std::cos(phi), y, -radius * std::sin(phi)), n);
    }
    for (int s = 0; s < segments; ++s) {
        const Index a = first + s, b = first + (s + 1) % segments;
        // The angle grows counter-clockwise seen from +y.
        if (up)
            triangle(m, centre, a, b);
        else
            triangle(m, centre, b, a);
    }
}

void sphere(RenderMesh& m, double radius, double yTop, double yBottom, int segments) {
    // Two hemispheres around the segment from yBottom to yTop (equal for a sphere).
    const int half = std::max(2, segments / 4);
    const int rings = 2 * half + 1 + (yTop != yBottom ? 1 : 0);
    lathe(m, rings, segments, [&](int r, double& rad, double& y, double& nr, double& ny) {
        int i = r;
        double centre = yTop;
        if (yTop != yBottom && r > half) {
            i = r - 1;  // the second ring of the equator, on the bottom hemisphere
            centre = yBottom;
        }
        const double theta = std::numbers::pi * i / (2 * half);  // 0 at the top pole
        nr = std::sin(theta);
        ny = std::cos(theta);
        if (i == 2 * half) nr = 0.0, ny = -1.0;
        if (i == 0) nr = 0.0, ny = 1.0;
        rad = radius * nr;
        y = centre + radius * ny;
    });
}

void box(RenderMesh& m, const Vec3& h) {
    for (int axis = 0; axis < 3; ++axis) {
        for (int sign : {1, -1}) {
            Vec3 n = Vec3::Zero();
            n[axis] = sign;
            // u, v span the face with u × v = n.
            Vec3 u = Vec3::Zero(), v = Vec3::Zero();
            u[(axis + 1) % 3] = 1;
            v[(axis + 2) % 3] = 1;
            if (sign < 0) std::swap(u, v);
            const Vec3 c = n.cwiseProduct(h);
            const Vec3 du = u.cwiseProduct(h), dv = v.cwiseProduct(h);
            const Index a = add(m, c - du - dv, n), b = add(m, c + du - dv, n), d = add(m, c + du + dv, n),
                        e = add(m, c - du + dv, n);
            quad(m, a, b, d, e);
        }
    }
}

void plane(RenderMesh& m, const Vec3& normal, double distance, double half) {
    const Vec3 n = normal.normalized();
    const Vec3 u = n.unitOrthogonal(), v = n.cross(u);
    const Vec3 c = n * distance;
    const Index a = add(m, c - half * u - half * v, n), b = add(m, c + half * u - half * v, n),
                d = add(m, c + half * u + half * v, n), e = add(m, c - half * u + half * v, n);
    quad(m, a, b, d, e);
}

void mesh(RenderMesh& m, const TriangleMesh& t) {
    for (const auto& tri : t.triangles) {
        const Vec3 &a = t.vertices[tri[0]], &b = t.vertices[tri[1]], &c = t.vertices[tri[2]];
        Vec3 n = (b - a).cross(c - a);
        if (n.norm() == 0.0) continue;  // degenerate: nothing to draw, no normal to give
        n.normalize();
        triangle(m, add(m, a, n), add(m, b, n), add(m, c, n));
    }
}

}  // namespace

RenderMesh tessellate(const ShapeDesc& shape, int segments, double planeHalfSize) {
    segments = std::max(segments, 3);
    RenderMesh m;
    switch (shape.type) {
        case ShapeType::Sphere: sphere(m, shape.radius, 0.0, 0.0, segments); break;
        case ShapeType::Capsule:
            sphere(m, shape.radius, shape.halfHeight, -shape.halfHeight, segments);
            break;
        case ShapeType::Cylinder: {
            const double r = shape.radius, h = shape.halfHeight;
            lathe(m, 2, segments, [&](int ring, double& rad, double& y, double& nr, double& ny) {
                rad = r;
                y = ring == 0 ? h : -h;
                nr = 1.0;
                ny = 0.0;
            });
            disc(m, r, h, true, segments);
            disc(m, r, -h, false, segments);
            break;
        }
        case ShapeType::Box: box(m, shape.halfExtents); break;
        case ShapeType::Plane: plane(m, shape.normal, shape.distance, planeHalfSize); break;
        case ShapeType::Mesh:
            if (shape.meshData) mesh(m, *shape.meshData);
            break;
        case ShapeType::Compound:
            // Every part's mesh placed in the body frame, one after another.
            for (const PartDesc& part : shape.parts) {
                if (part.shape.type == ShapeType::Compound) continue;  // refused by validate
                const RenderMesh pm = tessellate(part.shape, segments, planeHalfSize);
                const Mat3 R = part.orientation.normalized().toRotationMatrix();
                const Index first = static_cast<Index>(m.positions.size());
                for (size_t k = 0; k < pm.positions.size(); ++k) {
                    m.positions.push_back(R * pm.positions[k] + part.position);
                    m.normals.push_back(R * pm.normals[k]);
                }
                for (Index i : pm.indices) m.indices.push_back(first + i);
            }
            break;
    }
    return m;
}

}  // namespace tumble::io
