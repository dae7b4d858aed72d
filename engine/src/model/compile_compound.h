// Compile stage, compound bodies (ShapeType::Compound): the checks of their parts, and the
// collider and mass properties made of the parts (docs/scene-format.md "Compound bodies").
#pragma once

#include <tumble/collision.h>
#include <tumble/mass.h>
#include <tumble/scene.h>

#include <string>
#include <vector>

namespace tumble::compiling {

/// The most parts a compound may have (a manifold names its parts in 16 bits; a mesh split
/// into convex parts has 16 by default).
inline constexpr int kMostParts = 1024;

/// The values of a compound's parts, `path` naming the shape ("bodies[2].shape"): one part
/// at least and kMostParts at most, none a plane or a compound, each part's shape, pose,
/// friction, restitution and density. A part of a body that is not dynamic has no density.
void validateParts(const ShapeDesc& s, Motion motion, const std::string& path);

/// What a compound body's mass is made of, `path` naming the body ("bodies[2]"): a
/// dynamic body gives mass or density, or neither when every part has its own density; a
/// body's mass is shared by volume among the parts without their own density, so there
/// must be some.
void validateCompoundMass(const BodyDesc& b, const std::string& path);

struct BuiltCompound {
    collision::Shape collider;  ///< kind Compound
    MassProperties mass;        ///< body frame; dynamic bodies only
};

/// The collider of a compound body's parts (each part's friction and restitution its own,
/// or the body's) and, for a dynamic body, the exact sum of the parts' mass properties
/// (parallel axes): each part of its own density, the body's, or a share of the body's mass
/// by volume. Mesh parts are prepared as mesh bodies are; `who` ("bodies[3] (cart): ")
/// starts their notes. Throws SceneError naming the field.
BuiltCompound buildCompound(const BodyDesc& b, const std::string& path, const std::string& who,
                            std::vector<std::string>& notes);

}  // namespace tumble::compiling
