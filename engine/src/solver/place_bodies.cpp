// Where the bodies the contact solver pushed end the step (place_bodies.h).
#include "solver/place_bodies.h"

#include "solver/contact_rows.h"

#include <optional>

namespace tumble {

namespace {

using Point = ContactSolverScratch::Point;

// The bodies that slide over everything they touch this step, and the directions they
// slide in: for each, the normals of its manifolds, orthonormal (s.slideNormals), and how
// many (s.slideCount; -1: one of its manifolds holds it). A manifold slides when its
// surfaces touched at the start of the step without meeting fast, still slide faster than
// `sliding` at the end, and its friction is at the Coulomb limit (or it has none): the
// bodies then move under constant forces for the whole step. Friction inside the limit
// holds: a resting pile's side contacts hold almost no normal impulse, so their friction
// sits at its (tiny) limit while nothing moves. A landing's velocity change is sudden, not
// spread over the step: placed by the mean, the boxes of drop-3000 landing flat on each
// other were shifted by 1e-5 m, their columns never came to rest and none fell asleep.
// Whether the block's surfaces slid over each other at the start of the step too, or both
// bodies were at rest then (a push from rest): the step's change was made all through it.
// Not so for a body thrown sideways within the step by a landing or a bounce, whose new
// slip the mean would misplace (drop-3000's columns, shifted by 1e-5 m, never slept).
bool slidAtStart(const ContactSolverScratch& s, const ContactSolverScratch::Block& block, const Point& p,
                 double sliding) {
    const BodyVelocity &A = s.start[p.a], &B = s.start[p.b];
    if (A.v.isZero(0.0) && A.w.isZero(0.0) && B.v.isZero(0.0) && B.w.isZero(0.0)) return true;
    const Vec3 u = A.v + A.w.cross(block.rA) - B.v - B.w.cross(block.rB);
    return (u - u.dot(p.n) * p.n).norm() > sliding;
}

void slidingBodies(double sliding, ContactSolverScratch& s) {
    s.slideCount.resize(s.bodies.size());
    s.slideNormals.resize(s.bodies.size());
    s.slideBlock.resize(s.bodies.size());
    for (int i : s.involved) s.slideCount[i] = 0, s.slideBlock[i] = -1;
    for (size_t k = 0; k < s.blocks.size(); ++k) {
        const auto& block = s.blocks[k];
        bool slides = !block.arriving;  // (the cheap tests first: most blocks of a pile hold)
        if (block.mu > 0.0) {
            const double limit = block.mu * normalImpulse(s, block);
            slides = slides && limit > 0.0 && block.frictionApplied().norm() >= (1.0 - 1e-9) * limit;
        }
        const Point& p = s.points[block.begin];
        slides = slides && slipVelocity(s, block).norm() > sliding && slidAtStart(s, block, p, sliding);
        for (const int body : {p.a, p.b}) {
            int& count = s.slideCount[body];
            if (s.bodies[body].invMass == 0.0) continue;
            s.slideBlock[body] = s.slideBlock[body] == -1 ? static_cast<int>(k) : -2;
            if (count < 0) continue;
            if (!slides) {
                count = -1;
                continue;
            }
            Vec3 n = p.n;  // Gram-Schmidt against the normals already listed
            for (int k = 0; k < count; ++k) n -= n.dot(s.slideNormals[body][k]) * s.slideNormals[body][k];
            if (count < 3 && n.squaredNorm() > 1e-12) s.slideNormals[body][count++] = n.normalized();
        }
    }
}

// A body that slid on a support standing still and stopped within the step (held at the
// end, its one manifold's friction inside the limit) slid for t* of it at the constant
// deceleration of friction at the limit, against what else pushed it along û, its start
// slide's direction: m |v0t| = (μ jn + J·û + m |v0t|) t* / h, J the friction impulse, so
// it went ½ |v0t| t* along û. Returns that move (tangential), or nothing when the body is
// not such a body. (Placed with h v1 alone it stopped where it was at the step's start,
// short by up to v0 h / 2: 8.5e-5 of a 4.2 m slide at 1/60 s.)
std::optional<Vec3> stoppedSlide(const ContactSolverScratch& s, int i, const Vec3& v0, double sliding,
                                 double h) {
    if (s.slideCount[i] >= 0 || s.slideBlock[i] < 0) return std::nullopt;
    const auto& block = s.blocks[s.slideBlock[i]];
    const Point& p = s.points[block.begin];
    const SolverBody& other = s.bodies[p.a == i ? p.b : p.a];
    if (block.arriving || other.invMass != 0.0 || !other.v.isZero(0.0) || !other.w.isZero(0.0) ||
        !(block.mu > 0.0))
        return std::nullopt;
    const SolverBody& b = s.bodies[i];
    const Vec3 v0t = v0 - v0.dot(p.n) * p.n, v1t = b.v - b.v.dot(p.n) * p.n;
    const double speed = v0t.norm();
    if (!(speed > sliding) || v1t.norm() > sliding || b.w.norm() * block.radius > sliding)
        return std::nullopt;
    const Vec3 u = v0t / speed;
    const Eigen::Vector2d T = block.frictionApplied();
    const Vec3 J = (p.a == i ? 1.0 : -1.0) * (T[0] * block.t1 + T[1] * block.t2);
    const double decelerated = speed + b.invMass * (block.mu * normalImpulse(s, block) + J.dot(u));  // a h
    if (!(decelerated >= speed)) return std::nullopt;
    const double stop = h * speed / decelerated;
    return 0.5 * stop * v0t;
}

}  // namespace

// The pose of every body the solver pushed, from the start of the step with its new
// velocity (symplectic Euler for the bodies in contact), except that a body sliding over
// all it touches moves in its tangent plane by h (v0 + v1) / 2, the exact distance under
// constant forces: applied forces, gravity along a slope and sliding friction alike (issue
// 44: with friction alone at half weight a box pushed from rest slid 17 % too far at 1/30 s,
// 2.2 % at 1/240, an error of F h² / 2m a step). Along the normals it keeps h v1, which the
// contact rows made right. A body held by friction anywhere keeps h v1: at rest, v1 = 0.
void redoPoses(const Model& model, State& state, const State& before, double sliding,
               ContactSolverScratch& s) {
    const double h = state.time - before.time;
    slidingBodies(sliding, s);
    for (int i : s.involved) {
        if (isStill(s, i)) {  // ends where it started, as the solve would place it (still_islands.h)
            state.bodies[i] = before.bodies[i];
            continue;
        }
        if (model.bodies[i].motion != Motion::Dynamic || !s.bodies[i].touched || state.isAsleep(i)) continue;
        if (!model.jointed.empty() && model.jointed[i]) continue;  // placed by the joints' projection
        BodyState& b = state.bodies[i];
        Vec3 move = h * s.bodies[i].v;
        const Vec3 v0 = model.bodies[i].invMass * before.bodies[i].P;
        if (s.slideCount[i] > 0) {
            Vec3 change = s.bodies[i].v - v0;
            for (int k = 0; k < s.slideCount[i]; ++k)
                change -= change.dot(s.slideNormals[i][k]) * s.slideNormals[i][k];
            move -= 0.5 * h * change;
        } else if (const std::optional<Vec3> slid = stoppedSlide(s, i, v0, sliding, h)) {
            const Vec3& n = s.points[s.blocks[s.slideBlock[i]].begin].n;
            move = move.dot(n) * n + *slid;
        }
        b.x = before.bodies[i].x + move;
        const Vec3 turn = h * s.bodies[i].w;
        const double angle = turn.norm();
        b.q = angle > 0.0 ? (Quat(Eigen::AngleAxisd(angle, turn / angle)) * before.bodies[i].q).normalized()
                          : before.bodies[i].q;
    }
}

}  // namespace tumble
