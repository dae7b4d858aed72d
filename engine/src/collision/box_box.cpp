// Box against box by the separating axis test over the 15 candidate axes (3 face normals of
// each box, 9 edge-edge cross products). The axis of least penetration gives the normal and
// depth. A face axis yields a manifold by clipping the most anti-parallel (incident) face of
// the other box against the side planes of the reference face, which is what makes a box
// resting on a box stable (4 points); an edge axis yields one point, midway between the two
// closest edges. Face axes are preferred over edge axes unless an edge is clearly better, so
// that the manifold does not flicker between the two on nearly flat contacts.
#include "collision/contact_util.h"
#include "collision/narrowphase.h"

#include <cmath>

namespace tumble::collision {

namespace {

struct Box {
    Vec3 c;
    Mat3 R;   // columns: the box axes in the world
    Vec3 h;

    double radiusAlong(const Vec3& L) const {
        return h.x() * std::abs(L.dot(R.col(0))) + h.y() * std::abs(L.dot(R.col(1))) +
               h.z() * std::abs(L.dot(R.col(2)));
    }
};

struct ClipPoint {
    Vec3 p;
    std::uint32_t id;
};

// Keeps the part of the polygon with s·(x - origin) <= limit.
std::vector<ClipPoint> clip(const std::vector<ClipPoint>& poly, const Vec3& s, double limit, std::uint32_t side) {
    std::vector<ClipPoint> out;
    const size_t n = poly.size();
    for (size_t i = 0; i < n; ++i) {
        const ClipPoint& a = poly[i];
        const ClipPoint& b = poly[(i + 1) % n];
        const double da = s.dot(a.p) - limit, db = s.dot(b.p) - limit;
        if (da <= 0.0) out.push_back(a);
        if ((da < 0.0 && db > 0.0) || (da > 0.0 && db < 0.0)) {
            const double t = da / (da - db);
            out.push_back({a.p + t * (b.p - a.p), 0x100u | (a.id << 4) | side});
        }
    }
    return out;
}

// Face `axis` of box `ref` (sign +1/-1: the side facing the other box) is the reference;
// the face of `inc` most opposed to it is clipped against it.
void faceContact(const Box& ref, int axis, double sign, const Box& inc, const Vec3& normalBtoA,
                 bool refIsB, double margin, ManifoldList& out) {
    const Vec3 m = ref.R.col(axis) * sign;  // out of the reference box towards the other
    // Incident face: the face of inc whose outward normal is most against m.
    int incAxis = 0;
    double most = 0.0;
    for (int k = 0; k < 3; ++k) {
        const double d = std::abs(inc.R.col(k).dot(m));
        if (d > most) most = d, incAxis = k;
    }
    const double incSign = inc.R.col(incAxis).dot(m) > 0.0 ? -1.0 : 1.0;
    const int u = (incAxis + 1) % 3, v = (incAxis + 2) % 3;
    const Vec3 fc = inc.c + inc.R.col(incAxis) * (incSign * inc.h[incAxis]);
    const Vec3 eu = inc.R.col(u) * inc.h[u], ev = inc.R.col(v) * inc.h[v];
    const std::uint32_t incFace = static_cast<std::uint32_t>(incAxis * 2 + (incSign > 0 ? 1 : 0));
    std::vector<ClipPoint> poly{{fc + eu + ev, 0}, {fc - eu + ev, 1}, {fc - eu - ev, 2}, {fc + eu - ev, 3}};
    // Side planes of the reference face.
    const int ru = (axis + 1) % 3, rv = (axis + 2) % 3;
    for (int k = 0; k < 2; ++k) {
        const int a = k == 0 ? ru : rv;
        const Vec3 s = ref.R.col(a);
        const double centre = s.dot(ref.c);
        poly = clip(poly, s, centre + ref.h[a], static_cast<std::uint32_t>(2 * k));
        poly = clip(poly, -s, -centre + ref.h[a], static_cast<std::uint32_t>(2 * k + 1));
    }
    const double offset = m.dot(ref.c) + ref.h[axis];
    const std::uint32_t refFace = static_cast<std::uint32_t>(axis * 2 + (sign > 0 ? 1 : 0)) + (refIsB ? 6u : 0u);
    std::vector<Candidate> candidates;
    for (const ClipPoint& q : poly) {
        const double depth = offset - m.dot(q.p);
        if (depth > -margin) {
            candidates.push_back({q.p + m * (0.5 * depth), depth, (refFace << 16) | (incFace << 12) | q.id});
        }
    }
    addReduced(candidates, normalBtoA, out);
}

}  // namespace

void boxBox(const Shape& sa, const Pose& pa, const Shape& sb, const Pose& pb, double margin,
            ManifoldList& out) {
    const Box A{pa.p, pa.R, sa.halfExtents};
    const Box B{pb.p, pb.R, sb.halfExtents};
    const Vec3 d = A.c - B.c;
    const double size = std::max(A.h.maxCoeff(), B.h.maxCoeff());

    // Separation along each candidate axis; the largest is the least penetration.
    struct Best {
        double separation = -std::numeric_limits<double>::infinity();
        Vec3 axis = Vec3::Zero();  // unit, pointing from B to A
        int code = -1;  // 0-2 face of A, 3-5 face of B, 6-14 edge pairs
    };
    Best face, edge;
    auto consider = [&](const Vec3& L, int code, Best& best) {
        const double along = d.dot(L);
        const double separation = std::abs(along) - (A.radiusAlong(L) + B.radiusAlong(L));
        if (separation > best.separation) best = {separation, along >= 0.0 ? L : Vec3(-L), code};
        return separation;
    };
    for (int k = 0; k < 3; ++k) {
        if (consider(A.R.col(k), k, face) > margin) return;
    }
    Best faceB;
    for (int k = 0; k < 3; ++k) {
        if (consider(B.R.col(k), 3 + k, faceB) > margin) return;
    }
    // Prefer A's faces unless B's are clearly better (a stable choice frame to frame).
    const double tolerance = 1e-9 * size;
    if (faceB.separation > face.separation + 0.02 * std::abs(face.separation) + tolerance) face = faceB;
    for (int i = 0; i < 3; ++i) {
        for (int j = 0; j < 3; ++j) {
            Vec3 L = A.R.col(i).cross(B.R.col(j));
            const double len = L.norm();
            if (len < 1e-6) continue;  // parallel edges: the face axes cover them
            if (consider(L / len, 6 + 3 * i + j, edge) > margin) return;
        }
    }
    if (edge.code >= 0 && edge.separation > face.separation + 0.05 * std::abs(face.separation) + 10 * tolerance) {
        const int i = (edge.code - 6) / 3, j = (edge.code - 6) % 3;
        const Vec3 n = edge.axis;  // from B to A
        // The edge of A nearest B, and the edge of B nearest A.
        Vec3 ea = A.c, eb = B.c;
        for (int k = 0; k < 3; ++k) {
            if (k != i) ea -= A.R.col(k) * (A.h[k] * (A.R.col(k).dot(n) > 0.0 ? 1.0 : -1.0));
            if (k != j) eb += B.R.col(k) * (B.h[k] * (B.R.col(k).dot(n) > 0.0 ? 1.0 : -1.0));
        }
        const Vec3 ua = A.R.col(i) * A.h[i], ub = B.R.col(j) * B.h[j];
        double s, t;
        closestBetweenSegments(ea - ua, ea + ua, eb - ub, eb + ub, &s, &t);
        const Vec3 qa = ea - ua + 2.0 * s * ua, qb = eb - ub + 2.0 * t * ub;
        addReduced({{0.5 * (qa + qb), -edge.separation, 0x200000u | static_cast<std::uint32_t>(edge.code)}}, n, out);
        return;
    }
    const Vec3 n = face.axis;  // from B to A
    if (face.code < 3) {
        // Reference face on A, facing B: its outward normal is -n.
        const double sign = A.R.col(face.code).dot(n) > 0.0 ? -1.0 : 1.0;
        faceContact(A, face.code, sign, B, n, false, margin, out);
    } else {
        const int k = face.code - 3;
        const double sign = B.R.col(k).dot(n) > 0.0 ? 1.0 : -1.0;
        faceContact(B, k, sign, A, n, true, margin, out);
    }
}

}  // namespace tumble::collision
