// Jolt Physics behind jolt_world.h (issue 53). Built only when a Jolt source tree is named
// (TUMBLE_JOLT_SOURCE), with Jolt's own flags. Jolt is single precision here (its default).
//
// Translation, on Jolt's defaults otherwise (see docs/benchmarks.md, "Jolt"):
// - The body frame is Tumble's: Jolt's body position is the shape's origin, its rotation
//   the body's orientation. The centre of mass is Tumble's, through an
//   OffsetCenterOfMassShape where it differs from the shape's own; mass and inertia are
//   Tumble's, given (EOverrideMassProperties::MassAndInertiaProvided).
// - Shapes: SphereShape, BoxShape and CylinderShape (their convex radius Jolt's default
//   0.05 m, or the shape's smallest half size when that is smaller), CapsuleShape,
//   ConvexHullShape (Tumble's hull vertices, Jolt's default largest convex radius),
//   PlaneShape (static), MeshShape (static), StaticCompoundShape.
// - No damping of Jolt's own (its default is 0.05 1/s): Tumble's damping comes as forces.
//   Jolt's other defaults stay (mode careful: continuous collision and no speed limit,
//   Settings::careful): discrete collision (no continuous), 10 velocity and 2
//   position iterations, speculative contacts within 2 cm, its angular speed limit
//   (15 pi rad/s), its sleeping thresholds. Friction combines as sqrt(f1 f2), restitution
//   as the larger: Tumble's rules, and Jolt's own defaults.
// - Joints: ball (PointConstraint), hinge (HingeConstraint; body 1 is Tumble's B, body 2
//   its A, so that Jolt's angle is A's turn relative to B, as Tumble's; limits; a velocity
//   motor), fixed (FixedConstraint, the pose as placed). Joined bodies pass through each
//   other unless the joint says they collide: a GroupFilterTable over the jointed bodies.
#include "jolt_world.h"

#include <Jolt/Jolt.h>

#include <Jolt/Core/Factory.h>
#include <Jolt/Core/JobSystemSingleThreaded.h>
#include <Jolt/Core/TempAllocator.h>
#include <Jolt/Physics/Body/BodyCreationSettings.h>
#include <Jolt/Physics/Collision/BroadPhase/BroadPhaseLayerInterfaceTable.h>
#include <Jolt/Physics/Collision/BroadPhase/ObjectVsBroadPhaseLayerFilterTable.h>
#include <Jolt/Physics/Collision/ContactListener.h>
#include <Jolt/Physics/Collision/GroupFilterTable.h>
#include <Jolt/Physics/Collision/ObjectLayerPairFilterTable.h>
#include <Jolt/Physics/Collision/Shape/BoxShape.h>
#include <Jolt/Physics/Collision/Shape/CapsuleShape.h>
#include <Jolt/Physics/Collision/Shape/ConvexHullShape.h>
#include <Jolt/Physics/Collision/Shape/CylinderShape.h>
#include <Jolt/Physics/Collision/Shape/MeshShape.h>
#include <Jolt/Physics/Collision/Shape/OffsetCenterOfMassShape.h>
#include <Jolt/Physics/Collision/Shape/PlaneShape.h>
#include <Jolt/Physics/Collision/Shape/SphereShape.h>
#include <Jolt/Physics/Collision/Shape/StaticCompoundShape.h>
#include <Jolt/Physics/Constraints/FixedConstraint.h>
#include <Jolt/Physics/Constraints/HingeConstraint.h>
#include <Jolt/Physics/Constraints/PointConstraint.h>
#include <Jolt/Physics/PhysicsSystem.h>
#include <Jolt/RegisterTypes.h>

#include <algorithm>
#include <atomic>
#include <mutex>

namespace tumble::bench::jolt {

namespace {

constexpr JPH::ObjectLayer kStill = 0, kMoving = 1;

JPH::Vec3 jv(const V3& v) {
    return JPH::Vec3(float(v.x), float(v.y), float(v.z));
}
JPH::Quat jq(const Q4& q) {
    return JPH::Quat(float(q.x), float(q.y), float(q.z), float(q.w)).Normalized();
}

// Jolt's allocator, factory and shape types, once a process.
void registerJolt() {
    static std::once_flag once;
    std::call_once(once, [] {
        JPH::RegisterDefaultAllocator();
        JPH::Factory::sInstance = new JPH::Factory();
        JPH::RegisterTypes();
    });
}

// The contact points of the manifolds added or kept in a step (callbacks from the one job
// thread, counted atomically all the same).
class ContactCounter final : public JPH::ContactListener {
public:
    std::atomic<int> points{0};
    void OnContactAdded(const JPH::Body&, const JPH::Body&, const JPH::ContactManifold& m,
                        JPH::ContactSettings&) override {
        points += int(m.mRelativeContactPointsOn1.size());
    }
    void OnContactPersisted(const JPH::Body&, const JPH::Body&, const JPH::ContactManifold& m,
                            JPH::ContactSettings&) override {
        points += int(m.mRelativeContactPointsOn1.size());
    }
};

JPH::ShapeRefC made(const JPH::ShapeSettings& settings, std::string* why) {
    const JPH::ShapeSettings::ShapeResult r = settings.Create();
    if (r.HasError()) {
        *why = "Jolt refused the shape: " + std::string(r.GetError().c_str());
        return nullptr;
    }
    return r.Get();
}

JPH::ShapeRefC shapeOf(const Shape& s, bool sharp, std::string* why) {
    const float cvx = sharp ? 0.0f : JPH::cDefaultConvexRadius;
    switch (s.kind) {
        case ShapeKind::Sphere: return new JPH::SphereShape(float(s.radius));
        case ShapeKind::Box: {
            const JPH::Vec3 h = jv(s.halfExtents);
            return made(JPH::BoxShapeSettings(h, std::min(cvx, h.ReduceMin())), why);
        }
        case ShapeKind::Capsule: return made(JPH::CapsuleShapeSettings(float(s.halfHeight), float(s.radius)), why);
        case ShapeKind::Cylinder:
            return made(JPH::CylinderShapeSettings(float(s.halfHeight), float(s.radius),
                                                   std::min({cvx, float(s.halfHeight), float(s.radius)})),
                        why);
        case ShapeKind::Hull: {
            JPH::Array<JPH::Vec3> points;
            for (const V3& p : s.points) points.push_back(jv(p));
            return made(JPH::ConvexHullShapeSettings(points), why);
        }
        case ShapeKind::Plane:
            return made(JPH::PlaneShapeSettings(JPH::Plane(jv(s.planeNormal), -float(s.planeOffset))), why);
        case ShapeKind::Mesh: {
            JPH::VertexList vertices;
            for (const V3& p : s.points) vertices.push_back(JPH::Float3(float(p.x), float(p.y), float(p.z)));
            JPH::IndexedTriangleList triangles;
            for (const auto& t : s.triangles) triangles.push_back(JPH::IndexedTriangle(t[0], t[1], t[2], 0));
            return made(JPH::MeshShapeSettings(vertices, triangles), why);
        }
        case ShapeKind::Compound: {
            JPH::StaticCompoundShapeSettings compound;
            for (const Shape::Part& p : s.parts) {
                JPH::ShapeRefC part = shapeOf(p.shape, sharp, why);
                if (!part) return nullptr;
                compound.AddShape(jv(p.position), jq(p.orientation), part);
            }
            return made(compound, why);
        }
    }
    *why = "an unknown shape";
    return nullptr;
}

}  // namespace

struct World::Impl {
    Settings settings;
    // Made with the system, sized by its most bodies: its contact constraints take their room
    // here each step (64 MB alone ran out on free-10000, sized for 160 000 of them).
    std::unique_ptr<JPH::TempAllocatorImpl> temp;
    JPH::JobSystemSingleThreaded jobs{JPH::cMaxPhysicsJobs};
    JPH::ObjectLayerPairFilterTable layers{2};
    JPH::BroadPhaseLayerInterfaceTable broadphase{2, 2};
    std::unique_ptr<JPH::ObjectVsBroadPhaseLayerFilterTable> layerFilter;
    JPH::PhysicsSystem system;
    bool initialised = false;
    ContactCounter contacts;
    int lastContacts = 0;
    std::vector<JPH::BodyID> bodies;
    std::vector<JPH::Ref<JPH::GroupFilterTable>> groups;
    std::vector<int> subGroup;  // per body: its index among the jointed bodies, or -1
};

// (Jolt's allocator is set before Impl's members allocate.)
World::World(const Settings& settings) : d_((registerJolt(), std::make_unique<Impl>())) {
    d_->settings = settings;
    d_->layers.EnableCollision(kMoving, kMoving);
    d_->layers.EnableCollision(kMoving, kStill);
    d_->broadphase.MapObjectToBroadPhaseLayer(kStill, JPH::BroadPhaseLayer(0));
    d_->broadphase.MapObjectToBroadPhaseLayer(kMoving, JPH::BroadPhaseLayer(1));
    d_->layerFilter = std::make_unique<JPH::ObjectVsBroadPhaseLayerFilterTable>(d_->broadphase, 2, d_->layers, 2);
}

World::~World() = default;

std::string World::version() {
    return std::to_string(JPH_VERSION_MAJOR) + "." + std::to_string(JPH_VERSION_MINOR) + "." +
           std::to_string(JPH_VERSION_PATCH) +
#ifdef JPH_DOUBLE_PRECISION
           " (double precision"
#else
           " (single precision"
#endif
#ifdef JPH_USE_AVX2
           ", AVX2"
#endif
           ")";
}

int World::addBody(const Body& b, std::string* why) {
    Impl& d = *d_;
    if (!d.initialised) {
        const unsigned most = unsigned(std::max(1024, d.settings.maxBodies));
        d.system.Init(most, 0, std::max(65536u, 16 * most), std::max(65536u, 16 * most), d.broadphase,
                      *d.layerFilter, d.layers);
        d.temp = std::make_unique<JPH::TempAllocatorImpl>((64u << 20) + (16u << 10) * most);
        d.system.SetGravity(jv(d.settings.gravity));
        JPH::PhysicsSettings ps = d.system.GetPhysicsSettings();
        if (d.settings.velocitySteps > 0) ps.mNumVelocitySteps = unsigned(d.settings.velocitySteps);
        if (d.settings.positionSteps > 0) ps.mNumPositionSteps = unsigned(d.settings.positionSteps);
        d.system.SetPhysicsSettings(ps);
        d.system.SetContactListener(&d.contacts);
        d.initialised = true;
    }
    JPH::ShapeRefC shape = shapeOf(b.shape, d.settings.sharpBoxes, why);
    if (!shape) return -1;
    const bool plane = b.shape.kind == ShapeKind::Plane;
    if (b.dynamic) {
        const JPH::Vec3 com = jv(b.centerOfMass);
        if (!(shape->GetCenterOfMass() - com).IsNearZero(1e-12f)) {
            shape = made(JPH::OffsetCenterOfMassShapeSettings(com - shape->GetCenterOfMass(), shape), why);
            if (!shape) return -1;
        }
    }
    JPH::BodyCreationSettings c(shape, plane ? JPH::RVec3::sZero() : JPH::RVec3(jv(b.position)),
                                plane ? JPH::Quat::sIdentity() : jq(b.orientation),
                                b.dynamic ? JPH::EMotionType::Dynamic : JPH::EMotionType::Static,
                                b.dynamic ? kMoving : kStill);
    c.mFriction = float(b.friction);
    c.mRestitution = float(b.restitution);
    c.mLinearDamping = 0.0f;
    c.mAngularDamping = 0.0f;
    c.mAllowSleeping = d.settings.sleeping;
    if (b.dynamic && d.settings.careful) {
        c.mMotionQuality = JPH::EMotionQuality::LinearCast;
        c.mMaxAngularVelocity = 1.0e4f;
    }
    if (b.dynamic) {
        c.mOverrideMassProperties = JPH::EOverrideMassProperties::MassAndInertiaProvided;
        c.mMassPropertiesOverride.mMass = float(b.mass);
        JPH::Mat44 inertia = JPH::Mat44::sIdentity();
        for (int r = 0; r < 3; ++r)
            for (int k = 0; k < 3; ++k) inertia(r, k) = float(b.inertia[size_t(3 * r + k)]);
        c.mMassPropertiesOverride.mInertia = inertia;
        c.mLinearVelocity = jv(b.velocity);
        c.mAngularVelocity = jv(b.angularVelocity);
    }
    const JPH::BodyID id = d.system.GetBodyInterface().CreateAndAddBody(
        c, b.dynamic ? JPH::EActivation::Activate : JPH::EActivation::DontActivate);
    if (id.IsInvalid()) {
        *why = "Jolt has no room for another body";
        return -1;
    }
    d.bodies.push_back(id);
    d.subGroup.push_back(-1);
    return int(d.bodies.size()) - 1;
}

bool World::addJoint(const Joint& j, std::string* why) {
    Impl& d = *d_;
    JPH::BodyLockInterfaceNoLock& lock = const_cast<JPH::BodyLockInterfaceNoLock&>(d.system.GetBodyLockInterfaceNoLock());
    JPH::Body* a = lock.TryGetBody(d.bodies[size_t(j.a)]);
    JPH::Body* b = j.b < 0 ? &JPH::Body::sFixedToWorld : lock.TryGetBody(d.bodies[size_t(j.b)]);
    if (!a || !b) {
        *why = "a joint's body is not there";
        return false;
    }
    JPH::Ref<JPH::TwoBodyConstraint> c;
    switch (j.kind) {
        case JointKind::Ball: {
            JPH::PointConstraintSettings s;
            s.mPoint1 = JPH::RVec3(jv(j.anchorB));
            s.mPoint2 = JPH::RVec3(jv(j.anchorA));
            c = s.Create(*b, *a);
            break;
        }
        case JointKind::Hinge: {
            JPH::HingeConstraintSettings s;
            s.mPoint1 = JPH::RVec3(jv(j.anchorB));
            s.mPoint2 = JPH::RVec3(jv(j.anchorA));
            s.mHingeAxis1 = s.mHingeAxis2 = jv(j.axis).Normalized();
            s.mNormalAxis1 = s.mNormalAxis2 = jv(j.normal).Normalized();
            if (j.limited) {
                s.mLimitsMin = float(std::clamp(j.lower, -M_PI, 0.0));
                s.mLimitsMax = float(std::clamp(j.upper, 0.0, M_PI));
            }
            if (j.motor) s.mMotorSettings.SetTorqueLimit(float(j.motorMax));
            auto* h = static_cast<JPH::HingeConstraint*>(s.Create(*b, *a));
            if (j.motor) {
                h->SetMotorState(JPH::EMotorState::Velocity);
                h->SetTargetAngularVelocity(float(j.motorSpeed));
            }
            c = h;
            break;
        }
        case JointKind::Fixed: {
            JPH::FixedConstraintSettings s;
            s.mAutoDetectPoint = true;
            c = s.Create(*b, *a);
            break;
        }
    }
    d.system.AddConstraint(c);
    if (!j.collide && j.b >= 0) {
        // The two pass through each other: one group over every jointed body, a sub-group
        // each, the pair's collision turned off (the table sized once, for all bodies).
        if (d.groups.empty()) d.groups.push_back(new JPH::GroupFilterTable(JPH::uint(d.bodies.size())));
        JPH::GroupFilterTable& table = *d.groups.front();
        for (int i : {j.a, j.b}) {
            if (d.subGroup[size_t(i)] >= 0) continue;
            d.subGroup[size_t(i)] = i;
            d.system.GetBodyInterface().SetCollisionGroup(d.bodies[size_t(i)],
                                                          JPH::CollisionGroup(&table, 0, JPH::CollisionGroup::SubGroupID(i)));
        }
        table.DisableCollision(JPH::CollisionGroup::SubGroupID(j.a), JPH::CollisionGroup::SubGroupID(j.b));
    }
    return true;
}

void World::ready() {
    d_->system.OptimizeBroadPhase();
}

void World::push(int body, const V3& force, const V3& torque) {
    JPH::BodyInterface& bi = d_->system.GetBodyInterface();
    bi.AddForceAndTorque(d_->bodies[size_t(body)], jv(force), jv(torque));
}

void World::step() {
    d_->contacts.points = 0;
    d_->system.Update(float(d_->settings.dt), 1, d_->temp.get(), &d_->jobs);
    d_->lastContacts = d_->contacts.points;
}

void World::sample(int body, V3* x, Q4* q, V3* v, V3* w) const {
    const JPH::BodyInterface& bi = d_->system.GetBodyInterfaceNoLock();
    const JPH::BodyID id = d_->bodies[size_t(body)];
    const JPH::RVec3 c = bi.GetCenterOfMassPosition(id);
    const JPH::Quat r = bi.GetRotation(id);
    const JPH::Vec3 lv = bi.GetLinearVelocity(id), av = bi.GetAngularVelocity(id);
    *x = {double(c.GetX()), double(c.GetY()), double(c.GetZ())};
    *q = {double(r.GetW()), double(r.GetX()), double(r.GetY()), double(r.GetZ())};
    *v = {double(lv.GetX()), double(lv.GetY()), double(lv.GetZ())};
    *w = {double(av.GetX()), double(av.GetY()), double(av.GetZ())};
}

int World::contactCount() const {
    return d_->lastContacts;
}

}  // namespace tumble::bench::jolt
