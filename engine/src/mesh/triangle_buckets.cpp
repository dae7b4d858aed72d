#include "mesh/triangle_buckets.h"

#include "common/closest_point.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace tumble::mesh {

namespace {

// Where the line {x, y, z} (x free) crosses triangle abc, or NaN. Half-open edge rules
// (a point on an edge counts for one of the two triangles sharing it) keep the parity
// right for a line through an edge.
double crossingX(double y, double z, const Vec3& a, const Vec3& b, const Vec3& c) {
    auto edge = [&](const Vec3& p, const Vec3& q) {  // twice the signed area of (p, q, point) in yz
        return (q.y() - p.y()) * (z - p.z()) - (q.z() - p.z()) * (y - p.y());
    };
    double w0 = edge(b, c), w1 = edge(c, a), w2 = edge(a, b);
    const double area = w0 + w1 + w2;
    if (area == 0.0) return std::numeric_limits<double>::quiet_NaN();  // edge-on
    if (area < 0) {
        w0 = -w0, w1 = -w1, w2 = -w2;
    }
    // Top-left style tie-break on the yz plane: a zero weight counts only on one side.
    auto owns = [&](double w, const Vec3& p, const Vec3& q) {
        if (w != 0.0) return w > 0.0;
        const double dy = q.y() - p.y(), dz = q.z() - p.z();
        return (area > 0) == (dz > 0 || (dz == 0 && dy < 0));
    };
    if (!owns(w0, b, c) || !owns(w1, c, a) || !owns(w2, a, b))
        return std::numeric_limits<double>::quiet_NaN();
    const double s = std::abs(area);
    return (w0 * a.x() + w1 * b.x() + w2 * c.x()) / s;
}

}  // namespace

Buckets::Buckets(const TriangleMesh& m) : m_(m) {
    for (const Vec3& v : m.vertices) box_.add(v);
    box_ = box_.inflated(1e-9 * (box_.extent().norm() + 1.0));
    n_ = std::clamp(static_cast<int>(std::cbrt(static_cast<double>(m.triangles.size()) / 2.0)), 1, 48);
    cell_ = box_.extent() / n_;
    yz_.assign(static_cast<std::size_t>(n_ * n_), {});
    xyz_.assign(static_cast<std::size_t>(n_ * n_ * n_), {});
    for (int t = 0; t < static_cast<int>(m.triangles.size()); ++t) {
        collision::Aabb b;
        for (int k : m.triangles[t]) b.add(m.vertices[k]);
        const auto lo = cellOf(b.min), hi = cellOf(b.max);
        for (int k = lo[2]; k <= hi[2]; ++k)
            for (int j = lo[1]; j <= hi[1]; ++j) {
                yz_[static_cast<std::size_t>(j + n_ * k)].push_back(t);
                for (int i = lo[0]; i <= hi[0]; ++i) xyz_[index(i, j, k)].push_back(t);
            }
    }
}

void Buckets::crossings(double y, double z, std::vector<double>& xs) const {
    xs.clear();
    const auto c = cellOf(Vec3(box_.min.x(), y, z));
    if (y < box_.min.y() || y > box_.max.y() || z < box_.min.z() || z > box_.max.z()) return;
    for (int t : yz_[static_cast<std::size_t>(c[1] + n_ * c[2])]) {
        const auto& tri = m_.triangles[t];
        const double x = crossingX(y, z, m_.vertices[tri[0]], m_.vertices[tri[1]], m_.vertices[tri[2]]);
        if (!std::isnan(x)) xs.push_back(x);
    }
    std::sort(xs.begin(), xs.end());
}

bool Buckets::inside(const Vec3& p) const {
    // The line a hair off p's own y and z: a point on a regular mesh's grid would send it
    // along edges and faces, where parity means nothing (p's answer moves by no more).
    const double off = 1e-9 * (box_.extent().norm() + 1.0);
    std::vector<double> xs;
    crossings(p.y() + 1.3 * off, p.z() + 2.9 * off, xs);
    return (std::upper_bound(xs.begin(), xs.end(), p.x()) - xs.begin()) % 2 == 1;
}

double Buckets::distance(const Vec3& p) const {
    const auto c = cellOf(p);
    // How far p lies outside the grid, so that shells start from where it is.
    const double off = (p - p.cwiseMax(box_.min).cwiseMin(box_.max)).norm();
    const double step = cell_.minCoeff();
    double best = std::numeric_limits<double>::infinity();
    for (int r = 0; r <= n_; ++r) {
        for (int k = c[2] - r; k <= c[2] + r; ++k)
            for (int j = c[1] - r; j <= c[1] + r; ++j)
                for (int i = c[0] - r; i <= c[0] + r; ++i) {
                    if (std::max({std::abs(i - c[0]), std::abs(j - c[1]), std::abs(k - c[2])}) != r) continue;
                    if (i < 0 || j < 0 || k < 0 || i >= n_ || j >= n_ || k >= n_) continue;
                    for (int t : xyz_[index(i, j, k)]) {
                        const auto& tri = m_.triangles[t];
                        const Vec3 q = closestPointOnTriangle(p, m_.vertices[tri[0]], m_.vertices[tri[1]],
                                                              m_.vertices[tri[2]]);
                        best = std::min(best, (q - p).norm());
                    }
                }
        if (best <= off + r * step) break;
    }
    return best;
}

std::array<int, 3> Buckets::cellOf(const Vec3& p) const {
    std::array<int, 3> c;
    for (int a = 0; a < 3; ++a)
        c[a] = std::clamp(static_cast<int>(std::floor((p[a] - box_.min[a]) / cell_[a])), 0, n_ - 1);
    return c;
}

}  // namespace tumble::mesh
