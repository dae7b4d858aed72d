// Bullet 3.24 (Debian's libbullet-dev, the double-precision "-float64" libraries) behind the
// benchmark's adapter interface.
//
// Modes, most accurate first. All use btDiscreteDynamicsWorld with the sequential-impulse
// solver at settings.solverIterations iterations and one fixed step of dt per step()
// (stepSimulation(dt, 0): no substeps, no interpolation). They differ in how the gyroscopic
// term w x (I w) enters the velocity update (btRigidBody flags):
//   gyro-implicit-body   BT_ENABLE_GYROSCOPIC_FORCE_IMPLICIT_BODY: one Newton step of the
//                        implicit Euler update in body coordinates (Bullet's default)
//   gyro-implicit-world  BT_ENABLE_GYROSCOPIC_FORCE_IMPLICIT_WORLD: the same in world axes
//   gyro-explicit        BT_ENABLE_GYROSCOPIC_FORCE_EXPLICIT: explicit, clamped by
//                        btContactSolverInfo::m_maxGyroscopicForce (unlimited here)
//   no-gyro              no gyroscopic term: w changes only by torques (fastest)
//   touching-contacts    gyro-implicit-body with contacts solved only once they touch
//                        (every body's contact processing threshold 0: no speculative
//                        contacts) and all penetration removed by split impulse (threshold 0,
//                        no Baumgarte velocity). Restitution comes out right (a dropped ball's
//                        apex within 0.3 % of e^2 h at 1/240 s) but a tall stack creeps:
//                        the top of a 20-box tower drifts 20 cm in 5 s, against 1 cm.
// The first four keep Bullet's contact handling: speculative contacts (found up to the
// contact breaking threshold, 2 cm, before touching, with the velocity that closes the gap
// allowed) and Baumgarte velocity for penetration under 4 cm. A speculative contact eats
// the bounce: the ball of peer_check arrives with the gap still open, is stopped at the
// surface and leaves at almost nothing (apex 0 instead of e^2 h).
//
// Translation:
// - Mass, inertia and centre of mass are Tumble's (compile()). Bullet wants a diagonal
//   inertia at the body origin, so the Bullet body frame is Tumble's principal frame at the
//   centre of mass and the shape sits in a btCompoundShape at the inverse offset (when the
//   offset is not the identity).
// - Shapes: sphere, box, capsule (btCapsuleShape, y axis), cylinder (btCylinderShape, y
//   axis), plane (btStaticPlaneShape, static only), mesh as its convex hull (Tumble's hull
//   vertices in a btConvexHullShape), mesh triangles on a static body (btBvhTriangleMeshShape).
//   Collision margins: spheres and capsules carry theirs inside the radius, boxes and
//   cylinders inside the extents; a convex hull's margin is added outside, so it is set to
//   1 mm instead of Bullet's 4 cm. Convex pairs get a full manifold per step (the collision
//   configuration's multipoint iterations: 3 perturbations), not one point per step.
// - Materials: gCalculateCombinedRestitutionCallback and ...FrictionCallback are set to
//   Tumble's rules (max restitution, sqrt of the product of frictions) while an adapter is
//   loaded (they are process globals). Bullet gives no bounce below
//   m_restitutionVelocityThreshold, set here to 1e-3 m/s (Bullet's default 0.2).
// - Forces, torques and damping: Tumble's force stage evaluated at the start of each step
//   (peer_common.h) and applied as central force and torque; Bullet's own damping is off.
// - Continuous collision detection on every dynamic body: once it moves farther than its
//   inner radius in a step, Bullet sweeps a sphere of half that radius (setCcdMotionThreshold,
//   setCcdSweptSphereRadius) and stops it at the first hit.
// - Sleeping follows settings.sleeping (Bullet's deactivation, its own thresholds).
// - Joints (issue 20): ball (btPoint2PointConstraint), hinge (btHingeConstraint on frames
//   whose z is the axis, so that its angle is A's turn relative to B about
//   A's axis, zero as placed, as Tumble's), slider (btSliderConstraint along the frames' x,
//   without limits or motor) and fixed (btFixedConstraint holding the pose as placed), at
//   the anchors as the scene places them at t = 0. Hinge limits: setLimit (softness 0.9,
//   bias 0.3, relaxation 1, Bullet's defaults); motors: enableAngularMotor with the torque
//   limit times dt as the impulse limit; breaking: setBreakingImpulseThreshold at the
//   breaking force times dt. Joined bodies do not collide (addConstraint's flag), as in
//   Tumble. Bullet's default constraint solver settings (ERP 0.2).
// - Refused: springs, moving kinematic bodies, distance and rope joints, slider limits
//   and motors.
// - Differs: Bullet clamps the rotation per step to a quarter turn (|w| dt < pi/4 in
//   btTransformUtil::integrateTransform), so a body spinning faster than pi/(4 dt) is slowed.
#include "engine_adapter.h"
#include "peer_common.h"

#include <btBulletDynamicsCommon.h>

#include <cmath>
#include <limits>

namespace tumble::bench {
namespace {

btVector3 bt(const Vec3& v) {
    return btVector3(v.x(), v.y(), v.z());
}
Vec3 eig(const btVector3& v) {
    return Vec3(v.x(), v.y(), v.z());
}
btQuaternion bt(const Quat& q) {
    return btQuaternion(q.x(), q.y(), q.z(), q.w());
}
Quat eig(const btQuaternion& q) {
    return Quat(q.w(), q.x(), q.y(), q.z());
}

btScalar combinedRestitution(const btCollisionObject* a, const btCollisionObject* b) {
    return std::max(a->getRestitution(), b->getRestitution());
}
btScalar combinedFriction(const btCollisionObject* a, const btCollisionObject* b) {
    return std::sqrt(a->getFriction() * b->getFriction());
}

// The radius of a sphere that fits inside the shape (about its origin): Bullet's CCD sweeps
// a sphere of half this size once a body moves farther than this in one step.
double innerRadius(const collision::Shape& c) {
    switch (c.kind) {
        case collision::Kind::Sphere:
        case collision::Kind::Capsule: return c.radius;
        case collision::Kind::Box: return c.halfExtents.minCoeff();
        case collision::Kind::Cylinder: return std::min(c.radius, c.halfHeight);
        case collision::Kind::Hull: {
            double r = std::numeric_limits<double>::infinity();
            for (const auto& f : c.hull->faces)
                r = std::min(r, f.offset - f.normal.dot(c.hull->interiorPoint));
            return r;
        }
        case collision::Kind::Compound: {  // the thinnest part's
            double r = std::numeric_limits<double>::infinity();
            for (const auto& part : c.compound->parts) r = std::min(r, innerRadius(part.shape));
            return r;
        }
        case collision::Kind::Plane:
        case collision::Kind::Mesh: return 0.0;
    }
    return 0.0;
}

class BulletAdapter final : public EngineAdapter {
public:
    ~BulletAdapter() override { clear(); }

    std::string name() const override { return "bullet"; }
    std::vector<std::string> modes() const override {
        return {"gyro-implicit-body", "gyro-implicit-world", "gyro-explicit", "no-gyro", "touching-contacts"};
    }

    bool load(const SceneDesc& scene, const std::string& mode, double dt, std::string* why) override;
    void step() override;
    double time() const override { return time_; }
    int bodyCount() const override { return int(bodies_.size()); }
    BodySample body(int i) const override;
    int contactCount() const override;

private:
    struct Body {
        btRigidBody* rb = nullptr;
        Quat toBody = Quat::Identity();  ///< Bullet body frame (principal) to Tumble's body frame
        BodySample still;                ///< a static body's sample
    };

    void clear();
    bool makeJoint(const JointModel& j, std::string* why);
    btTransform frameIn(int i, const Vec3& p, const Vec3& axis, const Vec3& ref) const;
    btCollisionShape* makeShape(const BodyModel& b, const Vec3& position, const Quat& q, std::string* why);

    peer::PeerScene ps_;
    double dt_ = 0.0;
    double time_ = 0.0;
    bool loads_ = false;
    std::unique_ptr<btDefaultCollisionConfiguration> config_;
    std::unique_ptr<btCollisionDispatcher> dispatcher_;
    std::unique_ptr<btBroadphaseInterface> broadphase_;
    std::unique_ptr<btSequentialImpulseConstraintSolver> solver_;
    std::unique_ptr<btDiscreteDynamicsWorld> world_;
    std::vector<std::unique_ptr<btCollisionShape>> shapes_;
    std::vector<std::unique_ptr<btTriangleMesh>> meshes_;
    std::vector<std::unique_ptr<btRigidBody>> rigid_;
    std::vector<std::unique_ptr<btTypedConstraint>> constraints_;
    std::vector<std::pair<const JointModel*, btHingeConstraint*>> servos_;  // driven each step
    std::vector<Body> bodies_;
};

void BulletAdapter::clear() {
    if (world_) {
        for (auto& c : constraints_) world_->removeConstraint(c.get());
        for (auto& rb : rigid_) world_->removeRigidBody(rb.get());
    }
    constraints_.clear();
    servos_.clear();
    rigid_.clear();
    world_.reset();
    solver_.reset();
    broadphase_.reset();
    dispatcher_.reset();
    config_.reset();
    shapes_.clear();
    meshes_.clear();
    bodies_.clear();
}

btCollisionShape* BulletAdapter::makeShape(const BodyModel& b, const Vec3& position, const Quat& q,
                                           std::string* why) {
    const collision::Shape& c = b.collider;
    std::unique_ptr<btCollisionShape> s;
    switch (b.shape.type) {
        case ShapeType::Sphere: s = std::make_unique<btSphereShape>(c.radius); break;
        case ShapeType::Box: s = std::make_unique<btBoxShape>(bt(c.halfExtents)); break;
        case ShapeType::Capsule: s = std::make_unique<btCapsuleShape>(c.radius, 2.0 * c.halfHeight); break;
        case ShapeType::Cylinder:
            s = std::make_unique<btCylinderShape>(btVector3(c.radius, c.halfHeight, c.radius));
            break;
        case ShapeType::Plane: {
            // Static only: the plane in world coordinates on a body at the identity.
            Vec3 n;
            double d;
            peer::worldPlane(b, position, q, &n, &d);
            s = std::make_unique<btStaticPlaneShape>(bt(n), d);
            break;
        }
        case ShapeType::Mesh:
            if (b.shape.collision == MeshCollision::ConvexHull) {
                auto hull = std::make_unique<btConvexHullShape>();
                for (const Vec3& v : c.hull->vertices) hull->addPoint(bt(v), false);
                hull->recalcLocalAabb();
                hull->setMargin(0.001);
                s = std::move(hull);
            } else {
                if (!c.mesh) {
                    *why = "the mesh has no triangles";
                    return nullptr;
                }
                auto tm = std::make_unique<btTriangleMesh>(true, false);
                for (const auto& t : c.mesh->triangles)
                    tm->addTriangle(bt(c.mesh->vertices[t[0]]), bt(c.mesh->vertices[t[1]]),
                                    bt(c.mesh->vertices[t[2]]));
                s = std::make_unique<btBvhTriangleMeshShape>(tm.get(), true);
                meshes_.push_back(std::move(tm));
            }
            break;
        case ShapeType::Compound: {
            // A btCompoundShape of the parts (spheres, boxes, capsules, cylinders, hulls), each
            // at its pose in the body frame. (The parts' own materials are not translated:
            // Bullet takes one per body.)
            auto compound = std::make_unique<btCompoundShape>(true, int(c.compound->parts.size()));
            for (const collision::Compound::Part& part : c.compound->parts) {
                const collision::Shape& ps = part.shape;
                std::unique_ptr<btCollisionShape> child;
                switch (ps.kind) {
                    case collision::Kind::Sphere: child = std::make_unique<btSphereShape>(ps.radius); break;
                    case collision::Kind::Box:
                        child = std::make_unique<btBoxShape>(bt(ps.halfExtents));
                        break;
                    case collision::Kind::Capsule:
                        child = std::make_unique<btCapsuleShape>(ps.radius, 2.0 * ps.halfHeight);
                        break;
                    case collision::Kind::Cylinder:
                        child =
                            std::make_unique<btCylinderShape>(btVector3(ps.radius, ps.halfHeight, ps.radius));
                        break;
                    case collision::Kind::Hull: {
                        auto hull = std::make_unique<btConvexHullShape>();
                        for (const Vec3& v : ps.hull->vertices) hull->addPoint(bt(v), false);
                        hull->recalcLocalAabb();
                        hull->setMargin(0.001);
                        child = std::move(hull);
                        break;
                    }
                    default: *why = "a compound part of this kind is not translated"; return nullptr;
                }
                compound->addChildShape(btTransform(bt(Quat(part.pose.R)), bt(part.pose.p)), child.get());
                shapes_.push_back(std::move(child));
            }
            s = std::move(compound);
            break;
        }
    }
    shapes_.push_back(std::move(s));
    return shapes_.back().get();
}

bool BulletAdapter::load(const SceneDesc& scene, const std::string& mode, double dt, std::string* why) {
    clear();
    int gyro = 0;
    if (mode == "gyro-implicit-body") {
        gyro = BT_ENABLE_GYROSCOPIC_FORCE_IMPLICIT_BODY;
    } else if (mode == "gyro-implicit-world") {
        gyro = BT_ENABLE_GYROSCOPIC_FORCE_IMPLICIT_WORLD;
    } else if (mode == "gyro-explicit") {
        gyro = BT_ENABLE_GYROSCOPIC_FORCE_EXPLICIT;
    } else if (mode == "touching-contacts") {
        gyro = BT_ENABLE_GYROSCOPIC_FORCE_IMPLICIT_BODY;
    } else if (mode != "no-gyro") {
        if (why) *why = "unknown Bullet mode '" + mode + "'";
        return false;
    }
    std::string reason;
    if (!peer::prepare(
            scene,
            peer::PeerCaps{false, true,
                           peer::jointBit(JointType::Ball) | peer::jointBit(JointType::Hinge) |
                               peer::jointBit(JointType::Slider) | peer::jointBit(JointType::Fixed),
                           true, true, true, true, true, true},
            &ps_, &reason)) {
        if (why) *why = reason;
        return false;
    }
    dt_ = dt;
    time_ = 0.0;
    loads_ = peer::hasLoads(ps_.model);
    gCalculateCombinedRestitutionCallback = &combinedRestitution;
    gCalculateCombinedFrictionCallback = &combinedFriction;

    config_ = std::make_unique<btDefaultCollisionConfiguration>();
    // A full contact manifold in one step for convex shapes (otherwise one point per step,
    // accumulated over later steps: a hull on a plane rocks on a single point).
    config_->setConvexConvexMultipointIterations(3, 3);
    config_->setPlaneConvexMultipointIterations(3, 3);
    dispatcher_ = std::make_unique<btCollisionDispatcher>(config_.get());
    broadphase_ = std::make_unique<btDbvtBroadphase>();
    solver_ = std::make_unique<btSequentialImpulseConstraintSolver>();
    world_ = std::make_unique<btDiscreteDynamicsWorld>(dispatcher_.get(), broadphase_.get(), solver_.get(),
                                                       config_.get());
    world_->setGravity(bt(scene.settings.gravity));
    btContactSolverInfo& info = world_->getSolverInfo();
    info.m_numIterations = std::max(1, scene.settings.solverIterations);
    info.m_restitutionVelocityThreshold = 1e-3;
    const bool touching = mode == "touching-contacts";
    if (touching) info.m_splitImpulsePenetrationThreshold = 0.0;
    info.m_maxGyroscopicForce = std::numeric_limits<double>::max();

    const Model& m = ps_.model;
    for (int i = 0; i < int(m.bodies.size()); ++i) {
        const BodyModel& b = m.bodies[i];
        const BodyDesc& d = scene.bodies[i];
        const bool dynamic = b.motion == Motion::Dynamic;
        btCollisionShape* shape = makeShape(b, d.position, ps_.q[i], &reason);
        if (!shape) {
            if (why) *why = "bodies[" + std::to_string(i) + "]: " + reason;
            clear();
            return false;
        }
        Body out;
        btTransform start;
        btScalar mass = 0.0;
        btVector3 localInertia(0, 0, 0);
        if (b.shape.type == ShapeType::Plane) {
            start.setIdentity();
        } else if (dynamic) {
            // Bullet body frame: principal axes at the centre of mass.
            Quat principal(b.principalAxes);
            if (b.principalAxes.determinant() < 0.0) principal = Quat(Mat3(b.principalAxes * -1.0));
            principal.normalize();
            const Quat qBody = (ps_.q[i] * principal).normalized();
            out.toBody = principal.conjugate();
            const btTransform shapeInBody(bt(out.toBody), bt(out.toBody * -b.centerOfMass));
            const bool identity = b.centerOfMass.norm() == 0.0 && principal.vec().norm() == 0.0;
            if (!identity) {
                auto compound = std::make_unique<btCompoundShape>(false, 1);
                compound->addChildShape(shapeInBody, shape);
                shapes_.push_back(std::move(compound));
                shape = shapes_.back().get();
            }
            start = btTransform(bt(qBody), bt(ps_.com[i]));
            mass = b.mass;
            // The moments in the order of the principal axes' columns.
            const Vec3 moments = (b.principalAxes.transpose() * b.inertia * b.principalAxes).diagonal();
            localInertia = bt(moments);
        } else {
            start = btTransform(bt(ps_.q[i]), bt(d.position));
        }
        btRigidBody::btRigidBodyConstructionInfo ci(mass, nullptr, shape, localInertia);
        ci.m_startWorldTransform = start;
        ci.m_restitution = b.restitution;
        ci.m_friction = b.friction;
        ci.m_linearDamping = 0.0;
        ci.m_angularDamping = 0.0;
        auto rb = std::make_unique<btRigidBody>(ci);
        if (touching) rb->setContactProcessingThreshold(0.0);
        if (dynamic) {
            rb->setLinearVelocity(bt(ps_.v[i]));
            rb->setAngularVelocity(bt(ps_.w[i]));
            int flags = rb->getFlags() &
                        ~(BT_ENABLE_GYROSCOPIC_FORCE_EXPLICIT | BT_ENABLE_GYROSCOPIC_FORCE_IMPLICIT_WORLD |
                          BT_ENABLE_GYROSCOPIC_FORCE_IMPLICIT_BODY);
            rb->setFlags(flags | gyro);
            if (!scene.settings.sleeping) rb->setActivationState(DISABLE_DEACTIVATION);
            // Continuous collision for a body that moves more than its inner radius in a step.
            const double inner = innerRadius(b.collider);
            rb->setCcdMotionThreshold(inner);
            rb->setCcdSweptSphereRadius(0.5 * inner);
        } else {
            out.still.x = ps_.com[i];
            out.still.q = ps_.q[i];
        }
        out.rb = rb.get();
        world_->addRigidBody(rb.get());
        rigid_.push_back(std::move(rb));
        bodies_.push_back(out);
    }
    for (const JointModel& j : m.joints)
        if (!makeJoint(j, &reason)) {
            if (why) *why = "joints[" + std::to_string(j.index) + "] (" + j.name + "): " + reason;
            clear();
            return false;
        }
    return true;
}

// A frame in body i's Bullet coordinates at the world point p whose z is the world direction
// `axis` and whose x is the world direction `ref` (square to it); the world's frame for i < 0.
btTransform BulletAdapter::frameIn(int i, const Vec3& p, const Vec3& axis, const Vec3& ref) const {
    Mat3 basis;
    basis.col(0) = ref;
    basis.col(2) = axis;
    basis.col(1) = axis.cross(ref);
    const btTransform world(bt(Quat(basis).normalized()), bt(p));
    return i < 0 ? world : rigid_[i]->getCenterOfMassTransform().inverse() * world;
}

bool BulletAdapter::makeJoint(const JointModel& j, std::string* why) {
    Vec3 pa, pb, axis;
    peer::jointStart(ps_, j, &pa, &pb, &axis);
    btRigidBody& A = *rigid_[j.a];
    btRigidBody* B = j.b < 0 ? nullptr : rigid_[j.b].get();
    auto local = [&](int i, const Vec3& p) {
        return i < 0 ? bt(p) : rigid_[i]->getCenterOfMassTransform().inverse() * bt(p);
    };
    std::unique_ptr<btTypedConstraint> c;
    switch (j.type) {
        case JointType::Ball:
            if (j.swingLimited || j.twistLimited) {
                // btConeTwistConstraint: its frames' x the twist axis (B's axis), the first
                // swing span towards y (Tumble's first half-angle's direction), the second
                // towards z; its twist range is symmetric.
                if (j.twistLimited && std::abs(j.twistLower + j.twistUpper) > 1e-12) {
                    *why = "a twist range not symmetric about 0 is not translated to Bullet";
                    return false;
                }
                const Quat qb = j.b < 0 ? Quat::Identity() : ps_.q[j.b];
                const Vec3 n = qb * j.axisB, e1 = qb * j.swingCross;
                const btTransform fa = frameIn(j.a, pa, n.cross(e1), n), fb = frameIn(j.b, pb, n.cross(e1), n);
                // (To the world: the fixed body with B's frame; Bullet's one-body form puts
                // B's frame at the world's origin, turned as A's.)
                auto ct = std::make_unique<btConeTwistConstraint>(A, B ? *B : btTypedConstraint::getFixedBody(),
                                                                  fa, fb);
                ct->setLimit(j.swingLimited ? j.swingLimit[0] : M_PI, j.swingLimited ? j.swingLimit[1] : M_PI,
                             j.twistLimited ? j.twistUpper : M_PI);
                c = std::move(ct);
                break;
            }
            if (B)
                c = std::make_unique<btPoint2PointConstraint>(A, *B, local(j.a, pa), local(j.b, pb));
            else
                c = std::make_unique<btPoint2PointConstraint>(A, local(j.a, pa));
            break;
        case JointType::Hinge: {
            // B's frame at B's anchor, turned as A's at t = 0: the angle starts at zero.
            const Vec3 ref = peer::anyPerpendicular(axis);
            const btTransform fa = frameIn(j.a, pa, axis, ref), fb = frameIn(j.b, pb, axis, ref);
            // useReferenceFrameA false: Bullet's angle (and motor speed) is then A's turn
            // relative to B, as Tumble's (tumble-peer-check's limited bar; true reversed it).
            auto h = B ? std::make_unique<btHingeConstraint>(A, *B, fa, fb, false)
                       : std::make_unique<btHingeConstraint>(A, fa, false);
            if (j.limited) h->setLimit(j.lower, j.upper);
            if (j.motor) h->enableAngularMotor(true, j.motorSpeed, j.motorMax * dt_);
            if (j.servo) {  // (its speed set each step: peer::servoSpeed)
                h->enableAngularMotor(true, 0.0, std::isfinite(j.servoMax) ? j.servoMax * dt_ : 1e30);
                servos_.emplace_back(&j, h.get());
            }
            c = std::move(h);
            break;
        }
        case JointType::Slider: {
            if (j.limited || j.motor) {
                *why = "slider limits and motors are not translated to Bullet";
                return false;
            }
            // btSliderConstraint slides along its frames' x.
            const Vec3 ref = peer::anyPerpendicular(axis);
            const btTransform fa = frameIn(j.a, pa, ref.cross(axis), axis), fb = frameIn(j.b, pb, ref.cross(axis), axis);
            c = B ? std::make_unique<btSliderConstraint>(A, *B, fa, fb, true)
                  : std::make_unique<btSliderConstraint>(A, fa, true);
            break;
        }
        case JointType::Fixed: {
            const btTransform fa = frameIn(j.a, pa, Vec3::UnitZ(), Vec3::UnitX());
            const btTransform fb = frameIn(j.b, pa, Vec3::UnitZ(), Vec3::UnitX());
            c = std::make_unique<btFixedConstraint>(A, B ? *B : btTypedConstraint::getFixedBody(), fa, fb);
            break;
        }
        case JointType::Distance:
        case JointType::Rope:
        case JointType::SixAxis: *why = std::string("a ") + toString(j.type) + " joint is not translated to Bullet"; return false;
    }
    if (std::isfinite(j.breakForce)) c->setBreakingImpulseThreshold(j.breakForce * dt_);
    world_->addConstraint(c.get(), true);
    constraints_.push_back(std::move(c));
    return true;
}

void BulletAdapter::step() {
    if (loads_) {
        for (int i : ps_.model.dynamicBodies) {
            btRigidBody* rb = bodies_[i].rb;
            const BodySample s = body(i);
            Vec3 F, T;
            peer::appliedLoad(ps_.model, i, time_, s.q, s.v, s.w, &F, &T);
            if (F.isZero(0.0) && T.isZero(0.0)) continue;
            rb->activate();
            rb->applyCentralForce(bt(F));
            rb->applyTorque(bt(T));
        }
    }
    for (const auto& [j, hinge] : servos_) {  // a servo by its time constant, as Tumble's
        const BodySample a = body(j->a);
        const Vec3 w = a.w - (j->b >= 0 ? body(j->b).w : Vec3::Zero());
        const double speed = peer::servoSpeed(*j, hinge->getHingeAngle(), w.dot(a.q * j->axisA), time_, dt_);
        hinge->enableAngularMotor(true, speed, hinge->getMaxMotorImpulse());
        bodies_[j->a].rb->activate();
    }
    world_->stepSimulation(dt_, 0, dt_);
    time_ += dt_;
}

BodySample BulletAdapter::body(int i) const {
    const Body& b = bodies_[i];
    if (!b.rb || b.rb->isStaticOrKinematicObject()) return b.still;
    BodySample s;
    const btTransform& t = b.rb->getCenterOfMassTransform();
    s.x = eig(t.getOrigin());
    s.q = (eig(t.getRotation()) * b.toBody).normalized();
    s.v = eig(b.rb->getLinearVelocity());
    s.w = eig(b.rb->getAngularVelocity());
    return s;
}

int BulletAdapter::contactCount() const {
    int n = 0;
    for (int k = 0; k < dispatcher_->getNumManifolds(); ++k)
        n += dispatcher_->getManifoldByIndexInternal(k)->getNumContacts();
    return n;
}

}  // namespace

std::unique_ptr<EngineAdapter> makeBulletAdapter() {
    return std::make_unique<BulletAdapter>();
}

}  // namespace tumble::bench
