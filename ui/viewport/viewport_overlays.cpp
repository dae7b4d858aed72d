#include "viewport/viewport_overlays.h"

#include "viewport/viewport_overlay.h"

#include "document/body_keys.h"
#include "document/body_presets.h"
#include "document/joint_presets.h"

#include <tumble/contact_query.h>
#include <tumble/forces.h>
#include <tumble/key_path.h>

#include <Qt3DCore/QEntity>
#include <Qt3DExtras/QPerVertexColorMaterial>
#include <Qt3DRender/QGeometryRenderer>

#include <algorithm>
#include <array>
#include <numbers>
#include <cmath>

namespace tumble::ui {

namespace overlays {

namespace {

struct Rgb {
    float r, g, b;
};

constexpr Rgb kContactPoint{1.0f, 0.25f, 0.2f};
constexpr Rgb kContactNormal{1.0f, 0.55f, 0.45f};
constexpr Rgb kVelocity{0.3f, 0.9f, 0.35f};
constexpr Rgb kAngular{0.75f, 0.45f, 1.0f};
constexpr Rgb kForce{1.0f, 0.4f, 0.75f};
constexpr Rgb kCentre{1.0f, 1.0f, 1.0f};
constexpr Rgb kJoint{1.0f, 0.75f, 0.2f};
constexpr Rgb kJointAxis{0.95f, 0.55f, 0.1f};
constexpr Rgb kJointSelected{1.0f, 0.95f, 0.7f};
constexpr Rgb kPath{0.6f, 0.6f, 0.65f};
constexpr Rgb kPathSelected{1.0f, 0.63f, 0.0f};
constexpr Rgb kPoke{1.0f, 0.3f, 0.9f};

void vertex(std::vector<float>& out, const Vec3& p, Rgb c) {
    out.insert(out.end(), {float(p.x()), float(p.y()), float(p.z()), c.r, c.g, c.b});
}

void segment(std::vector<float>& out, const Vec3& a, const Vec3& b, Rgb c) {
    vertex(out, a, c);
    vertex(out, b, c);
}

// Any unit vector perpendicular to the unit vector n.
Vec3 perpendicular(const Vec3& n) {
    const Vec3 other = std::abs(n.x()) < 0.9 ? Vec3::UnitX() : Vec3::UnitY();
    return n.cross(other).normalized();
}

// A shaft from `from` along `vec` and a head of four lines (a fifth of the length).
void arrow(std::vector<float>& out, const Vec3& from, const Vec3& vec, Rgb c) {
    const double length = vec.norm();
    if (!(length > 0) || !std::isfinite(length)) return;
    const Vec3 tip = from + vec;
    segment(out, from, tip, c);
    const Vec3 n = vec / length;
    const Vec3 u = perpendicular(n), w = n.cross(u);
    const double head = 0.2 * length;
    for (const Vec3& side : {u, Vec3(-u), w, Vec3(-w)})
        segment(out, tip, tip - head * n + 0.4 * head * side, c);
}

void cross(std::vector<float>& out, const Vec3& at, double half, Rgb c) {
    for (int axis = 0; axis < 3; ++axis) {
        segment(out, at - half * Vec3::Unit(axis), at + half * Vec3::Unit(axis), c);
    }
}

double radiusOf(const BodyModel& b) {
    return collision::boundingRadius(b.collider);
}

}  // namespace

Lines contacts(const Model& model, const State& state) {
    Lines lines;
    // As the step finds them (every body awake: a sleeping one rests on its support all the same).
    const collision::ManifoldList found = contactsOf(model, state);
    for (const collision::Manifold& m : found) {
        double size =
            std::min(radiusOf(model.bodies[size_t(m.bodyA)]), radiusOf(model.bodies[size_t(m.bodyB)]));
        if (!std::isfinite(size) || size <= 0) size = 0.1;
        // The manifold's normal points out of B towards A; drawn into the body it pushes
        // away from one that stands still, else out of the lower-numbered body.
        const bool stillA = model.bodies[size_t(m.bodyA)].standsStill();
        const bool stillB = model.bodies[size_t(m.bodyB)].standsStill();
        const bool intoA = stillA != stillB ? stillB : m.bodyA > m.bodyB;
        const Vec3 normal = intoA ? m.normal : Vec3(-m.normal);
        for (int k = 0; k < m.count; ++k) {
            const Vec3& p = m.points[size_t(k)].position;
            cross(lines.xyzrgb, p, size / 6.0, kContactPoint);
            segment(lines.xyzrgb, p, p + 0.6 * size * normal, kContactNormal);
            ++lines.items;
        }
    }
    return lines;
}

Lines velocities(const Model& model, const State& state) {
    Lines lines;
    for (int i : model.dynamicBodies) {
        if (size_t(i) >= state.bodies.size()) continue;
        const Vec3 v = derive(model.bodies[size_t(i)], state.bodies[size_t(i)]).v;
        if (!(v.norm() > kSmallest)) continue;
        arrow(lines.xyzrgb, state.bodies[size_t(i)].x, kVelocitySeconds * v, kVelocity);
        ++lines.items;
    }
    return lines;
}

Lines angularVelocities(const Model& model, const State& state) {
    Lines lines;
    for (int i : model.dynamicBodies) {
        if (size_t(i) >= state.bodies.size()) continue;
        const Vec3 omega = derive(model.bodies[size_t(i)], state.bodies[size_t(i)]).omega;
        if (!(omega.norm() > kSmallest)) continue;
        arrow(lines.xyzrgb, state.bodies[size_t(i)].x, kAngularMetres * omega, kAngular);
        ++lines.items;
    }
    return lines;
}

Lines forces(const Model& model, const State& state) {
    Lines lines;
    if (state.bodies.size() != model.bodies.size()) return lines;
    std::vector<Wrench> wrenches;
    accumulateForces(model, state.bodies, state.time, wrenches);
    for (int i : model.dynamicBodies) {
        const BodyModel& b = model.bodies[size_t(i)];
        // accumulateForces starts each body's force at m g: taking it off leaves the rest.
        const Vec3 F = wrenches[size_t(i)].force - b.mass * model.settings.gravity;
        if (!(F.norm() > kSmallest) || !(b.mass > 0)) continue;
        arrow(lines.xyzrgb, state.bodies[size_t(i)].x, (kForceSeconds2 / b.mass) * F, kForce);
        ++lines.items;
    }
    return lines;
}

Lines centresOfMass(const Model& model, const State& state) {
    Lines lines;
    for (int i : model.dynamicBodies) {
        if (size_t(i) >= state.bodies.size()) continue;
        double r = radiusOf(model.bodies[size_t(i)]);
        if (!std::isfinite(r) || r <= 0) r = 0.1;
        cross(lines.xyzrgb, state.bodies[size_t(i)].x, 0.3 * r, kCentre);
        ++lines.items;
    }
    return lines;
}

namespace {

// A joint's line and its anchors' crosses; a hinge's or slider's axis (world, unit) as a
// line through anchor A, a body's size each way. The selected joint is drawn light, with
// crosses twice as large.
void jointLines(Lines& lines, const Vec3& a, const Vec3& b, double size, const Vec3* axis, bool selected) {
    if (!a.allFinite() || !b.allFinite()) return;
    if (!std::isfinite(size) || size <= 0) size = 0.1;
    const Rgb c = selected ? kJointSelected : kJoint;
    const double mark = (selected ? 0.5 : 0.25) * size;
    segment(lines.xyzrgb, a, b, c);
    cross(lines.xyzrgb, a, mark, c);
    cross(lines.xyzrgb, b, mark, c);
    if (axis && axis->allFinite()) segment(lines.xyzrgb, a - size * *axis, a + size * *axis, selected ? kJointSelected : kJointAxis);
    ++lines.items;
}

bool hasAxis(JointType t) {
    return t == JointType::Hinge || t == JointType::Slider;
}

// A joint's limits, drawn with its colour. A hinge's: an arc about its axis (unit, world)
// through anchor A, of radius `size`, from the lower to the upper angle, counted from
// `zero` (the direction, perpendicular to the axis, at which the hinge's angle is 0: where
// the scene placed body A), and a spoke at each end; a slider's: a segment along its axis
// from B's anchor plus the lower to plus the upper offset, a tick at each end.
void limitLines(Lines& lines, JointType type, const Vec3& anchorA, const Vec3& anchorB, const Vec3& axis,
                const Vec3& zero, double lower, double upper, double size, Rgb c) {
    if (!axis.allFinite() || !std::isfinite(lower) || !std::isfinite(upper) || !(size > 0)) return;
    if (type == JointType::Slider) {
        const Vec3 a = anchorB + lower * axis, b = anchorB + upper * axis, side = 0.15 * size * perpendicular(axis);
        segment(lines.xyzrgb, a, b, c);
        segment(lines.xyzrgb, a - side, a + side, c);
        segment(lines.xyzrgb, b - side, b + side, c);
        return;
    }
    const Vec3 u = zero, w = axis.cross(zero);
    // A limit range may pass a whole turn (the hinge's angle is counted on): at most one
    // turn is drawn, in steps of about 10 degrees.
    const double span = std::min(upper - lower, 2.0 * std::numbers::pi);
    const int n = std::max(2, int(std::ceil(span / 0.17)));
    auto at = [&](double phi) { return anchorA + size * (std::cos(phi) * u + std::sin(phi) * w); };
    segment(lines.xyzrgb, anchorA, at(lower), c);
    segment(lines.xyzrgb, anchorA, at(lower + span), c);
    for (int i = 0; i < n; ++i) segment(lines.xyzrgb, at(lower + span * i / n), at(lower + span * (i + 1) / n), c);
}

// A ball joint's limits: its swing cone about B's axis `n` (unit) from the anchor, `size`
// long (its rim, where A's axis stops, and four spokes; elliptical: θ₁ towards `e1`, θ₂
// towards n × e1), and its twist range as an arc about n from the lower to the upper angle
// counted from e1 (zero twist: where the scene placed A), a third of the size out.
void ballLimitLines(Lines& lines, const Vec3& anchor, const Vec3& n, const Vec3& e1, const double* cone,
                    const double* twist, double size, Rgb c) {
    if (!n.allFinite() || !e1.allFinite() || !(size > 0)) return;
    const Vec3 e2 = n.cross(e1);
    constexpr int kRim = 36;
    if (cone) {
        auto rim = [&](int i) {
            const double psi = 2.0 * std::numbers::pi * i / kRim, c1 = std::cos(psi), s1 = std::sin(psi);
            const double bound = 1.0 / std::sqrt(c1 * c1 / (cone[0] * cone[0]) + s1 * s1 / (cone[1] * cone[1]));
            return Vec3(anchor + size * (std::cos(bound) * n + std::sin(bound) * (c1 * e1 + s1 * e2)));
        };
        for (int i = 0; i < kRim; ++i) segment(lines.xyzrgb, rim(i), rim(i + 1), c);
        for (int i = 0; i < kRim; i += kRim / 4) segment(lines.xyzrgb, anchor, rim(i), c);
    }
    if (twist) {
        const double r = size / 3.0, span = twist[1] - twist[0];
        const int steps = std::max(2, int(std::ceil(span / 0.17)));
        auto at = [&](double phi) { return Vec3(anchor + r * (std::cos(phi) * e1 + std::sin(phi) * e2)); };
        segment(lines.xyzrgb, anchor, at(twist[0]), c);
        segment(lines.xyzrgb, anchor, at(twist[1]), c);
        for (int i = 0; i < steps; ++i)
            segment(lines.xyzrgb, at(twist[0] + span * i / steps), at(twist[0] + span * (i + 1) / steps), c);
    }
}

// The direction perpendicular to `axis` (unit) from `anchor` towards `centre` (body A's
// centre), or any perpendicular when the centre is on the axis.
Vec3 towards(const Vec3& anchor, const Vec3& centre, const Vec3& axis) {
    Vec3 d = centre - anchor;
    d -= axis * axis.dot(d);
    return d.norm() > 1e-9 ? Vec3(d.normalized()) : perpendicular(axis);
}

}  // namespace

Lines joints(const Model& model, const State& state, int selected) {
    Lines lines;
    if (state.bodies.size() != model.bodies.size()) return lines;
    const int n = int(model.bodies.size());
    for (const JointModel& j : model.joints) {
        if (j.a < 0 || j.a >= n || j.b >= n || state.jointBroken(j.index)) continue;  // a broken one is gone
        const BodyState& a = state.bodies[size_t(j.a)];
        const Vec3 pa = a.x + a.q * j.anchorA;
        const Vec3 pb = j.b < 0 ? j.anchorB : Vec3(state.bodies[size_t(j.b)].x + state.bodies[size_t(j.b)].q * j.anchorB);
        const Vec3 axis = a.q * j.axisA;
        const double size = radiusOf(model.bodies[size_t(j.a)]);
        jointLines(lines, pa, pb, size, hasAxis(j.type) ? &axis : nullptr, j.index == selected);
        if (j.limited && hasAxis(j.type)) {
            // The arc stays with B: its zero is A's direction now turned back by the hinge's
            // angle now (the last step's).
            const double angle = size_t(j.index) < state.hingeAngles.size() ? state.hingeAngles[size_t(j.index)] : 0.0;
            const Vec3 zero = Quat(Eigen::AngleAxisd(-angle, axis)) * towards(pa, a.x, axis);
            limitLines(lines, j.type, pa, pb, axis, zero, j.lower, j.upper, 0.6 * size,
                       j.index == selected ? kJointSelected : kJointAxis);
        }
        if (j.swingLimited || j.twistLimited) {  // with B: its axis and cross axis now
            const Quat qb = j.b < 0 ? Quat::Identity() : state.bodies[size_t(j.b)].q;
            const double twist[2] = {j.twistLower, j.twistUpper};
            ballLimitLines(lines, pb, qb * j.axisB, qb * j.swingCross, j.swingLimited ? j.swingLimit.data() : nullptr,
                           j.twistLimited ? twist : nullptr, 1.2 * size, j.index == selected ? kJointSelected : kJointAxis);
            segment(lines.xyzrgb, pa, pa + 1.2 * size * axis, j.index == selected ? kJointSelected : kJoint);
        }
    }
    return lines;
}

Lines joints(const SceneDesc& scene, int selected) {
    Lines lines;
    auto find = [&](const std::string& name) -> const BodyDesc* {
        for (const BodyDesc& b : scene.bodies)
            if (b.name == name) return &b;
        return nullptr;
    };
    for (size_t k = 0; k < scene.joints.size(); ++k) {
        const JointDesc& j = scene.joints[k];
        const BodyDesc* a = find(j.bodyA);
        const BodyDesc* b = j.bodyB.empty() ? nullptr : find(j.bodyB);
        if (!a || (!j.bodyB.empty() && !b)) continue;  // names the engine would refuse
        const Vec3 pa = a->position + a->orientation * j.anchorA;
        const Vec3 pb = b ? Vec3(b->position + b->orientation * j.anchorB) : j.anchorB;
        const bool axial = hasAxis(j.type) && j.axisA && j.axisA->norm() > 0.0;
        const Vec3 axis = axial ? Vec3(a->orientation * j.axisA->normalized()) : Vec3::Zero();
        jointLines(lines, pa, pb, boundingRadius(a->shape), axial ? &axis : nullptr, int(k) == selected);
        if (axial && j.limits) {  // as placed: the hinge's angle is 0
            limitLines(lines, j.type, pa, pb, axis, towards(pa, a->position, axis), (*j.limits)[0], (*j.limits)[1],
                       0.6 * boundingRadius(a->shape), int(k) == selected ? kJointSelected : kJointAxis);
        }
        if (j.type == JointType::SixAxis) {  // its frame at anchor A: free axes long, locked ones short
            const Vec3 x = j.axisA && j.axisA->norm() > 0.0 ? Vec3(j.axisA->normalized()) : Vec3::UnitX();
            const Vec3 y = firstCrossAxis(x);
            const Vec3 frame[3] = {a->orientation * x, a->orientation * y, a->orientation * x.cross(y)};
            const double size = 0.8 * boundingRadius(a->shape);
            for (int i = 0; i < 3; ++i) {
                const bool free = j.axes[i].free || j.axes[3 + i].free;
                const Rgb c = int(k) == selected ? kJointSelected : free ? kJointAxis : kJoint;
                segment(lines.xyzrgb, pa, pa + (free ? size : 0.35 * size) * frame[i], c);
            }
        }
        if (const auto f = ballLimitFrame(scene, j)) {  // (as placed: compile_joints.cpp)
            const Rgb c = int(k) == selected ? kJointSelected : kJointAxis;
            ballLimitLines(lines, f->anchor, f->n, f->e1, j.swingLimit ? j.swingLimit->data() : nullptr,
                           j.twistLimits ? j.twistLimits->data() : nullptr, f->size, c);
            const Vec3 aA = a->orientation * j.axisA->normalized();
            segment(lines.xyzrgb, pa, pa + f->size * aA, int(k) == selected ? kJointSelected : kJoint);
            if (int(k) == selected)  // the grips a drag sets the limits with (viewport_transform.cpp)
                for (int g = 0; g < 4; ++g)
                    if (const auto p = ballLimitGrip(*f, j, g)) cross(lines.xyzrgb, *p, 0.06 * f->size, c);
        }
    }
    return lines;
}

Lines paths(const SceneDesc& scene, const std::vector<int>& selected) {
    Lines lines;
    constexpr int kPerSegment = 24;
    for (size_t i = 0; i < scene.bodies.size(); ++i) {
        const BodyDesc& b = scene.bodies[i];
        if (b.motion != Motion::Animated || !keysMakeAPath(b)) continue;  // (bad keys: the panel says why)
        const bool chosen = std::find(selected.begin(), selected.end(), int(i)) != selected.end();
        const Rgb c = chosen ? kPathSelected : kPath;
        const KeyPath path(b.keys, b.interpolation);
        for (size_t k = 0; k + 1 < b.keys.size(); ++k) {
            const double t0 = b.keys[k].time, span = b.keys[k + 1].time - t0;
            Vec3 from = path.at(t0).position;
            for (int n = 1; n <= kPerSegment; ++n) {
                const Vec3 to =
                    path.at(n == kPerSegment ? std::nextafter(t0 + span, t0) : t0 + span * n / kPerSegment)
                        .position;
                segment(lines.xyzrgb, from, to, c);
                from = to;
            }
        }
        const double size = 0.15 * std::min(boundingRadius(b.shape), 1.0);
        for (const BodyKey& k : b.keys) cross(lines.xyzrgb, k.position, size, c);
        ++lines.items;
    }
    return lines;
}

Lines pokeArrow(const Vec3& from, const Vec3& drag) {
    Lines lines;
    arrow(lines.xyzrgb, from, drag, kPoke);
    lines.items = lines.xyzrgb.empty() ? 0 : 1;
    return lines;
}

Lines trails(const std::vector<std::vector<Vec3>>& tracks) {
    Lines lines;
    for (size_t t = 0; t < tracks.size(); ++t) {
        const std::vector<Vec3>& track = tracks[t];
        if (track.size() < 2) continue;
        // A hue per body (137° apart: the first dynamic body after a ground is cyan), so that
        // crossing trails stay apart.
        const float hue = float((43 + t * 137) % 360) / 360.0f;
        const float h6 = hue * 6.0f;
        const float x = 1.0f - std::abs(std::fmod(h6, 2.0f) - 1.0f);
        std::array<float, 3> rgb{};
        switch (int(h6) % 6) {
            case 0: rgb = {1, x, 0}; break;
            case 1: rgb = {x, 1, 0}; break;
            case 2: rgb = {0, 1, x}; break;
            case 3: rgb = {0, x, 1}; break;
            case 4: rgb = {x, 0, 1}; break;
            default: rgb = {1, 0, x}; break;
        }
        // Pastel: halfway to white.
        const Rgb c{0.5f + 0.5f * rgb[0], 0.5f + 0.5f * rgb[1], 0.5f + 0.5f * rgb[2]};
        for (size_t k = 1; k < track.size(); ++k) segment(lines.xyzrgb, track[k - 1], track[k], c);
        ++lines.items;
    }
    return lines;
}

int trailCap(int trails) {
    return std::clamp(kMaxTrailPointsTotal / std::max(1, trails), kMinTrailPoints, kMaxTrailPoints);
}

std::vector<Vec3> thinned(const std::vector<Vec3>& points, int cap) {
    const size_t n = points.size();
    if (cap < 2 || n <= size_t(cap)) return points;
    std::vector<Vec3> out;
    out.reserve(size_t(cap));
    // cap points at evenly spaced indices from the first to the last.
    for (int k = 0; k < cap; ++k) out.push_back(points[size_t(k) * (n - 1) / size_t(cap - 1)]);
    return out;
}

}  // namespace overlays

struct ViewportOverlays::Impl {
    Qt3DCore::QEntity* entity = nullptr;
    Qt3DExtras::QPerVertexColorMaterial* material = nullptr;
    std::array<Qt3DCore::QEntity*, KindCount> parts{};
    std::array<Qt3DRender::QGeometryRenderer*, KindCount> renderers{};
    std::array<int, KindCount> counts{};
};

ViewportOverlays::ViewportOverlays(Qt3DCore::QEntity* root) : d_(std::make_unique<Impl>()) {
    d_->entity = new Qt3DCore::QEntity(root);
    d_->material = new Qt3DExtras::QPerVertexColorMaterial(d_->entity);
}

ViewportOverlays::~ViewportOverlays() = default;  // the entities belong to the root

Qt3DCore::QEntity* ViewportOverlays::entity() const {
    return d_->entity;
}

void ViewportOverlays::set(Kind kind, const overlays::Lines& lines) {
    if (lines.xyzrgb.empty()) return clear(kind);
    Qt3DCore::QEntity*& part = d_->parts[size_t(kind)];
    Qt3DRender::QGeometryRenderer*& renderer = d_->renderers[size_t(kind)];
    if (!part) {
        part = new Qt3DCore::QEntity(d_->entity);
        renderer = makeColouredRenderer(lines.xyzrgb, Qt3DRender::QGeometryRenderer::Lines, part);
        part->addComponent(renderer);
        part->addComponent(d_->material);
    } else {
        setColouredData(renderer, lines.xyzrgb);
        part->setEnabled(true);
    }
    d_->counts[size_t(kind)] = lines.items;
}

void ViewportOverlays::clear(Kind kind) {
    if (Qt3DCore::QEntity* part = d_->parts[size_t(kind)]) part->setEnabled(false);
    d_->counts[size_t(kind)] = 0;
}

int ViewportOverlays::count(Kind kind) const {
    return d_->counts[size_t(kind)];
}

}  // namespace tumble::ui
