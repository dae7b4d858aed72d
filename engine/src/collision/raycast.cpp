// Ray casts over all bodies: each body's shape at its pose, the nearest hit kept. A body is
// only taken when strictly nearer, and later bodies are searched only up to the best
// distance so far, so a tie goes to the lower index.
#include <tumble/mass.h>
#include <tumble/model.h>
#include <tumble/raycast.h>

#include <algorithm>

namespace tumble {

namespace {

void keepNearest(std::optional<RayHit>& best, std::optional<RayHit> hit, int body) {
    if (hit && (!best || hit->distance < best->distance)) {
        best = hit;
        best->body = body;
    }
}

}  // namespace

std::optional<RayHit> rayCast(const Model& model, const State& state, const Vec3& origin,
                              const Vec3& direction, double maxDistance, RayStart start) {
    std::optional<RayHit> best;
    const size_t n = std::min(model.bodies.size(), state.bodies.size());
    for (size_t i = 0; i < n; ++i) {
        const BodyModel& b = model.bodies[i];
        collision::Pose pose;
        pose.R = state.bodies[i].q.toRotationMatrix();
        pose.p = state.bodies[i].x - pose.R * b.centerOfMass;
        keepNearest(best,
                    collision::rayShape(b.collider, pose, origin, direction,
                                        best ? best->distance : maxDistance, start),
                    static_cast<int>(i));
    }
    return best;
}

std::optional<RayHit> rayShapeDesc(const ShapeDesc& s, const Vec3& position, const Quat& orientation,
                                   const Vec3& origin, const Vec3& direction, double maxDistance,
                                   RayStart start) {
    using collision::Shape;
    const double qn = orientation.norm();
    if (!(qn > 0.0)) return std::nullopt;
    collision::Pose pose;
    pose.R = Quat(orientation.coeffs() / qn).toRotationMatrix();
    pose.p = position;
    Shape shape;
    switch (s.type) {
        case ShapeType::Sphere: shape = Shape::sphere(s.radius); break;
        case ShapeType::Box: shape = Shape::box(s.halfExtents); break;
        case ShapeType::Capsule: shape = Shape::capsule(s.radius, s.halfHeight); break;
        case ShapeType::Cylinder: shape = Shape::cylinder(s.radius, s.halfHeight); break;
        case ShapeType::Plane: shape = Shape::plane(s.normal.stableNormalized(), s.distance); break;
        case ShapeType::Compound: {
            std::optional<RayHit> best;
            for (int k = 0; k < static_cast<int>(s.parts.size()); ++k) {
                const PartDesc& part = s.parts[k];
                // (Refused by validate, but the editor holds scenes with problems too.)
                if (part.shape.type == ShapeType::Compound || !(part.orientation.norm() > 0.0) ||
                    !part.orientation.coeffs().allFinite() || !part.position.allFinite())
                    continue;
                const Quat q = Quat(orientation.coeffs() / qn) * part.orientation.normalized();
                auto hit = rayShapeDesc(part.shape, pose.toWorld(part.position), q, origin, direction,
                                        best ? best->distance : maxDistance, start);
                if (hit && (!best || hit->distance < best->distance)) {
                    best = hit;
                    best->part = k;
                }
            }
            return best;
        }
        case ShapeType::Mesh:
            if (!s.meshData) return std::nullopt;
            // Closedness costs a pass over the edges; only the solid query needs it.
            return collision::rayTriangles(s.meshData->vertices, s.meshData->triangles, pose, origin,
                                           direction, maxDistance, start,
                                           start == RayStart::Solid && isClosed(*s.meshData));
    }
    return collision::rayShape(shape, pose, origin, direction, maxDistance, start);
}

std::optional<RayHit> rayCastScene(const SceneDesc& scene, const Vec3& origin, const Vec3& direction,
                                   double maxDistance, RayStart start) {
    std::optional<RayHit> best;
    for (size_t i = 0; i < scene.bodies.size(); ++i) {
        const BodyDesc& b = scene.bodies[i];
        keepNearest(best,
                    rayShapeDesc(b.shape, b.position, b.orientation, origin, direction,
                                 best ? best->distance : maxDistance, start),
                    static_cast<int>(i));
    }
    return best;
}

}  // namespace tumble
