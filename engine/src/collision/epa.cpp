// EPA (expanding polytope, van den Bergen): penetration depth and normal of two
// overlapping cores. Starts from GJK's final simplex, grown to a tetrahedron around the
// origin, then repeatedly pushes out the face nearest the origin by the support point along
// its normal until the support gains no more than a relative tolerance on that face.
//
// When the Minkowski difference is flat (a triangle core against a point, two crossing
// segments...) no tetrahedron exists: the cores touch with zero depth, and the normal is
// the flat set's own normal, oriented by the triangle's face (mesh side) or the centres.
#include "collision/gjk.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

namespace tumble::collision::detail {

namespace {

constexpr double kGrowTol = 1e-9;   // a point must leave the simplex's span by this × scale
constexpr double kDoneTol = 1e-10;  // support gains less than this × scale: done
constexpr int kMaxIterations = 256;  // curved cores deep in each other need the most (~100)

// A face of the polytope, wound counter-clockwise seen from outside. Edge e runs from
// v[e] to v[(e + 1) % 3]; adj[e] is the face across it, where it is edge adjEdge[e].
struct Face {
    int v[3];
    int adj[3];
    int adjEdge[3];
    Vec3 n;
    double dist;
    bool alive;
};

// An edge of a face, seen from across it: the silhouette's walk and its result.
struct HorizonEdge {
    int face, edge;
};

Vec3 anyPerp(const Vec3& d) {
    const Vec3 axis =
        std::abs(d.x()) < 0.57 ? Vec3(1, 0, 0) : (std::abs(d.y()) < 0.57 ? Vec3(0, 1, 0) : Vec3(0, 0, 1));
    return d.cross(axis).normalized();
}

// A contact of flat cores: zero core depth, points by the weights of the origin in the
// simplex, normal given.
Penetration flatResult(const std::vector<SimplexVertex>& s, const Vec3& normal) {
    Penetration p;
    p.normal = normal;
    p.depth = 0.0;
    if (s.size() >= 3) {
        const auto l = closestOnTriangle(s[0].w, s[1].w, s[2].w);
        for (int i = 0; i < 3; ++i) {
            p.pointA += l[i] * s[i].a;
            p.pointB += l[i] * s[i].b;
        }
    } else if (s.size() == 2) {
        const Vec3 d = s[1].w - s[0].w;
        const double t = d.squaredNorm() > 0 ? std::clamp(-s[0].w.dot(d) / d.squaredNorm(), 0.0, 1.0) : 0.0;
        p.pointA = (1 - t) * s[0].a + t * s[1].a;
        p.pointB = (1 - t) * s[0].b + t * s[1].b;
    } else {
        p.pointA = s[0].a;
        p.pointB = s[0].b;
    }
    return p;
}

Vec3 triangleNormal(const ConvexProxy& p) {
    const auto& t = p.triangle;
    return (t[1] - t[0]).cross(t[2] - t[0]).normalized();
}

// Orientation of a normal that the flat geometry leaves free: the mesh triangle's front,
// else from B's centre towards A's.
Vec3 orient(const Vec3& n, const ConvexProxy& a, const ConvexProxy& b) {
    if (b.core == ConvexProxy::Core::Triangle) return triangleNormal(b).dot(n) >= 0 ? n : -n;
    if (a.core == ConvexProxy::Core::Triangle) return triangleNormal(a).dot(n) <= 0 ? n : -n;
    return (a.center() - b.center()).dot(n) >= 0 ? n : -n;
}

}  // namespace

Penetration epa(const ConvexProxy& A, const ConvexProxy& B, const SimplexVertex* simplex, int count,
                const Vec3& origin, double scale) {
    // Lists kept per thread between calls (the worker pool runs pairs side by side): four
    // allocations a call were a good part of a short expansion's cost.
    struct Scratch {
        std::vector<SimplexVertex> v;
        std::vector<Face> faces;
        std::vector<HorizonEdge> horizon, stack;
    };
    thread_local Scratch scratch;
    std::vector<SimplexVertex>& v = scratch.v;
    v.clear();
    v.reserve(kMaxIterations + 8);
    for (int i = 0; i < count; ++i) {
        bool dup = false;
        for (const auto& u : v) dup = dup || u.w == simplex[i].w;
        if (!dup) v.push_back(simplex[i]);
    }
    const double tolPt = kGrowTol * scale;
    auto support = [&](const Vec3& d) { return supportVertex(A, B, d, origin); };

    // Grow the simplex to a tetrahedron; a direction that finds nothing new means the
    // Minkowski difference is flat along it.
    if (v.size() == 1) {
        for (const Vec3& d :
             {Vec3(1, 0, 0), Vec3(-1, 0, 0), Vec3(0, 1, 0), Vec3(0, -1, 0), Vec3(0, 0, 1), Vec3(0, 0, -1)}) {
            const SimplexVertex w = support(d);
            if ((w.w - v[0].w).norm() > tolPt) {
                v.push_back(w);
                break;
            }
        }
        if (v.size() == 1) {
            const Vec3 c = A.center() - B.center();
            return flatResult(v, c.squaredNorm() > 0 ? c.normalized() : Vec3(0, 1, 0));
        }
    }
    if (v.size() == 2) {
        const Vec3 d = (v[1].w - v[0].w).normalized();
        const Vec3 e1 = anyPerp(d), e2 = d.cross(e1);
        for (const Vec3& dir : {e1, Vec3(-e1), e2, Vec3(-e2), Vec3(e1 + e2), Vec3(-e1 - e2)}) {
            const SimplexVertex w = support(dir);
            if ((w.w - v[0].w).cross(d).norm() > tolPt) {
                v.push_back(w);
                break;
            }
        }
        if (v.size() == 2) {
            const Vec3 c = A.center() - B.center();
            const Vec3 perp = c - c.dot(d) * d;
            return flatResult(v, perp.squaredNorm() > 1e-24 * c.squaredNorm() && perp.squaredNorm() > 0
                                     ? perp.normalized()
                                     : orient(e1, A, B));
        }
    }
    if (v.size() == 3) {
        const Vec3 n = (v[1].w - v[0].w).cross(v[2].w - v[0].w).normalized();
        const SimplexVertex wp = support(n), wm = support(-n);
        const double hp = (wp.w - v[0].w).dot(n), hm = -(wm.w - v[0].w).dot(n);
        if (std::max(hp, hm) <= tolPt) return flatResult(v, orient(n, A, B));
        v.push_back(hp >= hm ? wp : wm);
    }

    // The tetrahedron, faces wound outwards.
    std::vector<Face>& faces = scratch.faces;
    faces.clear();  // (grown as needed and kept: reserving for the worst case held 164 KB)
    auto makeFace = [&](int i, int j, int k) {
        Vec3 n = (v[j].w - v[i].w).cross(v[k].w - v[i].w);
        const double len = n.norm();
        Face f{{i, j, k}, {-1, -1, -1}, {0, 0, 0}, Vec3::Zero(), std::numeric_limits<double>::infinity(),
               true};
        if (len > 0) {
            f.n = n / len;
            f.dist = f.n.dot(v[i].w);
        }
        return f;
    };
    // One winding for all four faces, from the sign of the volume: decided face by face, a
    // nearly flat tetrahedron could get faces wound both ways, whose edges then found no
    // partner and the silhouette walked off the polytope (UBSan, tst_guard's large scene).
    const bool flip = (v[1].w - v[0].w).cross(v[2].w - v[0].w).dot(v[3].w - v[0].w) > 0.0;
    for (const auto& t : {std::array<int, 3>{0, 1, 2}, {0, 3, 1}, {0, 2, 3}, {1, 3, 2}})
        faces.push_back(flip ? makeFace(t[0], t[2], t[1]) : makeFace(t[0], t[1], t[2]));
    // Edge a->b of one face meets edge b->a of another: link them.
    auto link = [&](int fa, int ea, int fb, int eb) {
        faces[fa].adj[ea] = fb, faces[fa].adjEdge[ea] = eb;
        faces[fb].adj[eb] = fa, faces[fb].adjEdge[eb] = ea;
    };
    for (int fa = 0; fa < 4; ++fa)
        for (int ea = 0; ea < 3; ++ea)
            for (int fb = 0; fb < 4; ++fb)
                for (int eb = 0; eb < 3; ++eb)
                    if (faces[fa].v[ea] == faces[fb].v[(eb + 1) % 3] &&
                        faces[fa].v[(ea + 1) % 3] == faces[fb].v[eb])
                        link(fa, ea, fb, eb);

    // The silhouette of the polytope seen from w (van den Bergen): from the face being
    // replaced, walk across edges into faces that see w, removing them; an edge into a face
    // that does not see w is on the horizon. The walk keeps the removed region connected, so
    // a sliver face whose normal rounding has turned cannot tear the surface.
    std::vector<HorizonEdge>& horizon = scratch.horizon;
    std::vector<HorizonEdge>& stack = scratch.stack;
    bool torn = false;
    auto silhouette = [&](int start, const Vec3& w) {
        faces[start].alive = false;
        horizon.clear();
        stack.clear();
        for (int e = 2; e >= 0; --e) stack.push_back({faces[start].adj[e], faces[start].adjEdge[e]});
        while (!stack.empty()) {
            const HorizonEdge h = stack.back();
            stack.pop_back();
            if (h.face < 0) {  // an edge with no partner: the surface is torn
                torn = true;
                continue;
            }
            Face& g = faces[h.face];
            if (!g.alive) continue;
            if (g.n.dot(w - v[g.v[0]].w) > 0.0) {
                g.alive = false;
                // Depth first, the next edge round first: the horizon comes out as a loop.
                stack.push_back({g.adj[(h.edge + 2) % 3], g.adjEdge[(h.edge + 2) % 3]});
                stack.push_back({g.adj[(h.edge + 1) % 3], g.adjEdge[(h.edge + 1) % 3]});
            } else {
                horizon.push_back(h);
            }
        }
    };

    const double doneTol = kDoneTol * scale;
    int best = 0;
    double reach = 0.0;  // the support along the best face's normal: an upper bound of the depth
    for (int iter = 0; iter < kMaxIterations; ++iter) {
        best = -1;
        for (int i = 0; i < static_cast<int>(faces.size()); ++i)
            if (faces[i].alive && (best < 0 || faces[i].dist < faces[best].dist)) best = i;
        const Face f = faces[best];
        const SimplexVertex w = support(f.n);
        reach = f.n.dot(w.w);
        if (reach - f.dist <= doneTol) break;
        const int index = static_cast<int>(v.size());
        v.push_back(w);
        silhouette(best, w.w);
        // One new face on each horizon edge, wound like the face it replaces.
        const int first = static_cast<int>(faces.size());
        const int count = static_cast<int>(horizon.size());
        bool broken = count < 3 || torn;
        for (const HorizonEdge& h : horizon) {
            const Face& g = faces[h.face];
            const int a = g.v[(h.edge + 1) % 3], b = g.v[h.edge];
            faces.push_back(makeFace(a, b, index));
            const int nf = static_cast<int>(faces.size()) - 1;
            link(nf, 0, h.face, h.edge);
            broken = broken || faces[nf].dist < f.dist - doneTol;
        }
        // Side edges: b->w of one new face meets w->a of the face whose a is that b.
        for (int i = 0; i < count && !broken; ++i) {
            int match = -1;
            for (int j = 0; j < count; ++j)
                if (faces[first + j].v[0] == faces[first + i].v[1]) match = j;
            if (match < 0)
                broken = true;
            else
                link(first + i, 1, first + match, 2);
        }
        if (broken) {
            // Rounding made the polytope non-convex: the last face is the best answer we have.
            for (int i = first; i < static_cast<int>(faces.size()); ++i) faces[i].alive = false;
            break;
        }
    }

    // The witness points: the weights of the origin's projection in the nearest face. A
    // face of the difference is often split into coplanar triangles of equal distance, and
    // the projection lies in only one of them: take the one it is in (or nearest to).
    const Face& f = faces[best];
    const Vec3 q = f.n * f.dist;
    auto weights = [&](const Face& g, double& miss) {
        const auto l = closestOnTriangle(v[g.v[0]].w - q, v[g.v[1]].w - q, v[g.v[2]].w - q);
        miss = (l[0] * v[g.v[0]].w + l[1] * v[g.v[1]].w + l[2] * v[g.v[2]].w - q).squaredNorm();
        return l;
    };
    double miss = 0.0;
    int witness = best;
    auto l = weights(f, miss);
    for (int i = 0; i < static_cast<int>(faces.size()) && miss > 0.0; ++i) {
        const Face& g = faces[i];
        if (!g.alive || i == best || g.n.dot(f.n) < 1.0 - 1e-9 || std::abs(g.dist - f.dist) > doneTol) continue;
        double m = 0.0;
        const auto lg = weights(g, m);
        if (m < miss) miss = m, l = lg, witness = i;
    }
    const Face& fw = faces[witness];
    Penetration p;
    p.normal = -f.n;
    // The face's distance is a lower bound of the depth and the support along its normal an
    // upper one; they agree to the tolerance on convergence. Where the iterations ran out
    // (deep overlap of two curved cores) the upper bound is the one that, applied along the
    // normal, really separates the shapes.
    p.depth = reach;
    for (int i = 0; i < 3; ++i) {
        p.pointA += l[i] * v[fw.v[i]].a;
        p.pointB += l[i] * v[fw.v[i]].b;
    }
    return p;
}

}  // namespace tumble::collision::detail
