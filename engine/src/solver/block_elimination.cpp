#include "solver/block_elimination.h"

#include <Eigen/LU>

#include <algorithm>
#include <numeric>

namespace tumble {

namespace {

// A pivot block's inverse: closed form up to 3 × 3 (a ball joint's), else a fixed-size LU of
// the block padded with the identity (Eigen's dynamic LU was most of the solve's time).
Block inverse(const Block& d) {
    const int n = static_cast<int>(d.rows());
    if (n == 1) return Block::Constant(1, 1, 1.0 / d(0, 0));
    if (n == 3) return Block(Eigen::Matrix3d(d).inverse());
    Eigen::Matrix<double, 6, 6> padded = Eigen::Matrix<double, 6, 6>::Identity();
    padded.topLeftCorner(n, n) = d;
    return Block(padded.partialPivLu().inverse().topLeftCorner(n, n));
}

}  // namespace

Elimination eliminationOf(int count, const std::vector<std::pair<int, int>>& pairs) {
    std::vector<std::vector<int>> next(count);  // each node's neighbours, ascending
    for (const auto& [k, l] : pairs)
        if (k != l) next[k].push_back(l);
    auto index = [&](int k, int l) {
        const auto it = std::lower_bound(pairs.begin(), pairs.end(), std::pair{k, l});
        return it != pairs.end() && *it == std::pair{k, l} ? static_cast<int>(it - pairs.begin()) : -1;
    };
    Elimination e;
    e.diagonal.resize(count);
    for (int v = 0; v < count; ++v)
        if ((e.diagonal[v] = index(v, v)) < 0) return {};
    std::vector<char> alive(count, 1), queued(count, 1);
    std::vector<int> work(count), around;
    std::iota(work.rbegin(), work.rend(), 0);  // (popped from the back: the lowest first)
    // A node whose living neighbours are all joined to each other is taken; taking it can
    // only make its neighbours such nodes, so they are looked at again. In a chordal graph
    // one always remains, and taking any keeps the rest chordal.
    while (!work.empty()) {
        const int v = work.back();
        work.pop_back();
        queued[v] = 0;
        if (!alive[v]) continue;
        around.clear();
        for (int u : next[v])
            if (alive[u]) around.push_back(u);
        const std::size_t updates = e.update.size();
        bool clique = true;
        for (std::size_t i = 0; i < around.size() && clique; ++i)
            for (std::size_t j = 0; j < around.size() && clique; ++j) {
                const int target = index(around[i], around[j]);
                clique = target >= 0;
                if (clique) e.update.push_back({target, index(around[i], v), index(v, around[j])});
            }
        if (!clique) {
            e.update.resize(updates);
            continue;
        }
        alive[v] = 0;
        e.order.push_back(v);
        e.begin.push_back(static_cast<int>(e.later.size()));
        e.updateBegin.push_back(static_cast<int>(updates));
        for (int u : around) {
            e.later.push_back(u);
            e.column.push_back(index(u, v));
            e.row.push_back(index(v, u));
            if (!queued[u]) {
                queued[u] = 1;
                work.push_back(u);
            }
        }
    }
    if (static_cast<int>(e.order.size()) != count) return {};
    e.begin.push_back(static_cast<int>(e.later.size()));
    e.updateBegin.push_back(static_cast<int>(e.update.size()));
    return e;
}

Eigen::VectorXd solveByElimination(const Elimination& plan, std::vector<Block>& blocks,
                                   const std::vector<int>& offsets, const std::vector<int>& sizes,
                                   Eigen::VectorXd b) {
    const int count = static_cast<int>(plan.order.size());
    std::vector<Block> pivotInverse(count);
    for (int step = 0; step < count; ++step) {
        const int v = plan.order[step];
        pivotInverse[v] = inverse(blocks[plan.diagonal[v]]);
        // K(k, v) D⁻¹, kept where K(k, v) was; then the rows after v lose v's column.
        for (int i = plan.begin[step]; i < plan.begin[step + 1]; ++i)
            blocks[plan.column[i]] = Block(blocks[plan.column[i]] * pivotInverse[v]);
        for (int u = plan.updateBegin[step]; u < plan.updateBegin[step + 1]; ++u) {
            const Elimination::Update& x = plan.update[u];
            blocks[x.target] -= blocks[x.left] * blocks[x.right];
        }
        for (int i = plan.begin[step]; i < plan.begin[step + 1]; ++i) {
            const int k = plan.later[i];
            b.segment(offsets[k], sizes[k]) -= blocks[plan.column[i]] * b.segment(offsets[v], sizes[v]);
        }
    }
    Eigen::VectorXd x(b.size());
    for (int step = count; step-- > 0;) {
        const int v = plan.order[step];
        Eigen::Matrix<double, Eigen::Dynamic, 1, 0, 6, 1> rhs = b.segment(offsets[v], sizes[v]);
        for (int i = plan.begin[step]; i < plan.begin[step + 1]; ++i) {
            const int l = plan.later[i];
            rhs -= blocks[plan.row[i]] * x.segment(offsets[l], sizes[l]);
        }
        x.segment(offsets[v], sizes[v]) = pivotInverse[v] * rhs;
    }
    return x;
}

}  // namespace tumble
