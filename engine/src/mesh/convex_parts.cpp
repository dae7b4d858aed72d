#include <tumble/convex_parts.h>

#include "common/workers.h"
#include "mesh/convex_split.h"
#include "mesh/solid_frame.h"
#include "mesh/triangle_buckets.h"

#include <tumble/convex_hull.h>
#include <tumble/mass.h>

#include <Eigen/Eigenvalues>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <functional>
#include <limits>
#include <map>
#include <numbers>
#include <queue>
#include <stdexcept>
#include <thread>

namespace tumble::mesh {

double meshVolume(const TriangleMesh& m) {
    double v = 0.0;
    for (const auto& t : m.triangles)
        v += m.vertices[t[0]].dot(m.vertices[t[1]].cross(m.vertices[t[2]])) / 6.0;
    return v;
}

namespace {

// ---- Pieces -----------------------------------------------------------------------------

struct Plane {
    Vec3 n;  // the piece keeps n·x <= d
    double d;
};

// The polygon clipped to n·x <= d (Sutherland-Hodgman).
void clip(std::vector<Vec3>& poly, const Plane& p, std::vector<Vec3>& scratch) {
    scratch.clear();
    for (std::size_t i = 0; i < poly.size(); ++i) {
        const Vec3& a = poly[i];
        const Vec3& b = poly[(i + 1) % poly.size()];
        const double da = p.n.dot(a) - p.d, db = p.n.dot(b) - p.d;
        if (da <= 0) scratch.push_back(a);
        if ((da < 0 && db > 0) || (da > 0 && db < 0)) scratch.push_back(a + (da / (da - db)) * (b - a));
    }
    poly.swap(scratch);
}

struct Piece {
    std::vector<Plane> planes;
    std::vector<int> triangles;  // those that reach into the region
    std::vector<int> cells;      // the interior cells whose centres are in the region
    std::vector<Vec3> points;    // the surface clipped to the region, and the cells by its cuts
    collision::ConvexHull hull;
    double volume = 0.0;  // of the hull
    double pokeOut = 0.0;
    bool empty = false;  // no hull: nothing of the solid, or a flat sliver
};

bool inRegion(const std::vector<Plane>& planes, const Vec3& x) {
    for (const Plane& p : planes)
        if (p.n.dot(x) > p.d) return false;
    return true;
}

// Felzenszwalb and Huttenlocher's squared distance transform of one line (f: 0 at the
// sources, kFar elsewhere), in place: the lower envelope of the parabolas (q - v)^2 + f(v).
constexpr double kFar = 1e20;
void distanceLine(std::vector<double>& f, std::vector<double>& d, std::vector<int>& v,
                  std::vector<double>& z) {
    const int n = static_cast<int>(f.size());
    constexpr double kInf = std::numeric_limits<double>::infinity();
    int k = 0;
    v[0] = 0;
    z[0] = -kInf;
    z[1] = kInf;
    auto meet = [&](int q, int r) {
        return ((f[q] + double(q) * q) - (f[r] + double(r) * r)) / (2.0 * q - 2.0 * r);
    };
    for (int q = 1; q < n; ++q) {
        double s = meet(q, v[k]);
        while (s <= z[k]) {
            --k;
            s = meet(q, v[k]);
        }
        ++k;
        v[k] = q;
        z[k] = s;
        z[k + 1] = kInf;
    }
    k = 0;
    for (int q = 0; q < n; ++q) {
        while (z[k + 1] < q) ++k;
        d[q] = (q - v[k]) * double(q - v[k]) + f[v[k]];
    }
    for (int q = 0; q < n; ++q) f[q] = d[q];
}

// The principal axes of a cloud of points (unit columns; eigenvectors of its covariance).
Mat3 principalAxes(const std::vector<Vec3>& points) {
    Vec3 mean = Vec3::Zero();
    for (const Vec3& x : points) mean += x;
    mean /= static_cast<double>(points.size());
    Mat3 cov = Mat3::Zero();
    for (const Vec3& x : points) cov += (x - mean) * (x - mean).transpose();
    const Eigen::SelfAdjointEigenSolver<Mat3> eig(cov);
    Mat3 axes;
    for (int k = 0; k < 3; ++k) axes.col(k) = eig.eigenvectors().col(k).normalized();
    return axes;
}

// The least and largest of u·x over the points.
std::pair<double, double> spanAlong(const std::vector<Vec3>& points, const Vec3& u) {
    double lo = std::numeric_limits<double>::infinity(), hi = -lo;
    for (const Vec3& x : points) {
        lo = std::min(lo, u.dot(x));
        hi = std::max(hi, u.dot(x));
    }
    return {lo, hi};
}

// Candidate cuts are ranked on hulls of this many points at most, and this many of the best
// then scored exactly.
constexpr int kRankPoints = 200;
constexpr int kExactCandidates = 4;

class Decomposer {
public:
    Decomposer(const TriangleMesh& m, const ConvexPartsOptions& o, double tolerance)
        : m_(m), buckets_(m), tolerance_(tolerance) {
        const int threads = o.threads > 0 ? o.threads : static_cast<int>(std::thread::hardware_concurrency());
        if (threads > 1) pool_ = std::make_unique<Workers>(std::min(threads, 16));
        const Vec3 extent = buckets_.box().extent();
        scale_ = extent.norm();
        // Cells no larger than a third of the tolerance (the measure of how far a hull
        // reaches out is good to about a cell), within the resolution's bounds.
        const int resolution =
            std::clamp(static_cast<int>(std::ceil(3.0 * extent.maxCoeff() / tolerance)), o.resolution, 160);
        h_ = extent.maxCoeff() / resolution;
        origin_ = buckets_.box().min;
        for (int a = 0; a < 3; ++a) n_[a] = std::max(1, static_cast<int>(std::ceil(extent[a] / h_)));
        inside_.assign(cellCount(), 0);
        std::vector<double> xs;
        for (int k = 0; k < n_[2]; ++k)
            for (int j = 0; j < n_[1]; ++j) {
                const Vec3 c = centre(0, j, k);
                buckets_.crossings(c.y(), c.z(), xs);
                for (int i = 0; i < n_[0]; ++i) {
                    const double x = centre(i, j, k).x();
                    if ((std::upper_bound(xs.begin(), xs.end(), x) - xs.begin()) % 2 == 1)
                        inside_[index(i, j, k)] = 1;
                }
            }
        // Each outside cell's distance to the nearest interior cell's centre: how far a hull
        // holding that cell's centre reaches out of the solid (to about a cell).
        reach_.assign(cellCount(), 0.0);
        for (std::size_t c = 0; c < reach_.size(); ++c) reach_[c] = inside_[c] ? 0.0 : kFar;
        const int longest = std::max({n_[0], n_[1], n_[2]});
        std::vector<double> f(longest), d(longest), z(longest + 1);
        std::vector<int> v(longest);
        for (int axis = 0; axis < 3; ++axis) {
            const int a1 = (axis + 1) % 3, a2 = (axis + 2) % 3;
            f.resize(n_[axis]);
            d.resize(n_[axis]);
            for (int p = 0; p < n_[a1]; ++p)
                for (int q = 0; q < n_[a2]; ++q) {
                    std::array<int, 3> at;
                    at[a1] = p;
                    at[a2] = q;
                    for (at[axis] = 0; at[axis] < n_[axis]; ++at[axis])
                        f[at[axis]] = reach_[index(at[0], at[1], at[2])];
                    distanceLine(f, d, v, z);
                    for (at[axis] = 0; at[axis] < n_[axis]; ++at[axis])
                        reach_[index(at[0], at[1], at[2])] = f[at[axis]];
                }
        }
        for (double& r : reach_)
            r = r >= kFar / 2 ? 0.0 : std::sqrt(r) * h_;  // (no solid at all: nothing to reach from)
        findReflexPlanes();
    }

    // The planes of the two faces at each reflex (concave) edge bent by more than 15 degrees,
    // each once.
    void findReflexPlanes() {
        std::map<std::pair<int, int>, int> edgeFace;
        std::vector<Vec3> normal(m_.triangles.size());
        for (int t = 0; t < static_cast<int>(m_.triangles.size()); ++t) {
            const auto& tri = m_.triangles[t];
            const Vec3 n =
                (m_.vertices[tri[1]] - m_.vertices[tri[0]]).cross(m_.vertices[tri[2]] - m_.vertices[tri[0]]);
            normal[t] = n.norm() > 0 ? Vec3(n.normalized()) : Vec3::Zero();
            for (int e = 0; e < 3; ++e) edgeFace[{tri[e], tri[(e + 1) % 3]}] = t;
        }
        const double scale = buckets_.box().extent().norm();
        auto add = [&](int t) {
            const Plane c{normal[t], normal[t].dot(m_.vertices[m_.triangles[t][0]])};
            for (const Plane& o : reflexPlanes_)
                if (o.n.dot(c.n) > 1 - 1e-9 && std::abs(o.d - c.d) < 1e-9 * scale) return;
            reflexPlanes_.push_back(c);
        };
        for (const auto& [edge, t] : edgeFace) {
            if (edge.first > edge.second) continue;
            const auto other = edgeFace.find({edge.second, edge.first});
            if (other == edgeFace.end()) continue;
            const int u = other->second;
            if (normal[t].dot(normal[u]) > std::cos(15.0 * std::numbers::pi / 180.0)) continue;
            // Reflex: the other face's far corner lies outside this face's plane.
            int far = 0;
            for (int k : m_.triangles[u])
                if (k != edge.first && k != edge.second) far = k;
            if (normal[t].dot(m_.vertices[far] - m_.vertices[edge.first]) <= 0) continue;
            add(t);
            add(u);
        }
    }

    // `progress` (may be empty) hears the share of the pieces made of the most there may be.
    ConvexParts run(int maxParts, const ConvexPartsProgress& progress) {
        Piece whole;
        whole.triangles.resize(m_.triangles.size());
        for (int t = 0; t < static_cast<int>(whole.triangles.size()); ++t) whole.triangles[t] = t;
        for (int c = 0; c < static_cast<int>(inside_.size()); ++c)
            if (inside_[c]) whole.cells.push_back(c);
        finish(whole);
        std::vector<Piece> pieces;
        pieces.push_back(std::move(whole));
        // Split the piece that reaches out farthest while any is beyond the tolerance; then,
        // while the hulls hold 3 % more than the solid, the piece whose hull holds most
        // beyond its interior cells; up to twice the parts asked for, then the neighbours
        // whose joint hull adds least are merged back down to them (greedy cuts made early
        // are undone where they were not needed).
        const double solid = meshVolume(m_);
        const int most = std::min(2 * maxParts, 256);
        std::vector<std::uint8_t> uncuttable(1, 0);
        auto report = [&](double done) {
            if (progress && !progress(done)) throw ConvexPartsStopped();
        };
        while (static_cast<int>(pieces.size()) < most) {
            report(0.05 + 0.9 * static_cast<double>(pieces.size() - 1) / std::max(1, most - 1));
            int worst = -1;
            for (int i = 0; i < static_cast<int>(pieces.size()); ++i)
                if (!pieces[i].empty && !uncuttable[i] && pieces[i].pokeOut > tolerance_ &&
                    (worst < 0 || pieces[i].pokeOut > pieces[worst].pokeOut))
                    worst = i;
            if (worst < 0) {
                double total = 0.0, most = 0.0;
                for (int i = 0; i < static_cast<int>(pieces.size()); ++i) {
                    total += pieces[i].volume;
                    const double extra =
                        pieces[i].volume - static_cast<double>(pieces[i].cells.size()) * h_ * h_ * h_;
                    if (!pieces[i].empty && !uncuttable[i] && extra > most) {
                        most = extra;
                        worst = i;
                    }
                }
                if (total <= 1.03 * solid) break;
            }
            if (worst < 0) break;
            std::array<Piece, 2> halves;
            if (!split(pieces[worst], halves)) {
                uncuttable[worst] = 1;
                continue;
            }
            pieces[worst] = std::move(halves[0]);
            pieces.push_back(std::move(halves[1]));
            uncuttable.push_back(0);
        }
        std::erase_if(pieces, [](const Piece& p) { return p.empty; });
        report(0.95);
        merge(pieces, maxParts, [&] { report(0.95); });
        ConvexParts out;
        out.tolerance = tolerance_;
        out.meshVolume = solid;
        out.withinTolerance = true;
        for (Piece& p : pieces) {
            if (p.empty) continue;
            out.largestPokeOut = std::max(out.largestPokeOut, p.pokeOut);
            if (p.pokeOut > tolerance_) out.withinTolerance = false;
            out.partsVolume += p.volume;
            out.reachOut.push_back(p.pokeOut);
            out.parts.push_back(std::move(p.hull));
        }
        return out;
    }

private:
    std::size_t cellCount() const { return static_cast<std::size_t>(n_[0]) * n_[1] * n_[2]; }
    std::size_t index(int i, int j, int k) const {
        return static_cast<std::size_t>(i + n_[0] * (j + std::size_t(n_[1]) * k));
    }
    Vec3 centre(int i, int j, int k) const {
        // (a little off the cells' own lines, so that a line of a regular mesh does not run
        // along its edges)
        return origin_ + h_ * Vec3(i + 0.5, j + 0.5 + 1.3e-7, k + 0.5 + 2.9e-7);
    }
    Vec3 centre(std::size_t c) const {
        const int i = static_cast<int>(c % n_[0]);
        const int j = static_cast<int>((c / n_[0]) % n_[1]);
        const int k = static_cast<int>(c / (std::size_t(n_[0]) * n_[1]));
        return centre(i, j, k);
    }

    // The piece's surface points, hull, volume and how far the hull reaches out.
    void finish(Piece& p) {
        clipAndHull(p);
        if (!p.empty) p.pokeOut = pokeOut(p.hull);
    }

    // `cap` > 0: the hull of at most about that many of the points (the extremes along the
    // axes and the diagonals, and an even share of the rest): a volume a little short of the
    // whole's, to rank candidate cuts by, at a fraction of the cost.
    void clipAndHull(Piece& p, int cap = 0) const {
        std::vector<Vec3> poly, scratch;
        std::vector<int> kept;
        p.points.clear();
        const double eps = 1e-9 * scale_;
        for (int t : p.triangles) {
            const auto& tri = m_.triangles[t];
            // Wholly past the newest cut (a half's, most often): clipped to nothing, cheaply.
            if (!p.planes.empty() && std::all_of(tri.begin(), tri.end(), [&](int v) {
                    return p.planes.back().n.dot(m_.vertices[v]) - p.planes.back().d > eps;
                }))
                continue;
            poly = {m_.vertices[tri[0]], m_.vertices[tri[1]], m_.vertices[tri[2]]};
            const Vec3 facing = (poly[1] - poly[0]).cross(poly[2] - poly[0]);
            for (const Plane& pl : p.planes) {
                // A face in the cut belongs to the side its solid is on (behind its normal).
                if (std::all_of(poly.begin(), poly.end(),
                                [&](const Vec3& x) { return std::abs(pl.n.dot(x) - pl.d) <= eps; })) {
                    if (facing.dot(pl.n) <= 0) poly.clear();
                    if (poly.empty()) break;
                    continue;
                }
                clip(poly, pl, scratch);
                if (poly.empty()) break;
            }
            if (poly.empty()) continue;
            // What is left of a face that only touches the region (an edge or a corner on a
            // cut) is no part of the piece's solid.
            Vec3 area = Vec3::Zero();
            for (std::size_t i = 1; i + 1 < poly.size(); ++i)
                area += (poly[i] - poly[0]).cross(poly[i + 1] - poly[0]);
            if (area.norm() <= 1e-12 * scale_ * scale_ && !touchesSolid(p.planes, poly)) continue;
            kept.push_back(t);
            p.points.insert(p.points.end(), poly.begin(), poly.end());
        }
        p.triangles.swap(kept);
        // The region's corners inside the solid: with the clipped surface, every vertex of
        // the piece (a cut's face is the hull of its boundary, on the clipped triangles, and
        // of these).
        addCorners(p.planes, p.points);
        std::sort(p.points.begin(), p.points.end(), [](const Vec3& a, const Vec3& b) {
            return std::lexicographical_compare(a.data(), a.data() + 3, b.data(), b.data() + 3);
        });
        p.points.erase(std::unique(p.points.begin(), p.points.end()), p.points.end());
        if (cap > 0 && static_cast<int>(p.points.size()) > cap) thin(p.points, cap);
        try {
            p.hull = convexHull(p.points);
        } catch (const HullError&) {
            p.empty = true;  // no solid here, or a flat sliver of it
            return;
        }
        p.volume = hullVolume(p.hull);
    }

    // Keeps about `cap` of the points: the farthest along each axis and diagonal both ways,
    // and every k-th of the rest in their (sorted) order.
    static void thin(std::vector<Vec3>& points, int cap) {
        std::vector<std::uint8_t> keep(points.size(), 0);
        for (int dx = -1; dx <= 1; ++dx)
            for (int dy = -1; dy <= 1; ++dy)
                for (int dz = -1; dz <= 1; ++dz) {
                    if (!dx && !dy && !dz) continue;
                    const Vec3 u(dx, dy, dz);
                    std::size_t far = 0;
                    for (std::size_t i = 1; i < points.size(); ++i)
                        if (u.dot(points[i]) > u.dot(points[far])) far = i;
                    keep[far] = 1;
                }
        const std::size_t step = (points.size() + cap - 1) / static_cast<std::size_t>(cap);
        std::vector<Vec3> out;
        out.reserve(static_cast<std::size_t>(cap) + 26);
        for (std::size_t i = 0; i < points.size(); ++i)
            if (keep[i] || i % step == 0) out.push_back(points[i]);
        points.swap(out);
    }

    // Whether the solid lies next to these points on the region's side: their centre moved a
    // hair into the region, off every cut it lies on, is inside. (A face's remnant on a cut, or
    // a corner, that lies on the surface belongs to the piece when the solid is behind it,
    // as along a wall's edge the cut runs down; not when the solid there is across the cut.)
    bool touchesSolid(const std::vector<Plane>& planes, const std::vector<Vec3>& points) const {
        Vec3 c = Vec3::Zero();
        for (const Vec3& x : points) c += x;
        c /= static_cast<double>(points.size());
        const double eps = 1e-9 * scale_;
        Vec3 in = Vec3::Zero();
        for (const Plane& pl : planes)
            if (std::abs(pl.n.dot(c) - pl.d) <= eps) in -= pl.n;
        const Vec3 probe = c + 1e-6 * scale_ * (in.norm() > 0 ? Vec3(in.normalized()) : Vec3::Zero());
        return buckets_.box().contains(probe) && buckets_.inside(probe);
    }

    void addCorners(const std::vector<Plane>& planes, std::vector<Vec3>& out) const {
        const int n = static_cast<int>(planes.size());
        for (int i = 0; i < n; ++i)
            for (int j = i + 1; j < n; ++j)
                for (int k = j + 1; k < n; ++k) {
                    Mat3 A;
                    A.row(0) = planes[i].n.transpose();
                    A.row(1) = planes[j].n.transpose();
                    A.row(2) = planes[k].n.transpose();
                    if (std::abs(A.determinant()) < 1e-9) continue;
                    const Vec3 x = A.inverse() * Vec3(planes[i].d, planes[j].d, planes[k].d);
                    bool in = true;
                    for (const Plane& pl : planes)
                        in = in && pl.n.dot(x) <= pl.d + 1e-9 * (1.0 + std::abs(pl.d));
                    if (in && touchesSolid(planes, {x})) out.push_back(x);
                }
    }

    // The pieces on either side of `cut` (points, hull, volume; not yet the poke-out).
    bool halves(const Piece& p, const Plane& cut, std::array<Piece, 2>& out, int cap = 0) const {
        for (int s = 0; s < 2; ++s) {
            Piece& h = out[s];
            h = Piece{};
            h.planes = p.planes;
            h.planes.push_back(s == 0 ? cut : Plane{-cut.n, -cut.d});
            h.triangles = p.triangles;
            clipAndHull(h, cap);
            if (h.empty) return false;
        }
        return true;
    }

    // How far the hull reaches out of the solid: the largest reach of an outside cell whose
    // centre it holds. Line by line along x, the hull's span found from its faces.
    double pokeOut(const collision::ConvexHull& hull) const {
        collision::Aabb box;
        for (const Vec3& v : hull.vertices) box.add(v);
        const double eps = 1e-9 * (box.extent().norm() + 1.0);
        auto range = [&](int a, int& lo, int& hi) {
            lo = std::max(0, static_cast<int>(std::floor((box.min[a] - origin_[a]) / h_ - 0.5)));
            hi = std::min(n_[a] - 1, static_cast<int>(std::ceil((box.max[a] - origin_[a]) / h_ - 0.5)));
        };
        int j0, j1, k0, k1;
        range(1, j0, j1);
        range(2, k0, k1);
        double worst = 0.0;
        for (int k = k0; k <= k1; ++k)
            for (int j = j0; j <= j1; ++j) {
                const Vec3 c = centre(0, j, k);
                double lo = -1e300, hi = 1e300;
                for (const auto& f : hull.faces) {
                    // n·(x, y, z) < offset - eps along the line
                    const double rest = f.offset - eps - f.normal.y() * c.y() - f.normal.z() * c.z();
                    if (f.normal.x() > 1e-12)
                        hi = std::min(hi, rest / f.normal.x());
                    else if (f.normal.x() < -1e-12)
                        lo = std::max(lo, rest / f.normal.x());
                    else if (rest <= 0)
                        hi = lo - 1;  // the line misses the hull
                    if (hi < lo) break;
                }
                if (hi < lo) continue;
                const int i0 = std::max(0, static_cast<int>(std::ceil((lo - origin_.x()) / h_ - 0.5)));
                const int i1 =
                    std::min(n_[0] - 1, static_cast<int>(std::floor((hi - origin_.x()) / h_ - 0.5)));
                for (int i = i0; i <= i1; ++i) worst = std::max(worst, reach_[index(i, j, k)]);
            }
        return worst;
    }

    // Merges pairs of pieces whose boxes touch, the pair whose joint hull adds least volume
    // first, until there are `count` pieces.
    // `check` is called each round (a stop asked for is heard there too).
    void merge(std::vector<Piece>& pieces, int count, const std::function<void()>& check) {
        auto boxOf = [](const Piece& p) {
            collision::Aabb b;
            for (const Vec3& v : p.hull.vertices) b.add(v);
            return b;
        };
        auto joined = [&](const Piece& a, const Piece& b, Piece& out) {
            out = Piece{};
            out.points = a.points;
            out.points.insert(out.points.end(), b.points.begin(), b.points.end());
            try {
                out.hull = convexHull(out.points);
            } catch (const HullError&) {
                return false;
            }
            out.volume = hullVolume(out.hull);
            return true;
        };
        // What merging each pair would add (infinite for pairs apart), kept between rounds:
        // a merge changes only its own row and column. (The pairs scanned in the same order,
        // the first of the least kept, as when they were all tried again each round.)
        const double inf = std::numeric_limits<double>::infinity();
        auto costOf = [&](int i, int j) {
            if (!boxOf(pieces[i]).inflated(h_).overlaps(boxOf(pieces[j]).inflated(h_))) return inf;
            Piece trial;
            if (!joined(pieces[i], pieces[j], trial)) return inf;
            return trial.volume - pieces[i].volume - pieces[j].volume;
        };
        const int n = static_cast<int>(pieces.size());
        std::vector<std::vector<double>> cost(static_cast<std::size_t>(n), std::vector<double>(n, inf));
        forEachChunk(pool_.get(), n, 1, [&](int begin, int end) {
            for (int i = begin; i < end; ++i)
                for (int j = i + 1; j < n; ++j) cost[i][j] = costOf(i, j);
        });
        while (static_cast<int>(pieces.size()) > count) {
            check();
            const int m = static_cast<int>(pieces.size());
            int a = -1, b = -1;
            for (int i = 0; i < m; ++i)
                for (int j = i + 1; j < m; ++j)
                    if (std::isfinite(cost[i][j]) && (a < 0 || cost[i][j] < cost[a][b])) a = i, b = j;
            if (a < 0) break;  // nothing touches: the parts are as few as they can be
            Piece merged;
            joined(pieces[a], pieces[b], merged);
            merged.cells = pieces[a].cells;
            merged.cells.insert(merged.cells.end(), pieces[b].cells.begin(), pieces[b].cells.end());
            merged.pokeOut = pokeOut(merged.hull);
            pieces[a] = std::move(merged);
            pieces.erase(pieces.begin() + b);
            cost.erase(cost.begin() + b);
            for (auto& row : cost) row.erase(row.begin() + b);
            forEachChunk(pool_.get(), m - 1, 1, [&](int begin, int end) {
                for (int i = begin; i < end; ++i)
                    if (i < a)
                        cost[i][a] = costOf(i, a);
                    else if (i > a)
                        cost[a][i] = costOf(a, i);
            });
        }
    }

    // The least hull volume of `h` cut once across one of its principal axes at its middle
    // (its own hull volume when no such cut holds solid on both sides).
    double bestMiddleCut(const Piece& h) const {
        const Mat3 axes = principalAxes(h.points);
        double least = h.volume;
        std::array<Piece, 2> two;
        for (int k = 0; k < 3; ++k) {
            const Vec3 u = axes.col(k);
            const auto [lo, hi] = spanAlong(h.points, u);
            if (hi - lo < 2 * h_) continue;
            if (halves(h, {u, 0.5 * (lo + hi)}, two, kRankPoints))
                least = std::min(least, two[0].volume + two[1].volume);
        }
        return least;
    }

    // The best cut of p into two pieces that both hold solid (false if none): the one whose
    // halves' hulls hold the least volume (the piece's own is the same for every cut).
    // Candidates: the planes of the faces at the mesh's reflex edges that cross the piece
    // (the cuts a modelled part's concave corners ask for, in any pose), and across each of
    // the world's axes and the piece's principal axes (a ring's arc is cut across its chord)
    // at seven even steps.
    bool split(const Piece& p, std::array<Piece, 2>& out) {
        std::vector<Plane> candidates;
        auto crosses = [&](const Plane& c) {
            bool below = false, above = false;
            for (const Vec3& x : p.points) {
                const double off = c.n.dot(x) - c.d;
                below = below || off < -0.5 * h_;
                above = above || off > 0.5 * h_;
                if (below && above) return true;
            }
            return false;
        };
        for (const Plane& c : reflexPlanes_)
            if (crosses(c)) candidates.push_back(c);
        if (candidates.size() > 12) {
            std::vector<Plane> few;
            for (int k = 0; k < 12; ++k) few.push_back(candidates[candidates.size() * (2 * k + 1) / 24]);
            candidates.swap(few);
        }
        const std::size_t reflex = candidates.size();
        const Mat3 axes = principalAxes(p.points);
        std::vector<Vec3> directions = {Vec3::UnitX(), Vec3::UnitY(), Vec3::UnitZ()};
        for (int k = 0; k < 3; ++k) directions.push_back(axes.col(k));
        // and half way between each two principal axes (a tube's staves need more than two)
        for (int k = 0; k < 3; ++k)
            for (double sign : {1.0, -1.0})
                directions.push_back((axes.col(k) + sign * axes.col((k + 1) % 3)).normalized());
        for (const Vec3& u : directions) {
            const auto [lo, hi] = spanAlong(p.points, u);
            if (hi - lo < 2 * h_) continue;
            for (int k = 1; k <= 7; ++k) candidates.push_back({u, lo + (hi - lo) * k / 8.0});
        }
        // One cut ahead first; where no cut gains (a ring's or a tube's first cuts: each half's
        // hull is as large as its share of the whole), the reflex planes and the middle cuts
        // are looked at two ahead: each half cut once more, across its own principal axes
        // at their middle, the best of those counted.
        // Each candidate is first scored on its halves' hulls of a few hundred points each
        // (kRankPoints: a volume a little short, the same way for every cut); the best few
        // are then scored exactly and the cut is chosen among them. (Each candidate on its
        // own, spread over the pool's threads: each writes only its own slot, so the choice
        // is the same whatever the threads.)
        const int count = static_cast<int>(candidates.size());
        const double inf = std::numeric_limits<double>::infinity();
        std::vector<double> score(candidates.size(), inf);
        std::vector<std::array<Piece, 2>> trials(candidates.size());
        forEachChunk(pool_.get(), count, 1, [&](int begin, int end) {
            for (int i = begin; i < end; ++i)
                if (halves(p, candidates[i], trials[i], kRankPoints))
                    score[i] = trials[i][0].volume + trials[i][1].volume;
        });
        auto tieBroken = [&](std::size_t i, double v) {
            return i < reflex ? v * (1.0 - 1e-9)
                              : v;  // a reflex face's plane wins a tie: the part's own corner is there
        };
        std::vector<int> order;
        for (int i = 0; i < count; ++i)
            if (std::isfinite(score[i])) order.push_back(i);
        if (order.empty()) return false;
        std::stable_sort(order.begin(), order.end(),
                         [&](int a, int b) { return tieBroken(a, score[a]) < tieBroken(b, score[b]); });
        const int few = std::min<int>(kExactCandidates, static_cast<int>(order.size()));
        std::vector<std::array<Piece, 2>> exact(static_cast<std::size_t>(few));
        std::vector<double> exactScore(static_cast<std::size_t>(few), inf);
        forEachChunk(pool_.get(), few, 1, [&](int begin, int end) {
            for (int k = begin; k < end; ++k)
                if (halves(p, candidates[order[k]], exact[k]))
                    exactScore[k] = exact[k][0].volume + exact[k][1].volume;
        });
        int pick = -1;
        for (int k = 0; k < few; ++k)
            if (std::isfinite(exactScore[k]) &&
                (pick < 0 || tieBroken(order[k], exactScore[k]) < tieBroken(order[pick], exactScore[pick])))
                pick = k;
        if (pick < 0) return false;
        std::size_t chosen = static_cast<std::size_t>(order[pick]);
        // One ahead gains nothing (a ring's or a tube's first cuts: each half's hull is as
        // large as its share of the whole): the reflex planes and the middle cuts are scored
        // two ahead, each half cut once more across its own principal axes at their middle,
        // on the ranking's halves.
        const bool stalled = exactScore[pick] > (1.0 - 0.02) * p.volume;
        if (stalled) {
            auto middle = [&](std::size_t i) { return i >= reflex && (i - reflex) % 7 == 3; };
            std::vector<double> ahead(candidates.size(), inf);
            forEachChunk(pool_.get(), count, 1, [&](int begin, int end) {
                for (int i = begin; i < end; ++i) {
                    if (!std::isfinite(score[i])) continue;
                    if (static_cast<std::size_t>(i) < reflex || middle(i)) {
                        ahead[i] = 0.0;
                        for (const Piece& h : trials[i]) ahead[i] += bestMiddleCut(h);
                    } else {
                        ahead[i] = score[i];
                    }
                }
            });
            double bestScore = inf;
            for (std::size_t i = 0; i < candidates.size(); ++i)
                if (std::isfinite(ahead[i]) && tieBroken(i, ahead[i]) < bestScore) {
                    bestScore = tieBroken(i, ahead[i]);
                    chosen = i;
                }
        }
        const auto ranked = std::find(order.begin(), order.begin() + few, static_cast<int>(chosen));
        if (ranked != order.begin() + few && std::isfinite(exactScore[ranked - order.begin()])) {
            out = std::move(exact[ranked - order.begin()]);
        } else if (!halves(p, candidates[chosen], out)) {
            return false;
        }
        for (Piece& h : out) {
            for (int c : p.cells)
                if (inRegion({h.planes.back()}, centre(static_cast<std::size_t>(c)))) h.cells.push_back(c);
            h.pokeOut = pokeOut(h.hull);
        }
        return true;
    }

    const TriangleMesh& m_;
    Buckets buckets_;
    std::unique_ptr<Workers> pool_;  // the candidates' cuts tried side by side
    double tolerance_;
    double h_ = 0.0;
    Vec3 origin_;
    std::array<int, 3> n_{};
    std::vector<std::uint8_t> inside_;
    std::vector<Plane> reflexPlanes_;
    double scale_ = 1.0;         // the mesh's diagonal
    std::vector<double> reach_;  // per cell: 0 inside, else the distance to the nearest interior cell centre
};

}  // namespace

double hullVolume(const collision::ConvexHull& hull) {
    double v = 0.0;
    for (const auto& f : hull.faces) {
        const auto vs = hull.verticesOf(f);
        Vec3 area = Vec3::Zero();  // twice the polygon's vector area
        for (std::size_t i = 1; i + 1 < vs.size(); ++i)
            area += (hull.vertices[vs[i]] - hull.vertices[vs[0]])
                        .cross(hull.vertices[vs[i + 1]] - hull.vertices[vs[0]]);
        v += f.offset * f.normal.dot(area) / 6.0;
    }
    return v;
}

std::vector<double> distancesOutside(const TriangleMesh& mesh, const std::vector<Vec3>& points) {
    const Buckets b(mesh);
    std::vector<double> out;
    out.reserve(points.size());
    for (const Vec3& p : points) out.push_back(b.inside(p) ? 0.0 : b.distance(p));
    return out;
}

ConvexParts splitShell(const TriangleMesh& shell, const ConvexPartsOptions& options, double tolerance,
                       const ConvexPartsProgress& progress) {
    // Split in the solid's own frame (the grid of samples and the axes of the cuts are
    // square to it), and the parts carried back: the same parts in any pose.
    const collision::Pose frame = solidFrame(shell);
    TriangleMesh own = shell;
    for (Vec3& v : own.vertices) v = frame.toLocal(v);
    if (tolerance <= 0.0) {
        collision::Aabb box;
        for (const Vec3& v : own.vertices) box.add(v);
        tolerance = 0.01 * box.extent().norm();
    }
    Decomposer d(own, options, tolerance);
    ConvexParts out = d.run(options.maxParts, progress);
    for (collision::ConvexHull& hull : out.parts) carry(hull, frame);
    return out;
}

}  // namespace tumble::mesh
