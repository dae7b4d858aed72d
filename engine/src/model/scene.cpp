#include <tumble/scene.h>

namespace tumble {

const char* toString(Motion m) {
    switch (m) {
        case Motion::Dynamic: return "dynamic";
        case Motion::Static: return "static";
        case Motion::Kinematic: return "kinematic";
        case Motion::Animated: return "animated";
    }
    return "?";
}

const char* toString(ShapeType t) {
    switch (t) {
        case ShapeType::Sphere: return "sphere";
        case ShapeType::Box: return "box";
        case ShapeType::Capsule: return "capsule";
        case ShapeType::Cylinder: return "cylinder";
        case ShapeType::Plane: return "plane";
        case ShapeType::Mesh: return "mesh";
        case ShapeType::Compound: return "compound";
    }
    return "?";
}

const char* toString(MeshCollision c) {
    switch (c) {
        case MeshCollision::ConvexHull: return "convex-hull";
        case MeshCollision::Triangles: return "triangles";
        case MeshCollision::ConvexParts: return "convex-parts";
    }
    return "?";
}

const char* toString(ForceType t) {
    switch (t) {
        case ForceType::Force: return "force";
        case ForceType::Torque: return "torque";
        case ForceType::Spring: return "spring";
    }
    return "?";
}

const char* toString(Frame f) {
    return f == Frame::World ? "world" : "body";
}

const char* toString(ImpactTiming t) {
    return t == ImpactTiming::Exact ? "exact" : "end-of-step";
}

const char* toString(KeyInterpolation k) {
    return k == KeyInterpolation::Linear ? "linear" : "smooth";
}

const char* toString(JointType t) {
    switch (t) {
        case JointType::Ball: return "ball";
        case JointType::Distance: return "distance";
        case JointType::Rope: return "rope";
        case JointType::Hinge: return "hinge";
        case JointType::Slider: return "slider";
        case JointType::Fixed: return "fixed";
        case JointType::SixAxis: return "six_axis";
    }
    return "?";
}

bool ShapeDesc::operator==(const ShapeDesc& o) const {
    return type == o.type && radius == o.radius && halfHeight == o.halfHeight &&
           halfExtents == o.halfExtents && normal == o.normal && distance == o.distance && file == o.file &&
           scale == o.scale && collision == o.collision && maxParts == o.maxParts &&
           partsTolerance == o.partsTolerance && parts == o.parts;
}

bool PartDesc::operator==(const PartDesc& o) const {
    return name == o.name && shape == o.shape && position == o.position &&
           orientation.coeffs() == o.orientation.coeffs() && density == o.density && friction == o.friction &&
           restitution == o.restitution;
}

bool BodyDesc::operator==(const BodyDesc& o) const {
    // Eigen's quaternion has no operator==; compare its coefficients.
    return name == o.name && motion == o.motion && shape == o.shape && mass == o.mass &&
           density == o.density && inertia == o.inertia && centerOfMass == o.centerOfMass &&
           position == o.position && orientation.coeffs() == o.orientation.coeffs() &&
           velocity == o.velocity && angularVelocity == o.angularVelocity && restitution == o.restitution &&
           friction == o.friction && linearDamping == o.linearDamping && angularDamping == o.angularDamping &&
           forces == o.forces && collisionGroup == o.collisionGroup && keys == o.keys &&
           interpolation == o.interpolation;
}

}  // namespace tumble
