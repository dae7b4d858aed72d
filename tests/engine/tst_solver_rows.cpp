// The contact solver's block rows: the least-norm inverse of a manifold's K (the fast path
// against the eigen-decomposition it replaces) and the impulses that push.
#include "solver/solver_body.h"

#include <QtTest>

#include <random>

using namespace tumble;

namespace {

SolverBody randomBody(std::mt19937& rng, bool movable) {
    std::uniform_real_distribution<double> u(-1.0, 1.0);
    SolverBody b;
    b.x = Vec3(u(rng), u(rng), u(rng));
    if (!movable) return b;
    b.invMass = 0.1 + 2.0 * (u(rng) + 1.0);
    const Mat3 A = Mat3::Random() + 2.0 * Mat3::Identity();
    b.invI = A * A.transpose();  // symmetric positive definite
    return b;
}

// K of k points at `points` with the shared normal n (contact_rows.cpp's prepareBlock).
Eigen::Matrix4d blockK(const SolverBody& A, const SolverBody& B, const std::vector<Vec3>& points, const Vec3& n) {
    Eigen::Matrix4d K = Eigen::Matrix4d::Zero();
    const int k = static_cast<int>(points.size());
    for (int i = 0; i < k; ++i)
        for (int j = 0; j < k; ++j) {
            const Vec3 rAi = points[i] - A.x, rAj = points[j] - A.x, rBi = points[i] - B.x, rBj = points[j] - B.x;
            K(i, j) = A.invMass + B.invMass + n.dot((A.invI * rAj.cross(n)).cross(rAi)) +
                      n.dot((B.invI * rBj.cross(n)).cross(rBi));
        }
    return K;
}

}  // namespace

class TestSolverRows : public QObject {
    Q_OBJECT
private slots:
    // Random manifolds of 1 to 4 points (a face, three corners, an edge, a point, points in
    // a line, coincident points, one body immovable, masses over eight orders): the fast
    // inverse is the Moore-Penrose pseudo-inverse, as the eigen-decomposition gives it.
    void leastNormInverseMatchesTheEigenDecomposition() {
        std::mt19937 rng(11);
        std::uniform_real_distribution<double> u(-1.0, 1.0);
        double worst = 0.0;
        int fourPoint = 0;
        for (int trial = 0; trial < 4000; ++trial) {
            SolverBody A = randomBody(rng, true), B = randomBody(rng, trial % 3 != 0);
            const double massScale = std::pow(10.0, 4.0 * u(rng));
            A.invMass *= massScale;
            A.invI *= massScale;
            const Vec3 n = Vec3(u(rng), u(rng), u(rng)).normalized();
            Vec3 t1, t2;
            tangentFrame(n, t1, t2);
            const int k = 1 + trial % 4;
            const Vec3 c(u(rng), u(rng), u(rng));
            std::vector<Vec3> points;
            for (int i = 0; i < k; ++i) {
                double x = u(rng), y = u(rng);
                if (trial % 7 == 1) y = 0.5 * x;            // in a line
                if (trial % 11 == 2 && i == 1) x = y = 0.0; // two coincide
                if (trial % 11 == 2 && i == 0) x = y = 0.0;
                points.push_back(c + x * t1 + y * t2);
            }
            const Eigen::Matrix4d K = blockK(A, B, points, n);
            const Eigen::Matrix4d fast = leastNormInverse(K, k), ref = leastNormInverseReference(K, k);
            const double err = (fast - ref).norm() / std::max(ref.norm(), 1e-300);
            worst = std::max(worst, err);
            fourPoint += k == 4;
            QVERIFY2(err < 1e-7, qPrintable(QString("trial %1 (k = %2): relative difference %3").arg(trial).arg(k).arg(err)));
            // Moore-Penrose: K K+ K = K and K+ K K+ = K+ on the k x k block.
            const Eigen::MatrixXd Kk = K.topLeftCorner(k, k), Pk = fast.topLeftCorner(k, k);
            QVERIFY((Kk * Pk * Kk - Kk).norm() <= 1e-8 * Kk.norm());
            QVERIFY(fast.bottomRows(4 - k).isZero(0.0) && fast.rightCols(4 - k).isZero(0.0));
        }
        QVERIFY(fourPoint == 1000);
        qInfo("largest relative difference from the eigen-decomposition: %.2g", worst);
    }

    // A box face on the ground, four symmetric corners: the weight is shared equally (the
    // least-norm answer), not put on three corners.
    void aSymmetricFaceSharesItsLoad() {
        SolverBody box;
        box.invMass = 1.0;
        box.invI = Mat3::Identity() * 6.0;
        SolverBody ground;
        ground.x = Vec3(0, -10, 0);
        const Vec3 n = Vec3::UnitY();
        std::vector<Vec3> corners = {{0.5, -0.5, 0.5}, {-0.5, -0.5, 0.5}, {-0.5, -0.5, -0.5}, {0.5, -0.5, -0.5}};
        const Eigen::Matrix4d K = blockK(box, ground, corners, n);
        const Eigen::Vector4d g = Eigen::Vector4d::Constant(1.0);  // each corner: 1 m/s up
        const Eigen::Vector4d lambda = pushingImpulses(K, leastNormInverse(K, 4), g, 4);
        for (int i = 0; i < 4; ++i) QVERIFY(std::abs(lambda[i] - 0.25) < 1e-12);
    }
};

QTEST_APPLESS_MAIN(TestSolverRows)
#include "tst_solver_rows.moc"
