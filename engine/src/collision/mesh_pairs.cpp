// Concave meshes by the paper's tests, through the BVHs.
//
// Mesh-mesh gathers candidate points of three kinds, then groups them by normal:
// - a vertex of one mesh inside the other (ray parity; only vertices inside the other's
//   bounds are cast): depth = distance to the other's surface, found among the triangles
//   within the nearest crossing of the parity ray (the surface is at most that far);
// - a vertex outside within `margin` of the other's surface: a near contact;
// - an edge that passes through the other mesh, entering through one triangle and leaving
//   through another with no vertex inside (Fig. 3). Locally the other mesh is the wedge of
//   the two triangles' planes, whose ridge is the line where the planes meet; the edge clears
//   it fastest along the separating axis of the edge and the ridge, n = edge × ridge, and
//   the depth is the distance of the two lines along n. When that axis does not separate
//   (the planes are parallel: a slab, or n is outside the wedge's normal cone), or a third
//   face is nearer than the wedge's two (the wedge is not the local shape), the point's
//   distance to the surface and the way to the nearest surface point stand in.
// An edge's chords are read from its crossings sorted along it: a crossing enters where the
// edge runs against the triangle's outward normal and leaves where it runs with it.
#include "collision/mesh_pairs.h"

#include "collision/bvh.h"
#include "collision/reference.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <map>
#include <memory>
#include <set>
#include <utility>

namespace tumble::collision {

namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();
constexpr double kGroupCos = 0.95;  // points whose normals differ by < ~18° share a manifold

struct Candidate {
    Vec3 position;
    Vec3 normal;
    double depth = 0.0;
    std::uint32_t feature = 0;
};

std::uint32_t featureId(std::uint32_t kind, std::uint64_t index) {
    const std::uint64_t h = (index + 1) * 0x9e3779b97f4a7c15ull;
    return (kind << 30) | static_cast<std::uint32_t>((h >> 34) & 0x3fffffffu);
}

// Up to four points of a group, spread over the contact: the deepest, the farthest from
// it, the one making the largest triangle with those two, and the one farthest outside
// that triangle (all measured in the plane across the normal).
void reduce(std::vector<Candidate> group, const Vec3& n, Manifold& m) {
    std::stable_sort(group.begin(), group.end(),
                     [](const Candidate& x, const Candidate& y) { return x.depth > y.depth; });
    const auto across = [&](const Vec3& v) { return Vec3(v - n * n.dot(v)); };
    std::vector<int> picked{0};
    auto pickBest = [&](auto score) {
        int best = -1;
        double bestScore = 1e-12;
        for (int i = 0; i < static_cast<int>(group.size()); ++i) {
            if (std::find(picked.begin(), picked.end(), i) != picked.end()) continue;
            const double s = score(across(group[i].position));
            if (s > bestScore) {
                bestScore = s;
                best = i;
            }
        }
        if (best >= 0) picked.push_back(best);
        return best >= 0;
    };
    const Vec3 p0 = across(group[0].position);
    if (pickBest([&](const Vec3& q) { return (q - p0).squaredNorm(); })) {
        const Vec3 p1 = across(group[picked[1]].position);
        if (pickBest([&](const Vec3& q) { return (p1 - p0).cross(q - p0).norm(); })) {
            const Vec3 p2 = across(group[picked[2]].position);
            const Vec3 c = (p0 + p1 + p2) / 3.0;
            pickBest([&](const Vec3& q) {
                // Farthest outside any edge of the triangle (edges oriented away from c).
                double out = 0.0;
                const Vec3 tri[3] = {p0, p1, p2};
                for (int k = 0; k < 3; ++k) {
                    const Vec3 e = tri[(k + 1) % 3] - tri[k];
                    Vec3 side = n.cross(e);
                    if (side.dot(tri[k] - c) < 0.0) side = -side;
                    const double len = side.norm();
                    if (len > 0.0) out = std::max(out, side.dot(q - tri[k]) / len);
                }
                return out;
            });
        }
    }
    m.normal = n;
    m.count = 0;
    for (int i : picked) m.add(group[i].position, group[i].depth, group[i].feature);
}

// Greedy grouping by normal, deepest first; each group becomes one manifold.
void emit(std::vector<Candidate> cands, ManifoldList& out) {
    std::stable_sort(cands.begin(), cands.end(),
                     [](const Candidate& x, const Candidate& y) { return x.depth > y.depth; });
    std::vector<std::vector<Candidate>> groups;
    for (const Candidate& c : cands) {
        auto it = std::find_if(groups.begin(), groups.end(),
                               [&](const auto& g) { return g.front().normal.dot(c.normal) >= kGroupCos; });
        if (it == groups.end())
            groups.push_back({c});
        else
            it->push_back(c);
    }
    for (const auto& g : groups) {
        Manifold m;
        reduce(g, g.front().normal, m);
        out.push_back(m);
    }
}

std::shared_ptr<const TriangleBvh> bvhOf(const MeshShape& m) {
    return m.bvh ? m.bvh : std::make_shared<const TriangleBvh>(m.vertices, m.triangles);
}

Vec3 triangleNormal(const MeshShape& m, int t) {
    const auto& tri = m.triangles[t];
    const Vec3 n = (m.vertices[tri[1]] - m.vertices[tri[0]]).cross(m.vertices[tri[2]] - m.vertices[tri[0]]);
    const double len = n.norm();
    return len > 0.0 ? Vec3(n / len) : Vec3::Zero();
}

// Closest point of the mesh's triangles within `radius` of p (mesh frame); false if none.
// The search box starts small and grows fourfold: a triangle nearer than r meets the box of
// half-width r, so the first box in which something lies within r holds the closest. Most
// queries are for points just under the surface, so this visits few triangles.
bool closestWithin(const MeshShape& m, const TriangleBvh& bvh, const Vec3& p, double radius, Vec3& closest,
                   int& tri) {
    double r = std::min(radius, bvh.bounds().extent().norm() / 256.0);
    for (;;) {
        double best = kInf;
        tri = -1;
        const Aabb box{p.array() - r, p.array() + r};
        bvh.query(box, [&](int t) {
            const auto& v = m.triangles[t];
            const Vec3 q =
                reference::closestPointOnTriangle(p, m.vertices[v[0]], m.vertices[v[1]], m.vertices[v[2]]);
            const double d2 = (q - p).squaredNorm();
            if (d2 < best) {
                best = d2;
                closest = q;
                tri = t;
            }
        });
        if (tri >= 0 && best <= r * r) return true;
        if (r >= radius) return false;
        r = std::min(4.0 * r, radius);
    }
}

// The vertices of `body` (at poseBody) against `other` (at poseOther): inside by parity, or
// near within margin. `sign` = +1 when body is A, -1 when it is B (normals out of B).
void vertexContacts(const MeshShape& body, const Pose& poseBody, const MeshShape& other,
                    const TriangleBvh& otherBvh, const Pose& poseOther, double margin, double sign,
                    std::uint32_t kind, std::vector<Candidate>& out) {
    const Aabb reach = otherBvh.bounds().inflated(std::max(margin, 0.0));
    for (int i = 0; i < static_cast<int>(body.vertices.size()); ++i) {
        const Vec3 w = poseBody.toWorld(body.vertices[i]);
        const Vec3 p = poseOther.toLocal(w);
        if (!reach.contains(p)) continue;
        bool inside = false;
        double radius = margin;
        if (other.closed) {
            const reference::Parity parity = reference::rayParity(other, p);
            inside = parity.inside;
            if (inside) radius = parity.nearestHit;
        }
        if (!inside && margin <= 0.0) continue;
        Vec3 c;
        int tri;
        if (!closestWithin(other, otherBvh, p, radius, c, tri)) continue;
        const double dist = (c - p).norm();
        // The way out (inside) or the way apart (outside); on the surface, the face.
        Vec3 dir = triangleNormal(other, tri);
        if (dist > 1e-12 * (1.0 + p.norm())) dir = inside ? Vec3((c - p) / dist) : Vec3((p - c) / dist);
        const double depth = inside ? dist : -dist;
        if (depth <= -margin) continue;
        const Vec3 nWorld = poseOther.directionToWorld(dir);
        out.push_back(
            {w + 0.5 * depth * nWorld, sign * nWorld, depth, featureId(kind, static_cast<std::uint64_t>(i))});
    }
}

struct Crossing {
    double t;     // along the edge, 0..1
    int tri;      // the other mesh's triangle
    bool enters;  // the edge runs against the triangle's outward normal
};

// Strict crossing of segment p0-p1 with triangle (a, b, c) of outward normal n: the point
// parameter t, or false. Closed triangle: a crossing on an edge is reported by both sides.
bool segmentTriangle(const Vec3& p0, const Vec3& p1, const Vec3& a, const Vec3& b, const Vec3& c,
                     const Vec3& n, double& t) {
    const double e0 = n.dot(p0 - a), e1 = n.dot(p1 - a);
    if (!((e0 < 0.0 && e1 > 0.0) || (e0 > 0.0 && e1 < 0.0))) return false;
    t = e0 / (e0 - e1);
    const Vec3 x = p0 + t * (p1 - p0);
    return (b - a).cross(x - a).dot(n) >= 0.0 && (c - b).cross(x - b).dot(n) >= 0.0 &&
           (a - c).cross(x - c).dot(n) >= 0.0;
}

// Chords of the edges of `body` through `other`, both in the frame of `other`.
void edgeContacts(const MeshShape& body, const std::vector<Vec3>& bodyInOther, const MeshShape& other,
                  const TriangleBvh& otherBvh, const Pose& poseOther,
                  const std::set<std::pair<int, int>>& pairs, double sign, std::uint32_t kind,
                  std::vector<Candidate>& out) {
    std::map<std::pair<int, int>, std::vector<Crossing>> crossings;
    std::set<std::pair<std::pair<int, int>, int>> seen;
    for (const auto& [tb, to] : pairs) {
        const auto& tri = body.triangles[tb];
        const auto& ot = other.triangles[to];
        const Vec3 n = triangleNormal(other, to);
        if (n.isZero()) continue;
        for (int k = 0; k < 3; ++k) {
            const std::pair<int, int> edge{std::min(tri[k], tri[(k + 1) % 3]),
                                           std::max(tri[k], tri[(k + 1) % 3])};
            if (edge.first == edge.second || !seen.insert({edge, to}).second) continue;
            const Vec3& p0 = bodyInOther[edge.first];
            const Vec3& p1 = bodyInOther[edge.second];
            double t;
            if (segmentTriangle(p0, p1, other.vertices[ot[0]], other.vertices[ot[1]], other.vertices[ot[2]],
                                n, t))
                crossings[edge].push_back({t, to, n.dot(p1 - p0) < 0.0});
        }
    }
    for (auto& [edge, list] : crossings) {
        std::sort(list.begin(), list.end(), [](const Crossing& x, const Crossing& y) { return x.t < y.t; });
        const Vec3& p0 = bodyInOther[edge.first];
        const Vec3& p1 = bodyInOther[edge.second];
        const Vec3 d = p1 - p0;
        const Crossing* enter = nullptr;
        for (const Crossing& c : list) {
            if (c.enters) {
                enter = &c;
                continue;
            }
            if (!enter) continue;  // the edge starts inside: its vertex is a contact already
            const Crossing& in = *enter;
            enter = nullptr;
            const Vec3 c1 = p0 + in.t * d, c2 = p0 + c.t * d;
            const double chord = (c2 - c1).norm();
            if (chord <= 1e-12 * d.norm()) continue;  // grazes a ridge
            const Vec3 n1 = triangleNormal(other, in.tri), n2 = triangleNormal(other, c.tri);
            const Vec3 ridge = n1.cross(n2);
            Vec3 axis = d.cross(ridge);
            double depth = -1.0;
            Vec3 point;
            if (ridge.norm() > 1e-6 && axis.norm() > 1e-9 * d.norm() * ridge.norm()) {
                axis.normalize();
                if (axis.dot(n1 + n2) < 0.0) axis = -axis;
                // axis = alpha n1 + beta n2 with both >= 0: it separates the edge from the wedge.
                const double g = n1.dot(n2);
                const double a1 = axis.dot(n1), a2 = axis.dot(n2);
                const double alpha = (a1 - g * a2) / (1.0 - g * g), beta = (a2 - g * a1) / (1.0 - g * g);
                if (alpha >= -1e-9 && beta >= -1e-9) {
                    // A point of the ridge: on both planes, nearest the chord's start.
                    const Vec3& o1 = other.vertices[other.triangles[in.tri][0]];
                    const Vec3& o2 = other.vertices[other.triangles[c.tri][0]];
                    const double h1 = n1.dot(o1 - c1), h2 = n2.dot(o2 - c1);
                    const Vec3 onRidge = c1 + ((h1 - g * h2) * n1 + (h2 - g * h1) * n2) / (1.0 - g * g);
                    depth = axis.dot(onRidge - c1);
                    // The chord's point nearest the ridge line, kept on the chord.
                    const Vec3 u = ridge.normalized(), dd = d / d.norm();
                    const Vec3 r = c1 - onRidge;
                    const double b = dd.dot(u), den = 1.0 - b * b;
                    double s = den > 1e-12 ? (b * u.dot(r) - dd.dot(r)) / den : 0.0;
                    s = std::clamp(s, 0.0, chord);
                    point = c1 + s * dd;
                }
            }
            Vec3 dir = axis;
            bool wedge = depth >= 0.0 && depth <= chord;
            if (wedge) {
                // The wedge is the local shape only if no other face is nearer the point
                // than its two planes (an edge inside a thin part crosses one face and
                // leaves by another, while a third, nearer face binds).
                const Vec3& o1 = other.vertices[other.triangles[in.tri][0]];
                const Vec3& o2 = other.vertices[other.triangles[c.tri][0]];
                const double toPlanes = std::min(n1.dot(o1 - point), n2.dot(o2 - point));
                const double radius = std::max((point - c1).norm(), (point - c2).norm());
                Vec3 closest;
                int tri;
                if (closestWithin(other, otherBvh, point, radius, closest, tri) &&
                    (closest - point).norm() < toPlanes * (1.0 - 1e-9) - 1e-12 * radius)
                    wedge = false;
            } else {
                point = 0.5 * (c1 + c2);
            }
            if (!wedge) {
                const double radius = std::max((point - c1).norm(), (point - c2).norm());
                Vec3 closest;
                int tri;
                if (!closestWithin(other, otherBvh, point, radius, closest, tri)) continue;
                depth = (closest - point).norm();
                dir = depth > 0.0 ? Vec3((closest - point) / depth) : n1;
            }
            const Vec3 nWorld = poseOther.directionToWorld(dir);
            const Vec3 w = poseOther.toWorld(point) + 0.5 * depth * nWorld;
            const std::uint64_t key =
                (static_cast<std::uint64_t>(edge.first) << 32) ^ static_cast<std::uint32_t>(edge.second);
            out.push_back({w, sign * nWorld, depth, featureId(kind, key)});
        }
    }
}

}  // namespace

void collideMeshPlane(const Shape& mesh, const Pose& pm, const Shape& plane, const Pose& pp, double margin,
                      ManifoldList& out) {
    const Vec3 n = pp.directionToWorld(plane.normal);
    const double offset = plane.distance + n.dot(pp.p);
    // The whole mesh is farther than its bounding radius from its origin.
    if (reference::planeValue(n, -offset, pm.p) - boundingRadius(mesh) >= margin) return;
    std::vector<Vec3> world;
    world.reserve(mesh.mesh->vertices.size());
    for (const Vec3& v : mesh.mesh->vertices) world.push_back(pm.toWorld(v));
    std::vector<Candidate> cands;
    for (const auto& hit : reference::pointsAgainstPlane(world, n, offset, margin)) {
        if (hit.depth <= -margin) continue;
        cands.push_back({world[hit.vertex] + 0.5 * hit.depth * n, n, hit.depth,
                         featureId(0, static_cast<std::uint64_t>(hit.vertex))});
    }
    if (cands.empty()) return;
    Manifold m;
    reduce(std::move(cands), n, m);
    out.push_back(m);
}

void collideMeshMesh(const Shape& a, const Pose& pa, const Shape& b, const Pose& pb, double margin,
                     ManifoldList& out) {
    const MeshShape& ma = *a.mesh;
    const MeshShape& mb = *b.mesh;
    if (!bounds(a, pa).inflated(std::max(margin, 0.0)).overlaps(bounds(b, pb))) return;
    const auto bvhA = bvhOf(ma);
    const auto bvhB = bvhOf(mb);

    std::vector<Candidate> cands;
    vertexContacts(ma, pa, mb, *bvhB, pb, margin, 1.0, 0, cands);
    vertexContacts(mb, pb, ma, *bvhA, pa, margin, -1.0, 1, cands);

    // Triangle pairs whose boxes meet: the only places an edge can cross a face.
    const Pose bToA{pa.R.transpose() * pb.R, pa.R.transpose() * (pb.p - pa.p)};
    std::set<std::pair<int, int>> pairsAB, pairsBA;  // (triangle of the edges' mesh, other)
    bvhA->queryPairs(*bvhB, bToA, [&](int i, int j) {
        pairsAB.insert({i, j});
        pairsBA.insert({j, i});
    });
    if (!pairsAB.empty()) {
        std::vector<Vec3> aInB, bInA;
        for (const Vec3& v : ma.vertices) aInB.push_back(pb.toLocal(pa.toWorld(v)));
        for (const Vec3& v : mb.vertices) bInA.push_back(pa.toLocal(pb.toWorld(v)));
        edgeContacts(ma, aInB, mb, *bvhB, pb, pairsAB, 1.0, 2, cands);
        edgeContacts(mb, bInA, ma, *bvhA, pa, pairsBA, -1.0, 3, cands);
    }
    if (!cands.empty()) emit(std::move(cands), out);
}

}  // namespace tumble::collision
