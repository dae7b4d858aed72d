// Shape factories, world bounds and bounding radii.
#include <tumble/collision.h>

#include <algorithm>
#include <atomic>
#include <cmath>

namespace tumble::collision {

const char* toString(Kind k) {
    switch (k) {
    case Kind::Sphere: return "sphere";
    case Kind::Box: return "box";
    case Kind::Capsule: return "capsule";
    case Kind::Cylinder: return "cylinder";
    case Kind::Plane: return "plane";
    case Kind::Hull: return "convex-hull";
    case Kind::Mesh: return "triangles";
    case Kind::Compound: return "compound";
    }
    return "?";
}

Shape Shape::sphere(double r) {
    Shape s;
    s.kind = Kind::Sphere;
    s.radius = r;
    return s;
}

Shape Shape::box(const Vec3& h) {
    Shape s;
    s.kind = Kind::Box;
    s.halfExtents = h;
    return s;
}

Shape Shape::capsule(double r, double h) {
    Shape s;
    s.kind = Kind::Capsule;
    s.radius = r;
    s.halfHeight = h;
    return s;
}

Shape Shape::cylinder(double r, double h) {
    Shape s;
    s.kind = Kind::Cylinder;
    s.radius = r;
    s.halfHeight = h;
    return s;
}

Shape Shape::plane(const Vec3& n, double d) {
    Shape s;
    s.kind = Kind::Plane;
    s.normal = n;
    s.distance = d;
    return s;
}

namespace {

Aabb pointsBounds(const std::vector<Vec3>& points, const Pose& pose) {
    Aabb box;
    for (const Vec3& v : points) box.add(pose.toWorld(v));
    return box;
}

}  // namespace

std::uint64_t newCompoundSerial() {
    static std::atomic<std::uint64_t> next{1};
    return next.fetch_add(1, std::memory_order_relaxed);
}

Aabb bounds(const Shape& s, const Pose& pose) {
    const double inf = std::numeric_limits<double>::infinity();
    const Vec3 c = pose.p;
    switch (s.kind) {
    case Kind::Sphere: return {c.array() - s.radius, c.array() + s.radius};
    case Kind::Box: {
        // Half extent along each world axis: |R| h.
        const Vec3 e = pose.R.cwiseAbs() * s.halfExtents;
        return {c - e, c + e};
    }
    case Kind::Capsule: {
        const Vec3 axis = pose.R.col(1).cwiseAbs() * s.halfHeight;
        return {c.array() - axis.array() - s.radius, c.array() + axis.array() + s.radius};
    }
    case Kind::Cylinder: {
        // The rim of a disc of radius r with unit axis a reaches r sqrt(1 - a_i²) along axis i.
        const Vec3 a = pose.R.col(1);
        const Vec3 rim = s.radius * (Vec3::Ones() - a.cwiseProduct(a)).cwiseMax(0.0).cwiseSqrt();
        const Vec3 e = a.cwiseAbs() * s.halfHeight + rim;
        return {c - e, c + e};
    }
    case Kind::Plane: return {Vec3::Constant(-inf), Vec3::Constant(inf)};
    case Kind::Hull: return pointsBounds(s.hull->vertices, pose);
    case Kind::Mesh: return pointsBounds(s.mesh->vertices, pose);
    case Kind::Compound: {
        Aabb box;
        for (const Compound::Part& part : s.compound->parts) box.add(bounds(part.shape, pose * part.pose));
        return box;
    }
    }
    return {};
}

double boundingRadius(const Shape& s) {
    auto farthest = [](const std::vector<Vec3>& points) {
        double r2 = 0.0;
        for (const Vec3& v : points) r2 = std::max(r2, v.squaredNorm());
        return std::sqrt(r2);
    };
    switch (s.kind) {
    case Kind::Sphere: return s.radius;
    case Kind::Box: return s.halfExtents.norm();
    case Kind::Capsule: return s.halfHeight + s.radius;
    case Kind::Cylinder: return std::hypot(s.halfHeight, s.radius);
    case Kind::Plane: return std::numeric_limits<double>::infinity();
    case Kind::Hull: return farthest(s.hull->vertices);
    case Kind::Mesh: return farthest(s.mesh->vertices);
    case Kind::Compound: {
        double r = 0.0;
        for (const Compound::Part& part : s.compound->parts)
            r = std::max(r, part.pose.p.norm() + boundingRadius(part.shape));
        return r;
    }
    }
    return 0.0;
}

namespace {

// Hulls with more edges than this get the lower bound below instead of the exact width
// (the exact one looks at every pair of edges).
constexpr std::size_t kExactWidthEdges = 256;

// The extent of the hull along the unit direction n.
double extentAlong(const ConvexHull& h, const Vec3& n) {
    double lo = std::numeric_limits<double>::infinity(), hi = -lo;
    for (const Vec3& v : h.vertices) {
        const double d = n.dot(v);
        lo = std::min(lo, d);
        hi = std::max(hi, d);
    }
    return hi - lo;
}

// The hull's least width. The width along a direction is smallest where the two
// supporting planes touch a face and a vertex, or two edges: so the least width is the
// least extent along the face normals and the edges' cross products. A tetrahedron is
// narrower between two opposite edges than over any face. Past kExactWidthEdges edges the
// diameter of the ball about the interior point that fits inside, a lower bound.
double hullWidth(const ConvexHull& h) {
    double w = std::numeric_limits<double>::infinity();
    if (h.edges.size() <= kExactWidthEdges && !h.vertices.empty()) {
        for (const ConvexHull::Face& f : h.faces) w = std::min(w, extentAlong(h, f.normal));
        for (std::size_t i = 0; i < h.edges.size(); ++i) {
            const Vec3 a = h.vertices[h.edges[i][1]] - h.vertices[h.edges[i][0]];
            for (std::size_t j = i + 1; j < h.edges.size(); ++j) {
                const Vec3 n = a.cross(h.vertices[h.edges[j][1]] - h.vertices[h.edges[j][0]]);
                const double len = n.norm();
                if (len > 1e-12 * a.squaredNorm()) w = std::min(w, extentAlong(h, n / len));
            }
        }
    } else {
        double r = std::numeric_limits<double>::infinity();
        for (const ConvexHull::Face& f : h.faces) r = std::min(r, f.offset - f.normal.dot(h.interiorPoint));
        w = 2.0 * r;
    }
    return std::isfinite(w) && w > 0.0 ? w : 0.0;
}

}  // namespace

double thickness(const Shape& s) {
    switch (s.kind) {
    case Kind::Sphere:
    case Kind::Capsule: return 2.0 * s.radius;
    case Kind::Box: return 2.0 * s.halfExtents.minCoeff();
    case Kind::Cylinder: return 2.0 * std::min(s.radius, s.halfHeight);
    case Kind::Plane: return std::numeric_limits<double>::infinity();
    case Kind::Hull: return hullWidth(*s.hull);
    case Kind::Mesh: return 0.0;  // a surface, perhaps open
    case Kind::Compound: {
        // A body moving less than its thinnest part cannot pass through any part.
        double w = std::numeric_limits<double>::infinity();
        for (const Compound::Part& part : s.compound->parts) w = std::min(w, thickness(part.shape));
        return w;
    }
    }
    return 0.0;
}

double Manifold::maxDepth() const {
    double d = -std::numeric_limits<double>::infinity();
    for (int i = 0; i < count; ++i) d = std::max(d, points[i].depth);
    return d;
}

}  // namespace tumble::collision
