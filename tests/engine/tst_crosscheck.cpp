// The fast narrowphase (collide() in collision/narrowphase.h) checked against the reference
// tests of the paper (collision/reference.h) on thousands of random near-contact poses per
// pair of kinds. Every check counts its failures over the whole run and describes the first
// pair that failed it, so one run says what is wrong and how often.
//
// What is compared, and the tolerances (size = sum of the bounding radii):
// - Detection. The reference penetrates by more than touch = 1e-7 size (below that the pair
//   is touching and either answer is right) => the fast path reports a point with depth > 0.
//   The reference separates the pair by more than touch => no point deeper than touch;
//   by more than a margin of 0.05 size => nothing at all when asked with that margin.
// - Normal and depth against the separating-axis minimum of the reference (the minimum
//   translation), allowing for what each fast path promises:
//   * box-box is SAT too, but prefers a face axis unless an edge axis is 5% shallower (and
//     A's faces unless B's are 2% shallower) so that resting manifolds do not flicker: the
//     reference overlap along its normal, and its depth, lie in [1, 1/0.95] x the minimum.
//     (Directions are not compared: two axes may tie.)
//   * the general convex path (GJK/EPA) snaps the normal to a face normal within
//     acos(0.985) = 9.94 degrees to clip a face: its normal must be within that angle of
//     a minimal axis (overlap within 1e-6 relative of the minimum), and no point may be
//     deeper than the bodies overlap along the normal.
//   * planes and spheres: exact (1e-12 relative, the rounding of a few operations).
// - Points. For two convex bodies the reference points are the vertices of A ∩ B, so a
//   fast point lies in the reference's contact region when it is inside both bodies; a fast
//   point is midway between the surfaces, so it may be outside A ∩ B by half its depth.
#include <tumble/convex_hull.h>
#include "collision/narrowphase.h"
#include "collision/reference.h"

#include "test_random.h"

#include <QtTest>

#include <cstdint>
#include <map>
#include <numbers>
#include <string>

using namespace tumble;
using namespace tumble::collision;
namespace ref = tumble::collision::reference;

namespace {

const double kSnapCos = 0.985;  // the convex path's face-snapping cone (clip.cpp)

using test::Rng;

double maxPlaneValue(const ref::Polyhedron& body, const Vec3& p) {
    double e = -1e300;
    for (const auto& f : body.faces) e = std::max(e, ref::planeValue(f.normal, -f.offset, p));
    return e;
}

double angleDeg(const Vec3& u, const Vec3& v) {
    return std::acos(std::clamp(u.dot(v), -1.0, 1.0)) * 180.0 / std::numbers::pi;
}

enum class Path { BoxBox, Convex };

struct Stats {
    int penetrating = 0, separated = 0;
    double overlapHigh = 0.0;                  // overlap along the fast normal / minimum
    double depthLow = 1e300, depthHigh = 0.0;  // fast deepest / minimum
    double angleHigh = 0.0;                    // fast normal to the nearest minimal axis, degrees
    double outsideHigh = 0.0;                  // of a point, beyond half its depth, / size
    std::map<std::string, int> failures;
};

void describe(const char* why, const Shape& a, const Pose& pa, const Shape& b, const Pose& pb) {
    const ref::RefContacts rc = ref::referenceContacts(a, pa, b, pb);
    ManifoldList out;
    collide(a, pa, b, pb, 0.0, out);
    const ref::Polyhedron A = ref::worldPolyhedron(a, pa), B = ref::worldPolyhedron(b, pb);
    qWarning(
        "%s: %s at (%.6f %.6f %.6f) against %s at (%.6f %.6f %.6f); reference depth %.9g normal (%.6f %.6f "
        "%.6f)",
        why, toString(a.kind), pa.p.x(), pa.p.y(), pa.p.z(), toString(b.kind), pb.p.x(), pb.p.y(), pb.p.z(),
        rc.depth, rc.normal.x(), rc.normal.y(), rc.normal.z());
    for (const auto& m : out) {
        qWarning("  fast normal (%.6f %.6f %.6f), %.3f deg from the reference's, overlap along it %.9g",
                 m.normal.x(), m.normal.y(), m.normal.z(), angleDeg(m.normal, rc.normal),
                 ref::overlapAlong(A, B, m.normal));
        for (int i = 0; i < m.count; ++i)
            qWarning("    point (%.6f %.6f %.6f) depth %.9g; E(p) at most %.3g for A, %.3g for B",
                     m.points[i].position.x(), m.points[i].position.y(), m.points[i].position.z(),
                     m.points[i].depth, maxPlaneValue(A, m.points[i].position),
                     maxPlaneValue(B, m.points[i].position));
    }
}

// One pair of polyhedra (Box or Hull) at their poses.
void checkPair(Path path, const Shape& a, const Pose& pa, const Shape& b, const Pose& pb, Stats& st) {
    const ref::Polyhedron A = ref::worldPolyhedron(a, pa), B = ref::worldPolyhedron(b, pb);
    const auto axes = ref::separatingAxes(A, B);
    double minimum = 1e300;
    Vec3 minAxis = Vec3::UnitY();
    for (const auto& ax : axes)
        if (ax.overlap < minimum) minimum = ax.overlap, minAxis = ax.axis;
    const double size = boundingRadius(a) + boundingRadius(b);
    const double touch = 1e-7 * size, abs = 1e-9 * size;
    ManifoldList out;
    collide(a, pa, b, pb, 0.0, out);
    auto fail = [&](const char* why) {
        if (st.failures[why]++ == 0) describe(why, a, pa, b, pb);
    };
    if (minimum < -touch) {
        ++st.separated;
        for (const auto& m : out)
            if (m.maxDepth() > touch) fail("separated, yet a penetrating point");
        // The largest gap over the axes is a lower bound of the distance: beyond the margin,
        // not even near contacts.
        const double margin = 0.05 * size;
        if (minimum < -margin - touch) {
            out.clear();
            collide(a, pa, b, pb, margin, out);
            if (!out.empty()) fail("separated by more than the margin, yet contacts");
        }
        return;
    }
    if (minimum <= touch) return;
    ++st.penetrating;
    const Manifold* deepest = nullptr;
    for (const auto& m : out)
        if (m.count > 0 && (!deepest || m.maxDepth() > deepest->maxDepth())) deepest = &m;
    if (!deepest || deepest->maxDepth() <= 0.0) return fail("penetrating, yet no penetrating point");
    const Vec3 n = deepest->normal;
    const double depth = deepest->maxDepth();
    const double overlap = ref::overlapAlong(A, B, n);
    st.overlapHigh = std::max(st.overlapHigh, overlap / minimum);
    st.depthLow = std::min(st.depthLow, depth / minimum);
    st.depthHigh = std::max(st.depthHigh, depth / minimum);
    double angle = 180.0;
    for (const auto& ax : axes)
        if (ax.overlap <= minimum + 1e-6 * minimum + abs) angle = std::min(angle, angleDeg(n, ax.axis));
    st.angleHigh = std::max(st.angleHigh, angle);
    if (std::abs(n.norm() - 1.0) > 1e-12) fail("normal not unit");
    if (path == Path::BoxBox) {
        if (overlap > minimum / 0.95 + abs)
            fail("box-box: overlap along the normal above 1/0.95 x the minimum");
        if (depth > minimum / 0.95 + abs || depth < minimum - abs)
            fail("box-box: depth outside [1, 1/0.95] x the minimum");
    } else {
        if (angle > std::acos(kSnapCos) * 180.0 / std::numbers::pi + 1e-6)
            fail("convex: normal farther than the snapping cone from every minimal axis");
    }
    for (const auto& m : out) {
        const double along = ref::overlapAlong(A, B, m.normal);
        for (int i = 0; i < m.count; ++i) {
            const ContactPoint& c = m.points[i];
            if (c.depth > along + abs) fail("a point deeper than the overlap along its normal");
            const double outside = std::max(maxPlaneValue(A, c.position), maxPlaneValue(B, c.position)) -
                                   std::max(c.depth, 0.0) / 2;
            st.outsideHigh = std::max(st.outsideHigh, outside / size);
            if (outside > abs) fail("a point outside A and B by more than half its depth");
        }
    }
}

// Poses that put the pair near contact: A's centre along a random direction from B's at the
// distance where they just touch (from the reference's separating axes), then moved in by a
// random depth from -0.1 to 0.3 of the smaller size. One in four is a resting pose: A turned
// only slightly from B and approaching along one of B's axes.
template <class Make>
void randomPairs(Rng& rng, int n, Path path, Make make, Stats& st) {
    for (int k = 0; k < n; ++k) {
        const auto [a, b] = make(rng);
        const Mat3 Rb = rng.rotation();
        Mat3 Ra;
        Vec3 u;
        if (k % 4 == 0) {
            Ra = Rb * Eigen::AngleAxisd(rng.uniform(0, 0.05), rng.direction()).toRotationMatrix();
            u = Rb.col(k / 4 % 3) * (k / 12 % 2 ? 1.0 : -1.0);
            u = (u + 0.3 * rng.uniform(0, 1) * rng.direction()).normalized();
        } else {
            Ra = rng.rotation();
            u = rng.direction();
        }
        const Pose pb{Rb, rng.vec(-2, 2)};
        // Moving A by t u changes the overlap along each axis n by -t n·u, and the axes do
        // not change: the pair stops overlapping at the least o_n / n·u over n·u > 0.
        const ref::Polyhedron A0 = ref::worldPolyhedron(a, Pose{Ra, pb.p});
        const ref::Polyhedron B = ref::worldPolyhedron(b, pb);
        double lo = 1e300;
        for (const auto& ax : ref::separatingAxes(A0, B))
            if (ax.axis.dot(u) > 1e-12) lo = std::min(lo, ax.overlap / ax.axis.dot(u));
        const double small = std::min(boundingRadius(a), boundingRadius(b));
        checkPair(path, a, Pose{Ra, pb.p + (lo - rng.uniform(-0.1, 0.3) * small) * u}, b, pb, st);
    }
}

Shape randomHull(Rng& rng) {
    std::vector<Vec3> pts;
    const Vec3 scale = rng.vec(0.3, 1.0);
    for (int i = 0; i < 12; ++i) pts.push_back(rng.direction().cwiseProduct(scale));
    Shape s;
    s.kind = Kind::Hull;
    s.hull = std::make_shared<const ConvexHull>(mesh::convexHull(pts));
    return s;
}

void report(const char* name, const Stats& st) {
    qInfo(
        "%s: %d penetrating, %d separated; overlap along the fast normal <= %.4f x minimum; fast depth in "
        "[%.4f, %.4f] x minimum; normal <= %.3f deg from a minimal axis; points outside A∩B beyond half "
        "their "
        "depth by <= %.2g size",
        name, st.penetrating, st.separated, st.overlapHigh, st.depthLow, st.depthHigh, st.angleHigh,
        st.outsideHigh);
    for (const auto& [why, count] : st.failures) qWarning("  %d x %s", count, why.c_str());
}

bool clean(const Stats& st) {
    return st.failures.empty();
}

}  // namespace

class TestCrossCheck : public QObject {
    Q_OBJECT
private slots:
    void boxBox();
    void boxHull();
    void hullHull();
    void polyhedronPlane();
    void spherePlane();
    void sphereBox();
};

void TestCrossCheck::boxBox() {
    Rng rng{101};
    Stats st;
    randomPairs(
        rng, 3000, Path::BoxBox,
        [](Rng& r) {
            return std::pair{Shape::box(r.vec(0.1, 1.0)), Shape::box(r.vec(0.1, 1.0))};
        },
        st);
    report("box-box", st);
    QVERIFY(clean(st));
    QVERIFY(st.penetrating > 1500);
    QVERIFY(st.separated > 300);
}

void TestCrossCheck::boxHull() {
    Rng rng{202};
    Stats st;
    randomPairs(
        rng, 1500, Path::Convex,
        [](Rng& r) {
            return std::pair{Shape::box(r.vec(0.1, 1.0)), randomHull(r)};
        },
        st);
    report("box-hull", st);
    QVERIFY(clean(st));
    QVERIFY(st.penetrating > 700);
    QVERIFY(st.separated > 150);
}

void TestCrossCheck::hullHull() {
    Rng rng{303};
    Stats st;
    randomPairs(
        rng, 1500, Path::Convex,
        [](Rng& r) {
            return std::pair{randomHull(r), randomHull(r)};
        },
        st);
    report("hull-hull", st);
    QVERIFY(clean(st));
    QVERIFY(st.penetrating > 700);
    QVERIFY(st.separated > 150);
}

void TestCrossCheck::polyhedronPlane() {
    // Boxes and hulls against a plane through the plane test on their vertices: the fast
    // normal is the plane's, each point is a vertex moved up by half its depth with depth
    // -E(vertex), the deepest vertex is kept, and min(4, vertices below) points are kept.
    Rng rng{404};
    int penetrating = 0, separated = 0;
    for (int k = 0; k < 3000; ++k) {
        const Shape a = k % 2 ? Shape::box(rng.vec(0.1, 1.0)) : randomHull(rng);
        const Vec3 pn = rng.direction();
        const Shape plane = Shape::plane(pn, rng.uniform(-1, 1));
        const Pose pp{rng.rotation(), rng.vec(-1, 1)};
        const Vec3 n = pp.directionToWorld(pn);
        const double offset = plane.distance + n.dot(pp.p);
        // Resting (a face nearly on the plane) one time in three, else any orientation.
        Mat3 Ra = rng.rotation();
        if (k % 3 == 0) Ra = Quat::FromTwoVectors(Ra.col(1), -n).toRotationMatrix() * Ra;
        const Pose pa{Ra, Vec3::Zero()};
        const ref::Polyhedron A0 = ref::worldPolyhedron(a, pa);
        double lowest = 1e300;
        for (const Vec3& v : A0.vertices) lowest = std::min(lowest, n.dot(v) - offset);
        const Pose placed{Ra, n * (rng.uniform(-0.3, 0.1) - lowest)};
        const ref::RefContacts rc = ref::referenceContacts(a, placed, plane, pp);
        const ref::Polyhedron A = ref::worldPolyhedron(a, placed);
        const double size = boundingRadius(a), abs = 1e-12 * (size + placed.p.norm() + pp.p.norm() + 1);
        ManifoldList out;
        collide(a, placed, plane, pp, 0.0, out);
        if (rc.depth < -abs) {
            ++separated;
            QVERIFY(out.empty());
            continue;
        }
        if (rc.depth <= abs) continue;
        ++penetrating;
        QCOMPARE(out.size(), std::size_t(1));
        const Manifold& m = out[0];
        QVERIFY((m.normal - n).norm() < 1e-12);
        QVERIFY(std::abs(m.maxDepth() - rc.depth) < abs);
        QCOMPARE(m.count, std::min<int>(4, int(rc.points.size())));
        for (int i = 0; i < m.count; ++i) {
            const Vec3 v = m.points[i].position - 0.5 * m.points[i].depth * n;
            double nearest = 1e300;
            for (const Vec3& w : A.vertices) nearest = std::min(nearest, (w - v).norm());
            QVERIFY(nearest < abs);
            QVERIFY(std::abs(ref::planeValue(n, -offset, v) + m.points[i].depth) < abs);
        }
    }
    qInfo("polyhedron-plane: %d penetrating, %d separated", penetrating, separated);
    QVERIFY(penetrating > 2000);
    QVERIFY(separated > 300);
}

void TestCrossCheck::spherePlane() {
    // The point-based reference: the centre by the plane test, depth = r - E(c).
    Rng rng{505};
    int penetrating = 0;
    for (int k = 0; k < 3000; ++k) {
        const double r = rng.uniform(0.05, 1.0);
        const Vec3 pn = rng.direction();
        const Shape plane = Shape::plane(pn, rng.uniform(-1, 1));
        const Pose pp{rng.rotation(), rng.vec(-1, 1)};
        const Vec3 n = pp.directionToWorld(pn);
        const double offset = plane.distance + n.dot(pp.p);
        const Vec3 c = rng.vec(-2, 2);
        const Pose pa{rng.rotation(), c - n * (n.dot(c) - offset) + n * rng.uniform(-0.3 * r, 1.2 * r)};
        const double e = ref::planeValue(n, -offset, pa.p);
        const double depth = r - e;
        ManifoldList out;
        collide(Shape::sphere(r), pa, plane, pp, 0.0, out);
        const double abs = 1e-12 * (4 + pa.p.norm());
        if (depth < -abs) {
            QVERIFY(out.empty());
            continue;
        }
        if (depth <= abs) continue;
        ++penetrating;
        QCOMPARE(out.size(), std::size_t(1));
        QCOMPARE(out[0].count, 1);
        QVERIFY((out[0].normal - n).norm() < 1e-12);
        QVERIFY(std::abs(out[0].points[0].depth - depth) < abs);
        // Midway between the sphere's lowest point c - r n and the plane below c.
        QVERIFY((out[0].points[0].position - (pa.p - 0.5 * (r + e) * n)).norm() < abs);
    }
    QVERIFY(penetrating > 1500);
}

void TestCrossCheck::sphereBox() {
    // The point-based reference: the centre inside the box (the plane test on every face) is
    // pushed out through the nearest face, depth r + its distance; outside, the closest
    // point q of the box's faces gives depth r - |c - q| and the normal (c - q) / |c - q|.
    Rng rng{606};
    int inside = 0, outside = 0, separated = 0;
    for (int k = 0; k < 3000; ++k) {
        const double r = rng.uniform(0.05, 0.8);
        const Shape box = Shape::box(rng.vec(0.1, 1.0));
        const Pose pb{rng.rotation(), rng.vec(-1, 1)};
        const Pose pa{rng.rotation(),
                      pb.toWorld(rng.vec(-1.0, 1.0).cwiseProduct(box.halfExtents + Vec3::Constant(r)))};
        const ref::Polyhedron B = ref::worldPolyhedron(box, pb);
        const ref::Inside in = ref::pointInConvex(B, pa.p);
        double depth;
        Vec3 n, mid;
        if (in.inside) {
            // Skip centres about equally near two faces: either face is right.
            double second = 1e300;
            for (int f = 0; f < 6; ++f)
                if (f != in.face)
                    second = std::min(second, -ref::planeValue(B.faces[f].normal, -B.faces[f].offset, pa.p));
            if (second - in.depth < 1e-9) continue;
            depth = r + in.depth;
            n = in.normal;
            mid = 0.5 * ((pa.p - r * n) + (pa.p + in.depth * n));
        } else {
            Vec3 q;
            const double dist = ref::distanceToSurface(B, pa.p, q);
            if (dist < 1e-9) continue;
            depth = r - dist;
            n = (pa.p - q) / dist;
            mid = 0.5 * ((pa.p - r * n) + q);
        }
        ManifoldList out;
        collide(Shape::sphere(r), pa, box, pb, 0.0, out);
        const double abs = 1e-12 * (4 + pb.p.norm());
        if (depth < -abs) {
            ++separated;
            QVERIFY(out.empty());
            continue;
        }
        if (depth <= abs) continue;
        (in.inside ? inside : outside) += 1;
        QCOMPARE(out.size(), std::size_t(1));
        QCOMPARE(out[0].count, 1);
        QVERIFY((out[0].normal - n).norm() < 1e-9);
        QVERIFY(std::abs(out[0].points[0].depth - depth) < abs);
        QVERIFY((out[0].points[0].position - mid).norm() < 1e-9);
    }
    qInfo("sphere-box: %d with the centre inside, %d outside, %d separated", inside, outside, separated);
    QVERIFY(inside > 200);
    QVERIFY(outside > 1000);
    QVERIFY(separated > 300);
}

QTEST_APPLESS_MAIN(TestCrossCheck)
#include "tst_crosscheck.moc"
