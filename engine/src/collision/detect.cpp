#include "collision/detect.h"

#include "collision/compound_pairs.h"

#include "common/make_room.h"
#include "common/resting.h"
#include "common/workers.h"

#include "collision/narrowphase.h"
#include "collision/toi.h"

#include "common/pair_key.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>

namespace tumble {

using namespace collision;

namespace {
constexpr int kBodyGrain = 256;  // bodies per chunk on the worker threads (as the integrator's)

// The same bits: -0.0 and 0.0 differ here, as they may in what is computed from them.
bool samePose(const Pose& x, const Pose& y) {
    return std::memcmp(&x, &y, sizeof(Pose)) == 0;
}
}  // namespace

bool needsContacts(const Model& model) {
    int moving = 0;
    for (const BodyModel& b : model.bodies) moving += b.motion != Motion::Static;
    return model.bodies.size() >= 2 && moving > 0;
}

Pose bodyPose(const BodyModel& body, const BodyState& s) {
    Pose p;
    p.R = s.q.toRotationMatrix();
    p.p = s.x - p.R * body.centerOfMass;
    return p;
}

void bodyPoses(const Model& model, const State& state, std::vector<Pose>& out, Workers* pool, PoolGate* gate) {
    auto place = [&](size_t i) { out[i] = bodyPose(model.bodies[i], state.bodies[i]); };
    if (out.size() != model.bodies.size()) {
        out.resize(model.bodies.size());
        for (size_t i = 0; i < out.size(); ++i) place(i);
        return;
    }
    // Static bodies never move: their poses are the ones already there.
    const std::vector<int>& dynamic = model.dynamicBodies;
    forEachChunk(pool, static_cast<int>(dynamic.size()), kBodyGrain, [&](int begin, int end) {
        for (int k = begin; k < end; ++k) place(static_cast<size_t>(dynamic[k]));
    }, gate);
    for (int i : model.kinematicBodies) place(static_cast<size_t>(i));
}

void findPairs(const Model& model, const State& state, double margin, DetectScratch& s) {
    const size_t n = model.bodies.size();
    // A static body's box is the last one while the margin is the same.
    const bool keepStatic = s.swept.size() == n && s.sweptMargin == margin;
    // (A new margin: every box made again.)
    if (!keepStatic) s.boxFrom.assign(n, {});
    s.sweptMargin = margin;
    s.swept.resize(n);
    s.moving.resize(n);
    s.halfSpaces.clear();
    // Each body's box is its own: spread over the worker threads.
    forEachChunk(s.pool, static_cast<int>(n), kBodyGrain, [&](int begin, int end) {
        for (int i = begin; i < end; ++i) {
            const BodyModel& b = model.bodies[i];
            if (keepStatic && b.motion == Motion::Static && b.collider.kind != Kind::Plane) continue;
            s.moving[i] = !b.standsStill() && !state.isAsleep(i);
            const Pose* other = s.moving[i]                          ? &s.start[i]
                                : s.standing && (*s.standing)[i] ? &s.standFrom[i]
                                                                    : nullptr;
            // The same poses as the box was made from: the same box (a box or a sphere is
            // made faster than its poses are compared).
            const bool costly = b.collider.kind == Kind::Hull || b.collider.kind == Kind::Mesh ||
                                b.collider.kind == Kind::Compound;
            DetectScratch::BoxFrom& from = s.boxFrom[i];
            if (costly && from.with == (other ? 1 : 0) && samePose(from.end, s.end[i]) &&
                (!other || samePose(from.other, *other)))
                continue;
            s.swept[i] = bounds(b.collider, s.end[i]);
            if (other) s.swept[i].add(bounds(b.collider, *other));
            s.swept[i].min.array() -= margin;
            s.swept[i].max.array() += margin;
            if (costly) from = {s.end[i], other ? *other : Pose{}, other ? 1 : 0};
        }
    }, &s.boxesGate);
    // A plane that stands still is a half-space: it pairs only with the boxes reaching it.
    for (size_t i = 0; i < n; ++i) {
        const BodyModel& b = model.bodies[i];
        if (b.collider.kind != Kind::Plane || !b.standsStill()) continue;
        s.halfSpaces.resize(n);
        const Vec3 normal = s.end[i].R * b.collider.normal;
        s.halfSpaces[i] = {normal, normal.dot(s.end[i].p) + b.collider.distance, true};
    }
    s.broadphase.setPool(s.pool);
    s.broadphase.update(s.swept, s.moving, s.halfSpaces);
    // Pairs that collision groups or the scene's no_collide keep apart go before any
    // narrowphase work.
    if (model.filtered) s.broadphase.dropPairs([&](int a, int b) { return !model.mayCollide(a, b); });
}

namespace {

constexpr int kPairGrain = 8;  // pairs per chunk on the worker threads

// Runs pair(k, a, b, out) for every broadphase pair k = (a, b), appending to s.contacts (or
// s.impacts) in the pairs' order: on the worker threads each chunk of pairs fills a list of
// its own, and the lists are joined in chunk order, so the result does not depend on the
// threads.
// `gate` says whether this many pairs are worth the pool (workers.h PoolGate).
template <class List, class Pair>
void overPairs(DetectScratch& s, List& out, std::vector<List>& chunkOut, PoolGate& gate, Pair&& pair) {
    const auto& pairs = s.broadphase.pairs();
    const int n = static_cast<int>(pairs.size());
    if (!s.pool || s.pool->threads() == 1) {  // (one thread: nothing to time or gate)
        for (int k = 0; k < n; ++k) pair(k, pairs[k].first, pairs[k].second, out);
        return;
    }
    const auto start = std::chrono::steady_clock::now();
    auto booked = [&](bool pooled) {
        gate.record(s.pool, n, std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count(), pooled);
    };
    if (n <= kPairGrain || !gate.worthIt(s.pool, n)) {
        for (int k = 0; k < n; ++k) pair(k, pairs[k].first, pairs[k].second, out);
        booked(false);
        return;
    }
    const int chunks = (n + kPairGrain - 1) / kPairGrain;
    if (static_cast<int>(chunkOut.size()) < chunks) chunkOut.resize(chunks);
    s.pool->run(chunks, [&](int c) {
        // Filled as a list of the thread's own, its room taken from chunkOut[c] and given back
        // at the end: the chunks' lists lie side by side in chunkOut, and appending to them in
        // place had two threads writing the same cache lines at every manifold (pyramid-1240's
        // narrowphase on two threads 3.6 -> 3.0 ms a step; 3.9-4.1 on one).
        List mine;
        mine.swap(chunkOut[c]);
        mine.clear();
        const int end = std::min(n, (c + 1) * kPairGrain);
        for (int k = c * kPairGrain; k < end; ++k) pair(k, pairs[k].first, pairs[k].second, mine);
        chunkOut[c].swap(mine);
    });
    for (int c = 0; c < chunks; ++c) out.insert(out.end(), chunkOut[c].begin(), chunkOut[c].end());
    booked(true);
}

}  // namespace

namespace {

static_assert(sizeof(Pose) == 12 * sizeof(double), "a pose is compared as its bytes");

// Whether a joint that holds joins bodies a < b (they do not collide).
bool joined(const DetectScratch& s, int a, int b) {
    return !s.jointPairs.empty() &&
           std::binary_search(s.jointPairs.begin(), s.jointPairs.end(), pairKey(a, b));
}


// The pairs of this narrowphase and their manifolds, for the next one; each paired body's
// pose. Written over the last ones, which this narrowphase has done reading (a second
// memory traded with it held every manifold twice).
void rememberPairs(const Model& model, DetectScratch& s, double margin) {
    DetectScratch::PairMemory& next = s.lastPairs;
    next.keys.clear();
    next.ranges.clear();
    next.apart.swap(s.apart);  // (findContacts assigns s.apart afresh)
    // Grown by half when it must grow: assigned at its exact size, a list that grows by a
    // manifold or two a step (a heap filling up) was allocated anew each time, and each old
    // one left a hole in the heap that nothing later fitted.
    makeRoom(next.manifolds, s.contacts.size());
    next.manifolds.assign(s.contacts.begin(), s.contacts.end());
    next.margin = margin;
    if (s.pairedPose.size() != model.bodies.size()) s.pairedPose.assign(model.bodies.size(), Pose{});
    size_t m = 0;
    for (const auto& [a, b] : s.broadphase.pairs()) {
        const size_t first = m;
        while (m < s.contacts.size() && s.contacts[m].bodyA == a && s.contacts[m].bodyB == b) ++m;
        next.keys.push_back(pairKey(a, b));
        next.ranges.emplace_back(static_cast<int>(first), static_cast<int>(m));
        s.pairedPose[a] = s.end[a];
        s.pairedPose[b] = s.end[b];
    }
}

}  // namespace

// A pair whose two bodies stand exactly where they stood at the last narrowphase takes the
// manifolds found then: the same result, bit for bit, as finding them again. Mostly these
// are the pairs a step looks at again after a cut at a moment of impact, away from the
// impact (the islands without one keep their end of the step: hull-rain, 90 of its 93 such
// pairs a step), and a few bodies that stand exactly still from one step to the next.
// Nothing is approximated, so a run and its re-simulation from a saved state agree
// whatever this memory held.
void refreshJointPairs(const Model& model, const State& state, DetectScratch& s) {
    int broken = 0;
    for (const JointModel& j : model.joints) broken += state.jointBroken(j.index) ? 1 : 0;
    if (broken == s.jointPairsBroken) return;
    s.jointPairsBroken = broken;
    s.jointPairs.clear();
    for (const JointModel& j : model.joints)
        if (j.b >= 0 && !j.collideConnected && !state.jointBroken(j.index))
            s.jointPairs.push_back(pairKey(std::min(j.a, j.b), std::max(j.a, j.b)));
    std::sort(s.jointPairs.begin(), s.jointPairs.end());
}

namespace {

// The parts of each compound body in a pair, placed once at the end of the step.
void placeCompounds(const Model& model, DetectScratch& s, double margin) {
    s.placed.clear();
    s.placedAt.assign(model.bodies.size(), -1);
    for (const auto& [a, b] : s.broadphase.pairs()) {
        for (const int i : {a, b}) {
            const Shape& shape = model.bodies[i].collider;
            if (shape.kind != Kind::Compound || s.placedAt[i] >= 0) continue;
            s.placedAt[i] = static_cast<int>(s.placed.size());
            placeParts(shape, s.end[i], margin, s.placed);
        }
    }
}

}  // namespace

void findContacts(const Model& model, DetectScratch& s, double margin) {
    s.contacts.clear();
    // Room for about as many as the last time and an eighth: in a scene whose contacts keep
    // growing (a heap filling up), grown by half ahead of need rather than doubled by the
    // narrowphase's appends (hull-rain's ~300 manifolds held room for 512, 100 KB).
    const size_t lastCount = s.lastPairs.manifolds.size();
    makeRoom(s.contacts, lastCount + lastCount / 8 + 4);
    const DetectScratch::PairMemory& last = s.lastPairs;
    const bool remembered = last.margin == margin && s.pairedPose.size() == model.bodies.size();
    // The manifolds of (a, b) from the last narrowphase, if both bodies stand still since.
    auto lastOf = [&](int a, int b) -> const std::pair<int, int>* {
        if (!remembered || !samePose(s.pairedPose[a], s.end[a]) || !samePose(s.pairedPose[b], s.end[b]))
            return nullptr;
        const std::uint64_t key = pairKey(a, b);
        const auto it = std::lower_bound(last.keys.begin(), last.keys.end(), key);
        return it != last.keys.end() && *it == key ? &last.ranges[it - last.keys.begin()] : nullptr;
    };
    // The direction along which (a, b) were found apart last time, if they were (zero if not).
    auto lastApart = [&](int a, int b) -> Vec3 {
        const std::uint64_t key = pairKey(a, b);
        const auto it = std::lower_bound(last.keys.begin(), last.keys.end(), key);
        return it != last.keys.end() && *it == key ? last.apart[it - last.keys.begin()] : Vec3::Zero();
    };
    s.apart.assign(s.broadphase.pairs().size(), Vec3::Zero());
    placeCompounds(model, s, margin);
    // Counted per chunk (pair k is in chunk k / kPairGrain on the pool or not): one counter for
    // both threads was a cache line they wrote at every pair taken again.
    s.chunkTally.assign((s.broadphase.pairs().size() + kPairGrain - 1) / kPairGrain, {});
    overPairs(s, s.contacts, s.chunkContacts, s.contactsGate, [&](int k, int a, int b, ManifoldList& out) {
        if (const auto* range = lastOf(a, b)) {
            out.insert(out.end(), last.manifolds.begin() + range->first,
                       last.manifolds.begin() + range->second);
            s.apart[k] = last.apart[range - last.ranges.data()];
            ++s.chunkTally[k / kPairGrain].n[0];
            return;
        }
        if (joined(s, a, b)) return;  // a joint's bodies do not collide
        const Shape& A = model.bodies[a].collider;
        const Shape& B = model.bodies[b].collider;
        const size_t first = out.size();
        if (generalConvex(A.kind, B.kind)) {
            // Two convex shapes found apart last time are still apart if the same direction
            // still separates them by the margin; else GJK looks, and tells the new one.
            const Vec3 axis = lastApart(a, b);
            if (!axis.isZero(0.0) && apartAlong(A, s.end[a], B, s.end[b], axis, margin)) {
                s.apart[k] = axis;
                ++s.chunkTally[k / kPairGrain].n[1];
                return;
            }
            collide(A, s.end[a], B, s.end[b], margin, out, s.apart[k]);
        } else if (A.kind == Kind::Compound || B.kind == Kind::Compound) {
            auto ready = [&](int i) { return s.placedAt[i] >= 0 ? &s.placed[s.placedAt[i]] : nullptr; };
            collideCompound(A, s.end[a], B, s.end[b], margin, out, ready(a), ready(b));
        } else {
            collide(A, s.end[a], B, s.end[b], margin, out);
        }
        for (size_t k = first; k < out.size(); ++k) {
            out[k].bodyA = a;
            out[k].bodyB = b;
        }
    });
    for (const DetectScratch::ChunkTally& c : s.chunkTally) s.reusedPairs += c.n[0], s.apartPairs += c.n[1];
    rememberPairs(model, s, margin);
}

namespace {

// cos 45°: a contact at the end whose normal is this near the first touch's is on the near side.
constexpr double kSameSide = 0.7071;
constexpr double kSurelySameSide = 0.7660;  // cos 40°
constexpr double kNearTouch = 1e-3;         // of the smaller body

// A body's path over the step h: its centre on the parabola of the constant acceleration
// that takes its velocity from the start's to the end's (exact for a free flight under
// gravity, which the splitting step integrates exactly), its orientation by slerp.
// An animated body as its path arrives at time t: a step that lands on a key ends on the
// segment before it (its state there, KeyPath::at(t), already has the next segment's
// velocity: a paddle turning back at a key would bow the step's straight path).
BodyState arriving(const BodyModel& body, double t) {
    BodyState s;
    placeOnPath(body, std::nextafter(t, -HUGE_VAL), s);
    return s;
}

Sweep sweepOf(const BodyModel& body, const BodyState& before, const BodyState& after, double h, double end) {
    Sweep w;
    w.c0 = before.x;
    w.c1 = after.x;
    if (body.motion == Motion::Dynamic) w.bow = 0.5 * h * body.invMass * (after.P - before.P);
    if (body.path)
        w.bow = 0.5 * h * (arriving(body, end).P - before.P);  // (an animated body's P is its velocity)
    w.q0 = before.q;
    w.q1 = after.q;
    w.localCenter = body.centerOfMass;
    return w;
}

// How fast A's and B's points at `point` close along `normal` (out of B towards A) at the
// fraction s of the step: velocities and centres taken linearly between the start and the end.
double approachSpeed(const Model& model, const State& before, const State& after, int a, int b, double s,
                     const Vec3& point, const Vec3& normal) {
    auto pointVelocity = [&](int i) -> Vec3 {
        const BodyModel& body = model.bodies[i];
        if (body.motion == Motion::Static) return Vec3::Zero();
        if (body.motion == Motion::Kinematic && !body.path)
            return body.kinematicVelocity + body.kinematicAngularVelocity.cross(point - after.bodies[i].x);
        const Derived d0 = derive(body, before.bodies[i]),
                      d1 = derive(body, body.path ? arriving(body, after.time) : after.bodies[i]);
        const Vec3 x = (1.0 - s) * before.bodies[i].x + s * after.bodies[i].x;
        return (1.0 - s) * d0.v + s * d1.v + ((1.0 - s) * d0.omega + s * d1.omega).cross(point - x);
    };
    return -normal.dot(pointVelocity(a) - pointVelocity(b));
}

}  // namespace

void touchingPairs(const ManifoldList& contacts, double touchTolerance, std::vector<std::uint64_t>& out) {
    out.clear();
    for (const Manifold& m : contacts)
        if (m.maxDepth() >= -touchTolerance) out.push_back(pairKey(m.bodyA, m.bodyB));
    std::sort(out.begin(), out.end());
}

void findImpacts(const Model& model, const State& before, const State& after, double t0, double h,
                 double tolerance, double minApproach, const std::vector<double>& sizes,
                 const std::vector<double>* thickness, DetectScratch& s) {
    collision::forgetPartSweeps();  // (what compoundImpact kept is of another search)
    s.impacts.clear();
    if (thickness) {
        s.found.clear();
        for (int k = 0; k < static_cast<int>(s.contacts.size()); ++k)
            s.found.emplace_back(pairKey(s.contacts[k].bodyA, s.contacts[k].bodyB), k);
        std::sort(s.found.begin(), s.found.end());
    }
    // How far a point of body i moved in the step by its turn, at most.
    auto turnTravel = [&](int i) {
        const BodyModel& body = model.bodies[i];
        if (body.motion == Motion::Static) return 0.0;
        const BodyState &b0 = before.bodies[i], &b1 = after.bodies[i];
        return b0.q.angularDistance(b1.q) * (sizes[i] + body.centerOfMass.norm());
    };
    // How far a point of a moved in the step against a point of b, at most: only the bodies'
    // motion relative to each other can carry one through the other (two chairs falling side
    // by side at 10 m/s move 17 cm a step each, and nothing against each other). Their
    // centres' relative path is the chord of their displacements' difference, sagging from
    // it by at most a quarter of the difference of their bows (the pair's sweeps hold both).
    auto relativeTravel = [&](int a, int b, const Sweep& sa, const Sweep& sb) {
        return ((sa.c1 - sa.c0) - (sb.c1 - sb.c0)).norm() + 0.25 * (sa.bow - sb.bow).norm() + turnTravel(a) +
               turnTravel(b);
    };
    // A pair overlapping at the end by more than a thousandth of the smaller body but not
    // approaching there: it met within the step and is on its way out (a ball grazing a
    // box's edge at 1/30 s, 2.3 mm inside at the end, leaving along the end's normal). The
    // contact solver at the end has nothing to stop, so the end-of-step mode must find
    // its moment.
    auto leaving = [&](const Manifold& m) {
        int deepest = 0;
        for (int i = 1; i < m.count; ++i)
            if (m.points[i].depth > m.points[deepest].depth) deepest = i;
        const double size = std::min(sizes[m.bodyA], sizes[m.bodyB]);
        return m.count > 0 && m.points[deepest].depth > kNearTouch * size &&
               approachSpeed(model, before, after, m.bodyA, m.bodyB, 1.0, m.points[deepest].position,
                             m.normal) <= 0.0;
    };
    // The search of one pair not touching at the start: its impact, if any, into `out`.
    auto search = [&](int a, int b, std::vector<ImpactEvent>& out) {
        const BodyModel& A = model.bodies[a];
        const BodyModel& B = model.bodies[b];
        const Sweep sa = sweepOf(A, before.bodies[a], after.bodies[a], h, after.time);
        const Sweep sb = sweepOf(B, before.bodies[b], after.bodies[b], h, after.time);
        // The tolerance: a small fraction of the smaller body, so that thin bodies are resolved.
        const double size = std::min(sizes[a], sizes[b]);
        const bool compound = A.collider.kind == Kind::Compound || B.collider.kind == Kind::Compound;
        // (A compound's part sweeps are kept by body number for its other pairs.)
        auto impactWithin = [&](double tol, Window window) {
            return compound ? compoundImpact(A.collider, sa, B.collider, sb, tol, window, a, b)
                            : timeOfImpact(A.collider, sa, B.collider, sb, tol, window);
        };
        int found = -1;     // the pair's first manifold at the end (end-of-step mode), if any
        bool away = false;  // ... and the pair leaves it there (`leaving`)
        if (thickness) {
            // Touching at the end: left to the end unless the overlap can be past the middle
            // of the thinner solid (its normal would then point out of the far side and push
            // the body through). A plane's normal is its own whatever the overlap. A mesh's
            // triangles (thickness 0) are trusted as the end finds them: asking for a moment
            // whenever a body moved half its own width brought back 2.3 cuts a step in
            // hull-rain (1.7 -> 3.4 ms); a body sinking past a triangle's plane within one
            // step can go through, as in the peers (passLimit). A compound is asked part by
            // part: a chair is 4 cm thick only at its legs.
            const auto it =
                std::lower_bound(s.found.begin(), s.found.end(), std::make_pair(pairKey(a, b), -1));
            found = it != s.found.end() && it->first == pairKey(a, b) ? it->second : -1;
            away = found >= 0 && leaving(s.contacts[found]);
            const bool mayPass =
                compound
                    ? partsMayPass(A.collider, sa, B.collider, sb, tolerance * size, found >= 0, a, b)
                    : relativeTravel(a, b, sa, sb) >= passLimit((*thickness)[a], (*thickness)[b], found >= 0);
            if (!mayPass && !away) return;
        }
        double from = 0.0;  // the search for the moment starts there
        if (found >= 0 && !away) {
            // Touching at the end: whether the first touch was on the same side needs no
            // exact moment. Near it (within 1e-3 of the smaller body) its normal is taken
            // when it is well inside the same-side cone (40°, 5° to spare); else the moment
            // is found as for a cut.
            const auto near = impactWithin(kNearTouch * size, {});
            if (!near) return;
            if (s.contacts[found].normal.dot(near->normal) >= kSurelySameSide) return;
            from = near->s;
        }
        // (Before the near touch the pair stays apart by half its tolerance, far more than this
        // one: the search goes on from there.)
        const auto hit = impactWithin(tolerance * size, {from, 1.0});
        if (!hit) return;
        // Touching at the end along much the normal of the first touch: the end's contact is
        // on the side the bodies met, not past the middle, and the contact solver resolves
        // it there (hull-rain: nearly every landing of a hull on another moved more than
        // half a hull and was cut for nothing, 3.8 moments a step).
        if (found >= 0 && !away && s.contacts[found].normal.dot(hit->normal) >= kSameSide) return;
        // A slow approach is settling, the contact solver's work: no moment of impact.
        if (approachSpeed(model, before, after, a, b, hit->s, hit->point, hit->normal) <=
            minApproach * restingShare(model.settings.gravity, hit->normal))
            return;
        out.push_back({a, b, t0 + hit->s * h, hit->normal, hit->point});
    };
    // A pair found without an impact earlier in the step keeps that answer while neither
    // body's path changed (DetectScratch::noImpact). A sleeping or parked body stands still
    // in the search, unlike its path: such pairs are searched every time.
    auto awake = [&](int i) { return after.asleep.empty() || !after.asleep[i]; };
    auto keptFrom = [&](int a, int b) {
        const auto it = std::lower_bound(s.noImpact.begin(), s.noImpact.end(), std::make_pair(pairKey(a, b), -1));
        if (it == s.noImpact.end() || it->first != pairKey(a, b)) return -1;
        return it->second >= s.pathFrom[a] && it->second >= s.pathFrom[b] ? it->second : -1;
    };
    s.pathFrom.resize(model.bodies.size(), -1);
    s.noImpactFrom.assign(s.broadphase.pairs().size(), -1);
    s.chunkTally.assign((s.broadphase.pairs().size() + kPairGrain - 1) / kPairGrain, {});  // (see findContacts)
    overPairs(s, s.impacts, s.chunkImpacts, s.impactsGate, [&](int k, int a, int b, std::vector<ImpactEvent>& out) {
        if (joined(s, a, b)) return;
        // In contact already: no new impact.
        if (std::binary_search(s.touching.begin(), s.touching.end(), pairKey(a, b))) return;
        const bool bothAwake = awake(a) && awake(b);
        if (const int from = bothAwake && !s.noImpact.empty() ? keptFrom(a, b) : -1; from >= 0) {
            s.noImpactFrom[k] = from;
            ++s.chunkTally[k / kPairGrain].n[1];  // a search kept
            return;
        }
        ++s.chunkTally[k / kPairGrain].n[0];  // a search
        const size_t found = out.size();
        search(a, b, out);
        // (End-of-step's judgement that the end is right is no search of the whole path.)
        if (!thickness && bothAwake && out.size() == found) s.noImpactFrom[k] = s.subStep;
    });
    for (const DetectScratch::ChunkTally& c : s.chunkTally) s.impactSearches += c.n[0], s.impactSearchesKept += c.n[1];
    s.noImpact.clear();
    const auto& pairs = s.broadphase.pairs();
    for (size_t k = 0; k < pairs.size(); ++k)
        if (s.noImpactFrom[k] >= 0) s.noImpact.emplace_back(pairKey(pairs[k].first, pairs[k].second), s.noImpactFrom[k]);
    std::sort(s.noImpact.begin(), s.noImpact.end());
}

}  // namespace tumble
