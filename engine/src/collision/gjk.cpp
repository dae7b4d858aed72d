// GJK (Gilbert-Johnson-Keerthi) distance between convex cores, with the radii of round
// shapes applied afterwards, and the entry to EPA for overlapping cores.
//
// Precision: all simplex arithmetic is done relative to a reference point (B's centre), so
// a pair of millimetre shapes a kilometre from the world origin keeps its digits. The
// sub-algorithm is the Voronoi-region one (Ericson, Real-Time Collision Detection 5.1):
// closest point of a segment, triangle or tetrahedron to the origin, keeping only the
// vertices that support it. Termination is van den Bergen's: the gap between the upper
// bound |v| and the lower bound v̂·w falls below a relative tolerance; plus guards for a
// repeated support point and for no progress, which is where rounding ends the descent.
#include "collision/gjk.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

namespace tumble::collision {

namespace {

constexpr double kRelGap = 1e-10;       // relative gap |v| - v̂·w that ends the descent
constexpr double kOverlapScale = 1e-9;  // cores closer than this × their size overlap
constexpr int kMaxIterations = 128;

Vec3 coreSupportLocal(const ConvexProxy& p, const Vec3& d) {
    switch (p.core) {
        case ConvexProxy::Core::Point: return Vec3::Zero();
        case ConvexProxy::Core::Segment:
            return Vec3(0, d.y() >= 0 ? p.halfExtents.y() : -p.halfExtents.y(), 0);
        case ConvexProxy::Core::Box:
            return Vec3(d.x() >= 0 ? p.halfExtents.x() : -p.halfExtents.x(),
                        d.y() >= 0 ? p.halfExtents.y() : -p.halfExtents.y(),
                        d.z() >= 0 ? p.halfExtents.z() : -p.halfExtents.z());
        case ConvexProxy::Core::Cylinder: {
            const double rho = std::hypot(d.x(), d.z());
            const double h = d.y() >= 0 ? p.halfExtents.y() : -p.halfExtents.y();
            if (rho == 0.0) return Vec3(0, h, 0);
            const double k = p.halfExtents.x() / rho;
            return Vec3(k * d.x(), h, k * d.z());
        }
        case ConvexProxy::Core::Hull: {
            const auto& vs = p.hull->vertices;
            int best = 0;
            double bestDot = vs[0].dot(d);
            for (int i = 1; i < static_cast<int>(vs.size()); ++i) {
                const double t = vs[i].dot(d);
                if (t > bestDot) {
                    bestDot = t;
                    best = i;
                }
            }
            return vs[best];
        }
        case ConvexProxy::Core::Triangle: break;
    }
    return Vec3::Zero();
}

// Support point of the core along dir, minus `origin`; the pose translation is taken off
// first so that far-from-origin poses lose no precision in the relative result.
Vec3 supportFrom(const ConvexProxy& p, const Vec3& dir, const Vec3& origin) {
    if (p.core == ConvexProxy::Core::Triangle) {
        const auto& t = p.triangle;
        const double d0 = t[0].dot(dir), d1 = t[1].dot(dir), d2 = t[2].dot(dir);
        const int i = d0 >= d1 ? (d0 >= d2 ? 0 : 2) : (d1 >= d2 ? 1 : 2);
        return t[i] - origin;
    }
    if (p.turnedCount > 0) {
        int best = 0;
        double bestDot = p.turned[0].dot(dir);
        for (int i = 1; i < p.turnedCount; ++i) {
            const double t = p.turned[i].dot(dir);
            if (t > bestDot) {
                bestDot = t;
                best = i;
            }
        }
        return p.turned[best] + (p.pose.p - origin);
    }
    const Vec3 local = coreSupportLocal(p, p.pose.R.transpose() * dir);
    return p.pose.R * local + (p.pose.p - origin);
}

// Closest point of the current simplex to the origin; the simplex is reduced to the
// vertices that support it, and their weights are returned in `lambda`.
struct Closest {
    Vec3 v;
    double lambda[4];
};

Closest closestOnSegment(detail::SimplexVertex* s, int& n) {
    const Vec3 a = s[0].w, ab = s[1].w - s[0].w;
    const double len2 = ab.squaredNorm();
    const double t = len2 > 0 ? -a.dot(ab) / len2 : 0.0;
    if (t <= 0.0) {
        n = 1;
        return {a, {1, 0, 0, 0}};
    }
    if (t >= 1.0) {
        s[0] = s[1];
        n = 1;
        return {s[0].w, {1, 0, 0, 0}};
    }
    return {a + t * ab, {1 - t, t, 0, 0}};
}

Closest closestOnTriangle(detail::SimplexVertex* s, int& n) {
    const auto l = detail::closestOnTriangle(s[0].w, s[1].w, s[2].w);
    detail::SimplexVertex kept[3];
    Closest c{Vec3::Zero(), {0, 0, 0, 0}};
    int m = 0;
    for (int i = 0; i < 3; ++i) {
        if (l[i] > 0.0) {
            kept[m] = s[i];
            c.lambda[m] = l[i];
            c.v += l[i] * s[i].w;
            ++m;
        }
    }
    for (int i = 0; i < m; ++i) s[i] = kept[i];
    n = m;
    if (m == 3) {
        // Inside the triangle: v is the origin's projection on its plane. Weighting the
        // vertices loses digits on a thin triangle (three support points close together on
        // a curved rim); the normal from the two shorter edges keeps them.
        int pivot = 0;  // the vertex opposite the longest edge
        double longest = -1.0;
        for (int i = 0; i < 3; ++i) {
            const double e = (s[(i + 1) % 3].w - s[(i + 2) % 3].w).squaredNorm();
            if (e > longest) longest = e, pivot = i;
        }
        const Vec3& p = s[pivot].w;
        const Vec3 nrm = (s[(pivot + 1) % 3].w - p).cross(s[(pivot + 2) % 3].w - p);
        const double nn = nrm.squaredNorm();
        if (nn > 0) {
            c.v = nrm * (nrm.dot(p) / nn);
            // The weights of v itself, by signed areas, so the witness points agree with v.
            double sum = 0.0;
            double l[3];
            for (int i = 0; i < 3; ++i) {
                l[i] = std::max(0.0, nrm.dot((s[(i + 1) % 3].w - c.v).cross(s[(i + 2) % 3].w - c.v)));
                sum += l[i];
            }
            if (sum > 0)
                for (int i = 0; i < 3; ++i) c.lambda[i] = l[i] / sum;
        }
    }
    return c;
}

// The tetrahedron: the origin is inside unless it is strictly beyond one of the faces;
// then the closest point is the best of the faces it is beyond. A flat tetrahedron has
// every face "beyond" and the best face is still right (four triangles cover the flat hull).
Closest closestOnTetrahedron(detail::SimplexVertex* s, int& n, bool& inside) {
    static constexpr int kFaces[4][4] = {{0, 1, 2, 3}, {0, 2, 3, 1}, {0, 3, 1, 2}, {1, 3, 2, 0}};
    const double scale = (s[1].w - s[0].w).norm() * (s[2].w - s[0].w).norm() * (s[3].w - s[0].w).norm();
    inside = true;
    Closest best{Vec3::Zero(), {0, 0, 0, 0}};
    double bestD2 = std::numeric_limits<double>::infinity();
    detail::SimplexVertex bestS[3];
    int bestN = 0;
    for (const auto& f : kFaces) {
        const Vec3& a = s[f[0]].w;
        const Vec3 nrm = (s[f[1]].w - a).cross(s[f[2]].w - a);
        const double sideO = -a.dot(nrm);
        const double sideD = (s[f[3]].w - a).dot(nrm);
        const bool flat = std::abs(sideD) <= 1e-12 * scale;
        if (!flat && sideO * sideD >= 0.0) continue;  // origin on the inner side of this face
        inside = false;
        detail::SimplexVertex tri[3] = {s[f[0]], s[f[1]], s[f[2]]};
        int m = 3;
        const Closest c = closestOnTriangle(tri, m);
        const double d2 = c.v.squaredNorm();
        if (d2 < bestD2) {
            bestD2 = d2;
            best = c;
            bestN = m;
            std::copy(tri, tri + m, bestS);
        }
    }
    if (inside) return {Vec3::Zero(), {0, 0, 0, 0}};
    std::copy(bestS, bestS + bestN, s);
    n = bestN;
    return best;
}

struct GjkResult {
    bool overlap = false;
    bool apart = false;                       // proved farther apart than runGjk's `beyond`:
    double bound = 0.0;                       // by at least this, along v (the descent's direction then)
    Vec3 v = Vec3::Zero();                    // closest point of A - B to the origin (relative frame)
    Vec3 a = Vec3::Zero(), b = Vec3::Zero();  // closest points on the cores, relative
    detail::SimplexVertex simplex[4];
    int count = 0;
};

// `beyond`: the caller needs nothing of cores farther apart than this; the descent stops
// with `apart` set once a direction proves them so (for any direction v and the support
// point w of A - B along -v, every point x of A - B has v·x >= v·w: the cores are at least
// v·w / |v| apart along v̂). Of the triangles a rock is tried against (hull-rain), GJK
// finds two in five apart; this proves most of them so within an iteration or two.
GjkResult runGjk(const ConvexProxy& A, const ConvexProxy& B, const Vec3& origin, double scale,
                 double beyond = std::numeric_limits<double>::infinity()) {
    GjkResult r;
    const double overlap2 = (kOverlapScale * scale) * (kOverlapScale * scale);
    Vec3 v = A.center() - B.center();
    if (v.squaredNorm() == 0.0) v = Vec3(1, 0, 0);
    auto& s = r.simplex;
    int n = 0;
    double lambda[4] = {1, 0, 0, 0};
    double vv = std::numeric_limits<double>::infinity();
    bool haveV = false;
    for (int iter = 0; iter < kMaxIterations; ++iter) {
        const detail::SimplexVertex w = detail::supportVertex(A, B, -v, origin);
        const double vw = v.dot(w.w);
        if (vw > 0.0 && vw * vw > beyond * beyond * v.squaredNorm()) {
            r.apart = true;
            r.v = v;
            r.bound = vw / std::sqrt(v.squaredNorm());
            return r;
        }
        if (haveV) {
            // Gap between the upper bound |v| and the lower bound v̂·w, scaled by |v|.
            const double gap = vv - vw;
            if (gap <= kRelGap * vv + 1e-15 * scale * std::sqrt(vv)) break;
            bool repeated = false;
            for (int i = 0; i < n; ++i) repeated = repeated || (s[i].w == w.w);
            if (repeated) break;
        }
        detail::SimplexVertex saved[4];
        std::copy(s, s + n, saved);
        const int savedN = n;
        s[n++] = w;
        Closest c{w.w, {1, 0, 0, 0}};
        if (n == 2)
            c = closestOnSegment(s, n);
        else if (n == 3)
            c = closestOnTriangle(s, n);
        else if (n == 4) {
            bool inside = false;
            c = closestOnTetrahedron(s, n, inside);
            if (inside) {
                r.overlap = true;
                r.count = 4;
                return r;
            }
        }
        const double cc = c.v.squaredNorm();
        if (cc <= overlap2) {
            r.overlap = true;
            r.count = n;
            return r;
        }
        if (haveV && cc >= vv) {
            // No progress: rounding has taken over; keep the previous simplex.
            std::copy(saved, saved + savedN, s);
            n = savedN;
            break;
        }
        v = c.v;
        vv = cc;
        std::copy(c.lambda, c.lambda + 4, lambda);
        haveV = true;
    }
    r.count = n;
    r.v = v;
    for (int i = 0; i < n; ++i) {
        r.a += lambda[i] * s[i].a;
        r.b += lambda[i] * s[i].b;
    }
    return r;
}

double scaleOf(const ConvexProxy& a, const ConvexProxy& b) {
    return std::max(a.size() + b.size() + a.radius + b.radius, std::numeric_limits<double>::min());
}

}  // namespace

Vec3 ConvexProxy::support(const Vec3& dir) const {
    return supportFrom(*this, dir, Vec3::Zero());
}

Vec3 ConvexProxy::center() const {
    switch (core) {
        case Core::Hull: return pose.toWorld(hull->interiorPoint);
        case Core::Triangle: return (triangle[0] + triangle[1] + triangle[2]) / 3.0;
        default: return pose.p;
    }
}

void ConvexProxy::moveTo(const Pose& to) {
    pose = to;
    for (int i = 0; i < turnedCount; ++i) turned[i] = to.R * hull->vertices[i];
}

ConvexProxy proxyOf(const Shape& s, const Pose& pose) {
    ConvexProxy p;
    p.pose = pose;
    switch (s.kind) {
        case Kind::Sphere:
            p.core = ConvexProxy::Core::Point;
            p.radius = s.radius;
            break;
        case Kind::Capsule:
            p.core = ConvexProxy::Core::Segment;
            p.radius = s.radius;
            p.halfExtents = Vec3(0, s.halfHeight, 0);
            p.extent = s.halfHeight;
            break;
        case Kind::Box:
            p.core = ConvexProxy::Core::Box;
            p.halfExtents = s.halfExtents;
            p.extent = s.halfExtents.norm();
            break;
        case Kind::Cylinder:
            p.core = ConvexProxy::Core::Cylinder;
            p.halfExtents = Vec3(s.radius, s.halfHeight, 0);
            p.extent = std::hypot(s.radius, s.halfHeight);
            break;
        case Kind::Hull: {
            if (!s.hull || s.hull->vertices.empty())
                throw std::invalid_argument("proxyOf: hull shape without vertices");
            p.core = ConvexProxy::Core::Hull;
            p.hull = s.hull.get();
            double r2 = 0.0;
            for (const Vec3& v : s.hull->vertices)
                r2 = std::max(r2, (v - s.hull->interiorPoint).squaredNorm());
            p.extent = std::sqrt(r2);
            const int n = static_cast<int>(s.hull->vertices.size());
            if (n <= ConvexProxy::kTurned) {
                for (int i = 0; i < n; ++i) p.turned[i] = pose.R * s.hull->vertices[i];
                p.turnedCount = n;
            }
            break;
        }
        case Kind::Plane:
        case Kind::Mesh:
        case Kind::Compound:
            throw std::invalid_argument(std::string("proxyOf: not a convex shape: ") + toString(s.kind));
    }
    return p;
}

ConvexProxy triangleProxy(const Vec3& a, const Vec3& b, const Vec3& c) {
    ConvexProxy p;
    p.core = ConvexProxy::Core::Triangle;
    p.triangle = {a, b, c};
    const Vec3 m = (a + b + c) / 3.0;
    p.extent = std::sqrt(std::max({(a - m).squaredNorm(), (b - m).squaredNorm(), (c - m).squaredNorm()}));
    return p;
}

namespace detail {

SimplexVertex supportVertex(const ConvexProxy& a, const ConvexProxy& b, const Vec3& dir, const Vec3& origin) {
    SimplexVertex s;
    s.a = supportFrom(a, dir, origin);
    s.b = supportFrom(b, -dir, origin);
    s.w = s.a - s.b;
    return s;
}

std::array<double, 3> closestOnTriangle(const Vec3& a, const Vec3& b, const Vec3& c) {
    // Ericson 5.1.5 with p = origin, by Voronoi regions; a degenerate triangle falls back
    // to the best of its edges.
    const Vec3 ab = b - a, ac = c - a;
    const double d1 = -ab.dot(a), d2 = -ac.dot(a);
    if (d1 <= 0 && d2 <= 0) return {1, 0, 0};
    const double d3 = -ab.dot(b), d4 = -ac.dot(b);
    if (d3 >= 0 && d4 <= d3) return {0, 1, 0};
    const double vc = d1 * d4 - d3 * d2;
    if (vc <= 0 && d1 >= 0 && d3 <= 0) {
        const double t = d1 / (d1 - d3);
        return {1 - t, t, 0};
    }
    const double d5 = -ab.dot(c), d6 = -ac.dot(c);
    if (d6 >= 0 && d5 <= d6) return {0, 0, 1};
    const double vb = d5 * d2 - d1 * d6;
    if (vb <= 0 && d2 >= 0 && d6 <= 0) {
        const double t = d2 / (d2 - d6);
        return {1 - t, 0, t};
    }
    const double va = d3 * d6 - d5 * d4;
    if (va <= 0 && (d4 - d3) >= 0 && (d5 - d6) >= 0) {
        const double t = (d4 - d3) / ((d4 - d3) + (d5 - d6));
        return {0, 1 - t, t};
    }
    const double sum = va + vb + vc;
    if (!(sum > 1e-24 * ab.squaredNorm() * ac.squaredNorm()) || !std::isfinite(1.0 / sum)) {
        // Degenerate (nearly collinear): closest of the three edges.
        std::array<double, 3> best{1, 0, 0};
        double bestD2 = a.squaredNorm();
        const Vec3 p[3] = {a, b, c};
        for (int i = 0; i < 3; ++i) {
            const Vec3& p0 = p[i];
            const Vec3 e = p[(i + 1) % 3] - p0;
            const double len2 = e.squaredNorm();
            const double t = len2 > 0 ? std::clamp(-p0.dot(e) / len2, 0.0, 1.0) : 0.0;
            const double d2 = (p0 + t * e).squaredNorm();
            if (d2 < bestD2) {
                bestD2 = d2;
                best = {0, 0, 0};
                best[i] = 1 - t;
                best[(i + 1) % 3] = t;
            }
        }
        return best;
    }
    const double v = vb / sum, w = vc / sum;
    return {1 - v - w, v, w};
}

}  // namespace detail

Distance gjkCoreDistance(const ConvexProxy& a, const ConvexProxy& b) {
    const Vec3 origin = b.center();
    const GjkResult g = runGjk(a, b, origin, scaleOf(a, b));
    Distance d;
    d.overlap = g.overlap;
    if (g.overlap) {
        d.pointA = d.pointB = origin;
        return d;
    }
    d.distance = g.v.norm();
    d.normal = g.v / d.distance;
    d.pointA = g.a + origin;
    d.pointB = g.b + origin;
    return d;
}

namespace {

// Both queries from one GJK run; radii applied along the core normal.
Penetration penetrationFrom(const GjkResult& g, const ConvexProxy& a, const ConvexProxy& b,
                            const Vec3& origin, double scale) {
    Penetration p;
    if (!g.overlap) {
        const double dist = g.v.norm();
        p.normal = g.v / dist;
        p.depth = a.radius + b.radius - dist;
        p.pointA = g.a - a.radius * p.normal + origin;
        p.pointB = g.b + b.radius * p.normal + origin;
    } else {
        p = detail::epa(a, b, g.simplex, g.count, origin, scale);
        p.depth += a.radius + b.radius;
        p.pointA = p.pointA - a.radius * p.normal + origin;
        p.pointB = p.pointB + b.radius * p.normal + origin;
    }
    return p;
}

}  // namespace

Penetration penetration(const ConvexProxy& a, const ConvexProxy& b, double margin) {
    const Vec3 origin = b.center();
    const double scale = scaleOf(a, b);
    // Cores farther apart than the margin and both radii are no hit, whatever their exact
    // distance (the bound kept a billionth wide of the test below, so that rounding cannot
    // turn a hit into a miss).
    const double reach = std::max(margin, 0.0) + a.radius + b.radius;
    const GjkResult g = runGjk(a, b, origin, scale, reach * (1.0 + 1e-9) + 1e-12 * scale);
    if (g.apart) {  // a miss, along a direction that separates (for the caller's memory)
        Penetration p;
        p.normal = g.v.normalized();
        p.depth = a.radius + b.radius - g.bound;
        return p;
    }
    Penetration p = penetrationFrom(g, a, b, origin, scale);
    p.hit = p.depth > -margin;
    return p;
}

Distance gjkDistance(const ConvexProxy& a, const ConvexProxy& b) {
    const Vec3 origin = b.center();
    const double scale = scaleOf(a, b);
    const GjkResult g = runGjk(a, b, origin, scale);
    const Penetration p = penetrationFrom(g, a, b, origin, scale);
    Distance d;
    d.distance = -p.depth;
    d.normal = p.normal;
    d.pointA = p.pointA;
    d.pointB = p.pointB;
    d.overlap = d.distance <= 0.0;
    return d;
}

}  // namespace tumble::collision
