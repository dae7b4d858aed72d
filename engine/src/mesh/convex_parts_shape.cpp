// A scene's mesh shape split into convex parts (tumble/convex_parts.h): the shape's options,
// its mesh's hash, and the split of its cleaned mesh, timed.
#include <tumble/convex_parts.h>
#include <tumble/scene.h>

#include "mesh/mesh_body.h"

#include <chrono>
#include <cstring>
#include <stdexcept>

namespace tumble::mesh {

std::uint64_t meshHash(const TriangleMesh& mesh) {
    // FNV-1a over the bytes of the vertices and the triangles, with their counts.
    std::uint64_t h = 1469598103934665603ull;
    auto add = [&](const void* data, std::size_t bytes) {
        const auto* p = static_cast<const unsigned char*>(data);
        for (std::size_t i = 0; i < bytes; ++i) {
            h ^= p[i];
            h *= 1099511628211ull;
        }
    };
    const std::uint64_t counts[2] = {mesh.vertices.size(), mesh.triangles.size()};
    add(counts, sizeof counts);
    for (const Vec3& v : mesh.vertices) {
        const double xyz[3] = {v.x() == 0.0 ? 0.0 : v.x(), v.y() == 0.0 ? 0.0 : v.y(),
                               v.z() == 0.0 ? 0.0 : v.z()};
        add(xyz, sizeof xyz);
    }
    for (const auto& t : mesh.triangles) add(t.data(), sizeof(int) * 3);
    return h;
}

ConvexPartsOptions convexPartsOptionsOf(const ShapeDesc& shape) {
    ConvexPartsOptions o;
    o.maxParts = shape.maxParts;
    o.tolerance = shape.partsTolerance.value_or(0.0);
    return o;
}

bool convexPartsFit(const ConvexParts& parts, const ShapeDesc& shape) {
    const ConvexPartsOptions o = convexPartsOptionsOf(shape);
    return shape.meshData && parts.meshHash == meshHash(*shape.meshData) &&
           parts.options.maxParts == o.maxParts && parts.options.tolerance == o.tolerance &&
           parts.options.resolution == o.resolution;
}

ConvexParts convexPartsOfShape(const ShapeDesc& shape, const ConvexPartsProgress& progress) {
    if (!shape.meshData) throw std::invalid_argument("the mesh '" + shape.file + "' was never loaded");
    const auto start = std::chrono::steady_clock::now();
    const PreparedMesh prepared = prepareMesh(*shape.meshData, false, false, true);
    if (!prepared.closed) throw std::invalid_argument(notClosedForParts(prepared.filling));
    const ConvexPartsOptions options = convexPartsOptionsOf(shape);
    ConvexParts parts = convexParts(prepared.surface, options, progress);
    parts.meshHash = meshHash(*shape.meshData);
    parts.filledHoles = prepared.filling.closed ? prepared.filling.holes : 0;
    parts.options = options;
    parts.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    return parts;
}

}  // namespace tumble::mesh
