// Block elimination in a perfect elimination order (solver/block_elimination.h), the solve of
// a jointed group's Newton steps: against Eigen's dense LU of the same matrix, on the
// patterns groups have (a chain, a ragdoll's tree of bodies, a star, mixed block sizes), and
// the patterns it must refuse (a ring of four or more).
#include "solver/block_elimination.h"

#include "test_random.h"

#include <Eigen/LU>
#include <QtTest>

#include <algorithm>
#include <set>

using namespace tumble;

namespace {

// The pattern of joints over bodies: joints (a, b) (b = -1: the world) sharing a body are
// joined, as the projection's sharingPairs joins them; each pair with its mirror and (k, k).
std::vector<std::pair<int, int>> patternOf(const std::vector<std::pair<int, int>>& joints) {
    std::set<std::pair<int, int>> out;
    for (int k = 0; k < static_cast<int>(joints.size()); ++k)
        for (int l = 0; l < static_cast<int>(joints.size()); ++l) {
            const auto [a, b] = joints[k];
            const auto [c, d] = joints[l];
            if (k == l || a == c || a == d || (b >= 0 && (b == c || b == d))) out.insert({k, l});
        }
    return {out.begin(), out.end()};
}

}  // namespace

class TestBlockElimination : public QObject {
    Q_OBJECT
private slots:
    // A random matrix on the pattern, made diagonally dominant as K is (J M⁻¹ Jᵀ with the
    // arms now and at the start: nearly symmetric, its pivots well away from singular), and
    // not symmetric; the solve agrees with a dense LU to rounding.
    void matchesADenseSolve_data() {
        QTest::addColumn<QString>("shape");
        QTest::newRow("chain of 12") << "chain";
        QTest::newRow("ragdoll (5 balls, 4 hinges)") << "ragdoll";
        QTest::newRow("star of 6 on one body") << "star";
        QTest::newRow("single joint") << "single";
    }
    void matchesADenseSolve() {
        QFETCH(QString, shape);
        std::vector<std::pair<int, int>> joints;  // (body a, body b)
        std::vector<int> sizes;
        if (shape == "chain") {
            joints.push_back({0, -1});
            for (int i = 1; i < 12; ++i) joints.push_back({i, i - 1});
            sizes.assign(12, 3);
            sizes[4] = 5;  // a hinge among the balls
            sizes[7] = 6;  // a weld
        } else if (shape == "ragdoll") {
            // Torso 0; head 1; upper arms 2, 3; forearms 4, 5; thighs 6, 7; shins 8, 9.
            joints = {{1, 0}, {2, 0}, {3, 0}, {6, 0}, {7, 0}, {4, 2}, {5, 3}, {8, 6}, {9, 7}};
            sizes = {3, 3, 3, 3, 3, 6, 6, 6, 6};  // hinges with a limit row past
        } else if (shape == "star") {
            for (int i = 1; i <= 6; ++i) joints.push_back({i, 0});
            sizes = {1, 3, 5, 6, 3, 1};
        } else {
            joints = {{0, -1}};
            sizes = {5};
        }
        const int count = static_cast<int>(joints.size());
        const auto pairs = patternOf(joints);
        const Elimination plan = eliminationOf(count, pairs);
        QCOMPARE(static_cast<int>(plan.order.size()), count);
        std::vector<int> offsets;
        int size = 0;
        for (int n : sizes) offsets.push_back(std::exchange(size, size + n));
        test::Rng rng{17};
        std::vector<Block> blocks;
        Eigen::MatrixXd K = Eigen::MatrixXd::Zero(size, size);
        for (const auto& [k, l] : pairs) {
            Block b(sizes[k], sizes[l]);
            for (int i = 0; i < b.rows(); ++i)
                for (int j = 0; j < b.cols(); ++j) b(i, j) = rng.uniform(-1, 1);
            if (k == l) b.diagonal().array() += 8.0 * count;
            blocks.push_back(b);
            K.block(offsets[k], offsets[l], sizes[k], sizes[l]) = b;
        }
        Eigen::VectorXd rhs(size);
        for (int i = 0; i < size; ++i) rhs[i] = rng.uniform(-1, 1);
        const Eigen::VectorXd dense = K.partialPivLu().solve(rhs);
        const Eigen::VectorXd x = solveByElimination(plan, blocks, offsets, sizes, rhs);
        const double off = (x - dense).cwiseAbs().maxCoeff() / dense.cwiseAbs().maxCoeff();
        qInfo("%s: %d rows, %d blocks, relative difference %.1e", qPrintable(shape), size,
              static_cast<int>(pairs.size()), off);
        QVERIFY2(off < 1e-13, qPrintable(QString::number(off)));
        QVERIFY((K * x - rhs).cwiseAbs().maxCoeff() < 1e-12);
    }

    // Bodies joined in a ring of four (a four-bar linkage): its joints' pattern is a ring
    // of four with no chord, which no order eliminates without fill: refused, so the group
    // takes the dense LU. A ring of three (three joints at three bodies) is a clique: taken.
    void refusesARingOfFour() {
        const auto four = patternOf({{0, 1}, {1, 2}, {2, 3}, {3, 0}});
        QVERIFY(eliminationOf(4, four).empty());
        const auto three = patternOf({{0, 1}, {1, 2}, {2, 0}});
        QCOMPARE(static_cast<int>(eliminationOf(3, three).order.size()), 3);
    }

    // A singular pivot (a joint whose rows are dependent) gives a step that is not finite,
    // which the Newton steps refuse.
    void aSingularPivotIsNotFinite() {
        const auto pairs = patternOf({{0, -1}, {1, 0}});
        const Elimination plan = eliminationOf(2, pairs);
        std::vector<Block> blocks;
        for (const auto& [k, l] : pairs) blocks.push_back(k == l && k == 0 ? Block(Block::Zero(3, 3)) : Block(Block::Identity(3, 3)));
        const Eigen::VectorXd x = solveByElimination(plan, blocks, {0, 3}, {3, 3}, Eigen::VectorXd::Ones(6));
        QVERIFY(!x.allFinite());
    }
};

QTEST_APPLESS_MAIN(TestBlockElimination)
#include "tst_block_elimination.moc"
