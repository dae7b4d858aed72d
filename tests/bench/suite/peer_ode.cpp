// ODE 0.16 (Debian's libode-dev, double precision) behind the benchmark's adapter interface.
//
// Modes, most accurate first:
//   step              dWorldStep: the big-matrix LCP solver (exact for the contact set),
//                     gyroscopic term on (dBodySetGyroscopicMode 1, ODE's default)
//   step-nogyro       dWorldStep, gyroscopic term off: w changes only by torques
//   quickstep         dWorldQuickStep: iterative SOR-LCP, settings.solverIterations
//                     iterations, gyroscopic term on
//   quickstep-nogyro  dWorldQuickStep, gyroscopic term off (fastest)
// Every mode: one dWorldStep/QuickStep of dt per step(), world ERP 0.2 and CFM 1e-10
// (stiff contacts, a fifth of the penetration corrected per step), contact surface layer 0,
// no limit on the correcting velocity.
//
// Translation:
// - Mass, inertia and centre of mass are Tumble's (compile()): ODE takes the full inertia
//   tensor but needs the centre of mass at the body origin, so the ODE body frame is Tumble's
//   body frame moved to the centre of mass and the geom is offset by -centerOfMass.
// - Shapes: sphere, box, capsule and cylinder (ODE's axis is z, rotated onto Tumble's y),
//   plane (a non-placeable dPlane, static only), mesh as its convex hull (dConvex from
//   Tumble's hull faces and planes), mesh triangles on a static body (dTriMesh).
// - Contacts: up to 8 points per geom pair from dCollide, each a contact joint with
//   dContactBounce | dContactApprox1 (friction pyramid scaled by the normal force), with
//   Tumble's rules computed per pair: bounce = max of the restitutions, mu = sqrt of the
//   product of the frictions; bounce_vel 1e-3 m/s (no bounce below it).
// - Forces, torques and damping: Tumble's force stage evaluated at the start of each step
//   (peer_common.h) and added with dBodyAddForce / dBodyAddTorque; ODE's damping is off.
// - Kinematic bodies: dBodySetKinematic with their constant velocities.
// - Sleeping follows settings.sleeping (ODE's auto-disable, its own thresholds).
// - Joints (issue 20): ball (dJointCreateBall), hinge (dJointCreateHinge), slider
//   (dJointCreateSlider), fixed (dJointCreateFixed) and distance (dJointCreateDBall, at
//   Tumble's length), at the anchors and axes as the scene places them at t = 0, with ODE's
//   default joint ERP and CFM. Hinge and slider limits are dParamLoStop / dParamHiStop
//   (bounce 0, as Tumble's inelastic stops) and motors dParamVel / dParamFMax: ODE's
//   hinge angle and slider position are body 1's (Tumble's A) relative to body 2, zero
//   where they were attached, so a slider's stops are shifted by the offset at t = 0.
//   Joined bodies do not collide (dAreConnected), as in Tumble.
// - Refused: springs, ropes, breaking joints.
// - Known: dWorldStep's Dantzig LCP reports "LCP internal error, s <= 0" on a 20-box tower
//   from the first step (with 1 to 8 points per pair, CFM 1e-10 to 1e-3, with or without
//   the friction pyramid) and the tower falls; dWorldQuickStep keeps it standing. A step
//   that ODE reports failed (it returns 0 when its memory runs out: dWorldStep's matrices
//   grow with the square of the contact rows) throws, and the tables show the failure. A convex
//   hull resting on a triangle mesh (libccd, one point per triangle) rocks by a few mm.
#include "engine_adapter.h"
#include "peer_common.h"

#include <ode/ode.h>

#include <array>
#include <cstdarg>
#include <cstdio>
#include <mutex>
#include <set>
#include <stdexcept>

namespace tumble::bench {
namespace {

constexpr int kMaxContacts = 8;

// ODE prints its messages (e.g. "LCP internal error, s <= 0" from dWorldStep's Dantzig
// solver) on every step; say the first of each kind once.
void quietMessage(int num, const char* msg, va_list ap) {
    static std::set<int> seen;
    if (!seen.insert(num).second) return;
    std::fprintf(stderr, "ODE message %d (said once): ", num);
    std::vfprintf(stderr, msg, ap);
    std::fprintf(stderr, "\n");
}

void setQuat(dQuaternion out, const Quat& q) {
    out[0] = q.w();
    out[1] = q.x();
    out[2] = q.y();
    out[3] = q.z();
}

class OdeAdapter final : public EngineAdapter {
public:
    OdeAdapter() {
        static std::once_flag once;
        std::call_once(once, [] {
            dInitODE2(0);
            dSetMessageHandler(&quietMessage);
        });
    }
    ~OdeAdapter() override { clear(); }

    std::string name() const override { return "ode"; }
    std::vector<std::string> modes() const override {
        return {"step", "step-nogyro", "quickstep", "quickstep-nogyro"};
    }

    bool load(const SceneDesc& scene, const std::string& mode, double dt, std::string* why) override;
    void step() override;
    double time() const override { return time_; }
    int bodyCount() const override { return int(bodies_.size()); }
    BodySample body(int i) const override;
    int contactCount() const override { return contacts_; }

private:
    struct Body {
        dBodyID id = nullptr;  ///< null for a body that never moves
        BodySample still;
        double restitution = 0.0;
        double friction = 0.0;
    };
    struct Hull {  // dConvex keeps pointers to these
        std::vector<dReal> planes;
        std::vector<dReal> points;
        std::vector<unsigned int> polygons;
    };
    struct Mesh {  // dTriMesh keeps pointers to these
        std::vector<double> vertices;
        std::vector<dTriIndex> indices;
        dTriMeshDataID data = nullptr;
    };

    void clear();
    void makeJoint(const JointModel& j);
    dGeomID makeGeom(const BodyModel& b, const Vec3& position, const Quat& q);
    bool addCompound(const BodyModel& b, const BodyDesc& d, int i, bool gyro, Body& out);
    dBodyID makeBody(const BodyModel& b, int i, bool gyro);
    static void nearCallback(void* self, dGeomID a, dGeomID b);
    void collide(dGeomID a, dGeomID b);

    peer::PeerScene ps_;
    double dt_ = 0.0;
    double time_ = 0.0;
    bool quick_ = false;
    bool loads_ = false;
    std::vector<std::pair<const JointModel*, dJointID>> servos_;  // driven each step
    int contacts_ = 0;
    int pending_ = 0;
    dWorldID world_ = nullptr;
    dSpaceID space_ = nullptr;
    dJointGroupID group_ = nullptr;
    std::vector<Body> bodies_;
    std::vector<std::unique_ptr<Hull>> hulls_;
    std::vector<std::unique_ptr<Mesh>> meshes_;
};

void OdeAdapter::clear() {
    if (group_) dJointGroupDestroy(group_);
    if (space_) dSpaceDestroy(space_);  // destroys its geoms (cleanup mode on by default)
    if (world_) dWorldDestroy(world_);  // and the bodies
    for (auto& m : meshes_) dGeomTriMeshDataDestroy(m->data);
    group_ = nullptr;
    space_ = nullptr;
    world_ = nullptr;
    bodies_.clear();
    servos_.clear();
    hulls_.clear();
    meshes_.clear();
}

dGeomID OdeAdapter::makeGeom(const BodyModel& b, const Vec3& position, const Quat& q) {
    const collision::Shape& c = b.collider;
    switch (b.shape.type) {
        case ShapeType::Sphere: return dCreateSphere(space_, c.radius);
        case ShapeType::Box:
            return dCreateBox(space_, 2.0 * c.halfExtents.x(), 2.0 * c.halfExtents.y(),
                              2.0 * c.halfExtents.z());
        case ShapeType::Capsule: return dCreateCapsule(space_, c.radius, 2.0 * c.halfHeight);
        case ShapeType::Cylinder: return dCreateCylinder(space_, c.radius, 2.0 * c.halfHeight);
        case ShapeType::Plane: {
            Vec3 n;
            double d;
            peer::worldPlane(b, position, q, &n, &d);
            return dCreatePlane(space_, n.x(), n.y(), n.z(), d);
        }
        case ShapeType::Mesh:
            if (b.shape.collision == MeshCollision::ConvexHull) {
                auto h = std::make_unique<Hull>();
                for (const Vec3& v : c.hull->vertices)
                    h->points.insert(h->points.end(), {v.x(), v.y(), v.z()});
                for (const auto& f : c.hull->faces) {
                    h->planes.insert(h->planes.end(), {f.normal.x(), f.normal.y(), f.normal.z(), f.offset});
                    h->polygons.push_back(unsigned(f.count));
                    for (int v : c.hull->verticesOf(f)) h->polygons.push_back(unsigned(v));
                }
                dGeomID g =
                    dCreateConvex(space_, h->planes.data(), unsigned(c.hull->faces.size()), h->points.data(),
                                  unsigned(c.hull->vertices.size()), h->polygons.data());
                hulls_.push_back(std::move(h));
                return g;
            } else {
                auto m = std::make_unique<Mesh>();
                for (const Vec3& v : c.mesh->vertices)
                    m->vertices.insert(m->vertices.end(), {v.x(), v.y(), v.z()});
                for (const auto& t : c.mesh->triangles)
                    m->indices.insert(m->indices.end(), {dTriIndex(t[0]), dTriIndex(t[1]), dTriIndex(t[2])});
                m->data = dGeomTriMeshDataCreate();
                dGeomTriMeshDataBuildDouble(m->data, m->vertices.data(), 3 * sizeof(double),
                                            int(c.mesh->vertices.size()), m->indices.data(),
                                            int(m->indices.size()), 3 * sizeof(dTriIndex));
                // Convex-against-triangles collision (libccd) needs the face angles.
                dGeomTriMeshDataPreprocess2(m->data, 1U << dTRIDATAPREPROCESS_BUILD_FACE_ANGLES, nullptr);
                dGeomID g = dCreateTriMesh(space_, m->data, nullptr, nullptr, nullptr);
                meshes_.push_back(std::move(m));
                return g;
            }
        case ShapeType::Compound: break;  // (refused by peer::prepare)
    }
    return nullptr;
}

// The ODE body of a moving body: its mass and inertia about the centre of mass (dynamic) or
// kinematic, placed and moving as the scene says, undamped.
dBodyID OdeAdapter::makeBody(const BodyModel& b, int i, bool gyro) {
    const dBodyID id = dBodyCreate(world_);
    if (b.motion == Motion::Dynamic) {
        dMass mass;
        const Mat3& I = b.inertia;
        dMassSetParameters(&mass, b.mass, 0, 0, 0, I(0, 0), I(1, 1), I(2, 2), I(0, 1), I(0, 2), I(1, 2));
        dBodySetMass(id, &mass);
        dBodySetGyroscopicMode(id, gyro ? 1 : 0);
    } else {
        dBodySetKinematic(id);
    }
    const Vec3& x = ps_.com[i];
    dBodySetPosition(id, x.x(), x.y(), x.z());
    dQuaternion qq;
    setQuat(qq, ps_.q[i]);
    dBodySetQuaternion(id, qq);
    dBodySetLinearVel(id, ps_.v[i].x(), ps_.v[i].y(), ps_.v[i].z());
    dBodySetAngularVel(id, ps_.w[i].x(), ps_.w[i].y(), ps_.w[i].z());
    dBodySetLinearDamping(id, 0.0);
    dBodySetAngularDamping(id, 0.0);
    dBodySetMaxAngularSpeed(id, dInfinity);
    return id;
}

bool OdeAdapter::addCompound(const BodyModel& b, const BodyDesc& d, int i, bool gyro, Body& out) {
    std::vector<dGeomID> geoms;
    for (const collision::Compound::Part& part : b.collider.compound->parts) {
        const collision::Shape& c = part.shape;
        dGeomID g = nullptr;
        switch (c.kind) {
            case collision::Kind::Sphere: g = dCreateSphere(space_, c.radius); break;
            case collision::Kind::Box:
                g = dCreateBox(space_, 2.0 * c.halfExtents.x(), 2.0 * c.halfExtents.y(),
                               2.0 * c.halfExtents.z());
                break;
            case collision::Kind::Capsule: g = dCreateCapsule(space_, c.radius, 2.0 * c.halfHeight); break;
            case collision::Kind::Cylinder: g = dCreateCylinder(space_, c.radius, 2.0 * c.halfHeight); break;
            default: return false;
        }
        dGeomSetData(g, reinterpret_cast<void*>(std::intptr_t(i)));
        geoms.push_back(g);
    }
    auto partTurn = [&](size_t k) {
        const collision::Shape& c = b.collider.compound->parts[k].shape;
        const Quat q(b.collider.compound->parts[k].pose.R);
        return c.kind == collision::Kind::Capsule || c.kind == collision::Kind::Cylinder
                   ? Quat(q * peer::zToY())
                   : q;
    };
    dQuaternion qq;
    if (b.standsStill()) {
        out.still.x = ps_.com[i];
        out.still.q = ps_.q[i];
        for (size_t k = 0; k < geoms.size(); ++k) {
            const Vec3 p = d.position + ps_.q[i] * b.collider.compound->parts[k].pose.p;
            dGeomSetPosition(geoms[k], p.x(), p.y(), p.z());
            setQuat(qq, Quat(ps_.q[i] * partTurn(k)));
            dGeomSetQuaternion(geoms[k], qq);
        }
        return true;
    }
    out.id = makeBody(b, i, gyro);
    for (size_t k = 0; k < geoms.size(); ++k) {
        dGeomSetBody(geoms[k], out.id);
        const Vec3 offset = b.collider.compound->parts[k].pose.p - b.centerOfMass;
        dGeomSetOffsetPosition(geoms[k], offset.x(), offset.y(), offset.z());
        setQuat(qq, partTurn(k));
        dGeomSetOffsetQuaternion(geoms[k], qq);
    }
    return true;
}

bool OdeAdapter::load(const SceneDesc& scene, const std::string& mode, double dt, std::string* why) {
    clear();
    bool gyro = true;
    if (mode == "step") {
        quick_ = false;
    } else if (mode == "step-nogyro") {
        quick_ = false;
        gyro = false;
    } else if (mode == "quickstep") {
        quick_ = true;
    } else if (mode == "quickstep-nogyro") {
        quick_ = true;
        gyro = false;
    } else {
        if (why) *why = "unknown ODE mode '" + mode + "'";
        return false;
    }
    std::string reason;
    if (!peer::prepare(
            scene,
            peer::PeerCaps{true, true,
                           peer::jointBit(JointType::Ball) | peer::jointBit(JointType::Hinge) |
                               peer::jointBit(JointType::Slider) | peer::jointBit(JointType::Fixed) |
                               peer::jointBit(JointType::Distance),
                           true, true, false, true, false, true},
            &ps_, &reason)) {
        if (why) *why = reason;
        return false;
    }
    dt_ = dt;
    time_ = 0.0;
    contacts_ = 0;
    loads_ = peer::hasLoads(ps_.model);

    world_ = dWorldCreate();
    space_ = dHashSpaceCreate(nullptr);
    group_ = dJointGroupCreate(0);
    const Vec3& g = scene.settings.gravity;
    dWorldSetGravity(world_, g.x(), g.y(), g.z());
    dWorldSetERP(world_, 0.2);
    dWorldSetCFM(world_, 1e-10);
    dWorldSetContactSurfaceLayer(world_, 0.0);
    dWorldSetQuickStepNumIterations(world_, std::max(1, scene.settings.solverIterations));
    dWorldSetAutoDisableFlag(world_, scene.settings.sleeping ? 1 : 0);
    dWorldSetLinearDamping(world_, 0.0);
    dWorldSetAngularDamping(world_, 0.0);

    const Model& m = ps_.model;
    for (int i = 0; i < int(m.bodies.size()); ++i) {
        const BodyModel& b = m.bodies[i];
        const BodyDesc& d = scene.bodies[i];
        Body out;
        out.restitution = b.restitution;
        out.friction = b.friction;
        if (b.shape.type == ShapeType::Compound) {
            // A geom per part on one body, each offset to its place (its own materials are
            // not translated: the contact callback takes the body's).
            if (!addCompound(b, d, i, gyro, out)) {
                if (why)
                    *why =
                        "bodies[" + std::to_string(i) + "]: a compound part of this kind is not translated";
                clear();
                return false;
            }
            bodies_.push_back(out);
            continue;
        }
        dGeomID geom = makeGeom(b, d.position, ps_.q[i]);
        if (!geom) {
            if (why) *why = "bodies[" + std::to_string(i) + "]: the shape is not translated";
            clear();
            return false;
        }
        dGeomSetData(geom, reinterpret_cast<void*>(std::intptr_t(i)));
        const bool axisZ = b.shape.type == ShapeType::Capsule || b.shape.type == ShapeType::Cylinder;
        dQuaternion qq;
        if (b.standsStill()) {
            out.still.x = ps_.com[i];
            out.still.q = ps_.q[i];
            if (b.shape.type != ShapeType::Plane) {
                dGeomSetPosition(geom, d.position.x(), d.position.y(), d.position.z());
                setQuat(qq, axisZ ? Quat(ps_.q[i] * peer::zToY()) : ps_.q[i]);
                dGeomSetQuaternion(geom, qq);
            }
        } else {
            out.id = makeBody(b, i, gyro);
            dGeomSetBody(geom, out.id);
            const Vec3& com = b.centerOfMass;
            if (com.norm() > 0.0) dGeomSetOffsetPosition(geom, -com.x(), -com.y(), -com.z());
            if (axisZ) {
                setQuat(qq, peer::zToY());
                dGeomSetOffsetQuaternion(geom, qq);
            }
        }
        bodies_.push_back(out);
    }
    for (const JointModel& j : m.joints) makeJoint(j);
    return true;
}

void OdeAdapter::makeJoint(const JointModel& j) {
    Vec3 pa, pb, axis;
    peer::jointStart(ps_, j, &pa, &pb, &axis);
    dJointID id = nullptr;
    switch (j.type) {
        case JointType::Ball: id = dJointCreateBall(world_, nullptr); break;
        case JointType::Hinge: id = dJointCreateHinge(world_, nullptr); break;
        case JointType::Slider: id = dJointCreateSlider(world_, nullptr); break;
        case JointType::Fixed: id = dJointCreateFixed(world_, nullptr); break;
        case JointType::Distance: id = dJointCreateDBall(world_, nullptr); break;
        case JointType::Rope:
        case JointType::SixAxis: return;  // refused by prepare
    }
    dJointAttach(id, bodies_[j.a].id, j.b < 0 ? nullptr : bodies_[j.b].id);
    // Limits and motor of the one free coordinate (hinge and slider).
    auto axial = [&](int lo, int hi, int vel, int fmax, double shift) {
        auto set = j.type == JointType::Hinge ? dJointSetHingeParam : dJointSetSliderParam;
        if (j.limited) {
            set(id, lo, j.lower - shift);
            set(id, hi, j.upper - shift);
            set(id, dParamBounce, 0.0);
        }
        if (j.motor) {
            set(id, vel, j.motorSpeed);
            set(id, fmax, j.motorMax);
        }
    };
    switch (j.type) {
        case JointType::Ball: dJointSetBallAnchor(id, pa.x(), pa.y(), pa.z()); break;
        case JointType::Hinge:
            dJointSetHingeAnchor(id, pa.x(), pa.y(), pa.z());
            dJointSetHingeAxis(id, axis.x(), axis.y(), axis.z());
            axial(dParamLoStop, dParamHiStop, dParamVel, dParamFMax, 0.0);
            if (j.servo) {  // (its speed set each step: peer::servoSpeed)
                dJointSetHingeParam(id, dParamFMax, std::isfinite(j.servoMax) ? j.servoMax : dInfinity);
                servos_.emplace_back(&j, id);
            }
            break;
        case JointType::Slider:
            dJointSetSliderAxis(id, axis.x(), axis.y(), axis.z());
            axial(dParamLoStop, dParamHiStop, dParamVel, dParamFMax, (pa - pb).dot(axis));
            break;
        case JointType::Fixed: dJointSetFixed(id); break;
        case JointType::Distance:
            dJointSetDBallAnchor1(id, pa.x(), pa.y(), pa.z());
            dJointSetDBallAnchor2(id, pb.x(), pb.y(), pb.z());
            dJointSetDBallDistance(id, j.length);
            break;
        case JointType::Rope:
        case JointType::SixAxis: break;
    }
}

void OdeAdapter::nearCallback(void* self, dGeomID a, dGeomID b) {
    static_cast<OdeAdapter*>(self)->collide(a, b);
}

void OdeAdapter::collide(dGeomID ga, dGeomID gb) {
    dBodyID ba = dGeomGetBody(ga), bb = dGeomGetBody(gb);
    if (!ba && !bb) return;
    if (ba && ba == bb) return;  // two parts of one compound
    if (ba && bb && dAreConnected(ba, bb)) return;
    const Body& A = bodies_[std::intptr_t(dGeomGetData(ga))];
    const Body& B = bodies_[std::intptr_t(dGeomGetData(gb))];
    std::array<dContact, kMaxContacts> c{};
    const int n = dCollide(ga, gb, kMaxContacts, &c[0].geom, sizeof(dContact));
    for (int k = 0; k < n; ++k) {
        c[k].surface.mode = dContactBounce | dContactApprox1;
        c[k].surface.mu = std::sqrt(A.friction * B.friction);
        c[k].surface.bounce = std::max(A.restitution, B.restitution);
        c[k].surface.bounce_vel = 1e-3;
        dJointID j = dJointCreateContact(world_, group_, &c[k]);
        dJointAttach(j, ba, bb);
    }
    pending_ += n;
}

void OdeAdapter::step() {
    if (loads_) {
        for (int i : ps_.model.dynamicBodies) {
            dBodyID id = bodies_[i].id;
            const BodySample s = body(i);
            Vec3 F, T;
            peer::appliedLoad(ps_.model, i, time_, s.q, s.v, s.w, &F, &T);
            if (F.isZero(0.0) && T.isZero(0.0)) continue;
            dBodyEnable(id);
            dBodyAddForce(id, F.x(), F.y(), F.z());
            dBodyAddTorque(id, T.x(), T.y(), T.z());
        }
    }
    for (const auto& [j, id] : servos_) {  // a servo by its time constant, as Tumble's
        dJointSetHingeParam(id, dParamVel,
                            peer::servoSpeed(*j, dJointGetHingeAngle(id), dJointGetHingeAngleRate(id), time_, dt_));
        dBodyEnable(bodies_[j->a].id);
    }
    pending_ = 0;
    dSpaceCollide(space_, this, &OdeAdapter::nearCallback);
    // Both return 0 when ODE could not allocate its working memory; the world is then left
    // as it was (no step taken). dWorldStep needs memory of the order of the square of the
    // constraint rows: on pyramid-1240 (some 78 000 rows in one island) it fails at every
    // step, and a benchmark that ignored it timed ODE's collision alone and reported a
    // pyramid that "stands" because it never moved.
    const int ok = quick_ ? dWorldQuickStep(world_, dt_) : dWorldStep(world_, dt_);
    dJointGroupEmpty(group_);
    if (!ok) {
        char what[160];
        std::snprintf(what, sizeof what,
                      "ODE's %s failed at t = %g s: it could not allocate its working memory "
                      "(%d contact points); no step was taken",
                      quick_ ? "dWorldQuickStep" : "dWorldStep", time_, pending_);
        throw std::runtime_error(what);
    }
    contacts_ = pending_;
    time_ += dt_;
}

BodySample OdeAdapter::body(int i) const {
    const Body& b = bodies_[i];
    if (!b.id) return b.still;
    BodySample s;
    const dReal* x = dBodyGetPosition(b.id);
    const dReal* q = dBodyGetQuaternion(b.id);
    const dReal* v = dBodyGetLinearVel(b.id);
    const dReal* w = dBodyGetAngularVel(b.id);
    s.x = Vec3(x[0], x[1], x[2]);
    s.q = Quat(q[0], q[1], q[2], q[3]);
    s.v = Vec3(v[0], v[1], v[2]);
    s.w = Vec3(w[0], w[1], w[2]);
    return s;
}

}  // namespace

std::unique_ptr<EngineAdapter> makeOdeAdapter() {
    return std::make_unique<OdeAdapter>();
}

}  // namespace tumble::bench
