#include "viewport/viewport_wire.h"

#include <tumble/convex_hull.h>
#include <tumble/convex_parts.h>

#include <tumble/mass.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <set>
#include <utility>

namespace tumble::ui {

namespace {

constexpr int kCircleSegments = 48;

// A circle (or an arc from angle a0 to a1) about `centre` in the plane of unit u and w.
void arc(std::vector<Vec3>& out, const Vec3& centre, const Vec3& u, const Vec3& w, double radius, double a0,
         double a1, int segments) {
    for (int i = 0; i < segments; ++i) {
        const double t0 = a0 + (a1 - a0) * i / segments;
        const double t1 = a0 + (a1 - a0) * (i + 1) / segments;
        out.push_back(centre + radius * (std::cos(t0) * u + std::sin(t0) * w));
        out.push_back(centre + radius * (std::cos(t1) * u + std::sin(t1) * w));
    }
}

void circle(std::vector<Vec3>& out, const Vec3& centre, const Vec3& u, const Vec3& w, double radius) {
    arc(out, centre, u, w, radius, 0.0, 2.0 * M_PI, kCircleSegments);
}

void triangleEdges(std::vector<Vec3>& out, const TriangleMesh& mesh) {
    std::set<std::pair<int, int>> edges;
    for (const auto& t : mesh.triangles) {
        for (int k = 0; k < 3; ++k) {
            const int a = t[size_t(k)], b = t[size_t((k + 1) % 3)];
            edges.insert({std::min(a, b), std::max(a, b)});
        }
    }
    for (const auto& [a, b] : edges) {
        out.push_back(mesh.vertices[size_t(a)]);
        out.push_back(mesh.vertices[size_t(b)]);
    }
}

}  // namespace

std::array<float, 3> pieceColour(int k) {
    if (k <= 0) return {70 / 255.0f, 235 / 255.0f, 200 / 255.0f};
    // Hue by the golden angle from the cyan, full saturation, bright: HSV to RGB.
    const double h = std::fmod(168.0 + 137.508 * k, 360.0) / 60.0, s = 0.75, v = 1.0;
    const double c = v * s, x = c * (1 - std::abs(std::fmod(h, 2.0) - 1)), m = v - c;
    const int sector = static_cast<int>(h) % 6;
    const std::array<std::array<double, 3>, 6> rgb = {
        {{c, x, 0}, {x, c, 0}, {0, c, x}, {0, x, c}, {x, 0, c}, {c, 0, x}}};
    const auto& o = rgb[static_cast<size_t>(sector)];
    return {float(o[0] + m), float(o[1] + m), float(o[2] + m)};
}

std::vector<Vec3> collisionWire(const ShapeDesc& s, std::vector<int>* pieces) {
    std::vector<Vec3> out;
    const Vec3 x = Vec3::UnitX(), y = Vec3::UnitY(), z = Vec3::UnitZ();
    switch (s.type) {
        case ShapeType::Sphere:
            circle(out, Vec3::Zero(), x, y, s.radius);
            circle(out, Vec3::Zero(), y, z, s.radius);
            circle(out, Vec3::Zero(), z, x, s.radius);
            break;
        case ShapeType::Box: {
            const Vec3& h = s.halfExtents;
            for (int axis = 0; axis < 3; ++axis) {
                const int i = (axis + 1) % 3, j = (axis + 2) % 3;
                for (double si : {-1.0, 1.0}) {
                    for (double sj : {-1.0, 1.0}) {
                        Vec3 a = Vec3::Zero();
                        a[i] = si * h[i];
                        a[j] = sj * h[j];
                        Vec3 b = a;
                        a[axis] = -h[axis];
                        b[axis] = h[axis];
                        out.push_back(a);
                        out.push_back(b);
                    }
                }
            }
            break;
        }
        case ShapeType::Cylinder:
        case ShapeType::Capsule: {
            const double r = s.radius, h = s.halfHeight;
            circle(out, h * y, z, x, r);
            circle(out, -h * y, z, x, r);
            for (const Vec3& side : {Vec3(r, 0, 0), Vec3(-r, 0, 0), Vec3(0, 0, r), Vec3(0, 0, -r)}) {
                out.push_back(side + h * y);
                out.push_back(side - h * y);
            }
            if (s.type == ShapeType::Capsule) {
                // The caps: half circles over the top and under the bottom, in two planes.
                for (const Vec3& u : {x, z}) {
                    arc(out, h * y, u, y, r, 0.0, M_PI, kCircleSegments / 2);
                    arc(out, -h * y, u, y, r, M_PI, 2.0 * M_PI, kCircleSegments / 2);
                }
            }
            break;
        }
        case ShapeType::Plane: break;
        case ShapeType::Mesh: {
            if (!s.meshData || s.meshData->vertices.empty()) break;
            if (s.collision == MeshCollision::Triangles) {
                triangleEdges(out, *s.meshData);
                break;
            }
            if (s.collision == MeshCollision::ConvexParts && s.convexParts) {
                // Each part's hull: the split as the collision sees it.
                for (size_t k = 0; k < s.convexParts->parts.size(); ++k) {
                    const collision::ConvexHull& hull = s.convexParts->parts[k];
                    for (const auto& e : hull.edges) {
                        out.push_back(hull.vertices[size_t(e[0])]);
                        out.push_back(hull.vertices[size_t(e[1])]);
                        if (pieces) pieces->push_back(int(k));
                    }
                }
                return out;
            }
            try {
                const collision::ConvexHull hull = mesh::convexHull(s.meshData->vertices);
                for (const auto& e : hull.edges) {
                    out.push_back(hull.vertices[size_t(e[0])]);
                    out.push_back(hull.vertices[size_t(e[1])]);
                }
            } catch (const mesh::HullError&) {
                triangleEdges(out, *s.meshData);  // flat: compile refuses it; show what there is
            }
            break;
        }
        case ShapeType::Compound:
            // Each part's wire placed in the body frame.
            for (size_t k = 0; k < s.parts.size(); ++k) {
                const PartDesc& p = s.parts[k];
                if (p.shape.type == ShapeType::Compound) continue;  // refused by validate
                const Mat3 R = p.orientation.normalized().toRotationMatrix();
                const std::vector<Vec3> wire = collisionWire(p.shape);
                for (const Vec3& q : wire) out.push_back(R * q + p.position);
                if (pieces) pieces->insert(pieces->end(), wire.size() / 2, int(k));
            }
            return out;
    }
    if (pieces) pieces->assign(out.size() / 2, 0);
    return out;
}

}  // namespace tumble::ui
