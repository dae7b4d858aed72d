#include "mesh/mesh_holes.h"

#include <array>
#include <map>
#include <numeric>
#include <queue>
#include <set>

namespace tumble::mesh {

namespace {

int root(std::vector<int>& parent, int x) {
    while (parent[x] != x) x = parent[x] = parent[parent[x]];
    return x;
}

// Each vertex's piece, as a union-find forest over the triangles' shared vertices.
std::vector<int> piecesOf(const TriangleMesh& mesh) {
    std::vector<int> parent(mesh.vertices.size());
    std::iota(parent.begin(), parent.end(), 0);
    for (const auto& t : mesh.triangles)
        for (int k = 1; k < 3; ++k) parent[root(parent, t[k])] = root(parent, t[0]);
    return parent;
}

std::pair<int, int> undirected(int a, int b) {
    return {std::min(a, b), std::max(a, b)};
}

// Turns triangles so that each two sharing an edge (and only they) run it opposite ways,
// spreading from each shell's first triangle: files mix windings (the assimp spider has
// ten edges run the same way by both their triangles). Returns how many were turned.
int windAlike(TriangleMesh& m) {
    std::map<std::pair<int, int>, std::vector<int>> byEdge;
    for (int t = 0; t < static_cast<int>(m.triangles.size()); ++t)
        for (int k = 0; k < 3; ++k)
            byEdge[undirected(m.triangles[t][k], m.triangles[t][(k + 1) % 3])].push_back(t);
    auto runs = [&](int t, int a, int b) {  // triangle t has the edge a -> b
        const auto& v = m.triangles[t];
        for (int k = 0; k < 3; ++k)
            if (v[k] == a && v[(k + 1) % 3] == b) return true;
        return false;
    };
    std::vector<std::uint8_t> seen(m.triangles.size(), 0);
    int turned = 0;
    for (int first = 0; first < static_cast<int>(m.triangles.size()); ++first) {
        if (seen[first]) continue;
        seen[first] = 1;
        std::queue<int> frontier;
        frontier.push(first);
        while (!frontier.empty()) {
            const int t = frontier.front();
            frontier.pop();
            for (int k = 0; k < 3; ++k) {
                const int a = m.triangles[t][k], b = m.triangles[t][(k + 1) % 3];
                const auto& two = byEdge[undirected(a, b)];
                if (two.size() != 2) continue;  // an open edge, or one of many
                const int o = two[0] == t ? two[1] : two[0];
                if (seen[o]) continue;
                seen[o] = 1;
                if (runs(o, a, b)) {
                    std::swap(m.triangles[o][1], m.triangles[o][2]);
                    ++turned;
                }
                frontier.push(o);
            }
        }
    }
    return turned;
}

}  // namespace

TriangleMesh fillHoles(const TriangleMesh& mesh, HoleFilling* filling) {
    HoleFilling f;
    TriangleMesh out = mesh;
    f.turned = windAlike(out);
    // The connected pieces, through shared vertices.
    std::vector<int> parent = piecesOf(out);
    std::set<int> shells, open;
    for (const auto& t : out.triangles) shells.insert(root(parent, t[0]));
    // The open edges: a -> b with no b -> a.
    std::set<std::pair<int, int>> directed;
    for (const auto& t : out.triangles)
        for (int k = 0; k < 3; ++k) directed.insert({t[k], t[(k + 1) % 3]});
    std::multimap<int, int> openFrom;  // a -> b, by a
    for (const auto& [a, b] : directed)
        if (!directed.contains({b, a})) openFrom.emplace(a, b);
    // Follow each loop: from b, the open edge that leaves b.
    while (!openFrom.empty()) {
        auto it = openFrom.begin();
        const int start = it->first;
        std::vector<int> loop{start};
        int at = it->second;
        openFrom.erase(it);
        while (at != start) {
            const auto next = openFrom.find(at);
            if (next == openFrom.end()) break;  // a run that does not come back: left open
            loop.push_back(at);
            at = next->second;
            openFrom.erase(next);
        }
        if (at != start || loop.size() < 3) continue;
        Vec3 middle = Vec3::Zero();
        for (int v : loop) middle += mesh.vertices[v];
        middle /= static_cast<double>(loop.size());
        const int c = static_cast<int>(out.vertices.size());
        out.vertices.push_back(middle);
        parent.push_back(root(parent, start));  // the new vertex is of its loop's shell
        // The open edge a -> b gets its twin b -> a in the triangle (c, b, a).
        for (std::size_t k = 0; k < loop.size(); ++k)
            out.triangles.push_back({c, loop[(k + 1) % loop.size()], loop[k]});
        ++f.holes;
        open.insert(root(parent, start));
    }
    // Each closed shell facing outwards on its own (one shell turned inside out would take
    // its volume from the others').
    std::map<int, double> volume;
    for (const auto& t : out.triangles)
        volume[root(parent, t[0])] +=
            out.vertices[t[0]].dot(out.vertices[t[1]].cross(out.vertices[t[2]])) / 6.0;
    for (auto& t : out.triangles) {
        if (volume[root(parent, t[0])] < 0.0) std::swap(t[1], t[2]);
    }
    f.shells = static_cast<int>(shells.size());
    f.openShells = static_cast<int>(open.size());
    f.closed = isClosed(out);
    if (filling) *filling = f;
    return out;
}

std::vector<TriangleMesh> shellsOf(const TriangleMesh& mesh) {
    std::vector<int> parent = piecesOf(mesh);
    std::map<int, int> shellOf;                // root -> shell
    std::vector<std::map<int, int>> renumber;  // per shell: the mesh's vertex -> the shell's
    std::vector<TriangleMesh> out;
    for (const auto& t : mesh.triangles) {
        const auto [it, fresh] = shellOf.emplace(root(parent, t[0]), static_cast<int>(out.size()));
        if (fresh) {
            out.emplace_back();
            renumber.emplace_back();
        }
        TriangleMesh& shell = out[it->second];
        std::array<int, 3> mapped{};
        for (int k = 0; k < 3; ++k) {
            const auto [v, added] =
                renumber[it->second].emplace(t[k], static_cast<int>(shell.vertices.size()));
            if (added) shell.vertices.push_back(mesh.vertices[t[k]]);
            mapped[k] = v->second;
        }
        shell.triangles.push_back(mapped);
    }
    return out;
}

std::string notClosedForParts(const HoleFilling& filling) {
    return "the mesh is not closed, so it bounds no solid to split into convex parts, and filling its " +
           std::to_string(filling.holes) + (filling.holes == 1 ? " hole" : " holes") +
           " did not close it (an edge is shared by more than two triangles, or a run of open edges "
           "does not come back to its start); use \"convex-hull\" or \"triangles\"";
}

}  // namespace tumble::mesh
