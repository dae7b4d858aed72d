// Compound pairs. The parts of a body are few (a table's five, a decomposed mesh's 16), so
// a part's box in the body frame is looked at in turn; what keeps the cost linear is that
// only the parts whose boxes meet the other body's box (carried into the body frame) are
// paired, and two compounds pair only those near parts of each whose world boxes overlap.
#include "collision/compound_pairs.h"

#include "collision/contact_util.h"
#include "collision/narrowphase.h"

#include <algorithm>
#include <array>
#include <atomic>
#include <cmath>
#include <cstdint>
#include <limits>
#include <vector>

namespace tumble::collision {

namespace {

// The box of a world box turned into the frame of `pose` (the box about the turned box).
Aabb intoFrame(const Aabb& world, const Pose& pose) {
    const Vec3 c = pose.toLocal(world.center());
    const Vec3 e = pose.R.transpose().cwiseAbs() * (0.5 * world.extent());
    return {c - e, c + e};
}

// A box that holds the shape at the pose, for culling: a compound's is its box in the body
// frame carried into the world (one turn of a box, where its exact bounds are a pass over
// every part, and every hull part's vertices); any other shape's own bounds.
Aabb cullBox(const Shape& shape, const Pose& pose) {
    if (shape.kind != Kind::Compound) return bounds(shape, pose);
    const Aabb& local = shape.compound->box;
    const Vec3 c = pose.toWorld(local.center());
    const Vec3 e = pose.R.cwiseAbs() * (0.5 * local.extent());
    return {c - e, c + e};
}

PlacedPart placed(const Shape& shape, const Pose& pose, int k, double margin) {
    if (shape.kind != Kind::Compound) return {0, pose, bounds(shape, pose).inflated(margin)};
    const Pose at = pose * shape.compound->parts[k].pose;
    return {k, at, bounds(shape.compound->parts[k].shape, at).inflated(margin)};
}

// The parts of `shape` at `pose` whose boxes meet `other` (world), or the shape itself as
// part 0 when it is not a compound; `ready`, if given, holds them all (placeParts).
void nearParts(const Shape& shape, const Pose& pose, const Aabb& other, double margin,
               const PlacedPart* ready, std::vector<PlacedPart>& out) {
    out.clear();
    if (shape.kind != Kind::Compound) {
        out.push_back(ready ? ready[0] : placed(shape, pose, 0, margin));
        return;
    }
    const Compound& c = *shape.compound;
    auto take = [&](int k) {
        const PlacedPart p = ready ? ready[k] : placed(shape, pose, k, margin);
        if (p.box.overlaps(other)) out.push_back(p);
    };
    if (!other.min.allFinite() || !other.max.allFinite()) {  // a plane: every part
        for (int k = 0; k < static_cast<int>(c.parts.size()); ++k) take(k);
        return;
    }
    c.query(intoFrame(other.inflated(margin), pose), take);
}

// A pair of parts' feature ids, kept apart from every other pair's.
std::uint32_t mixed(std::uint32_t feature, int partA, int partB) {
    const std::uint32_t parts =
        static_cast<std::uint32_t>(partA) * 0x10001u + static_cast<std::uint32_t>(partB);
    return feature ^ (parts * 0x9E3779B1u);
}

// Normals this near (within 0.08°) are one contact plane.
constexpr double kSamePlane = 1.0 - 1e-6;

// Whether contacts on parts p and q of a compound (or the shape itself) act alike: the same
// material and the same roundness, so that one manifold can carry both.
bool alike(const Shape& shape, int p, int q) {
    if (p == q || shape.kind != Kind::Compound) return true;
    const auto& a = shape.compound->parts[p];
    const auto& b = shape.compound->parts[q];
    return a.friction == b.friction && a.restitution == b.restitution &&
           roundness(a.shape) == roundness(b.shape);
}

// Keeps at most four of the points, those that span the most of the contact plane: the
// farthest from their middle, the farthest from it, the largest triangle with both, the
// most area added on the far side. (collision::addReduced starts from the deepest point
// instead; merged from several parts, the points are often at one depth to rounding, and
// that rounding chose a leg's inner corner.) For a rigid contact in one plane the depth is
// an affine function of the position, so its deepest point is at a corner of the spread;
// a deeper point that is not (curved parts) takes the place of the chosen point nearest it.
void addSpread(const std::vector<Candidate>& c, const Vec3& normal, ManifoldList& out) {
    if (c.size() <= Manifold::kMaxPoints) {
        addReduced(c, normal, out);
        return;
    }
    auto flat = [&](size_t i) { return Vec3(c[i].position - normal * normal.dot(c[i].position)); };
    auto area = [&](size_t a, size_t b, size_t i) {
        return (flat(b) - flat(a)).cross(flat(i) - flat(a)).dot(normal);
    };
    Vec3 middle = Vec3::Zero();
    for (size_t i = 0; i < c.size(); ++i) middle += flat(i) / static_cast<double>(c.size());
    // The first candidate whose value is the largest to within rounding (1e-9 of it): a tie,
    // as the four legs of a symmetric table make, goes to the lower index whatever the
    // rounding of the pose, so a turned world chooses the same points.
    auto firstLargest = [&](auto&& value) {
        double best = -std::numeric_limits<double>::infinity();
        for (size_t i = 0; i < c.size(); ++i) best = std::max(best, value(i));
        for (size_t i = 0; i < c.size(); ++i)
            if (value(i) >= best - 1e-9 * std::abs(best)) return i;
        return size_t{0};
    };
    auto farthestFrom = [&](const Vec3& q) {
        return firstLargest([&](size_t i) { return (flat(i) - q).squaredNorm(); });
    };
    std::array<size_t, 4> pick;
    pick[0] = farthestFrom(middle);
    pick[1] = farthestFrom(flat(pick[0]));
    pick[2] = firstLargest([&](size_t i) { return std::abs(area(pick[0], pick[1], i)); });
    const double side = area(pick[0], pick[1], pick[2]);
    const double none = -std::numeric_limits<double>::infinity();
    pick[3] = firstLargest([&](size_t i) {
        const double a = area(pick[0], pick[1], i);
        return a * side < 0.0 ? std::abs(a) : none;
    });
    if (area(pick[0], pick[1], pick[3]) * side >= 0.0) pick[3] = pick[0];  // nothing on the far side
    size_t deepest = 0;
    for (size_t i = 1; i < c.size(); ++i)
        if (c[i].depth > c[deepest].depth) deepest = i;
    double chosenDepth = -std::numeric_limits<double>::infinity();
    for (size_t i : pick) chosenDepth = std::max(chosenDepth, c[i].depth);
    if (c[deepest].depth > chosenDepth + 1e-9 * (flat(pick[0]) - flat(pick[1])).norm()) {
        size_t nearest = 0;
        for (size_t k = 1; k < 4; ++k)
            if ((flat(pick[k]) - flat(deepest)).squaredNorm() <
                (flat(pick[nearest]) - flat(deepest)).squaredNorm())
                nearest = k;
        pick[nearest] = deepest;
    }
    Manifold m;
    m.normal = normal;
    for (size_t k = 0; k < 4; ++k) {
        bool seen = false;
        for (size_t j = 0; j < k; ++j) seen = seen || pick[j] == pick[k];
        if (!seen) m.add(c[pick[k]].position, c[pick[k]].depth, c[pick[k]].feature);
    }
    out.push_back(m);
}

// The manifolds out[first ..] that share a contact plane and act alike become one, reduced to
// the four points that span the most (addSpread). A table on the floor is one
// manifold of the four legs' outer corners, not four manifolds of a leg each: the contact
// solver's block shares the weight over the corners by least norm, a quarter on each leg,
// where four separate blocks solved one after another ended wherever their history left
// them (113 to 192 N on the legs of a 608 N table).
void mergeSamePlane(const Shape& a, const Shape& b, size_t first, ManifoldList& out) {
    if (out.size() - first < 2) return;
    thread_local std::vector<Manifold> kept;
    thread_local std::vector<std::vector<Candidate>> points;
    kept.clear();
    points.clear();
    for (size_t m = first; m < out.size(); ++m) {
        const Manifold& x = out[m];
        size_t g = 0;
        while (g < kept.size() && !(kept[g].normal.dot(x.normal) >= kSamePlane &&
                                    alike(a, kept[g].partA, x.partA) && alike(b, kept[g].partB, x.partB)))
            ++g;
        if (g == kept.size()) {
            kept.push_back(x);
            points.emplace_back();
        }
        for (int i = 0; i < x.count; ++i)
            points[g].push_back({x.points[i].position, x.points[i].depth, x.points[i].feature});
    }
    if (kept.size() == out.size() - first) return;
    out.resize(first);
    for (size_t g = 0; g < kept.size(); ++g) {
        const size_t at = out.size();
        addSpread(points[g], kept[g].normal, out);
        for (size_t m = at; m < out.size(); ++m) {
            out[m].partA = kept[g].partA;
            out[m].partB = kept[g].partB;
        }
    }
}

}  // namespace

void placeParts(const Shape& shape, const Pose& pose, double margin, std::vector<PlacedPart>& out) {
    const int parts = shape.kind == Kind::Compound ? static_cast<int>(shape.compound->parts.size()) : 1;
    for (int k = 0; k < parts; ++k) out.push_back(placed(shape, pose, k, margin));
}

void collideCompound(const Shape& a, const Pose& pa, const Shape& b, const Pose& pb, double margin,
                     ManifoldList& out, const PlacedPart* readyA, const PlacedPart* readyB) {
    thread_local std::vector<PlacedPart> nearA, nearB;
    nearParts(a, pa, cullBox(b, pb), margin, readyA, nearA);
    if (nearA.empty()) return;
    nearParts(b, pb, cullBox(a, pa), margin, readyB, nearB);
    const size_t first = out.size();
    for (const PlacedPart& x : nearA) {
        for (const PlacedPart& y : nearB) {
            if (!x.box.overlaps(y.box)) continue;
            const size_t first = out.size();
            collide(partShape(a, x.part), x.pose, partShape(b, y.part), y.pose, margin, out);
            for (size_t m = first; m < out.size(); ++m) {
                out[m].partA = static_cast<std::uint16_t>(x.part);
                out[m].partB = static_cast<std::uint16_t>(y.part);
                for (int i = 0; i < out[m].count; ++i)
                    out[m].points[i].feature = mixed(out[m].points[i].feature, x.part, y.part);
            }
        }
    }
    mergeSamePlane(a, b, first, out);
}

Sweep partSweep(const Sweep& body, const Pose& part) {
    Sweep s = body;
    const Quat turn(part.R);
    s.q0 = body.q0 * turn;
    s.q1 = body.q1 * turn;
    // The part's frame origin is the body's plus R part.p, so the centre of mass sits at
    // R_part^T (localCenter - part.p) in the part's frame.
    s.localCenter = part.R.transpose() * (body.localCenter - part.p);
    return s;
}

namespace {

// A ball that holds a part wherever the step takes it: about the part frame's origin, whose
// path is its chord between the step's ends but for the body's turn (a point at distance d
// from the centre of mass leaves the chord by at most θ d) and the centre's sag.
struct SweptBall {
    Vec3 p0, p1;
    double radius = 0.0;  // infinite for a plane
    Aabb box;             // all the part sweeps through (infinite for a plane)
    double drift = 0.0;   // how far any point of the part strays from its origin's chord
    double thickness = 0.0;
};

// The body's poses at the step's ends and its turn, once for all its parts.
struct SweepEnds {
    Pose start, end;
    double turn = 0.0;
    explicit SweepEnds(const Sweep& sw)
        : start(sw.at(0.0)), end(sw.at(1.0)), turn(sw.q0.angularDistance(sw.q1)) {}
};

SweptBall sweptBall(const Shape& shape, const Sweep& sw, const SweepEnds& ends, const Pose& part) {
    SweptBall b;
    const Aabb everywhere{Vec3::Constant(-std::numeric_limits<double>::infinity()),
                          Vec3::Constant(std::numeric_limits<double>::infinity())};
    b.thickness = thickness(shape);
    if (shape.kind == Kind::Plane) {
        b.radius = std::numeric_limits<double>::infinity();
        b.box = everywhere;
        return b;
    }
    b.p0 = ends.start.toWorld(part.p);
    b.p1 = ends.end.toWorld(part.p);
    const double own = boundingRadius(shape);
    b.radius = own + ends.turn * (part.p - sw.localCenter).norm() + 0.25 * sw.bow.norm();
    // The box the part sweeps: its boxes at the two ends, and how far any of its points strays
    // from the straight line between its two places. A point at r from the centre of mass
    // turning at a steady rate through θ accelerates by r θ² (over s in [0, 1]); a path's
    // distance from the line through its ends is at most an eighth of its greatest
    // acceleration, and the centre's bow adds a quarter of itself. Past a radian or two that
    // bound outgrows the ball: the box is left infinite, the ball decides.
    b.box = bounds(shape, ends.start * part);
    b.box.add(bounds(shape, ends.end * part));
    const double arm = (part.p - sw.localCenter).norm() + own;
    const double stray = arm * ends.turn * ends.turn / 8.0 + 0.25 * sw.bow.norm();
    b.box = ends.turn < 2.0 ? b.box.inflated(stray) : everywhere;
    // (The origin's path leaves its chord by at most the stray; a point of the part turns
    // about the origin through the body's angle, by at most that angle times its reach.)
    b.drift = (part.p - sw.localCenter).norm() * ends.turn * ends.turn / 8.0 + 0.25 * sw.bow.norm() +
              ends.turn * own;
    return b;
}

// The two balls never come within `tol` over the step (their centres' gap is linear in s).
bool ballsMiss(const SweptBall& a, const SweptBall& b, double tol) {
    if (!a.box.inflated(tol).overlaps(b.box)) return true;  // (a plane's box is the whole space)
    if (!std::isfinite(a.radius) || !std::isfinite(b.radius)) return false;
    const Vec3 d0 = a.p0 - b.p0, dd = (a.p1 - b.p1) - d0;
    const double t = dd.squaredNorm() > 0 ? std::clamp(-d0.dot(dd) / dd.squaredNorm(), 0.0, 1.0) : 0.0;
    return (d0 + t * dd).norm() - a.radius - b.radius > tol;
}

// The earliest fraction of the step at which the two balls can come within `tol` (their
// centres' gap is linear in s): no point of the parts meets before it.
double ballsEarliest(const SweptBall& a, const SweptBall& b, double tol) {
    if (!std::isfinite(a.radius) || !std::isfinite(b.radius)) return 0.0;
    const double reach = a.radius + b.radius + tol;
    const Vec3 d0 = a.p0 - b.p0, dd = (a.p1 - b.p1) - d0;
    // |d0 + s dd|^2 = reach^2: the smaller root, if the gap shrinks to reach at all.
    const double c = d0.squaredNorm() - reach * reach;
    if (c <= 0.0) return 0.0;
    const double qa = dd.squaredNorm(), qb = d0.dot(dd);
    const double disc = qb * qb - qa * c;
    if (qa <= 0.0 || qb >= 0.0 || disc < 0.0) return 0.0;  // (ballsMiss has ruled these out)
    return std::max(0.0, c / (-qb + std::sqrt(disc)));     // the smaller root, without cancellation
}
}  // namespace

namespace {

// A body's parts' swept balls and sweeps over one step. A body meets several others in a
// step, and each pair is asked up to three times (may a part pass, near the end, the
// moment): each thread keeps every body's it has made in the search under way, by the
// body's number, and checks the shape and the sweep exactly before it takes one.
struct PartSweeps {
    std::uint64_t epoch = 0;  // the search it was made in (forgetPartSweeps); 0: none
    const Shape* shape = nullptr;
    Sweep sweep;
    std::vector<SweptBall> balls;
    std::vector<Sweep> sweeps;
    // For partsMayPass's first look: the most any part's origin moves other than with the
    // centre of mass, the most any part drifts from its origin's chord, and the thinnest part
    // (zero if a part is not a finite solid).
    double turnMove = 0.0, drift = 0.0, thinnest = 0.0;
};

bool sameSweep(const Sweep& x, const Sweep& y) {
    return x.c0 == y.c0 && x.c1 == y.c1 && x.bow == y.bow && x.q0.coeffs() == y.q0.coeffs() &&
           x.q1.coeffs() == y.q1.coeffs() && x.localCenter == y.localCenter;
}

// The search for impacts under way (forgetPartSweeps starts a new one).
std::atomic<std::uint64_t> searches{1};

void fill(PartSweeps& e, const Shape& shape, const Sweep& sw) {
    e.shape = &shape;
    e.sweep = sw;
    e.balls.clear();
    e.sweeps.clear();
    const SweepEnds ends(sw);
    const int parts = shape.kind == Kind::Compound ? static_cast<int>(shape.compound->parts.size()) : 1;
    for (int j = 0; j < parts; ++j) {
        const Pose pose = shape.kind == Kind::Compound ? shape.compound->parts[j].pose : Pose{};
        e.balls.push_back(sweptBall(partShape(shape, j), sw, ends, pose));
        e.sweeps.push_back(shape.kind == Kind::Compound ? partSweep(sw, pose) : sw);
    }
    e.turnMove = e.drift = 0.0;
    e.thinnest = std::numeric_limits<double>::infinity();
    for (const SweptBall& b : e.balls) {
        e.turnMove = std::max(e.turnMove, ((b.p1 - b.p0) - (sw.c1 - sw.c0)).norm());
        e.drift = std::max(e.drift, b.drift);
        const bool solid = std::isfinite(b.thickness) && b.thickness > 0.0;
        e.thinnest = solid ? std::min(e.thinnest, b.thickness) : 0.0;
    }
}

// The part sweeps of a pair: kept by body number when it is given (>= 0), else made anew.
struct PairSweeps {
    const PartSweeps* a;
    const PartSweeps* b;
};
PairSweeps pairSweeps(const Shape& a, const Sweep& sa, int bodyA, const Shape& b, const Sweep& sb,
                      int bodyB) {
    thread_local std::array<PartSweeps, 2> loose;  // for a pair asked without numbers
    thread_local std::vector<PartSweeps> byBody;
    const std::uint64_t epoch = searches.load(std::memory_order_relaxed);
    const size_t need = static_cast<size_t>(std::max(bodyA, bodyB) + 1);
    if (byBody.size() < need) byBody.resize(need);  // (before any entry is taken)
    auto of = [&](const Shape& shape, const Sweep& sw, int body, PartSweeps& spare) -> const PartSweeps* {
        if (body < 0) {
            fill(spare, shape, sw);
            return &spare;
        }
        PartSweeps& e = byBody[static_cast<size_t>(body)];
        if (e.epoch != epoch || e.shape != &shape || !sameSweep(e.sweep, sw)) {
            e.epoch = epoch;
            fill(e, shape, sw);
        }
        return &e;
    };
    return {of(a, sa, bodyA, loose[0]), of(b, sb, bodyB, loose[1])};
}

}  // namespace

double passLimit(double ta, double tb, bool touching) {
    const bool solids = std::isfinite(ta) && std::isfinite(tb) && ta > 0.0 && tb > 0.0;
    const double thinner = solids ? std::min(ta, tb) : std::numeric_limits<double>::infinity();
    return touching ? 0.5 * thinner : ta + tb;
}

bool partsMayPass(const Shape& a, const Sweep& sa, const Shape& b, const Sweep& sb, double tolerance,
                  bool touching, int bodyA, int bodyB) {
    const PairSweeps p = pairSweeps(a, sa, bodyA, b, sb, bodyB);
    // No pair of parts moves against each other by more than the centres do and what each
    // body's turn adds; below the thinnest parts' limit, none can pass.
    if (p.a->thinnest > 0.0 && p.b->thinnest > 0.0) {
        const double most = ((sa.c1 - sa.c0) - (sb.c1 - sb.c0)).norm() + p.a->turnMove + p.b->turnMove +
                            p.a->drift + p.b->drift;
        if (most < passLimit(p.a->thinnest, p.b->thinnest, touching)) return false;
    }
    for (const SweptBall& x : p.a->balls) {
        for (const SweptBall& y : p.b->balls) {
            const double limit = passLimit(x.thickness, y.thickness, touching);
            if (!std::isfinite(limit)) continue;
            const double moved = ((x.p1 - x.p0) - (y.p1 - y.p0)).norm() + x.drift + y.drift;
            if (moved >= limit && !ballsMiss(x, y, tolerance)) return true;
        }
    }
    return false;
}

void forgetPartSweeps() {
    searches.fetch_add(1, std::memory_order_relaxed);
}

std::optional<Impact> compoundImpact(const Shape& a, const Sweep& sa, const Shape& b, const Sweep& sb,
                                     double tolerance, Window window, int bodyA, int bodyB) {
    // Only the pairs of parts whose swept boxes and balls meet are swept part against part: a
    // chair landing on a chair has 36 pairs of parts, of which a few come near.
    const PairSweeps p = pairSweeps(a, sa, bodyA, b, sb, bodyB);
    const PartSweeps& A = *p.a;
    const PartSweeps& B = *p.b;
    // The pairs of parts in the order their balls can first meet: once one has its moment,
    // a pair whose balls meet only later is not looked at, and the others' searches stop as
    // soon as they pass it. The answer is the one a search of every pair in turn would give
    // (on a tie, the first pair in part order).
    struct Candidate {
        double earliest;
        int i, j;
    };
    thread_local std::vector<Candidate> order;
    order.clear();
    for (size_t i = 0; i < A.balls.size(); ++i) {
        for (size_t j = 0; j < B.balls.size(); ++j) {
            if (ballsMiss(A.balls[i], B.balls[j], tolerance)) continue;
            // (timeOfImpact may widen a tolerance to a rounding floor of the parts' sizes.)
            const double tol = std::max(tolerance, 1e-12 * (A.balls[i].radius + B.balls[j].radius));
            order.push_back({std::max(window.from, ballsEarliest(A.balls[i], B.balls[j], tol)),
                             static_cast<int>(i), static_cast<int>(j)});
        }
    }
    std::sort(order.begin(), order.end(), [](const Candidate& x, const Candidate& y) {
        return x.earliest != y.earliest ? x.earliest < y.earliest
                                        : std::make_pair(x.i, x.j) < std::make_pair(y.i, y.j);
    });
    std::optional<Impact> best;
    std::pair<int, int> bestPair;
    for (const Candidate& c : order) {
        if (best && c.earliest > best->s) break;
        if (c.earliest > window.notAfter) break;
        auto hit = timeOfImpact(partShape(a, c.i), A.sweeps[c.i], partShape(b, c.j), B.sweeps[c.j], tolerance,
                                {window.from, best ? std::min(best->s, window.notAfter) : window.notAfter});
        if (hit &&
            (!best || hit->s < best->s || (hit->s == best->s && std::make_pair(c.i, c.j) < bestPair))) {
            best = hit;
            bestPair = {c.i, c.j};
        }
    }
    return best;
}

}  // namespace tumble::collision
