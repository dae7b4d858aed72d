#include "collision/contact_util.h"

#include <algorithm>
#include <cmath>

namespace tumble::collision {

Vec3 closestOnSegment(const Vec3& p0, const Vec3& p1, const Vec3& q) {
    const Vec3 d = p1 - p0;
    const double dd = d.squaredNorm();
    if (dd <= 0.0) return p0;
    const double s = std::clamp((q - p0).dot(d) / dd, 0.0, 1.0);
    return p0 + s * d;
}

void closestBetweenSegments(const Vec3& p0, const Vec3& p1, const Vec3& q0, const Vec3& q1,
                            double* sOut, double* tOut) {
    const Vec3 d1 = p1 - p0, d2 = q1 - q0, r = p0 - q0;
    const double a = d1.squaredNorm(), e = d2.squaredNorm(), f = d2.dot(r);
    double s = 0.0, t = 0.0;
    if (a <= 0.0 && e <= 0.0) {
        // two points
    } else if (a <= 0.0) {
        t = std::clamp(f / e, 0.0, 1.0);
    } else {
        const double c = d1.dot(r);
        if (e <= 0.0) {
            s = std::clamp(-c / a, 0.0, 1.0);
        } else {
            const double b = d1.dot(d2);
            const double denom = a * e - b * b;  // >= 0; ~0 when parallel
            if (denom > 1e-12 * a * e) {
                s = std::clamp((b * f - c * e) / denom, 0.0, 1.0);
            } else {
                // Parallel: the middle of the overlap of q's projection onto p, so that the
                // answer does not jump between the ends as the segments slide.
                const double u0 = std::clamp((q0 - p0).dot(d1) / a, 0.0, 1.0);
                const double u1 = std::clamp((q1 - p0).dot(d1) / a, 0.0, 1.0);
                s = 0.5 * (u0 + u1);
            }
            t = (b * s + f) / e;
            if (t < 0.0) {
                t = 0.0;
                s = std::clamp(-c / a, 0.0, 1.0);
            } else if (t > 1.0) {
                t = 1.0;
                s = std::clamp((b - c) / a, 0.0, 1.0);
            }
        }
    }
    *sOut = s;
    *tOut = t;
}

Vec3 anyPerpendicular(const Vec3& n) {
    const Vec3 other = std::abs(n.x()) < 0.57 ? Vec3::UnitX() : (std::abs(n.y()) < 0.57 ? Vec3::UnitY() : Vec3::UnitZ());
    return n.cross(other).normalized();
}

void addReduced(const std::vector<Candidate>& c, const Vec3& normal, ManifoldList& out) {
    if (c.empty()) return;
    Manifold m;
    m.normal = normal;
    if (c.size() <= Manifold::kMaxPoints) {
        for (const Candidate& k : c) m.add(k.position, k.depth, k.feature);
        out.push_back(m);
        return;
    }
    // Project into the contact plane; choose 1) deepest, 2) farthest from it, 3) largest
    // triangle with both, 4) largest signed area on the other side of the edge.
    auto deepest = std::max_element(c.begin(), c.end(), [](auto& x, auto& y) { return x.depth < y.depth; });
    const size_t i0 = static_cast<size_t>(deepest - c.begin());
    auto flat = [&](size_t i) { return Vec3(c[i].position - normal * normal.dot(c[i].position)); };
    size_t i1 = i0;
    double best = -1.0;
    for (size_t i = 0; i < c.size(); ++i) {
        const double d = (flat(i) - flat(i0)).squaredNorm();
        if (d > best) best = d, i1 = i;
    }
    size_t i2 = i0;
    best = -1.0;
    double sideOf2 = 0.0;
    for (size_t i = 0; i < c.size(); ++i) {
        const double area = (flat(i1) - flat(i0)).cross(flat(i) - flat(i0)).dot(normal);
        if (std::abs(area) > best) best = std::abs(area), i2 = i, sideOf2 = area;
    }
    size_t i3 = i0;
    best = 0.0;
    for (size_t i = 0; i < c.size(); ++i) {
        // The point that adds most area on the far side of edge i0-i1 from i2.
        const double area = (flat(i1) - flat(i0)).cross(flat(i) - flat(i0)).dot(normal);
        if (area * sideOf2 < 0.0 && std::abs(area) > best) best = std::abs(area), i3 = i;
    }
    if (i3 == i0) {
        // Everything on one side: take the one that grows the triangle most instead.
        best = -1.0;
        for (size_t i = 0; i < c.size(); ++i) {
            if (i == i0 || i == i1 || i == i2) continue;
            const double a = std::abs((flat(i2) - flat(i1)).cross(flat(i) - flat(i1)).dot(normal)) +
                             std::abs((flat(i0) - flat(i2)).cross(flat(i) - flat(i2)).dot(normal));
            if (a > best) best = a, i3 = i;
        }
    }
    for (size_t i : {i0, i1, i2, i3}) {
        bool seen = false;
        for (int k = 0; k < m.count; ++k) seen |= m.points[k].feature == c[i].feature && m.points[k].position == c[i].position;
        if (!seen) m.add(c[i].position, c[i].depth, c[i].feature);
    }
    out.push_back(m);
}

}  // namespace tumble::collision
