#include "common/closest_point.h"

namespace tumble {

Vec3 closestPointOnTriangle(const Vec3& p, const Vec3& a, const Vec3& b, const Vec3& c) {
    // Voronoi regions of the vertices, then the edges, else the interior.
    const Vec3 ab = b - a, ac = c - a, ap = p - a;
    const double d1 = ab.dot(ap), d2 = ac.dot(ap);
    if (d1 <= 0.0 && d2 <= 0.0) return a;
    const Vec3 bp = p - b;
    const double d3 = ab.dot(bp), d4 = ac.dot(bp);
    if (d3 >= 0.0 && d4 <= d3) return b;
    const double vc = d1 * d4 - d3 * d2;
    if (vc <= 0.0 && d1 >= 0.0 && d3 <= 0.0) return a + (d1 / (d1 - d3)) * ab;
    const Vec3 cp = p - c;
    const double d5 = ab.dot(cp), d6 = ac.dot(cp);
    if (d6 >= 0.0 && d5 <= d6) return c;
    const double vb = d5 * d2 - d1 * d6;
    if (vb <= 0.0 && d2 >= 0.0 && d6 <= 0.0) return a + (d2 / (d2 - d6)) * ac;
    const double va = d3 * d6 - d5 * d4;
    if (va <= 0.0 && (d4 - d3) >= 0.0 && (d5 - d6) >= 0.0)
        return b + ((d4 - d3) / ((d4 - d3) + (d5 - d6))) * (c - b);
    const double denom = va + vb + vc;
    if (denom == 0.0) {  // degenerate triangle: the closest of its three edges
        Vec3 best = a;
        auto seg = [&](const Vec3& s, const Vec3& e) {
            const double len2 = (e - s).squaredNorm();
            const double t = len2 > 0.0 ? std::clamp((p - s).dot(e - s) / len2, 0.0, 1.0) : 0.0;
            const Vec3 q = s + t * (e - s);
            if ((q - p).squaredNorm() < (best - p).squaredNorm()) best = q;
        };
        seg(a, b);
        seg(b, c);
        seg(c, a);
        return best;
    }
    return a + ab * (vb / denom) + ac * (vc / denom);
}

}  // namespace tumble
