#include "viewport_raycast.h"

#include <tumble/mass.h>

#include <algorithm>
#include <cmath>
#include <limits>

namespace tumble::ui {

namespace {

// Keeps the smaller of two optional hits.
void keepNearest(std::optional<double>& best, std::optional<double> t) {
    if (t && (!best || *t < *best)) best = t;
}

// Roots of a t² + 2 b t + c = 0 (half-b form), smallest first; false if none.
bool solveQuadratic(double a, double b, double c, double& t0, double& t1) {
    if (a <= 0.0) return false;
    const double disc = b * b - a * c;
    if (disc < 0.0) return false;
    const double s = std::sqrt(disc);
    t0 = (-b - s) / a;
    t1 = (-b + s) / a;
    return true;
}

std::optional<double> firstNonNegative(double t0, double t1) {
    if (t0 >= 0.0) return t0;
    if (t1 >= 0.0) return t1;
    return std::nullopt;
}

}  // namespace

std::optional<double> raySphere(const Ray& ray, const Vec3& centre, double radius) {
    const Vec3 m = ray.origin - centre;
    const Vec3& d = ray.direction;
    double t0, t1;
    if (!solveQuadratic(d.squaredNorm(), m.dot(d), m.squaredNorm() - radius * radius, t0, t1)) {
        return std::nullopt;
    }
    return firstNonNegative(t0, t1);
}

std::optional<double> rayBox(const Ray& ray, const Vec3& h) {
    // Slabs: the ray is inside the box for t in [tNear, tFar].
    double tNear = -std::numeric_limits<double>::infinity();
    double tFar = std::numeric_limits<double>::infinity();
    for (int i = 0; i < 3; ++i) {
        const double o = ray.origin[i];
        const double d = ray.direction[i];
        if (d == 0.0) {
            if (o < -h[i] || o > h[i]) return std::nullopt;
            continue;
        }
        double ta = (-h[i] - o) / d;
        double tb = (h[i] - o) / d;
        if (ta > tb) std::swap(ta, tb);
        tNear = std::max(tNear, ta);
        tFar = std::min(tFar, tb);
        if (tNear > tFar) return std::nullopt;
    }
    return firstNonNegative(tNear, tFar);
}

std::optional<double> rayCylinder(const Ray& ray, double r, double h) {
    const Vec3& o = ray.origin;
    const Vec3& d = ray.direction;
    std::optional<double> best;
    // The side: x² + z² = r² with |y| <= h.
    double t0, t1;
    if (solveQuadratic(d.x() * d.x() + d.z() * d.z(), o.x() * d.x() + o.z() * d.z(),
                       o.x() * o.x() + o.z() * o.z() - r * r, t0, t1)) {
        for (double t : {t0, t1}) {
            if (t < 0.0) continue;
            const double y = o.y() + t * d.y();
            if (std::abs(y) <= h) keepNearest(best, t);
        }
    }
    // The caps: y = ±h with x² + z² <= r².
    if (d.y() != 0.0) {
        for (double y : {-h, h}) {
            const double t = (y - o.y()) / d.y();
            if (t < 0.0) continue;
            const Vec3 p = o + t * d;
            if (p.x() * p.x() + p.z() * p.z() <= r * r) keepNearest(best, t);
        }
    }
    return best;
}

std::optional<double> rayCapsule(const Ray& ray, double r, double h) {
    const Vec3& o = ray.origin;
    const Vec3& d = ray.direction;
    std::optional<double> best;
    double t0, t1;
    if (solveQuadratic(d.x() * d.x() + d.z() * d.z(), o.x() * d.x() + o.z() * d.z(),
                       o.x() * o.x() + o.z() * o.z() - r * r, t0, t1)) {
        for (double t : {t0, t1}) {
            if (t < 0.0) continue;
            if (std::abs(o.y() + t * d.y()) <= h) keepNearest(best, t);
        }
    }
    // The hemispheres: hits on each end sphere beyond its end of the segment.
    for (double y : {-h, h}) {
        const Vec3 c(0, y, 0);
        const Vec3 m = o - c;
        if (!solveQuadratic(d.squaredNorm(), m.dot(d), m.squaredNorm() - r * r, t0, t1)) continue;
        for (double t : {t0, t1}) {
            if (t < 0.0) continue;
            const double py = o.y() + t * d.y();
            if ((y > 0 && py >= h) || (y < 0 && py <= -h) || h == 0.0) keepNearest(best, t);
        }
    }
    return best;
}

std::optional<double> rayPlane(const Ray& ray, const Vec3& n, double distance) {
    const double denom = n.dot(ray.direction);
    if (denom == 0.0) return std::nullopt;
    const double t = (distance - n.dot(ray.origin)) / denom;
    if (t < 0.0) return std::nullopt;
    return t;
}

std::optional<double> rayTriangle(const Ray& ray, const Vec3& a, const Vec3& b, const Vec3& c) {
    // Möller–Trumbore, both faces.
    const Vec3 e1 = b - a;
    const Vec3 e2 = c - a;
    const Vec3 p = ray.direction.cross(e2);
    const double det = e1.dot(p);
    if (det == 0.0) return std::nullopt;
    const double inv = 1.0 / det;
    const Vec3 s = ray.origin - a;
    const double u = s.dot(p) * inv;
    if (u < 0.0 || u > 1.0) return std::nullopt;
    const Vec3 q = s.cross(e1);
    const double v = ray.direction.dot(q) * inv;
    if (v < 0.0 || u + v > 1.0) return std::nullopt;
    const double t = e2.dot(q) * inv;
    if (t < 0.0) return std::nullopt;
    return t;
}

std::optional<double> rayMesh(const Ray& ray, const TriangleMesh& mesh) {
    std::optional<double> best;
    for (const auto& tri : mesh.triangles) {
        keepNearest(best, rayTriangle(ray, mesh.vertices[static_cast<size_t>(tri[0])],
                                      mesh.vertices[static_cast<size_t>(tri[1])],
                                      mesh.vertices[static_cast<size_t>(tri[2])]));
    }
    return best;
}

std::optional<double> rayShape(const Ray& worldRay, const ShapeDesc& shape, const Vec3& position,
                               const Quat& orientation) {
    // Into the body frame: a rotation keeps t in the same units.
    const Quat inv = orientation.normalized().conjugate();
    const Ray local{inv * (worldRay.origin - position), inv * worldRay.direction};
    switch (shape.type) {
        case ShapeType::Sphere: return raySphere(local, Vec3::Zero(), shape.radius);
        case ShapeType::Box: return rayBox(local, shape.halfExtents);
        case ShapeType::Capsule: return rayCapsule(local, shape.radius, shape.halfHeight);
        case ShapeType::Cylinder: return rayCylinder(local, shape.radius, shape.halfHeight);
        case ShapeType::Plane: {
            const double len = shape.normal.norm();
            if (len == 0.0) return std::nullopt;
            return rayPlane(local, shape.normal / len, shape.distance);
        }
        case ShapeType::Mesh:
            if (!shape.meshData) return std::nullopt;
            return rayMesh(local, *shape.meshData);
    }
    return std::nullopt;
}

}  // namespace tumble::ui
