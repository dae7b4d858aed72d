// Collision geometry and contacts: the shapes the collision stages work on, their world
// bounds, and the contact manifolds they produce. Conventions, used by every stage:
// - A Pose places the body frame (not the centre of mass) in the world: w = R l + p.
// - A manifold's normal is a unit world vector that points out of body B towards body A
//   (the paper's n, "out of B"): moving A along +normal separates the pair.
// - depth > 0 when the shapes overlap; a point with depth in (-margin, 0] is a near
//   contact reported because the caller asked for a margin (speculative contact).
// - A contact point's position is midway between the two surfaces along the normal.
#pragma once

#include <tumble/math.h>
#include <tumble/page_vector.h>
#include <tumble/scene.h>

#include <array>
#include <cstdint>
#include <limits>
#include <memory>
#include <span>
#include <vector>

namespace tumble::collision {

struct Pose {
    Mat3 R = Mat3::Identity();
    Vec3 p = Vec3::Zero();

    Vec3 toWorld(const Vec3& local) const { return R * local + p; }
    Vec3 toLocal(const Vec3& world) const { return R.transpose() * (world - p); }
    Vec3 directionToWorld(const Vec3& local) const { return R * local; }
    Vec3 directionToLocal(const Vec3& world) const { return R.transpose() * world; }
    /// The pose of a frame placed at `inner` in this one (a compound's part in the world).
    Pose operator*(const Pose& inner) const { return {R * inner.R, R * inner.p + p}; }
};

/// Axis-aligned box; empty (min > max) by default.
struct Aabb {
    Vec3 min = Vec3::Constant(std::numeric_limits<double>::infinity());
    Vec3 max = Vec3::Constant(-std::numeric_limits<double>::infinity());

    bool empty() const { return (min.array() > max.array()).any(); }
    bool overlaps(const Aabb& o) const {
        return (min.array() <= o.max.array()).all() && (o.min.array() <= max.array()).all();
    }
    bool contains(const Vec3& q) const {
        return (min.array() <= q.array()).all() && (q.array() <= max.array()).all();
    }
    void add(const Vec3& q) {
        min = min.cwiseMin(q);
        max = max.cwiseMax(q);
    }
    void add(const Aabb& o) {
        min = min.cwiseMin(o.min);
        max = max.cwiseMax(o.max);
    }
    Aabb inflated(double m) const { return {min.array() - m, max.array() + m}; }
    Vec3 center() const { return 0.5 * (min + max); }
    Vec3 extent() const { return max - min; }
};

/// A convex polyhedron in the body frame, as qhull builds it with coplanar facets merged.
struct ConvexHull {
    struct Face {
        Vec3 normal;          ///< outward unit normal
        double offset = 0.0;  ///< normal·p == offset on the face, < offset inside
        int first = 0;        ///< its vertices are faceVertices[first .. first + count)
        int count = 0;
    };
    std::vector<Vec3> vertices;
    std::vector<Face> faces;
    /// Every face's vertex indices, face after face, each face's counter-clockwise seen from
    /// outside. (One list for all: a list per face was a heap block per face, and half of
    /// the memory of a small hull.)
    std::vector<int> faceVertices;
    std::vector<std::array<int, 2>> edges;  ///< each undirected edge once
    Vec3 interiorPoint = Vec3::Zero();      ///< strictly inside (the mean of the vertices)

    std::span<const int> verticesOf(const Face& f) const {
        return {faceVertices.data() + f.first, static_cast<std::size_t>(f.count)};
    }
    /// Appends a face with these vertices.
    void addFace(const Vec3& normal, double offset, std::span<const int> vertexIndices) {
        faces.push_back({normal, offset, static_cast<int>(faceVertices.size()), static_cast<int>(vertexIndices.size())});
        faceVertices.insert(faceVertices.end(), vertexIndices.begin(), vertexIndices.end());
    }
};

class TriangleBvh;  // engine internal: a bounding-volume hierarchy over a mesh's triangles

/// A triangle mesh used as it is, concave allowed, in the body frame (already scaled).
struct MeshShape {
    std::vector<Vec3> vertices;
    std::vector<std::array<int, 3>> triangles;  ///< counter-clockwise seen from outside
    bool closed = false;                        ///< bounds a solid: ray parity is meaningful
    std::shared_ptr<const TriangleBvh> bvh;
};

enum class Kind { Sphere, Box, Capsule, Cylinder, Plane, Hull, Mesh, Compound };
const char* toString(Kind k);

struct Compound;  // below

/// A collision shape in the body frame. Only the fields of `kind` are used. The axis of a
/// capsule or cylinder is y; a plane's free side is normal·p > distance.
struct Shape {
    Kind kind = Kind::Sphere;
    double radius = 0.0;
    double halfHeight = 0.0;
    Vec3 halfExtents = Vec3::Zero();
    Vec3 normal = Vec3(0, 1, 0);
    double distance = 0.0;
    std::shared_ptr<const ConvexHull> hull;
    std::shared_ptr<const MeshShape> mesh;
    std::shared_ptr<const Compound> compound;

    static Shape sphere(double r);
    static Shape box(const Vec3& halfExtents);
    static Shape capsule(double r, double halfHeight);
    static Shape cylinder(double r, double halfHeight);
    static Shape plane(const Vec3& unitNormal, double distance);
};

/// Several shapes as one body's (a table's top and legs, a mesh's convex parts): each part
/// a shape of any kind but a plane or a compound, placed in the body frame. A manifold
/// between two bodies comes from one pair of parts, which it names (Manifold::partA, partB).
/// A number no other Compound made in this process has (the engine's caches tell compounds
/// apart by it, not by where they happen to be in memory).
std::uint64_t newCompoundSerial();

struct Compound {
    std::uint64_t serial = newCompoundSerial();
    struct Part {
        Shape shape;
        Pose pose;  ///< the part's frame in the body frame
        Aabb box;   ///< the part's bounds in the body frame
        double friction = 0.5;
        double restitution = 0.5;
    };
    std::vector<Part> parts;
    Aabb box;  ///< all the parts' bounds, body frame

    /// Calls visit(int part) for every part whose box (body frame) overlaps `box`.
    template <class Visit>
    void query(const Aabb& localBox, Visit&& visit) const {
        if (!box.overlaps(localBox)) return;
        for (int k = 0; k < static_cast<int>(parts.size()); ++k)
            if (parts[k].box.overlaps(localBox)) visit(k);
    }
};

/// The part's shape of a manifold's body: the part named for a compound, else the shape.
inline const Shape& partShape(const Shape& shape, int part) {
    return shape.kind == Kind::Compound ? shape.compound->parts[part].shape : shape;
}

/// The radius by which a shape's surface is its core grown (a sphere's centre, a capsule's
/// segment); 0 for shapes whose contact points are points of the body. (The contact solver
/// takes a round surface's gap from its core; contacts of parts alike in it can be merged.)
inline double roundness(const Shape& shape) {
    return shape.kind == Kind::Sphere || shape.kind == Kind::Capsule ? shape.radius : 0.0;
}

/// World bounds of a shape at a pose; a plane's bounds are infinite.
Aabb bounds(const Shape& shape, const Pose& pose);

/// The largest distance from the body origin to a point of the shape (infinite for a plane).
double boundingRadius(const Shape& shape);

/// The narrowest width of the solid, or a lower bound of it (a hull of more than 256 edges:
/// the diameter of the ball about its interior point that fits inside; infinite for a
/// plane, a half-space; 0 for a triangle mesh, which may be an open surface): a body moving less than this cannot
/// pass through it without still overlapping it at the end.
double thickness(const Shape& shape);

struct ContactPoint {
    Vec3 position = Vec3::Zero();  ///< world, midway between the surfaces
    double depth = 0.0;            ///< > 0 when overlapping
    std::uint32_t feature = 0;     ///< identifies the pair of features, stable while they touch
};

/// Up to four contact points sharing one normal.
struct Manifold {
    static constexpr int kMaxPoints = 4;
    int bodyA = -1;
    int bodyB = -1;
    Vec3 normal = Vec3(0, 1, 0);   ///< out of B towards A
    std::array<ContactPoint, kMaxPoints> points{};
    int count = 0;
    /// The parts the manifold is between, when a body is a compound (Compound::parts); 0
    /// otherwise.
    std::uint16_t partA = 0, partB = 0;

    void add(const Vec3& position, double depth, std::uint32_t feature = 0) {
        if (count < kMaxPoints) points[count++] = {position, depth, feature};
    }
    double maxDepth() const;
};

/// A list of manifolds. The step's lists live from step to step and grow with the contacts:
/// their large rooms are pages of their own, given back when a list outgrows them.
using ManifoldList = PageVector<Manifold>;

/// A pair that came into contact during a step: first touch at `time` (s), found by the
/// time-of-impact stage so that the response can act at the moment of impact.
struct ImpactEvent {
    int bodyA = -1;
    int bodyB = -1;
    double time = 0.0;
    Vec3 normal = Vec3(0, 1, 0);   ///< out of B towards A, at the time of impact
    Vec3 point = Vec3::Zero();     ///< world, at the time of impact
};

}  // namespace tumble::collision
