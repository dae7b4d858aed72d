// Face clipping for multi-point manifolds. One penetration query (GJK/EPA) gives the normal;
// the reference face is the face, of either shape, best aligned with it (within ~10
// degrees; B wins near-ties so the choice does not flicker), the incident feature is the
// other shape's feature facing it. The incident feature is clipped against the reference
// face's side planes and its points kept where they are within the margin of the reference
// plane. A cylinder's cap is a 16-gon whose first vertex is the rim point that faces the
// other shape, so the deepest rim point is always a vertex. Feature ids mix the two
// features and the clip planes that made each point, so they stay put while the same
// features touch.
#include "collision/clip.h"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace tumble::collision::detail {

namespace {

constexpr double kFaceAlign = 1.0 - 1e-6;  // cos(~0.08 deg): the normal is this face's (else an edge contact)
constexpr double kSegmentAlign = 0.985;  // cos(~10 deg): two round segments lie side by side
constexpr double kRefHysteresis =
    1e-4;  // A's face must be this much better aligned (cosine, ~0.8 deg) to be the reference
constexpr int kCapSides = 16;
constexpr int kMaxClip = 2 * Feature::kMax + 2;

void setPolygon(Feature& f, const Vec3& normal, std::uint32_t id) {
    f.normal = normal;
    f.face = true;
    f.id = id;
    // Wind counter-clockwise about the normal (first vertex kept).
    if (f.count >= 3 && (f.v[1] - f.v[0]).cross(f.v[2] - f.v[1]).dot(normal) < 0)
        std::reverse(f.v.begin() + 1, f.v.begin() + f.count);
}

// Makes `f` the single point of `p` farthest along `dir`. (It fills the caller's Feature:
// returning a second Feature from supportingFeature would cost its named return value
// optimisation, a copy of 3 KB of vertices a call, 3 % of hull-rain's step.)
void pointFeature(Feature& f, const ConvexProxy& p, const Vec3& dir) {
    f.count = 1;
    f.v[0] = p.support(dir) + p.radius * dir;
    f.face = false;
    f.id = 0xfff;
}

}  // namespace

Feature supportingFeature(const ConvexProxy& p, const Vec3& dir) {
    Feature f;
    const Pose& pose = p.pose;
    const Vec3 d = pose.R.transpose() * dir;
    const Vec3& h = p.halfExtents;
    switch (p.core) {
        case ConvexProxy::Core::Point:
            pointFeature(f, p, dir);
            return f;
        case ConvexProxy::Core::Segment: {
            const Vec3 axis = pose.R.col(1);
            f.count = 2;
            f.v[0] = pose.p + h.y() * axis + p.radius * dir;
            f.v[1] = pose.p - h.y() * axis + p.radius * dir;
            f.id = 0x100;
            return f;
        }
        case ConvexProxy::Core::Box: {
            int k = 0;
            d.cwiseAbs().maxCoeff(&k);
            const double s = d[k] >= 0 ? 1.0 : -1.0;
            const int u = (k + 1) % 3, w = (k + 2) % 3;
            const double corners[4][2] = {{1, 1}, {-1, 1}, {-1, -1}, {1, -1}};
            f.count = 4;
            for (int i = 0; i < 4; ++i) {
                Vec3 c = Vec3::Zero();
                c[k] = s * h[k];
                c[u] = corners[i][0] * h[u];
                c[w] = corners[i][1] * h[w];
                f.v[i] = pose.toWorld(c);
            }
            Vec3 n = Vec3::Zero();
            n[k] = s;
            setPolygon(f, pose.R * n, static_cast<std::uint32_t>(2 * k + (s < 0)));
            return f;
        }
        case ConvexProxy::Core::Cylinder: {
            const double r = h.x(), hh = h.y();
            const double radial = std::hypot(d.x(), d.z());
            const double dn = d.norm();
            if (std::abs(d.y()) >= std::numbers::sqrt2 / 2 * dn) {
                const double s = d.y() >= 0 ? 1.0 : -1.0;
                // Facing almost straight: a fixed polygon, so the points and their ids hold still.
                const double start = radial > 0.01 * dn ? std::atan2(d.z(), d.x()) : 0.0;
                f.count = kCapSides;
                for (int i = 0; i < kCapSides; ++i) {
                    const double t = start + 2.0 * std::numbers::pi * i / kCapSides;
                    f.v[i] = pose.toWorld(Vec3(r * std::cos(t), s * hh, r * std::sin(t)));
                }
                setPolygon(f, pose.R.col(1) * s, s > 0 ? 1u : 2u);
                return f;
            }
            const Vec3 rho = Vec3(d.x(), 0, d.z()) / radial;
            f.count = 2;
            f.v[0] = pose.toWorld(r * rho + Vec3(0, hh, 0));
            f.v[1] = pose.toWorld(r * rho - Vec3(0, hh, 0));
            f.id = 3;
            return f;
        }
        case ConvexProxy::Core::Hull: {
            const auto& faces = p.hull->faces;
            int best = -1;
            double bestDot = -2.0;
            for (int i = 0; i < static_cast<int>(faces.size()); ++i) {
                const double t = faces[i].normal.dot(d);
                if (t > bestDot) bestDot = t, best = i;
            }
            if (best < 0 || faces[best].count > Feature::kMax) {
                pointFeature(f, p, dir);
                return f;
            }
            const auto& face = faces[best];
            const std::span<const int> v = p.hull->verticesOf(face);
            f.count = face.count;
            for (int i = 0; i < f.count; ++i) f.v[i] = pose.toWorld(p.hull->vertices[v[i]]);
            f.normal = pose.R * face.normal;
            f.face = true;
            f.id = static_cast<std::uint32_t>(best);
            return f;
        }
        case ConvexProxy::Core::Triangle: {
            const auto& t = p.triangle;
            const Vec3 n = (t[1] - t[0]).cross(t[2] - t[0]);
            if (n.squaredNorm() == 0.0) {
                pointFeature(f, p, dir);
                return f;
            }
            const bool front = n.dot(dir) >= 0;
            f.count = 3;
            f.v[0] = t[0];
            f.v[1] = front ? t[1] : t[2];
            f.v[2] = front ? t[2] : t[1];
            f.normal = (front ? n : Vec3(-n)).normalized();
            f.face = true;
            f.id = front ? 0 : 1;
            return f;
        }
    }
    pointFeature(f, p, dir);
    return f;
}

namespace {

struct Poly {
    int n = 0;
    std::array<Vec3, kMaxClip> v;
    std::array<std::uint32_t, kMaxClip> tag;
};

// Keeps the part of `in` where (x - p0)·inward >= 0.
void clipPolygon(const Poly& in, const Vec3& p0, const Vec3& inward, std::uint32_t planeTag, Poly& out) {
    out.n = 0;
    for (int i = 0; i < in.n; ++i) {
        const int j = (i + 1) % in.n;
        const double di = (in.v[i] - p0).dot(inward), dj = (in.v[j] - p0).dot(inward);
        if (di >= 0 && out.n < kMaxClip) {
            out.v[out.n] = in.v[i];
            out.tag[out.n++] = in.tag[i];
        }
        if ((di >= 0) != (dj >= 0) && out.n < kMaxClip) {
            const double t = di / (di - dj);
            out.v[out.n] = in.v[i] + t * (in.v[j] - in.v[i]);
            out.tag[out.n++] = mixId(mixId(in.tag[i], in.tag[j]), planeTag);
        }
    }
}

// A segment is a polygon of two points that is not closed: clip its ends.
void clipSegment(Poly& seg, const Vec3& p0, const Vec3& inward, std::uint32_t planeTag) {
    if (seg.n < 2) return;
    const double d0 = (seg.v[0] - p0).dot(inward), d1 = (seg.v[1] - p0).dot(inward);
    if (d0 < 0 && d1 < 0) {
        seg.n = 0;
        return;
    }
    if (d0 < 0 || d1 < 0) {
        const int out = d0 < 0 ? 0 : 1;
        const double t = d0 / (d0 - d1);
        seg.v[out] = seg.v[0] + t * (seg.v[1] - seg.v[0]);
        seg.tag[out] = mixId(seg.tag[out], planeTag);
    }
}

// Clips `inc` by the side planes of `ref` (a polygon, or a segment whose side planes are
// its two end planes) and keeps the points within the margin of the reference plane,
// measured along `refNormal`.
void clipAgainst(const Feature& ref, const Vec3& refNormal, const Feature& inc, double margin,
                 std::uint32_t baseId, std::vector<Candidate>& out) {
    Poly a, b;
    a.n = inc.count;
    for (int i = 0; i < inc.count; ++i) a.v[i] = inc.v[i], a.tag[i] = static_cast<std::uint32_t>(i);
    Poly* cur = &a;
    Poly* next = &b;
    if (ref.count == 2) {
        const Vec3 u = ref.v[1] - ref.v[0];
        for (int e = 0; e < 2; ++e) {
            const Vec3 p0 = ref.v[e];
            const Vec3 inward = e == 0 ? u : Vec3(-u);
            if (cur->n == 2)
                clipSegment(*cur, p0, inward, 0x200u + e);
            else {
                clipPolygon(*cur, p0, inward, 0x200u + e, *next);
                std::swap(cur, next);
            }
        }
    } else {
        for (int e = 0; e < ref.count && cur->n > 0; ++e) {
            const Vec3& p0 = ref.v[e];
            const Vec3 inward = ref.normal.cross(ref.v[(e + 1) % ref.count] - p0);
            if (cur->n == 2)
                clipSegment(*cur, p0, inward, 0x200u + e);
            else {
                clipPolygon(*cur, p0, inward, 0x200u + e, *next);
                std::swap(cur, next);
            }
        }
    }
    for (int i = 0; i < cur->n; ++i) {
        const Vec3& q = cur->v[i];
        const double depth = (ref.v[0] - q).dot(refNormal);
        if (depth > -margin) out.push_back({q + 0.5 * depth * refNormal, depth, mixId(baseId, cur->tag[i])});
    }
}

}  // namespace

namespace {

// The core segment of a capsule or the axis of a cylinder, and the radius around it.
void coreSegment(const ConvexProxy& p, Vec3& c0, Vec3& c1, double& r) {
    const Vec3 axis = p.pose.R.col(1) * p.halfExtents.y();
    c0 = p.pose.p + axis;
    c1 = p.pose.p - axis;
    r = p.core == ConvexProxy::Core::Cylinder ? p.halfExtents.x() : p.radius;
}

// Two round segments (capsules, cylinder sides) side by side: A's core clipped to the end
// planes of B's, each end's depth from the true distance between the cores.
void segmentPair(const ConvexProxy& a, const ConvexProxy& b, const Vec3& n, double margin,
                 std::uint32_t baseId, std::vector<Candidate>& out) {
    Vec3 a0, a1, b0, b1;
    double ra, rb;
    coreSegment(a, a0, a1, ra);
    coreSegment(b, b0, b1, rb);
    Poly seg;
    seg.n = 2;
    seg.v[0] = a0, seg.v[1] = a1;
    seg.tag[0] = 0, seg.tag[1] = 1;
    const Vec3 u = b1 - b0;
    clipSegment(seg, b0, u, 0x200u);
    clipSegment(seg, b1, -u, 0x201u);
    const double len2 = u.squaredNorm();
    for (int i = 0; i < seg.n; ++i) {
        const Vec3& c = seg.v[i];
        const double t = len2 > 0 ? std::clamp((c - b0).dot(u) / len2, 0.0, 1.0) : 0.0;
        const double depth = ra + rb - (c - (b0 + t * u)).norm();
        if (depth > -margin) out.push_back({c - ra * n + 0.5 * depth * n, depth, mixId(baseId, seg.tag[i])});
    }
}

// The clipped points can miss the deepest place: skewed segments are deepest between their
// ends, a cap's 16-gon cuts off the rim, two nearly coplanar hull faces meet at an edge
// within the face tolerance. Then the penetration's own point is kept as well.
void keepDeepest(const Penetration& pen, std::uint32_t id, const ConvexProxy& a, const ConvexProxy& b,
                 std::vector<Candidate>& out) {
    double deepest = out[0].depth;
    for (const Candidate& c : out) deepest = std::max(deepest, c.depth);
    if (pen.depth > deepest + 1e-7 * (a.size() + b.size() + a.radius + b.radius))
        out.push_back({0.5 * (pen.pointA + pen.pointB), pen.depth, id});
}

}  // namespace

void contactPoints(const ConvexProxy& a, const ConvexProxy& b, const Penetration& pen, double margin,
                   Vec3& normal, std::vector<Candidate>& out) {
    out.clear();
    const Vec3& n = pen.normal;
    const Feature fA = supportingFeature(a, -n);
    const Feature fB = supportingFeature(b, n);
    const double alignA = fA.face && fB.count >= 2 ? fA.normal.dot(-n) : -2.0;
    const double alignB = fB.face && fA.count >= 2 ? fB.normal.dot(n) : -2.0;
    const std::uint32_t single = mixId(mixId(0x54u, fA.id), fB.id);
    if (std::max(alignA, alignB) >= kFaceAlign) {
        const bool refOnB = alignB >= alignA - kRefHysteresis;
        const Feature& ref = refOnB ? fB : fA;
        // The incident feature is the one facing the reference face itself, not the
        // normal: a round incident shape then gives its deepest points along that face.
        const Feature inc = supportingFeature(refOnB ? a : b, -ref.normal);
        if (inc.count >= 2) {
            const std::uint32_t base = mixId(mixId(refOnB ? 0x51u : 0x52u, ref.id), inc.id);
            clipAgainst(ref, ref.normal, inc, margin, base, out);
            if (!out.empty()) {
                keepDeepest(pen, single, a, b, out);
                normal = refOnB ? ref.normal : Vec3(-ref.normal);
                return;
            }
        }
    } else if (fA.count == 2 && fB.count == 2) {
        const Vec3 uA = (fA.v[1] - fA.v[0]).normalized(), uB = (fB.v[1] - fB.v[0]).normalized();
        if (std::abs(uA.dot(uB)) >= kSegmentAlign && std::abs(uB.dot(n)) <= 0.17) {
            segmentPair(a, b, n, margin, mixId(mixId(0x53u, fB.id), fA.id), out);
            if (!out.empty()) {
                keepDeepest(pen, single, a, b, out);
                normal = n;
                return;
            }
        }
    }
    normal = n;
    out.push_back({0.5 * (pen.pointA + pen.pointB), pen.depth, single});
}

void appendReduced(const std::vector<Candidate>& all, const Vec3& normal, ManifoldList& out) {
    // Coincident points (a degenerate face, two clips meeting at a corner) count once.
    thread_local std::vector<Candidate> c;  // kept between calls, per thread
    c.clear();
    c.reserve(all.size());
    for (const Candidate& p : all) {
        bool dup = false;
        for (const Candidate& q : c)
            dup = dup || (p.position - q.position).norm() <= 1e-12 * (1.0 + p.position.norm());
        if (!dup) c.push_back(p);
    }
    const int n = static_cast<int>(c.size());
    if (n == 0) return;
    Manifold m;
    m.normal = normal;
    if (n <= Manifold::kMaxPoints) {
        for (const Candidate& p : c) m.add(p.position, p.depth, p.feature);
        out.push_back(m);
        return;
    }
    // The deepest point; among points equally deep (to rounding) the one farthest from the
    // centroid, which is a corner of their hull, not a point where two clips met inside it.
    Vec3 centroid = Vec3::Zero();
    double deepest = c[0].depth;
    for (const Candidate& p : c) centroid += p.position, deepest = std::max(deepest, p.depth);
    centroid /= n;
    double spread = 0.0;
    for (const Candidate& p : c) spread = std::max(spread, (p.position - centroid).norm());
    int i0 = -1;
    double bestFar = -1.0;
    for (int i = 0; i < n; ++i) {
        if (c[i].depth < deepest - 1e-9 * spread) continue;
        const double d2 = (c[i].position - centroid).squaredNorm();
        if (d2 > bestFar) bestFar = d2, i0 = i;
    }
    const Vec3& p0 = c[i0].position;
    int i1 = i0;
    double far2 = 0.0;
    for (int i = 0; i < n; ++i) {
        const double d2 = (c[i].position - p0).squaredNorm();
        if (d2 > far2) far2 = d2, i1 = i;
    }
    m.add(c[i0].position, c[i0].depth, c[i0].feature);
    if (i1 == i0) {
        out.push_back(m);
        return;
    }
    m.add(c[i1].position, c[i1].depth, c[i1].feature);
    const Vec3& p1 = c[i1].position;
    auto area = [&](const Vec3& x, const Vec3& y, const Vec3& z) { return (y - x).cross(z - x).dot(normal); };
    int i2 = -1;
    double best = 0.0;
    for (int i = 0; i < n; ++i) {
        const double a = std::abs(area(p0, p1, c[i].position));
        if (a > best) best = a, i2 = i;
    }
    if (i2 < 0) {
        out.push_back(m);
        return;
    }
    m.add(c[i2].position, c[i2].depth, c[i2].feature);
    const Vec3& p2 = c[i2].position;
    const double sign = area(p0, p1, p2) > 0 ? 1.0 : -1.0;
    // The fourth point adds the most area outside one of the triangle's edges.
    int i3 = -1;
    best = 0.0;
    for (int i = 0; i < n; ++i) {
        const Vec3& q = c[i].position;
        const double add =
            std::max({-sign * area(p0, p1, q), -sign * area(p1, p2, q), -sign * area(p2, p0, q)});
        if (add > best) best = add, i3 = i;
    }
    if (i3 >= 0) m.add(c[i3].position, c[i3].depth, c[i3].feature);
    out.push_back(m);
}

}  // namespace tumble::collision::detail
