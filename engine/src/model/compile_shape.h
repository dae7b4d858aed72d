// Compile stage, shapes: the checks of a shape's values, a mesh shape's preparation, the
// collider of a shape, and the value checks the rest of compile shares. Each takes the
// path of the field it checks ("bodies[2].shape", "bodies[2].shape.parts[1].shape"), so a
// compound's parts are checked and built as bodies' shapes are.
#pragma once

#include <tumble/collision.h>
#include <tumble/scene.h>

#include "mesh/mesh_body.h"

#include <string>
#include <vector>

namespace tumble::compiling {

/// The largest energy, momentum or reach a body may start with, or a key may place it at: a
/// run squares and sums them (contact impulses, the energy guard), so 1e308 loaded and then
/// stopped as "ran away ... energy rose by -nan J"; refused, naming the field.
inline constexpr double kLargestHeld = 1e150;

/// The most parts a mesh may be split into (max_parts).
inline constexpr int kMostConvexParts = 256;

/// Each throws SceneError(path, ...) for a value outside its range.
void requireFinite(double v, const std::string& path);
void requireFinite(const Vec3& v, const std::string& path);
void requirePositive(double v, const std::string& path);
/// Positive and at most 1e6 m: the largest size a shape may have.
void requireLength(double v, const std::string& path);
void requireNonNegative(double v, const std::string& path);

/// The values of a shape (`path` names it) of a body moving as `motion`. A compound's
/// parts are checked by compiling::validateParts (compile_compound.h), which this calls.
void validateShape(const ShapeDesc& s, Motion motion, const std::string& path);

/// A mesh shape's geometry, cleaned, with what its collider and mass need (`wantMass`: the
/// solid integrated). The mesh file is read by the scene loader (tumble_io); a scene built
/// in code must fill meshData itself. Throws SceneError naming path + ".file".
mesh::PreparedMesh prepareMeshShape(const ShapeDesc& s, bool wantMass, const std::string& path);

/// Things worth telling the user about a mesh shape (`who`: "bodies[3] (rock): "): where
/// its mass comes from (`dynamic`), and what cleaning changed.
void noteMesh(const ShapeDesc& s, bool dynamic, const std::string& who, const mesh::PreparedMesh& p,
              std::vector<std::string>& notes);

/// The collision shape of a primitive, or of a mesh from its prepared geometry. Not for a
/// compound (compiling::compoundCollider).
collision::Shape colliderOf(const ShapeDesc& s, const std::string& path, const mesh::PreparedMesh* prepared);

/// The collider of a mesh shape with collision convex-parts: a compound of the parts'
/// hulls, each of the given material. The parts are the shape's own (ShapeDesc::convexParts)
/// when they fit its mesh and options, else they are made here, with a note (`who` starts
/// it) of how many, how long, and how well. Throws SceneError naming path + ".collision"
/// when the mesh bounds no solid.
collision::Shape convexPartsCollider(const ShapeDesc& s, const std::string& path, const std::string& who,
                                     double friction, double restitution, std::vector<std::string>& notes);

}  // namespace tumble::compiling
