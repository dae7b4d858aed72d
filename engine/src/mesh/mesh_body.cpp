#include "mesh/mesh_body.h"

#include <tumble/convex_hull.h>

namespace tumble::mesh {

namespace {

double surfaceArea(const TriangleMesh& m) {
    double area = 0.0;
    for (const auto& t : m.triangles) {
        area += 0.5 * (m.vertices[t[1]] - m.vertices[t[0]]).cross(m.vertices[t[2]] - m.vertices[t[0]]).norm();
    }
    return area;
}

// Integrates the solid bounded by the closed, outward surface `m` at density 1.
void integrate(const TriangleMesh& m, double tolerance, PreparedMesh& out) {
    double volume = 0.0;
    const MassProperties mp = meshMassProperties(m, 1.0, &volume);
    if (2.0 * volume > tolerance * surfaceArea(m) && mp.inertia.allFinite()) {
        out.volume = volume;
        out.unitDensity = mp;
    }
}

}  // namespace

TriangleMesh hullSurface(const collision::ConvexHull& hull) {
    TriangleMesh m;
    m.vertices = hull.vertices;
    for (const auto& f : hull.faces) {
        const std::span<const int> v = hull.verticesOf(f);
        for (size_t k = 1; k + 1 < v.size(); ++k) m.triangles.push_back({v[0], v[k], v[k + 1]});
    }
    return m;
}

PreparedMesh prepareMesh(const TriangleMesh& raw, bool wantHull, bool wantMass, bool fillOpen) {
    PreparedMesh p;
    const double tolerance = weldTolerance(raw.vertices);
    p.surface = cleanMesh(raw, tolerance, &p.stats);
    p.closed = isClosed(p.surface);
    if (!p.closed && fillOpen && !p.surface.triangles.empty()) {
        TriangleMesh filled = fillHoles(p.surface, &p.filling);
        if (p.filling.closed) {
            p.surface = std::move(filled);
            p.closed = true;
        }
    }
    if (p.closed) {
        double volume = 0.0;
        meshMassProperties(p.surface, 1.0, &volume);
        if (volume < 0.0) {
            for (auto& t : p.surface.triangles) std::swap(t[1], t[2]);
            p.turnedOutward = true;
        }
    }
    p.massFromHull = wantMass && !p.closed;
    if ((wantHull || p.massFromHull) && !p.surface.triangles.empty()) {
        try {
            p.hull = std::make_shared<const collision::ConvexHull>(convexHull(p.surface.vertices));
        } catch (const HullError& e) {
            p.hullProblem = e.what();
        }
    } else if (wantHull || p.massFromHull) {
        p.hullProblem = "the mesh has no triangles";
    }
    if (wantMass) {
        if (p.closed)
            integrate(p.surface, tolerance, p);
        else if (p.hull)
            integrate(hullSurface(*p.hull), tolerance, p);
    }
    return p;
}

}  // namespace tumble::mesh
