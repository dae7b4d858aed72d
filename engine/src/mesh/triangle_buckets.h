// Triangles bucketed for the convex-parts split (convex_parts.cpp): by their yz bounds, for
// lines along x (which points lie inside the solid, by the parity of the crossings), and by
// their 3D bounds, for a point's distance to the surface. Internal to the engine.
#pragma once

#include <tumble/collision.h>
#include <tumble/mass.h>

#include <array>
#include <cstddef>
#include <vector>

namespace tumble::mesh {

class Buckets {
public:
    explicit Buckets(const TriangleMesh& m);

    /// Sorted x of every crossing of the line {x, y, z}.
    void crossings(double y, double z, std::vector<double>& xs) const;
    /// Whether p is inside the solid the (closed) mesh bounds: the parity of the crossings.
    bool inside(const Vec3& p) const;
    /// Distance to the nearest triangle: cells searched in shells until the nearest found is
    /// nearer than any unsearched cell can be.
    double distance(const Vec3& p) const;
    const collision::Aabb& box() const { return box_; }

private:
    std::array<int, 3> cellOf(const Vec3& p) const;
    std::size_t index(int i, int j, int k) const { return static_cast<std::size_t>(i + n_ * (j + n_ * k)); }

    const TriangleMesh& m_;
    collision::Aabb box_;
    int n_ = 1;
    Vec3 cell_;
    std::vector<std::vector<int>> yz_, xyz_;
};

}  // namespace tumble::mesh
