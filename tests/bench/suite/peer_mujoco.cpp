// MuJoCo 2.2.2 (Debian's libmujoco-dev) behind the benchmark's adapter interface. The scene
// is written as MJCF (an XML string, loaded through MuJoCo's virtual file system).
//
// Modes, most accurate first (mjOption.integrator):
//   rk4       mjINT_RK4: 4th-order Runge-Kutta on the smooth dynamics (contacts solved at
//             each stage)
//   implicit  mjINT_IMPLICIT: Euler, implicit in the velocity-dependent forces
//   euler     mjINT_EULER: semi-implicit Euler (MuJoCo's default, fastest)
// Every mode: one mj_step of dt per step(), the Newton solver with at most
// settings.solverIterations iterations, pyramidal friction cones, condim 3.
//
// Translation:
// - Every dynamic body is a <body> with a <freejoint>, its frame at Tumble's centre of mass
//   and oriented as Tumble's body frame, an explicit <inertial> with Tumble's mass and full
//   inertia (compile()), and one geom offset by -centerOfMass. Static bodies (and kinematic
//   ones at rest) are geoms of the world body. Shapes: sphere, box, capsule and cylinder
//   (MuJoCo's axis is z, rotated onto Tumble's y), plane (static only), mesh as its convex
//   hull (Tumble's hull, triangulated, as a mesh asset; MuJoCo collides with convex hulls).
// - Contacts are soft in MuJoCo: a spring-damper in each contact's normal direction. Each
//   geom gets a direct stiffness and damping per unit mass (negative solref, so MuJoCo's
//   "refsafe" rule, time constant >= 2 dt, does not apply): an undamped half period of
//   1/30 s (8 steps at 240 Hz), or 4 steps when dt is coarser, and the damping ratio whose
//   spring-damper, letting go when its force reaches zero, has the body's restitution e as
//   coefficient of restitution (solved once per value; critical for e = 0). solimp is
//   (0.99, 0.99, 0.001): a constant impedance of 0.99, so at rest only 1 % of the weight
//   sinks into the spring (a ball rests ~2 um deep at 240 Hz). Restitution therefore needs
//   the contact to last several steps: a dropped ball's apex is 13 % (rk4) and 23 % (euler)
//   low at dt = 1/240 and converges towards e^2 h as dt shrinks (5 % low at 1/3840, where
//   gravity during the 1/30 s contact is what is left). MuJoCo's positive solref with
//   dampratio < 1 bounces instead at the stiffest refsafe allows (2 dt), resolved in about
//   one step, and overshoots (apex +116 % at 1/240).
// - Materials: MuJoCo does not combine per pair as Tumble does. A geom's priority is the
//   rank of its restitution, so the pair takes the higher restitution (Tumble's max rule)
//   and then that geom's friction; between equal restitutions MuJoCo takes the larger
//   friction. Tumble's sqrt(mu_a mu_b) is reproduced only when the frictions are equal.
// - Forces, torques and damping: Tumble's force stage evaluated at the start of each step
//   (peer_common.h) written to xfrc_applied (world force and torque at the centre of mass,
//   held for the whole step, also through the RK4 stages).
// - Angular velocity: a free joint's qvel holds the linear velocity in world axes and the
//   angular velocity in the body's own axes (MuJoCo 2.2); body() rotates it to world.
// - No sleeping in MuJoCo 2.2; settings.sleeping is ignored.
// - Memory: MuJoCo 2.2 sizes its constraint arrays from njmax: njmax x njmax for efc_AR and
//   njmax x nv for efc_J and efc_JT (with int column indices), in one buffer of at most 2 GB,
//   and its automatic stack at about 6.3 njmax^2 numbers (1.2 GB for 4 864 rows), all
//   cleared while loading. njmax is 48 rows per dynamic body (12 points of 4 pyramid rows),
//   capped so the arrays stay under 0.6 GB (about 1 300 rows with 3 000 boxes, 400 with
//   10 000 bodies): a big pile does not fit, and loading a hundred bodies takes seconds
//   (100 boxes: 4 864 rows, 6 s). A smaller stack (<size nstack>) loads faster but the
//   Newton solver overflows it once the rows fill (the 120-box pyramid at t = 0). When a
//   run fills the arrays MuJoCo drops contacts, so from then on body() reports NaN and one
//   line on stderr says why, rather than measure a different simulation.
// - Joints (issue 20), kept as constraints between free bodies (each body keeps its free
//   joint; MuJoCo's own joint tree is not built): a ball joint is an equality <connect> at
//   A's anchor, a hinge two <connect>s on its axis a body size apart, both with MuJoCo's
//   default soft constraint (solref 0.02 1); the joined bodies' contacts are excluded, as
//   in Tumble.
// - Refused: springs, moving kinematic bodies, meshes collided as triangles; slider, fixed,
//   distance and rope joints, joint limits, motors and breaking.
#include "engine_adapter.h"
#include "peer_common.h"

#include <mujoco/mujoco.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <limits>
#include <map>
#include <set>
#include <sstream>

namespace tumble::bench {
namespace {

constexpr double kMaxBytes = 0.6e9;
constexpr double kContactTime = 1.0 / 30.0;  // s
constexpr double kContactSteps = 4.0;

std::string lastWarning;
void keepWarning(const char* msg) {
    lastWarning = msg;
}

std::string str(const Vec3& v) {
    std::ostringstream os;
    os.precision(17);
    os << v.x() << ' ' << v.y() << ' ' << v.z();
    return os.str();
}
std::string str(const Quat& q) {
    std::ostringstream os;
    os.precision(17);
    os << q.w() << ' ' << q.x() << ' ' << q.y() << ' ' << q.z();
    return os.str();
}

// The restitution of a linear spring-damper contact p'' = -w0^2 p - 2 zeta w0 p' that lets go
// when its force k p + b p' falls to zero (a contact never pulls), for an impact at unit speed
// with w0 = 1 (the answer depends on neither). Integrated with RK4 at a fine step.
double springDamperRestitution(double zeta) {
    double p = 0.0, u = 1.0;
    const double h = 1e-4;
    auto acc = [zeta](double pp, double uu) { return -pp - 2.0 * zeta * uu; };
    for (int k = 0; k < 1000000; ++k) {
        const double k1p = u, k1u = acc(p, u);
        const double k2p = u + 0.5 * h * k1u, k2u = acc(p + 0.5 * h * k1p, u + 0.5 * h * k1u);
        const double k3p = u + 0.5 * h * k2u, k3u = acc(p + 0.5 * h * k2p, u + 0.5 * h * k2u);
        const double k4p = u + h * k3u, k4u = acc(p + h * k3p, u + h * k3u);
        p += h / 6.0 * (k1p + 2.0 * k2p + 2.0 * k3p + k4p);
        u += h / 6.0 * (k1u + 2.0 * k2u + 2.0 * k3u + k4u);
        if (u < 0.0 && (p + 2.0 * zeta * u <= 0.0 || p <= 0.0)) return -u;
    }
    return 0.0;
}

// The damping ratio of that contact for a coefficient of restitution e (bisection; e = 0:
// critical damping). It is below the textbook exp(-pi zeta / sqrt(1 - zeta^2)) = e, which
// ignores that the contact lets go before the spring is back at rest length.
double dampingRatio(double e) {
    if (e <= 0.0) return 1.0;
    e = std::min(e, 0.99);
    double lo = 0.0, hi = 1.0;
    for (int k = 0; k < 40; ++k) {
        const double mid = 0.5 * (lo + hi);
        (springDamperRestitution(mid) > e ? lo : hi) = mid;
    }
    return 0.5 * (lo + hi);
}

// Direct stiffness and damping per unit mass (negative solref): an undamped half period of
// kContactTime, or kContactSteps steps when dt is coarser.
std::string solref(double dt, double zeta) {
    const double halfPeriod = std::max(kContactTime, kContactSteps * dt);
    const double w0 = M_PI / halfPeriod;
    std::ostringstream os;
    os.precision(17);
    os << -w0 * w0 << ' ' << -2.0 * zeta * w0;
    return os.str();
}

// Rows of the constraint arrays (njmax): 12 contact points of 4 pyramid rows per dynamic
// body (MuJoCo's box-box collider gives up to 8 points a pair; the 15-layer pyramid, whose
// boxes also touch side by side, starts with over 10 per box), and no more than fits in
// kMaxBytes: MuJoCo 2.2 allocates njmax x njmax (efc_AR and its column indices) and twice
// njmax x nv (efc_J, efc_JT and theirs) in one buffer whose size is an int, and clears it
// several times while loading (load time grows as njmax^2: 6 s for 4 900 rows).
int constraintRows(int dynamic, std::size_t nv) {
    const double want = 48.0 * dynamic + 64.0;
    // 12 njmax^2 + 24 nv njmax <= kMaxBytes
    const double b = 24.0 * double(nv), fit = (-b + std::sqrt(b * b + 48.0 * kMaxBytes)) / 24.0;
    return int(std::max(64.0, std::min(want, fit)));
}

class MujocoAdapter final : public EngineAdapter {
public:
    ~MujocoAdapter() override { clear(); }

    std::string name() const override { return "mujoco"; }
    std::vector<std::string> modes() const override { return {"rk4", "implicit", "euler"}; }

    bool load(const SceneDesc& scene, const std::string& mode, double dt, std::string* why) override;
    void step() override;
    double time() const override { return time_; }
    int bodyCount() const override { return int(bodies_.size()); }
    BodySample body(int i) const override;
    int contactCount() const override { return d_ ? d_->ncon : 0; }

private:
    struct Body {
        int mjBody = -1;  ///< -1: a world geom
        int qpos = 0;
        int qvel = 0;
        BodySample still;
    };

    void clear();
    std::string xml(double dt, int integrator) const;

    peer::PeerScene ps_;
    double dt_ = 0.0;
    double time_ = 0.0;
    bool loads_ = false;
    bool overflow_ = false;
    mjModel* m_ = nullptr;
    mjData* d_ = nullptr;
    std::vector<Body> bodies_;
};

void MujocoAdapter::clear() {
    if (d_) mj_deleteData(d_);
    if (m_) mj_deleteModel(m_);
    d_ = nullptr;
    m_ = nullptr;
    bodies_.clear();
}

std::string MujocoAdapter::xml(double dt, int integrator) const {
    const Model& model = ps_.model;
    const SceneDesc& scene = ps_.scene;
    const int n = int(model.bodies.size());
    const int dynamic = int(model.dynamicBodies.size());
    const int rows = constraintRows(dynamic, model.dynamicBodies.size() * 6);

    // Priority = rank of the restitution (Tumble takes the larger one).
    std::set<double> levels;
    for (const BodyModel& b : model.bodies) levels.insert(b.restitution);
    std::map<double, int> rank;
    std::map<double, double> zeta;
    for (double e : levels) {
        rank.emplace(e, int(rank.size()));
        zeta.emplace(e, dampingRatio(e));
    }

    std::ostringstream os;
    os.precision(17);
    const char* names[] = {"Euler", "RK4", "implicit"};
    os << "<mujoco model=\"tumble\">\n"
       << "<compiler angle=\"radian\" inertiafromgeom=\"false\" boundmass=\"0\" boundinertia=\"0\" "
          "balanceinertia=\"false\"/>\n"
       << "<option timestep=\"" << dt << "\" gravity=\"" << str(scene.settings.gravity) << "\" integrator=\""
       << names[integrator] << "\" iterations=\"" << std::max(1, scene.settings.solverIterations)
       << "\" cone=\"pyramidal\"/>\n"
       << "<size njmax=\"" << rows << "\" nconmax=\"" << rows / 4 << "\"/>\n";
    os << "<asset>\n";
    for (int i = 0; i < n; ++i) {
        const BodyModel& b = model.bodies[i];
        if (b.shape.type != ShapeType::Mesh) continue;
        const collision::ConvexHull& h = *b.collider.hull;
        os << "<mesh name=\"mesh" << i << "\" vertex=\"";
        for (const Vec3& v : h.vertices) os << str(v) << ' ';
        os << "\" face=\"";
        for (const auto& f : h.faces) {
            const std::span<const int> v = h.verticesOf(f);
            for (std::size_t k = 1; k + 1 < v.size(); ++k) os << v[0] << ' ' << v[k] << ' ' << v[k + 1] << ' ';
        }
        os << "\"/>\n";
    }
    os << "</asset>\n<worldbody>\n";

    auto geom = [&](int i, const Vec3& pos, const Quat& q) {
        const BodyModel& b = model.bodies[i];
        const collision::Shape& c = b.collider;
        if (b.shape.type == ShapeType::Compound) {
            // A geom per part, each at its place in the body (the body's material on all).
            int k = 0;
            for (const collision::Compound::Part& part : c.compound->parts) {
                os << "<geom name=\"g" << i << "_" << k++ << "\" condim=\"3\" friction=\"" << b.friction
                   << " 0 0\" solref=\"" << solref(dt, zeta.at(b.restitution))
                   << "\" solimp=\"0.99 0.99 0.001\" priority=\"" << rank.at(b.restitution) << "\" ";
                const collision::Shape& ps = part.shape;
                Quat turn = q * Quat(part.pose.R);
                switch (ps.kind) {
                    case collision::Kind::Sphere:
                        os << "type=\"sphere\" size=\"" << ps.radius << "\" ";
                        break;
                    case collision::Kind::Box:
                        os << "type=\"box\" size=\"" << str(ps.halfExtents) << "\" ";
                        break;
                    case collision::Kind::Capsule:
                        os << "type=\"capsule\" size=\"" << ps.radius << ' ' << ps.halfHeight << "\" ";
                        turn = turn * peer::zToY();
                        break;
                    default:  // a cylinder (hull parts are refused by load)
                        os << "type=\"cylinder\" size=\"" << ps.radius << ' ' << ps.halfHeight << "\" ";
                        turn = turn * peer::zToY();
                        break;
                }
                os << "pos=\"" << str(Vec3(pos + q * part.pose.p)) << "\" quat=\"" << str(turn.normalized())
                   << "\"/>\n";
            }
            return;
        }
        os << "<geom name=\"g" << i << "\" condim=\"3\" friction=\"" << b.friction << " 0 0\" solref=\""
           << solref(dt, zeta.at(b.restitution)) << "\" solimp=\"0.99 0.99 0.001\" priority=\""
           << rank.at(b.restitution) << "\" ";
        Quat shapeQ = q;
        switch (b.shape.type) {
            case ShapeType::Sphere: os << "type=\"sphere\" size=\"" << c.radius << "\" "; break;
            case ShapeType::Box: os << "type=\"box\" size=\"" << str(c.halfExtents) << "\" "; break;
            case ShapeType::Capsule:
                os << "type=\"capsule\" size=\"" << c.radius << ' ' << c.halfHeight << "\" ";
                shapeQ = q * peer::zToY();
                break;
            case ShapeType::Cylinder:
                os << "type=\"cylinder\" size=\"" << c.radius << ' ' << c.halfHeight << "\" ";
                shapeQ = q * peer::zToY();
                break;
            case ShapeType::Mesh: os << "type=\"mesh\" mesh=\"mesh" << i << "\" "; break;
            case ShapeType::Plane: {
                Vec3 nrm;
                double dist;
                peer::worldPlane(b, scene.bodies[i].position, ps_.q[i], &nrm, &dist);
                os << "type=\"plane\" size=\"0 0 1\" pos=\"" << str(Vec3(nrm * dist)) << "\" quat=\""
                   << str(Quat::FromTwoVectors(Vec3::UnitZ(), nrm)) << "\"/>\n";
                return;
            }
            case ShapeType::Compound: return;  // (above)
        }
        os << "pos=\"" << str(pos) << "\" quat=\"" << str(shapeQ.normalized()) << "\"/>\n";
    };

    for (int i = 0; i < n; ++i) {
        const BodyModel& b = model.bodies[i];
        if (b.standsStill()) {
            geom(i, scene.bodies[i].position, ps_.q[i]);
            continue;
        }
        const Mat3& I = b.inertia;
        os << "<body name=\"b" << i << "\" pos=\"" << str(ps_.com[i]) << "\" quat=\"" << str(ps_.q[i])
           << "\">\n"
           << "<freejoint name=\"j" << i << "\"/>\n"
           << "<inertial pos=\"0 0 0\" mass=\"" << b.mass << "\" fullinertia=\"" << I(0, 0) << ' ' << I(1, 1)
           << ' ' << I(2, 2) << ' ' << I(0, 1) << ' ' << I(0, 2) << ' ' << I(1, 2) << "\"/>\n";
        geom(i, -b.centerOfMass, Quat::Identity());
        os << "</body>\n";
    }
    os << "</worldbody>\n";
    // Joints between the free bodies: equality constraints (a hinge is two points on its axis).
    if (!model.joints.empty()) {
        os << "<equality>\n";
        for (const JointModel& j : model.joints) {
            auto connect = [&](const Vec3& anchor) {
                os << "<connect body1=\"b" << j.a << "\"";
                if (j.b >= 0 && !model.bodies[j.b].standsStill()) os << " body2=\"b" << j.b << "\"";
                os << " anchor=\"" << str(anchor) << "\"/>\n";
            };
            if (j.type == JointType::Hinge) {
                const double reach = std::max(0.05, 0.5 * collision::boundingRadius(model.bodies[j.a].collider));
                connect(j.anchorA + reach * j.axisA);
                connect(j.anchorA - reach * j.axisA);
            } else {
                connect(j.anchorA);
            }
        }
        os << "</equality>\n<contact>\n";
        for (const JointModel& j : model.joints)
            if (j.b >= 0 && !model.bodies[j.b].standsStill())
                os << "<exclude body1=\"b" << j.a << "\" body2=\"b" << j.b << "\"/>\n";
        os << "</contact>\n";
    }
    os << "</mujoco>\n";
    return os.str();
}

bool MujocoAdapter::load(const SceneDesc& scene, const std::string& mode, double dt, std::string* why) {
    clear();
    int integrator;
    if (mode == "rk4") {
        integrator = mjINT_RK4;
    } else if (mode == "implicit") {
        integrator = mjINT_IMPLICIT;
    } else if (mode == "euler") {
        integrator = mjINT_EULER;
    } else {
        if (why) *why = "unknown MuJoCo mode '" + mode + "'";
        return false;
    }
    std::string reason;
    if (!peer::prepare(
            scene,
            peer::PeerCaps{false, false, peer::jointBit(JointType::Ball) | peer::jointBit(JointType::Hinge),
                           false, false, false, true},
            &ps_, &reason)) {
        if (why) *why = reason;
        return false;
    }
    for (const BodyModel& b : ps_.model.bodies)
        if (b.collider.kind == collision::Kind::Compound)
            for (const auto& part : b.collider.compound->parts)
                if (part.shape.kind == collision::Kind::Hull || part.shape.kind == collision::Kind::Mesh) {
                    if (why) *why = b.name + ": a compound's mesh parts are not translated to MuJoCo";
                    return false;
                }
    dt_ = dt;
    time_ = 0.0;
    overflow_ = false;
    loads_ = peer::hasLoads(ps_.model);
    mju_user_warning = &keepWarning;

    const std::string text = xml(dt, integrator);
    auto vfs = std::make_unique<mjVFS>();
    mj_defaultVFS(vfs.get());
    mj_makeEmptyFileVFS(vfs.get(), "scene.xml", int(text.size()));
    const int f = mj_findFileVFS(vfs.get(), "scene.xml");
    std::memcpy(vfs->filedata[f], text.data(), text.size());
    char error[1000] = "";
    m_ = mj_loadXML("scene.xml", vfs.get(), error, sizeof(error));
    mj_deleteVFS(vfs.get());
    if (!m_) {
        if (why) *why = std::string("MuJoCo refused the generated model: ") + error;
        return false;
    }
    d_ = mj_makeData(m_);

    for (int i = 0; i < int(ps_.model.bodies.size()); ++i) {
        const BodyModel& b = ps_.model.bodies[i];
        Body out;
        if (b.standsStill()) {
            out.still.x = ps_.com[i];
            out.still.q = ps_.q[i];
        } else {
            std::string name = "b";  // not "b" + to_string(i): a false -Wrestrict in GCC 12
            name += std::to_string(i);
            out.mjBody = mj_name2id(m_, mjOBJ_BODY, name.c_str());
            const int j = m_->body_jntadr[out.mjBody];
            out.qpos = m_->jnt_qposadr[j];
            out.qvel = m_->jnt_dofadr[j];
            const Vec3 wBody = ps_.q[i].conjugate() * ps_.w[i];
            for (int k = 0; k < 3; ++k) {
                d_->qvel[out.qvel + k] = ps_.v[i][k];
                d_->qvel[out.qvel + 3 + k] = wBody[k];
            }
        }
        bodies_.push_back(out);
    }
    mj_forward(m_, d_);
    return true;
}

void MujocoAdapter::step() {
    if (loads_) {
        for (int i : ps_.model.dynamicBodies) {
            const BodySample s = body(i);
            Vec3 F, T;
            peer::appliedLoad(ps_.model, i, time_, s.q, s.v, s.w, &F, &T);
            mjtNum* x = d_->xfrc_applied + 6 * bodies_[i].mjBody;
            for (int k = 0; k < 3; ++k) {
                x[k] = F[k];
                x[3 + k] = T[k];
            }
        }
    }
    mj_step(m_, d_);
    time_ += dt_;
    if (!overflow_ &&
        (d_->warning[mjWARN_CNSTRFULL].number > 0 || d_->warning[mjWARN_CONTACTFULL].number > 0)) {
        overflow_ = true;
        std::fprintf(stderr, "mujoco: %s (njmax %d, nconmax %d): results from t = %g s are invalid\n",
                     lastWarning.c_str(), m_->njmax, m_->nconmax, time_);
    }
}

BodySample MujocoAdapter::body(int i) const {
    const Body& b = bodies_[i];
    if (b.mjBody < 0) return b.still;
    BodySample s;
    if (overflow_) {
        const double nan = std::numeric_limits<double>::quiet_NaN();
        s.x = s.v = s.w = Vec3::Constant(nan);
        s.q = Quat(nan, nan, nan, nan);
        return s;
    }
    const mjtNum* qp = d_->qpos + b.qpos;
    const mjtNum* qv = d_->qvel + b.qvel;
    s.x = Vec3(qp[0], qp[1], qp[2]);
    s.q = Quat(qp[3], qp[4], qp[5], qp[6]).normalized();
    s.v = Vec3(qv[0], qv[1], qv[2]);
    s.w = s.q * Vec3(qv[3], qv[4], qv[5]);
    return s;
}

}  // namespace

std::unique_ptr<EngineAdapter> makeMujocoAdapter() {
    return std::make_unique<MujocoAdapter>();
}

}  // namespace tumble::bench
