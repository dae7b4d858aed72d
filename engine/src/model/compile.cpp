// SceneDesc -> Model: every semantic check on a scene, then the resolution of mass
// properties, materials and forces. The scene reader checks syntax and types; the
// checks here also guard scenes built in code or by the editor.
#include <tumble/errors.h>
#include <tumble/mass.h>
#include <tumble/model.h>

#include "collision/bvh.h"
#include "common/number_text.h"
#include "mesh/mesh_body.h"
#include "model/compile_compound.h"
#include "model/compile_groups.h"
#include "model/compile_joints.h"
#include "model/compile_keys.h"
#include "model/compile_shape.h"

#include <Eigen/Eigenvalues>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <optional>
#include <set>
#include <stdexcept>
#include <string>

namespace tumble {

namespace {

using namespace compiling;

std::string at(int i) {
    return "bodies[" + std::to_string(i) + "]";
}

void requireHoldable(double v, const std::string& path, const std::string& what, const std::string& unit,
                     const std::string& given = {}) {
    if (!(std::abs(v) <= kLargestHeld)) {
        throw SceneError(path, "gives " + what + " of " + numberText(v) + " " + unit + given +
                                   ", more than a run can carry in double precision (at most 1e150)");
    }
}

// A body's start within what double precision carries through a run: momentum, kinetic
// and potential energy (over its reach in the run), or a kinematic body's travel.
void requireHoldableStart(const BodyDesc& d, int i, double mass, const Mat3& inertia, const Settings& s) {
    const double speed = d.velocity.stableNorm();
    const double reach = d.position.stableNorm() + speed * s.duration;
    if (d.motion == Motion::Kinematic) {
        requireHoldable(reach, at(i) + ".velocity", "a travel over the run", "m");
        return;
    }
    if (d.motion != Motion::Dynamic) return;
    const std::string given = " (mass " + numberText(mass) + " kg)";
    requireHoldable(mass * speed, at(i) + ".velocity", "a momentum", "kg m/s", given);
    requireHoldable(0.5 * mass * speed * speed, at(i) + ".velocity", "a kinetic energy", "J", given);
    const Vec3 w = d.orientation.normalized().conjugate() * d.angularVelocity;  // body axes
    requireHoldable(0.5 * w.dot(inertia * w), at(i) + ".angular_velocity", "a kinetic energy of turning",
                    "J");
    requireHoldable(mass * s.gravity.stableNorm() * reach, at(i) + ".position",
                    "a potential energy over the run", "J", given);
}

// The most steps a run may take: far more than any run needs (10^10 steps of one free body
// take hours here).
constexpr double kMostSteps = 1e10;

void validateSettings(const Settings& s) {
    requireFinite(s.gravity, "settings.gravity");
    requirePositive(s.dt, "settings.dt");
    requireNonNegative(s.duration, "settings.duration");
    requirePositive(s.frameRate, "settings.frame_rate");
    if (s.solverIterations < 1 || s.solverIterations > 10000)
        throw SceneError("settings.solver_iterations", "must be from 1 to 10000");
    if (s.duration * s.frameRate > 1e8) {
        throw SceneError("settings.duration", "with this frame_rate gives more than 10^8 frames");
    }
    // A step count that cannot be counted or run (1e-300 s: the count overflowed and the run
    // took one step a frame) is a bad input, not a run.
    if (s.duration / s.dt > kMostSteps) {
        char text[160];
        std::snprintf(text, sizeof text,
                      "%g s is too small: %.3g steps for the duration of %g s (at most 10^10)", s.dt,
                      s.duration / s.dt, s.duration);
        throw SceneError("settings.dt", text);
    }
    if (!s.integrator.empty() && !findIntegrator(s.integrator)) {
        throw SceneError("settings.integrator",
                         "unknown integrator '" + s.integrator + "' (see --list-integrators)");
    }
}

void validateForce(const ForceDesc& f, const std::string& path) {
    requireFinite(f.vector, path + ".vector");
    if (f.point) requireFinite(*f.point, path + ".point");
    if (f.type == ForceType::Spring) {
        requireFinite(f.anchor, path + ".anchor");
        requireNonNegative(f.stiffness, path + ".stiffness");
        requireNonNegative(f.restLength, path + ".rest_length");
        requireNonNegative(f.damping, path + ".damping");
    }
    if (f.start) requireFinite(*f.start, path + ".start");
    if (f.end) requireFinite(*f.end, path + ".end");
    if (f.start && f.end && !(*f.end > *f.start)) {
        throw SceneError(path + ".end", "must be later than start");
    }
}

MassProperties massPropertiesOf(const BodyDesc& b, int i, const mesh::PreparedMesh* prepared = nullptr,
                                const MassProperties* compound = nullptr);
MassProperties meshBodyMassProperties(const BodyDesc& b, int i, const mesh::PreparedMesh& p);

void validateBody(const BodyDesc& b, int i) {
    const std::string p = at(i);
    if (b.name.empty()) throw SceneError(p + ".name", "must not be empty");
    validateShape(b.shape, b.motion, p + ".shape");
    const bool dynamic = b.motion == Motion::Dynamic;
    if (dynamic && b.shape.type == ShapeType::Compound) {
        validateCompoundMass(b, p);
    } else if (dynamic) {
        if (b.mass && b.density) throw SceneError(p, "give mass or density, not both");
        if (!b.mass && !b.density) throw SceneError(p, "a dynamic body needs mass or density");
        if (b.mass) requirePositive(*b.mass, p + ".mass");
        if (b.density) requirePositive(*b.density, p + ".density");
    } else {
        const char* key = b.mass ? ".mass" : b.density ? ".density" : b.inertia ? ".inertia" : nullptr;
        if (key) {
            throw SceneError(p + key, std::string(b.motion == Motion::Animated ? "an " : "a ") +
                                          toString(b.motion) + " body has no mass properties; remove it");
        }
    }
    if (b.inertia) {
        const std::string problem = inertiaProblem(*b.inertia);
        if (!problem.empty()) throw SceneError(p + ".inertia", problem);
    }
    if (b.centerOfMass) requireFinite(*b.centerOfMass, p + ".center_of_mass");
    requireFinite(b.position, p + ".position");
    if (!b.orientation.coeffs().allFinite()) {
        throw SceneError(p + ".orientation", "must be finite numbers");
    }
    if (!(b.orientation.coeffs().stableNorm() > 1e-12)) {
        throw SceneError(p + ".orientation", "must not be the zero quaternion");
    }
    requireFinite(b.velocity, p + ".velocity");
    requireFinite(b.angularVelocity, p + ".angular_velocity");
    validateKeys(b, p);
    if (b.motion == Motion::Static && (b.velocity != Vec3::Zero() || b.angularVelocity != Vec3::Zero())) {
        throw SceneError(p + (b.velocity != Vec3::Zero() ? ".velocity" : ".angular_velocity"),
                         "a static body cannot move; make it kinematic");
    }
    requireNonNegative(b.restitution, p + ".restitution");
    if (b.restitution > 1.0) throw SceneError(p + ".restitution", "must be between 0 and 1");
    requireNonNegative(b.friction, p + ".friction");
    requireNonNegative(b.linearDamping, p + ".linear_damping");
    requireNonNegative(b.angularDamping, p + ".angular_damping");
    if (!b.forces.empty() && !dynamic) {
        throw SceneError(p + ".forces", "forces act on dynamic bodies only");
    }
    for (size_t k = 0; k < b.forces.size(); ++k) {
        validateForce(b.forces[k], p + ".forces[" + std::to_string(k) + "]");
    }
    // Throws if unusable (a mesh's, and a compound's, need their meshes prepared: compile).
    if (dynamic && b.shape.type != ShapeType::Mesh && b.shape.type != ShapeType::Compound)
        massPropertiesOf(b, i);
}

// A mesh body's mass properties, scaled from those of its solid at density 1.
MassProperties meshBodyMassProperties(const BodyDesc& b, int i, const mesh::PreparedMesh& p) {
    if (p.volume > 0.0) {
        MassProperties mp = p.unitDensity;
        const double factor = b.mass ? *b.mass / p.volume : *b.density;
        mp.mass = b.mass ? *b.mass : *b.density * p.volume;
        mp.inertia *= factor;
        return mp;
    }
    // A flat mesh has no volume: a mass alone is enough only with inertia and centre given.
    const std::string why =
        b.shape.file + ": the mesh encloses no volume (" +
        (p.massFromHull && !p.hullProblem.empty() ? p.hullProblem : std::string("it is flat")) + ")";
    if (b.density) throw SceneError(at(i) + ".density", why + ", so a density gives it no mass");
    if (!b.inertia || !b.centerOfMass) {
        throw SceneError(at(i) + ".shape.file",
                         why +
                             ", so its centre of mass and inertia cannot be computed; give "
                             "center_of_mass and inertia, or use a mesh with volume");
    }
    MassProperties mp;
    mp.mass = *b.mass;
    return mp;
}

MassProperties massPropertiesOf(const BodyDesc& b, int i, const mesh::PreparedMesh* prepared,
                                const MassProperties* compound) {
    MassProperties mp;
    if (compound) {
        mp = *compound;
    } else if (b.shape.type == ShapeType::Mesh) {
        if (!prepared)
            throw SceneError(at(i) + ".shape.file", "the mesh '" + b.shape.file + "' was never loaded");
        mp = meshBodyMassProperties(b, i, *prepared);
    } else {
        mp = primitiveMassProperties(b.shape, b.mass ? *b.mass : *b.density * shapeVolume(b.shape));
    }
    if (b.inertia) mp.inertia = *b.inertia;
    if (b.centerOfMass) mp.centerOfMass = *b.centerOfMass;
    // Each input can be finite and positive while their product over- or underflows
    // (a radius of 1e300, a density of 1e-300): refuse the body rather than simulate NaN.
    const std::string field = at(i) + (b.mass ? ".mass" : ".density");
    if (!std::isfinite(mp.mass) || !(mp.mass > 0.0)) {
        throw SceneError(field, "with this shape gives a mass of " + numberText(mp.mass) +
                                    " kg, which is not a usable finite positive number");
    }
    if (!b.inertia && !inertiaProblem(mp.inertia).empty()) {
        throw SceneError(field,
                         "with this shape gives an inertia tensor that is not finite and "
                         "positive definite (largest entry " +
                             numberText(mp.inertia.cwiseAbs().maxCoeff()) + " kg m^2)");
    }
    return mp;
}

}  // namespace

std::vector<SceneError> sceneProblems(const SceneDesc& scene) {
    std::vector<SceneError> found;
    auto check = [&](auto&& part) {
        try {
            part();
        } catch (const SceneError& e) {
            found.push_back(e);
        }
    };
    check([&] { validateSettings(scene.settings); });
    std::set<std::string> names;
    for (size_t i = 0; i < scene.bodies.size(); ++i) {
        check([&] {
            validateBody(scene.bodies[i], static_cast<int>(i));
            if (!names.insert(scene.bodies[i].name).second) {
                throw SceneError(at(static_cast<int>(i)) + ".name",
                                 "'" + scene.bodies[i].name + "' is already the name of another body");
            }
        });
    }
    check([&] { validateJoints(scene); });
    check([&] { validateCollisionGroups(scene); });
    return found;
}

void validate(const SceneDesc& scene) {
    const std::vector<SceneError> problems = sceneProblems(scene);
    if (!problems.empty()) throw problems.front();
}

Model compile(const SceneDesc& scene) {
    validate(scene);

    Model m;
    m.settings = scene.settings;
    if (std::string note = stepNote(scene.settings); !note.empty()) m.notes.push_back(std::move(note));
    m.integrator =
        scene.settings.integrator.empty() ? &defaultIntegrator() : findIntegrator(scene.settings.integrator);
    m.bodies.reserve(scene.bodies.size());
    for (size_t i = 0; i < scene.bodies.size(); ++i) {
        const BodyDesc& d = scene.bodies[i];
        const int index = static_cast<int>(i);
        BodyModel b;
        b.name = d.name;
        b.motion = d.motion;
        b.shape = d.shape;
        if (b.shape.type == ShapeType::Plane) b.shape.normal.stableNormalize();
        const std::string who = at(index) + " (" + d.name + "): ";
        std::optional<mesh::PreparedMesh> prepared;
        std::optional<BuiltCompound> compound;
        if (d.shape.type == ShapeType::Mesh) {
            prepared = prepareMeshShape(d.shape, d.motion == Motion::Dynamic, at(index) + ".shape");
            // A missing volume is the first thing to report: it is what a density or inertia needs.
            if (d.motion == Motion::Dynamic) meshBodyMassProperties(d, index, *prepared);
            noteMesh(d.shape, d.motion == Motion::Dynamic, who, *prepared, m.notes);
            b.collider = d.shape.collision == MeshCollision::ConvexParts
                             ? convexPartsCollider(d.shape, at(index) + ".shape", who, d.friction,
                                                   d.restitution, m.notes)
                             : colliderOf(d.shape, at(index) + ".shape", &*prepared);
        } else if (d.shape.type == ShapeType::Compound) {
            compound = buildCompound(d, at(index), who, m.notes);
            b.collider = compound->collider;
        } else {
            b.collider = colliderOf(d.shape, at(index) + ".shape", nullptr);
        }
        // The collider holds what the stages need (the hull, or the triangles in their tree):
        // the model keeps no share of the mesh as read (300 small meshes of hull-rain were
        // 0.1 MB once the scene they came with was gone). The scene still has it.
        b.shape.meshData.reset();
        b.shape.convexParts.reset();
        for (PartDesc& part : b.shape.parts) {
            part.shape.meshData.reset();
            part.shape.convexParts.reset();
        }
        b.restitution = d.restitution;
        b.friction = d.friction;
        b.linearDamping = d.linearDamping;
        b.angularDamping = d.angularDamping;
        if (d.centerOfMass) b.centerOfMass = *d.centerOfMass;
        switch (d.motion) {
            case Motion::Dynamic: {
                const MassProperties mp = massPropertiesOf(d, index, prepared ? &*prepared : nullptr,
                                                           compound ? &compound->mass : nullptr);
                requireHoldableStart(d, index, mp.mass, mp.inertia, scene.settings);
                b.mass = mp.mass;
                b.invMass = 1.0 / mp.mass;
                b.inertia = mp.inertia;
                b.invInertia = mp.inertia.inverse();
                b.centerOfMass = mp.centerOfMass;
                const Eigen::SelfAdjointEigenSolver<Mat3> eig(mp.inertia);
                b.principalMoments = eig.eigenvalues();
                b.principalAxes = eig.eigenvectors();
                // A rotation, not a reflection: the free rotation turns Π about these axes.
                if (b.principalAxes.determinant() < 0.0) b.principalAxes.col(2) *= -1.0;
                b.sphericalInertia = b.invInertia.isDiagonal(0.0) &&
                                     b.invInertia(0, 0) == b.invInertia(1, 1) &&
                                     b.invInertia(1, 1) == b.invInertia(2, 2);
                m.dynamicBodies.push_back(index);
                break;
            }
            case Motion::Kinematic:
                requireHoldableStart(d, index, 0.0, Mat3::Zero(), scene.settings);
                b.kinematicVelocity = d.velocity;
                b.kinematicAngularVelocity = d.angularVelocity;
                m.kinematicBodies.push_back(index);
                break;
            case Motion::Animated:
                compileAnimated(d, b, m.forceSwitchTimes);
                m.kinematicBodies.push_back(index);
                break;
            case Motion::Static: break;
        }
        for (const ForceDesc& f : d.forces) {
            ForceTerm t;
            t.body = index;
            t.type = f.type;
            t.frame = f.frame;
            t.vector = f.vector;
            if (f.point) t.arm = *f.point - b.centerOfMass;
            t.anchor = f.anchor;
            t.stiffness = f.stiffness;
            t.restLength = f.restLength;
            t.damping = f.damping;
            if (f.start) {
                t.start = *f.start;
                m.forceSwitchTimes.push_back(*f.start);
            }
            if (f.end) {
                t.end = *f.end;
                m.forceSwitchTimes.push_back(*f.end);
            }
            m.forces.push_back(t);
        }
        m.bodies.push_back(std::move(b));
    }
    std::sort(m.forceSwitchTimes.begin(), m.forceSwitchTimes.end());
    m.forceSwitchTimes.erase(std::unique(m.forceSwitchTimes.begin(), m.forceSwitchTimes.end()),
                             m.forceSwitchTimes.end());
    compileCollisionGroups(scene, m);
    if (!scene.joints.empty()) compileJoints(scene, initialState(m, scene), m);
    return m;
}

State initialState(const Model& model, const SceneDesc& scene) {
    State s;
    s.bodies.resize(model.bodies.size());
    for (size_t i = 0; i < model.bodies.size(); ++i) {
        const BodyModel& b = model.bodies[i];
        const BodyDesc& d = scene.bodies[i];
        BodyState& st = s.bodies[i];
        st.q = d.orientation.normalized();
        if (!st.q.coeffs().allFinite()) st.q.coeffs() = d.orientation.coeffs().stableNormalized();
        st.x = d.position + st.q * b.centerOfMass;
        if (b.path) placeOnPath(b, s.time, st);
        if (b.motion == Motion::Dynamic) {
            st.P = b.mass * d.velocity;
            const Mat3 R = st.q.toRotationMatrix();
            st.L = R * b.inertia * R.transpose() * d.angularVelocity;
        }
    }
    return s;
}

}  // namespace tumble
