// GJK distance and EPA penetration against closed forms (spheres, boxes, capsules at known
// poses) and against brute-force references on random convex hulls: the distance of two
// disjoint hulls is the least distance of any triangle of their Minkowski difference's
// vertices to the origin (exact: every such triangle lies in the difference, and a boundary
// one reaches the closest point); the penetration depth of two overlapping polytopes is the
// least overlap of their projections over the face normals of both and the cross products
// of their edges (the separating axis theorem's candidates are the difference's normals).
#include <tumble/convex_hull.h>
#include "collision/gjk.h"

#include <QtTest>

#include <cmath>
#include <memory>
#include <numbers>
#include <random>

using namespace tumble;
using namespace tumble::collision;

namespace {

Pose pose(const Vec3& p, const Quat& q = Quat::Identity()) {
    Pose r;
    r.R = q.normalized().toRotationMatrix();
    r.p = p;
    return r;
}

Quat randomRotation(std::mt19937& rng) {
    std::normal_distribution<double> g;
    return Quat(g(rng), g(rng), g(rng), g(rng)).normalized();
}

std::shared_ptr<ConvexHull> randomHull(std::mt19937& rng, int n, double size) {
    std::uniform_real_distribution<double> u(-size, size);
    std::vector<Vec3> pts;
    for (int i = 0; i < n; ++i) pts.emplace_back(u(rng), u(rng), u(rng));
    return std::make_shared<ConvexHull>(mesh::convexHull(pts));
}

Shape hullShape(std::shared_ptr<ConvexHull> h) {
    Shape s;
    s.kind = Kind::Hull;
    s.hull = std::move(h);
    return s;
}

std::vector<Vec3> worldVertices(const ConvexHull& h, const Pose& p) {
    std::vector<Vec3> out;
    for (const Vec3& v : h.vertices) out.push_back(p.toWorld(v));
    return out;
}

// Distance from the origin to the triangle (a, b, c), by dense minimisation free of the
// code under test: clamp-projected onto the plane, else the best edge.
double segmentDistance(const Vec3& a, const Vec3& b) {
    const Vec3 d = b - a;
    const double t = d.squaredNorm() > 0 ? std::clamp(-a.dot(d) / d.squaredNorm(), 0.0, 1.0) : 0.0;
    return (a + t * d).norm();
}
double triangleDistance(const Vec3& a, const Vec3& b, const Vec3& c) {
    const Vec3 n = (b - a).cross(c - a);
    double best = std::min({segmentDistance(a, b), segmentDistance(b, c), segmentDistance(c, a)});
    if (n.squaredNorm() > 0) {
        const Vec3 nn = n.normalized();
        const Vec3 q = nn * a.dot(nn);  // projection of the origin on the plane
        const bool inside = (b - a).cross(q - a).dot(n) >= 0 && (c - b).cross(q - b).dot(n) >= 0 &&
                            (a - c).cross(q - c).dot(n) >= 0;
        if (inside) best = std::min(best, q.norm());
    }
    return best;
}

// SAT depth of two polytopes (> 0 overlapping): least projection overlap over the candidates.
double satDepth(const ConvexHull& ha, const Pose& pa, const ConvexHull& hb, const Pose& pb, Vec3* axisOut) {
    const auto va = worldVertices(ha, pa), vb = worldVertices(hb, pb);
    std::vector<Vec3> axes;
    for (const auto& f : ha.faces) axes.push_back(pa.R * f.normal);
    for (const auto& f : hb.faces) axes.push_back(pb.R * f.normal);
    for (const auto& ea : ha.edges)
        for (const auto& eb : hb.edges) {
            const Vec3 c = (va[ea[1]] - va[ea[0]]).cross(vb[eb[1]] - vb[eb[0]]);
            if (c.norm() > 1e-9) axes.push_back(c.normalized());
        }
    double best = std::numeric_limits<double>::infinity();
    for (const Vec3& n : axes) {
        double minA = 1e300, maxA = -1e300, minB = 1e300, maxB = -1e300;
        for (const Vec3& v : va) minA = std::min(minA, n.dot(v)), maxA = std::max(maxA, n.dot(v));
        for (const Vec3& v : vb) minB = std::min(minB, n.dot(v)), maxB = std::max(maxB, n.dot(v));
        const double o1 = maxB - minA, o2 = maxA - minB;  // push A along +n by o1, or along -n by o2
        if (o1 < best) best = o1, *axisOut = n;
        if (o2 < best) best = o2, *axisOut = -n;
    }
    return best;
}

// Support function of the full shapes' difference A - B: h(u) = max over A - B of u·x.
double support(const ConvexProxy& a, const ConvexProxy& b, const Vec3& u) {
    return u.dot(a.support(u)) - u.dot(b.support(-u)) + a.radius + b.radius;
}

// Minimum over unit vectors of f: the best of a Fibonacci sphere of directions, then a
// pattern search about it with a shrinking step.
template <class F>
double minOverSphere(F&& f) {
    const int n = 4000;
    Vec3 best(0, 0, 1);
    double fb = f(best);
    for (int i = 0; i < n; ++i) {
        const double z = 1.0 - 2.0 * (i + 0.5) / n, r = std::sqrt(1 - z * z);
        const double t = i * std::numbers::pi * (3.0 - std::sqrt(5.0));
        const Vec3 u(r * std::cos(t), r * std::sin(t), z);
        const double fu = f(u);
        if (fu < fb) fb = fu, best = u;
    }
    for (double step = 0.05; step > 1e-9;) {
        const Vec3 e1 = best.unitOrthogonal(), e2 = best.cross(e1);
        bool improved = false;
        for (const Vec3& d :
             {e1, Vec3(-e1), e2, Vec3(-e2), Vec3(e1 + e2), Vec3(e1 - e2), Vec3(-e1 + e2), Vec3(-e1 - e2)}) {
            const Vec3 u = (best + step * d).normalized();
            const double fu = f(u);
            if (fu < fb) fb = fu, best = u, improved = true;
        }
        if (!improved) step *= 0.5;
    }
    return fb;
}

}  // namespace

class TestGjk : public QObject {
    Q_OBJECT

private slots:
    void sphereSphereDistance() {
        const ConvexProxy a = proxyOf(Shape::sphere(1.0), pose(Vec3(3, 0, 0)));
        const ConvexProxy b = proxyOf(Shape::sphere(0.5), pose(Vec3::Zero()));
        const Distance d = gjkDistance(a, b);
        QVERIFY(!d.overlap);
        QVERIFY(std::abs(d.distance - 1.5) < 1e-12);
        QVERIFY((d.pointA - Vec3(2, 0, 0)).norm() < 1e-12);
        QVERIFY((d.pointB - Vec3(0.5, 0, 0)).norm() < 1e-12);
    }

    void sphereBoxDistance() {
        const Quat q(Eigen::AngleAxisd(0.7, Vec3(1, 2, 3).normalized()));
        const Pose pb = pose(Vec3(10, -4, 2), q);
        const ConvexProxy box = proxyOf(Shape::box(Vec3(1, 2, 3)), pb);
        // Face region: local (3, 0.5, 0.5) is 2 from the +x face.
        Distance d = gjkDistance(proxyOf(Shape::sphere(0.5), pose(pb.toWorld(Vec3(3, 0.5, 0.5)))), box);
        QVERIFY(std::abs(d.distance - 1.5) < 1e-11);
        QVERIFY((d.pointB - pb.toWorld(Vec3(1, 0.5, 0.5))).norm() < 1e-11);
        // Corner region: local (2, 3, 4) is sqrt(3) from the corner (1, 2, 3).
        d = gjkDistance(proxyOf(Shape::sphere(0.25), pose(pb.toWorld(Vec3(2, 3, 4)))), box);
        QVERIFY(std::abs(d.distance - (std::sqrt(3.0) - 0.25)) < 1e-11);
        QVERIFY((d.pointB - pb.toWorld(Vec3(1, 2, 3))).norm() < 1e-11);
    }

    void boxBoxDistance() {
        // B turned 45 degrees about z shows an edge at x0 - sqrt(2) to A's face at x = 1.
        const double x0 = 4.0;
        const ConvexProxy a = proxyOf(Shape::box(Vec3(1, 1, 1)), pose(Vec3(0, 0, 0)));
        const ConvexProxy b =
            proxyOf(Shape::box(Vec3(1, 1, 0.5)),
                    pose(Vec3(x0, 0.2, 0.1), Quat(Eigen::AngleAxisd(std::numbers::pi / 4, Vec3::UnitZ()))));
        const Distance d = gjkDistance(a, b);
        QVERIFY(std::abs(d.distance - (x0 - std::sqrt(2.0) - 1.0)) < 1e-12);
        QVERIFY(std::abs(d.pointA.x() - 1.0) < 1e-12);
        QVERIFY(std::abs(d.pointB.x() - (x0 - std::sqrt(2.0))) < 1e-12);
    }

    void overlappingSpheres() {
        const ConvexProxy a = proxyOf(Shape::sphere(1.0), pose(Vec3(1.5, 0, 0)));
        const ConvexProxy b = proxyOf(Shape::sphere(1.0), pose(Vec3::Zero()));
        const Penetration p = penetration(a, b, 0.0);
        QVERIFY(p.hit);
        QVERIFY(std::abs(p.depth - 0.5) < 1e-12);
        QVERIFY((p.normal - Vec3(1, 0, 0)).norm() < 1e-12);
        QVERIFY((p.pointA - Vec3(0.5, 0, 0)).norm() < 1e-12);
        QVERIFY((p.pointB - Vec3(1, 0, 0)).norm() < 1e-12);
        // Negative depth within the margin, nothing beyond it.
        const ConvexProxy far = proxyOf(Shape::sphere(1.0), pose(Vec3(0, 2.1, 0)));
        const Penetration near = penetration(far, b, 0.2);
        QVERIFY(near.hit && std::abs(near.depth + 0.1) < 1e-12);
        QVERIFY(!penetration(far, b, 0.05).hit);
    }

    void boxBoxFaceOverlap() {
        const ConvexProxy a = proxyOf(Shape::box(Vec3(1, 1, 1)), pose(Vec3(0.3, 1.9, -0.2)));
        const ConvexProxy b = proxyOf(Shape::box(Vec3(1, 1, 1)), pose(Vec3::Zero()));
        const Penetration p = penetration(a, b, 0.0);
        QVERIFY(p.hit);
        QVERIFY(std::abs(p.depth - 0.1) < 1e-12);
        QVERIFY((p.normal - Vec3(0, 1, 0)).norm() < 1e-12);
        QVERIFY(std::abs(p.pointA.y() - 0.9) < 1e-12 && std::abs(p.pointB.y() - 1.0) < 1e-12);
        const Distance d = gjkDistance(a, b);
        QVERIFY(d.overlap && std::abs(d.distance + 0.1) < 1e-12);
    }

    void deepPointInBox() {
        // A sphere centre inside a box: EPA on the box core against a point.
        const Pose pb = pose(Vec3(5, 5, 5), Quat(Eigen::AngleAxisd(0.3, Vec3::UnitY())));
        const ConvexProxy b = proxyOf(Shape::box(Vec3(1, 1, 1)), pb);
        const ConvexProxy a = proxyOf(Shape::sphere(0.1), pose(pb.toWorld(Vec3(0.7, 0.1, 0))));
        const Penetration p = penetration(a, b, 0.0);
        QVERIFY(std::abs(p.depth - 0.4) < 1e-12);
        QVERIFY((p.normal - pb.R.col(0)).norm() < 1e-12);
        // A box inside a box: the y faces are nearest (0.7 against 1.5 along x).
        const ConvexProxy inner =
            proxyOf(Shape::box(Vec3(0.5, 0.5, 0.5)), pose(pb.toWorld(Vec3(0, 0.8, 0)), Quat(pb.R)));
        const Penetration q = penetration(inner, b, 0.0);
        QVERIFY(std::abs(q.depth - 0.7) < 1e-12);
        QVERIFY((q.normal - pb.R.col(1)).norm() < 1e-12);
    }

    void capsulesCrossed() {
        const Quat alongX(Eigen::AngleAxisd(std::numbers::pi / 2, Vec3::UnitZ()));
        const Quat alongZ(Eigen::AngleAxisd(std::numbers::pi / 2, Vec3::UnitX()));
        const ConvexProxy b = proxyOf(Shape::capsule(0.5, 2.0), pose(Vec3::Zero(), alongZ));
        // Axes 0.8 apart: the cores stay apart, depth 1 - 0.8 along y.
        const Penetration p =
            penetration(proxyOf(Shape::capsule(0.5, 2.0), pose(Vec3(0.3, 0.8, -0.1), alongX)), b, 0.0);
        QVERIFY(std::abs(p.depth - 0.2) < 1e-12);
        QVERIFY((p.normal - Vec3(0, 1, 0)).norm() < 1e-12);
        // Axes crossing: the difference of the cores is flat; depth is the sum of the radii
        // along the common normal, towards A's centre.
        const Penetration q =
            penetration(proxyOf(Shape::capsule(0.5, 2.0), pose(Vec3(0.3, 0, 0), alongX)), b, 0.0);
        QVERIFY(std::abs(q.depth - 1.0) < 1e-12);
        QVERIFY(std::abs(std::abs(q.normal.y()) - 1.0) < 1e-12);
        // Axes crossing slightly below: the way out is down.
        const Penetration r =
            penetration(proxyOf(Shape::capsule(0.5, 2.0), pose(Vec3(0.3, -0.05, 0), alongX)), b, 0.0);
        QVERIFY(std::abs(r.depth - 0.95) < 1e-12);
        QVERIFY((r.normal - Vec3(0, -1, 0)).norm() < 1e-12);
    }

    void cylinderDistances() {
        // Cylinder (r 1, half height 2) along y; a sphere beside the side, one over the rim.
        const Pose pc = pose(Vec3(1, 2, 3), Quat(Eigen::AngleAxisd(0.4, Vec3(1, 1, 0).normalized())));
        const ConvexProxy c = proxyOf(Shape::cylinder(1.0, 2.0), pc);
        Distance d = gjkDistance(proxyOf(Shape::sphere(0.5), pose(pc.toWorld(Vec3(0, 0.5, 3)))), c);
        QVERIFY(std::abs(d.distance - 1.5) < 1e-9);
        d = gjkDistance(proxyOf(Shape::sphere(0.5), pose(pc.toWorld(Vec3(0.6 * 3, 2 + 4, 0.8 * 3)))), c);
        QVERIFY(std::abs(d.distance - (std::hypot(2.0, 4.0) - 0.5)) < 1e-9);
        // Overlap with the cap from above: depth 0.3, normal the axis.
        const Penetration p = penetration(
            proxyOf(Shape::box(Vec3(0.2, 0.2, 0.2)), pose(pc.toWorld(Vec3(0.1, 2.1, 0)), Quat(pc.R))), c,
            0.0);
        QVERIFY(std::abs(p.depth - 0.1) < 1e-9);
        QVERIFY((p.normal - pc.R.col(1)).norm() < 1e-7);
    }

    void scaleInvariance() {
        // The same box-box and sphere-box configuration from a millimetre to a kilometre,
        // a long way from the world origin: relative error stays at rounding level.
        for (double s : {1e-3, 1.0, 1e3}) {
            const Vec3 far(7e3, -3e3, 1e4);
            const Quat q(Eigen::AngleAxisd(std::numbers::pi / 4, Vec3::UnitZ()));
            const ConvexProxy a = proxyOf(Shape::box(Vec3(s, s, s)), pose(far));
            const ConvexProxy b =
                proxyOf(Shape::box(Vec3(s, s, 0.5 * s)), pose(far + Vec3(4 * s, 0.2 * s, 0), q));
            const Distance d = gjkDistance(a, b);
            QVERIFY2(std::abs(d.distance - s * (3 - std::sqrt(2.0))) < 1e-9 * s,
                     qPrintable(QString::number(s)));
            const ConvexProxy c = proxyOf(Shape::box(Vec3(s, s, s)), pose(far + Vec3(0.3 * s, 1.9 * s, 0)));
            const Penetration p = penetration(c, a, 0.0);
            QVERIFY(std::abs(p.depth - 0.1 * s) < 1e-9 * s);
            QVERIFY((p.normal - Vec3(0, 1, 0)).norm() < 1e-9);
        }
    }

    void randomHullsAgainstBruteForce() {
        std::mt19937 rng(12345);
        std::uniform_real_distribution<double> u(-1.0, 1.0);
        int separated = 0, overlapping = 0;
        double worstDist = 0.0, worstDepth = 0.0;
        for (int trial = 0; trial < 300; ++trial) {
            const auto ha = randomHull(rng, 8, 1.0), hb = randomHull(rng, 8, 0.7);
            const Pose pa = pose(Vec3(u(rng), u(rng), u(rng)) * 1.2, randomRotation(rng));
            const Pose pb = pose(Vec3(u(rng), u(rng), u(rng)) * 1.2, randomRotation(rng));
            const ConvexProxy a = proxyOf(hullShape(ha), pa), b = proxyOf(hullShape(hb), pb);
            const auto va = worldVertices(*ha, pa), vb = worldVertices(*hb, pb);
            std::vector<Vec3> m;
            for (const Vec3& x : va)
                for (const Vec3& y : vb) m.push_back(x - y);
            Vec3 axis;
            const double depth = satDepth(*ha, pa, *hb, pb, &axis);
            const Distance d = gjkDistance(a, b);
            if (depth < 0) {
                double ref = std::numeric_limits<double>::infinity();
                const int n = static_cast<int>(m.size());
                for (int i = 0; i < n; ++i)
                    for (int j = i + 1; j < n; ++j)
                        for (int k = j + 1; k < n; ++k)
                            ref = std::min(ref, triangleDistance(m[i], m[j], m[k]));
                QVERIFY(!d.overlap);
                worstDist = std::max(worstDist, std::abs(d.distance - ref));
                QVERIFY2(std::abs(d.distance - ref) < 1e-9,
                         qPrintable(QString("trial %1: %2 vs %3").arg(trial).arg(d.distance).arg(ref)));
                QVERIFY(std::abs((d.pointA - d.pointB).norm() - ref) < 1e-9);
                ++separated;
            } else {
                const Penetration p = penetration(a, b, 0.0);
                QVERIFY(p.hit && d.overlap);
                worstDepth = std::max(worstDepth, std::abs(p.depth - depth));
                QVERIFY2(std::abs(p.depth - depth) < 1e-9,
                         qPrintable(QString("trial %1: %2 vs %3").arg(trial).arg(p.depth).arg(depth)));
                // Moving A out by the depth along the normal leaves the shapes touching.
                Pose moved = pa;
                moved.p += p.normal * (p.depth + 1e-7);
                QVERIFY(!gjkDistance(proxyOf(hullShape(ha), moved), b).overlap);
                ++overlapping;
            }
        }
        qInfo(
            "random hulls: %d separated (worst distance error %.2e), %d overlapping (worst depth error %.2e)",
            separated, worstDist, overlapping, worstDepth);
        QVERIFY(separated > 50 && overlapping > 50);
    }

    void randomPairsOfAllKindsAgainstSupportFunction() {
        // Every kind against every kind at random poses. With h the support function of the
        // difference A - B, any direction u bounds the answer: distance >= -h(-u) when apart,
        // depth <= h(u) when overlapping; the best direction found by search must not beat
        // GJK / EPA, and their own normal must certify their answer.
        std::mt19937 rng(777);
        std::uniform_real_distribution<double> size(0.2, 1.2), u(-1.0, 1.0);
        std::uniform_real_distribution<double> decade(-3.0, 3.0);
        double k = 1.0;  // each trial at its own scale, from a millimetre to a kilometre
        auto randomShape = [&](int kind) {
            switch (kind) {
                case 0: return Shape::sphere(k * size(rng));
                case 1: return Shape::box(k * Vec3(size(rng), size(rng), size(rng)));
                case 2: return Shape::capsule(k * size(rng), k * size(rng));
                case 3: return Shape::cylinder(k * size(rng), k * size(rng));
                default: return hullShape(randomHull(rng, 12, k));
            }
        };
        int apart = 0, overlapping = 0;
        double worst = 0.0;
        for (int trial = 0; trial < 300; ++trial) {
            k = std::pow(10.0, decade(rng));
            const Vec3 far = Vec3(30, -20, 50) * k;
            const Shape sa = randomShape(trial % 5), sb = randomShape((trial / 5) % 5);
            const ConvexProxy a =
                proxyOf(sa, pose(far + Vec3(u(rng), u(rng), u(rng)) * 1.5 * k, randomRotation(rng)));
            const ConvexProxy b =
                proxyOf(sb, pose(far + Vec3(u(rng), u(rng), u(rng)) * 1.5 * k, randomRotation(rng)));
            const Distance d = gjkDistance(a, b);
            const QString where =
                QString("trial %1 kinds %2 %3").arg(trial).arg(trial % 5).arg((trial / 5) % 5);
            if (!d.overlap) {
                // No direction may prove them farther apart than GJK says ...
                const double best = -minOverSphere([&](const Vec3& v) { return support(a, b, -v); });
                QVERIFY2(d.distance >= best - 1e-12 * k, qPrintable(where));
                // ... and GJK's own direction proves its answer: the plane normal to the
                // closest points' difference separates the shapes by that distance.
                const Vec3 n = d.normal;
                QVERIFY2((d.pointA - d.pointB - d.distance * n).norm() < 1e-9 * k, qPrintable(where));
                QVERIFY2(-support(a, b, -n) >= d.distance - 1e-9 * k,
                         qPrintable(where + QString(": %1 vs %2").arg(d.distance).arg(-support(a, b, -n))));
                worst = std::max(worst, (d.distance + support(a, b, -n)) / k);
                ++apart;
            } else {
                const Penetration p = penetration(a, b, 0.0);
                const double best = minOverSphere([&](const Vec3& v) { return support(a, b, v); });
                // No direction found by search is a shorter way out than EPA's (to its 1e-10
                // relative stopping gap) ...
                QVERIFY2(p.depth <= best + 1e-9 * k,
                         qPrintable(where + QString(": %1 vs %2").arg(p.depth).arg(best)));
                // The witness points are the deepest points, one depth apart along the normal
                // (on curved cores EPA's nearest face is a chord: ~1e-8 of the size).
                QVERIFY2((p.pointA - p.pointB + p.depth * p.normal).norm() < 1e-6 * k, qPrintable(where + QString(": %1 at depth %2").arg((p.pointA - p.pointB + p.depth * p.normal).norm() / k).arg(p.depth / k)));
                // ... and EPA's way out is as long as it says (the support along the normal).
                QVERIFY2(std::abs(support(a, b, -p.normal) - p.depth) < 1e-9 * k,
                         qPrintable(where + QString(": %1 vs %2")
                                                .arg(p.depth, 0, 'g', 15)
                                                .arg(support(a, b, -p.normal), 0, 'g', 15)));
                worst = std::max(worst, std::abs(support(a, b, -p.normal) - p.depth) / k);
                ++overlapping;
            }
        }
        qInfo(
            "all kinds: %d apart, %d overlapping, worst gap between the answer and its own certificate %.2e "
            "of the scale",
            apart, overlapping, worst);
        QVERIFY(apart > 50 && overlapping > 50);
    }
};

QTEST_APPLESS_MAIN(TestGjk)
#include "tst_gjk.moc"
