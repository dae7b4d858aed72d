// Compile stage, shapes (compile_shape.h).
#include "model/compile_shape.h"

#include <tumble/errors.h>

#include <tumble/convex_parts.h>

#include "collision/bvh.h"
#include "model/compile_compound.h"

#include <cmath>
#include <cstdio>
#include <stdexcept>

namespace tumble::compiling {

void requireFinite(double v, const std::string& path) {
    if (!std::isfinite(v)) throw SceneError(path, "must be a finite number");
}

void requireFinite(const Vec3& v, const std::string& path) {
    if (!v.allFinite()) throw SceneError(path, "must be finite numbers");
}

void requirePositive(double v, const std::string& path) {
    requireFinite(v, path);
    if (!(v > 0.0)) throw SceneError(path, "must be greater than 0");
}

// The largest size a shape may have, in metres: a thousand kilometres. The engine's
// tolerances are fractions of the bodies' sizes, and beyond it its arithmetic loses what a
// scene of everyday bodies needs (a box of 4e93 m made three steps take seconds and its
// energies overflow: the scene fuzzer).
constexpr double kLargestSize = 1e6;

void requireLength(double v, const std::string& path) {
    requirePositive(v, path);
    if (v > kLargestSize) throw SceneError(path, "must be at most 1e6 m");
}

void requireNonNegative(double v, const std::string& path) {
    requireFinite(v, path);
    if (v < 0.0) throw SceneError(path, "must be 0 or greater");
}

void validateShape(const ShapeDesc& s, Motion motion, const std::string& path) {
    switch (s.type) {
        case ShapeType::Sphere: requireLength(s.radius, path + ".radius"); break;
        case ShapeType::Box:
            for (int k = 0; k < 3; ++k) {
                requireLength(s.halfExtents[k], path + ".half_extents[" + std::to_string(k) + "]");
            }
            break;
        case ShapeType::Capsule:
        case ShapeType::Cylinder:
            requireLength(s.radius, path + ".radius");
            requireLength(s.halfHeight, path + ".half_height");
            break;
        case ShapeType::Plane:
            requireFinite(s.normal, path + ".normal");
            requireFinite(s.distance, path + ".distance");
            if (!(s.normal.stableNorm() > 1e-12)) throw SceneError(path + ".normal", "must not be zero");
            if (motion != Motion::Static) {
                throw SceneError(path + ".type", "a plane must belong to a static body");
            }
            break;
        case ShapeType::Mesh:
            if (s.file.empty()) throw SceneError(path + ".file", "must name a mesh file");
            for (int k = 0; k < 3; ++k) {
                requirePositive(s.scale[k], path + ".scale[" + std::to_string(k) + "]");
            }
            if (s.collision == MeshCollision::ConvexParts) {
                if (s.maxParts < 1 || s.maxParts > kMostConvexParts)
                    throw SceneError(path + ".max_parts",
                                     "must be from 1 to " + std::to_string(kMostConvexParts));
                if (s.partsTolerance) requireLength(*s.partsTolerance, path + ".tolerance");
            }
            break;
        case ShapeType::Compound: validateParts(s, motion, path); break;
    }
}

mesh::PreparedMesh prepareMeshShape(const ShapeDesc& s, bool wantMass, const std::string& path) {
    const std::string field = path + ".file";
    if (!s.meshData) {
        throw SceneError(field, "the mesh '" + s.file +
                                    "' was never loaded (scenes read with io::readSceneFile load their "
                                    "meshes; a scene built in code must set shape.meshData)");
    }
    mesh::PreparedMesh p;
    try {
        p = mesh::prepareMesh(*s.meshData, s.collision == MeshCollision::ConvexHull, wantMass,
                              s.collision == MeshCollision::ConvexParts);
    } catch (const std::invalid_argument& e) {
        throw SceneError(field, s.file + ": " + e.what());
    }
    if (p.surface.triangles.empty()) {
        throw SceneError(field, s.file + ": has no triangles with an area (every one is degenerate)");
    }
    if (s.collision == MeshCollision::ConvexParts && !p.closed) {
        throw SceneError(path + ".collision", s.file + ": " + mesh::notClosedForParts(p.filling));
    }
    return p;
}

void noteMesh(const ShapeDesc& s, bool dynamic, const std::string& who, const mesh::PreparedMesh& p,
              std::vector<std::string>& notes) {
    const bool filled = p.filling.holes > 0 && p.filling.closed;
    if (filled) {
        notes.push_back(who + "the mesh was open: its " + std::to_string(p.filling.holes) +
                        (p.filling.holes == 1 ? " hole was" : " holes were") + " filled (in " +
                        std::to_string(p.filling.openShells) + " of its " + std::to_string(p.filling.shells) +
                        (p.filling.shells == 1 ? " piece" : " pieces") + ") to split it into convex parts" +
                        (dynamic ? "; mass properties come from the filled surface" : ""));
    } else if (dynamic) {
        notes.push_back(who + (p.closed
                                   ? "the mesh is closed; mass properties come from its surface"
                                   : "the mesh is not closed; mass properties come from its convex hull"));
    }
    if (p.turnedOutward) notes.push_back(who + "the mesh's triangles face inwards; they were turned around");
    if (p.stats.degenerateTriangles > 0 || p.stats.duplicateTriangles > 0) {
        notes.push_back(who + std::to_string(p.stats.degenerateTriangles) + " degenerate and " +
                        std::to_string(p.stats.duplicateTriangles) +
                        " repeated triangles of the mesh were dropped");
    }
    if (s.collision == MeshCollision::Triangles && !p.closed) {
        notes.push_back(who +
                        "the mesh is not closed; as collision \"triangles\" it is a surface with no inside");
    }
}

collision::Shape colliderOf(const ShapeDesc& s, const std::string& path, const mesh::PreparedMesh* prepared) {
    using collision::Shape;
    switch (s.type) {
        case ShapeType::Sphere: return Shape::sphere(s.radius);
        case ShapeType::Box: return Shape::box(s.halfExtents);
        case ShapeType::Capsule: return Shape::capsule(s.radius, s.halfHeight);
        case ShapeType::Cylinder: return Shape::cylinder(s.radius, s.halfHeight);
        case ShapeType::Plane: return Shape::plane(s.normal.stableNormalized(), s.distance);
        case ShapeType::Mesh: break;
        case ShapeType::Compound:
            throw std::logic_error("colliderOf: a compound's collider is compoundCollider's");
    }
    if (!prepared) throw SceneError(path + ".file", "the mesh '" + s.file + "' was never loaded");
    Shape shape;
    if (s.collision == MeshCollision::ConvexHull) {
        if (!prepared->hull) {
            throw SceneError(path + ".file", s.file + ": has no convex hull: " + prepared->hullProblem +
                                                 "; use \"collision\": \"triangles\" for a flat mesh");
        }
        shape.kind = collision::Kind::Hull;
        shape.hull = prepared->hull;
    } else {
        auto m = std::make_shared<collision::MeshShape>();
        m->vertices = prepared->surface.vertices;
        m->triangles = prepared->surface.triangles;
        m->closed = prepared->closed;
        m->bvh = std::make_shared<const collision::TriangleBvh>(m->vertices, m->triangles);
        shape.kind = collision::Kind::Mesh;
        shape.mesh = std::move(m);
    }
    return shape;
}

collision::Shape convexPartsCollider(const ShapeDesc& s, const std::string& path, const std::string& who,
                                     double friction, double restitution, std::vector<std::string>& notes) {
    std::shared_ptr<const mesh::ConvexParts> parts = s.convexParts;
    if (!parts || !mesh::convexPartsFit(*parts, s)) {
        try {
            parts = std::make_shared<const mesh::ConvexParts>(mesh::convexPartsOfShape(s));
        } catch (const std::invalid_argument& e) {
            throw SceneError(path + ".collision", s.file + ": " + e.what());
        }
        char text[256];
        std::snprintf(
            text, sizeof text,
            "split into %zu convex parts in %.2f s (their hulls %+.1f %% of the mesh's volume, reaching "
            "out of it %.3g m at most%s)",
            parts->parts.size(), parts->seconds, 100.0 * (parts->partsVolume / parts->meshVolume - 1.0),
            parts->largestPokeOut,
            parts->withinTolerance ? "" : "; max_parts was reached before the tolerance");
        notes.push_back(who + text);
    }
    auto compound = std::make_shared<collision::Compound>();
    for (const collision::ConvexHull& hull : parts->parts) {
        collision::Compound::Part part;
        part.shape.kind = collision::Kind::Hull;
        part.shape.hull = std::make_shared<const collision::ConvexHull>(hull);
        part.box = bounds(part.shape, part.pose);
        part.friction = friction;
        part.restitution = restitution;
        compound->box.add(part.box);
        compound->parts.push_back(std::move(part));
    }
    collision::Shape shape;
    shape.kind = collision::Kind::Compound;
    shape.compound = std::move(compound);
    return shape;
}

}  // namespace tumble::compiling
