// Compile stage, compound bodies (compile_compound.h).
#include "model/compile_compound.h"

#include <tumble/errors.h>
#include <tumble/mass.h>

#include "common/number_text.h"
#include "model/compile_shape.h"

#include <algorithm>
#include <optional>

namespace tumble::compiling {

namespace {

std::string partPath(const std::string& shapePath, size_t j) {
    return shapePath + ".parts[" + std::to_string(j) + "]";
}

// A part's solid at density 1, in the part's frame.
struct UnitSolid {
    double volume = 0.0;
    MassProperties props;
};

}  // namespace

void validateParts(const ShapeDesc& s, Motion motion, const std::string& path) {
    if (s.parts.empty()) throw SceneError(path + ".parts", "a compound needs at least one part");
    if (s.parts.size() > static_cast<size_t>(kMostParts))
        throw SceneError(path + ".parts", "has " + std::to_string(s.parts.size()) + " parts; at most " +
                                              std::to_string(kMostParts));
    for (size_t j = 0; j < s.parts.size(); ++j) {
        const PartDesc& part = s.parts[j];
        const std::string p = partPath(path, j);
        if (part.shape.type == ShapeType::Compound)
            throw SceneError(p + ".shape.type",
                             "a part cannot be a compound (nested compounds are not supported: list its "
                             "parts in this one)");
        if (part.shape.type == ShapeType::Plane)
            throw SceneError(p + ".shape.type", "a plane cannot be a part; make it a static body of its own");
        validateShape(part.shape, motion, p + ".shape");
        requireFinite(part.position, p + ".position");
        if (!part.orientation.coeffs().allFinite())
            throw SceneError(p + ".orientation", "must be finite numbers");
        if (!(part.orientation.coeffs().stableNorm() > 1e-12))
            throw SceneError(p + ".orientation", "must not be the zero quaternion");
        if (part.friction) requireNonNegative(*part.friction, p + ".friction");
        if (part.restitution) {
            requireNonNegative(*part.restitution, p + ".restitution");
            if (*part.restitution > 1.0) throw SceneError(p + ".restitution", "must be between 0 and 1");
        }
        if (part.density) {
            if (motion != Motion::Dynamic)
                throw SceneError(p + ".density", std::string(motion == Motion::Animated ? "an " : "a ") +
                                                     toString(motion) +
                                                     " body has no mass properties; remove it");
            requirePositive(*part.density, p + ".density");
        }
    }
}

namespace {

std::string tooLittleMass(double fixedMass) {
    return "is not more than the " + numberText(fixedMass) +
           " kg of the parts with their own density: nothing is left for the others";
}

}  // namespace

void validateCompoundMass(const BodyDesc& b, const std::string& path) {
    const auto& parts = b.shape.parts;
    size_t own = 0;
    for (const PartDesc& part : parts) own += part.density ? 1 : 0;
    if (b.mass && b.density) throw SceneError(path, "give mass or density, not both");
    if (b.mass) requirePositive(*b.mass, path + ".mass");
    if (b.density) requirePositive(*b.density, path + ".density");
    if (b.mass && own == parts.size())
        throw SceneError(path + ".mass",
                         "every part has its own density, so the mass follows from them; remove mass (or a "
                         "part's density, to give that part a share of it)");
    // The parts of their own density must leave some of the body's mass for the others. Their
    // volumes are known here for primitives; a mesh part's needs its hull (buildCompound says).
    if (b.mass && std::none_of(parts.begin(), parts.end(), [](const PartDesc& part) {
            return part.density && part.shape.type == ShapeType::Mesh;
        })) {
        double fixedMass = 0.0;
        for (const PartDesc& part : parts)
            if (part.density) fixedMass += *part.density * shapeVolume(part.shape);
        if (!(*b.mass > fixedMass)) throw SceneError(path + ".mass", tooLittleMass(fixedMass));
    }
    if (!b.mass && !b.density) {
        for (size_t j = 0; j < parts.size(); ++j)
            if (!parts[j].density)
                throw SceneError(partPath(path + ".shape", j) + ".density",
                                 "is needed: the body has neither mass nor density to share with this part");
    }
}

BuiltCompound buildCompound(const BodyDesc& b, const std::string& path, const std::string& who,
                            std::vector<std::string>& notes) {
    const bool dynamic = b.motion == Motion::Dynamic;
    const std::string shapePath = path + ".shape";
    auto compound = std::make_shared<collision::Compound>();
    std::vector<UnitSolid> solids;
    for (size_t j = 0; j < b.shape.parts.size(); ++j) {
        const PartDesc& d = b.shape.parts[j];
        const std::string p = partPath(shapePath, j);
        std::optional<mesh::PreparedMesh> prepared;
        if (d.shape.type == ShapeType::Mesh) {
            prepared = prepareMeshShape(d.shape, dynamic, p + ".shape");
            noteMesh(d.shape, dynamic, who + "part " + std::to_string(j) + ": ", *prepared, notes);
        }
        collision::Compound::Part part;
        part.pose.R = d.orientation.normalized().toRotationMatrix();
        part.pose.p = d.position;
        part.friction = d.friction.value_or(b.friction);
        part.restitution = d.restitution.value_or(b.restitution);
        if (d.shape.type == ShapeType::Mesh && d.shape.collision == MeshCollision::ConvexParts) {
            // A mesh split into convex parts: each hull a part of this compound, in the
            // part's frame (a compound holds no compound).
            const collision::Shape split =
                convexPartsCollider(d.shape, p + ".shape", who + "part " + std::to_string(j) + ": ",
                                    part.friction, part.restitution, notes);
            for (collision::Compound::Part hull : split.compound->parts) {
                hull.pose = part.pose * hull.pose;
                hull.box = bounds(hull.shape, hull.pose);
                compound->box.add(hull.box);
                compound->parts.push_back(std::move(hull));
            }
        } else {
            part.shape = colliderOf(d.shape, p + ".shape", prepared ? &*prepared : nullptr);
            part.box = bounds(part.shape, part.pose);
            compound->box.add(part.box);
            compound->parts.push_back(std::move(part));
        }
        if (!dynamic) continue;
        UnitSolid solid;
        if (prepared) {
            if (!(prepared->volume > 0.0))
                throw SceneError(p + ".shape.file",
                                 d.shape.file +
                                     ": the mesh encloses no volume, so it cannot be a part "
                                     "of a dynamic body");
            solid.volume = prepared->volume;
            solid.props = prepared->unitDensity;
        } else {
            solid.volume = shapeVolume(d.shape);
            solid.props = primitiveMassProperties(d.shape, solid.volume);
        }
        solids.push_back(solid);
    }
    if (compound->parts.size() > static_cast<size_t>(kMostParts))
        throw SceneError(shapePath + ".parts",
                         "makes " + std::to_string(compound->parts.size()) +
                             " collision parts with its meshes' convex parts; at most " +
                             std::to_string(kMostParts));
    BuiltCompound built;
    built.collider.kind = collision::Kind::Compound;
    built.collider.compound = compound;
    if (!dynamic) return built;

    // Each part's density: its own, the body's, or the body's mass less the parts of their
    // own density, shared by volume.
    const auto& parts = b.shape.parts;
    double fixedMass = 0.0, sharedVolume = 0.0;
    for (size_t j = 0; j < parts.size(); ++j) {
        if (parts[j].density)
            fixedMass += *parts[j].density * solids[j].volume;
        else
            sharedVolume += solids[j].volume;
    }
    double sharedDensity = b.density.value_or(0.0);
    if (b.mass) {
        if (!(*b.mass > fixedMass)) throw SceneError(path + ".mass", tooLittleMass(fixedMass));
        sharedDensity = (*b.mass - fixedMass) / sharedVolume;
    }
    // Mass and centre of mass, then the inertia about that centre (parallel axes).
    MassProperties& mp = built.mass;
    std::vector<double> masses(parts.size());
    std::vector<Vec3> centres(parts.size());
    for (size_t j = 0; j < parts.size(); ++j) {
        masses[j] = parts[j].density.value_or(sharedDensity) * solids[j].volume;
        const collision::Pose& pose = compound->parts[j].pose;
        centres[j] = pose.toWorld(solids[j].props.centerOfMass);
        mp.mass += masses[j];
        mp.centerOfMass += masses[j] * centres[j];
    }
    mp.centerOfMass /= mp.mass;
    for (size_t j = 0; j < parts.size(); ++j) {
        const Mat3& R = compound->parts[j].pose.R;
        const double density = masses[j] / solids[j].volume;
        const Vec3 r = centres[j] - mp.centerOfMass;
        mp.inertia += density * (R * solids[j].props.inertia * R.transpose()) +
                      masses[j] * (r.squaredNorm() * Mat3::Identity() - r * r.transpose());
    }
    mp.inertia = 0.5 * (mp.inertia + mp.inertia.transpose());
    return built;
}

}  // namespace tumble::compiling
