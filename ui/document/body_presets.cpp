#include "document/body_presets.h"

#include <tumble/mass.h>

#include <algorithm>
#include <cmath>

namespace tumble::ui {

double boundingRadius(const ShapeDesc& s) {
    switch (s.type) {
        case ShapeType::Sphere: return s.radius;
        case ShapeType::Box: return s.halfExtents.norm();
        case ShapeType::Capsule: return s.radius + s.halfHeight;
        case ShapeType::Cylinder: return std::hypot(s.radius, s.halfHeight);
        case ShapeType::Plane: return 0.0;
        case ShapeType::Mesh: {
            if (!s.meshData || s.meshData->vertices.empty()) return 1.0;
            double r = 0.0;
            for (const Vec3& v : s.meshData->vertices) r = std::max(r, v.norm());
            return r;
        }
        case ShapeType::Compound: {
            double r = 0.0;
            for (const PartDesc& p : s.parts)
                if (p.shape.type != ShapeType::Compound)
                    r = std::max(r, p.position.norm() + boundingRadius(p.shape));
            return r > 0.0 ? r : 1.0;
        }
    }
    return 1.0;
}

Vec3 halfSize(const BodyDesc& body) {
    const ShapeDesc& s = body.shape;
    // Unrotated primitives have a tight answer; anything else falls back to the sphere.
    const bool upright = body.orientation.coeffs().isApprox(Quat::Identity().coeffs()) ||
                         body.orientation.coeffs().isApprox(-Quat::Identity().coeffs());
    if (upright) {
        switch (s.type) {
            case ShapeType::Sphere: return Vec3::Constant(s.radius);
            case ShapeType::Box: return s.halfExtents;
            case ShapeType::Capsule: return Vec3(s.radius, s.radius + s.halfHeight, s.radius);
            case ShapeType::Cylinder: return Vec3(s.radius, s.halfHeight, s.radius);
            default: break;
        }
    }
    return Vec3::Constant(boundingRadius(s));
}

double halfHeightAboveOrigin(const BodyDesc& body) {
    return halfSize(body).y();
}

BodyDesc presetBody(ShapeType type, const SceneDesc& scene) {
    BodyDesc b;
    b.name = toString(type);
    b.shape.type = type;
    switch (type) {
        case ShapeType::Sphere: b.shape.radius = 0.5; break;
        case ShapeType::Box: b.shape.halfExtents = Vec3(0.5, 0.5, 0.5); break;
        case ShapeType::Capsule:
            b.shape.radius = 0.25;
            b.shape.halfHeight = 0.5;
            break;
        case ShapeType::Cylinder:
            b.shape.radius = 0.5;
            b.shape.halfHeight = 0.5;
            break;
        case ShapeType::Plane:
            b.name = "floor";
            b.motion = Motion::Static;
            b.shape.normal = Vec3::UnitY();
            b.shape.distance = 0.0;
            return b;
        case ShapeType::Mesh: break;
        case ShapeType::Compound:
            // A table-like start: a slab on a post, to be edited part by part.
            b.shape.parts.resize(2);
            b.shape.parts[0].name = "top";
            b.shape.parts[0].shape.type = ShapeType::Box;
            b.shape.parts[0].shape.halfExtents = Vec3(0.5, 0.05, 0.5);
            b.shape.parts[0].position = Vec3(0, 0.45, 0);
            b.shape.parts[1].name = "post";
            b.shape.parts[1].shape.type = ShapeType::Cylinder;
            b.shape.parts[1].shape.radius = 0.05;
            b.shape.parts[1].shape.halfHeight = 0.45;
            b.shape.parts[1].position = Vec3(0, 0, 0);
            break;
    }
    b.mass = 1.0;

    return placedAbove(b, pileTop(scene));
}

double pileTop(const SceneDesc& scene) {
    double top = 0.0;
    for (const BodyDesc& other : scene.bodies) {
        if (other.shape.type == ShapeType::Plane) continue;
        top = std::max(top, other.position.y() + halfHeightAboveOrigin(other));
    }
    return top;
}

BodyDesc placedAbove(BodyDesc body, double top) {
    if (body.shape.type == ShapeType::Plane) return body;
    body.position.y() = top + 0.5 + halfHeightAboveOrigin(body);
    return body;
}

}  // namespace tumble::ui
