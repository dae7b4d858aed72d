#include "document/grouping.h"

#include <tumble/errors.h>
#include <tumble/mass.h>
#include <tumble/model.h>

#include <algorithm>
#include <set>

namespace tumble::ui {

namespace {

std::string who(const SceneDesc& scene, int i) {
    return "bodies[" + std::to_string(i) + "] (" + scene.bodies[static_cast<size_t>(i)].name + ")";
}

// The volume of a shape that is not a compound (m³), or nothing for a mesh without a closed,
// loaded mesh.
std::optional<double> volumeOf(const ShapeDesc& s) {
    if (s.type != ShapeType::Mesh) return shapeVolume(s);
    if (!s.meshData || !isClosed(*s.meshData)) return std::nullopt;
    double volume = 0.0;
    meshMassProperties(*s.meshData, 1.0, &volume);
    return std::abs(volume) > 0.0 ? std::optional(std::abs(volume)) : std::nullopt;
}

// A body as parts (its own shape as one, or a compound's parts), each with the density that
// gives it its mass (dynamic bodies only: nullopt otherwise), in the body's frame.
struct Piece {
    PartDesc part;
    std::optional<double> density;
};

std::optional<std::vector<Piece>> piecesOf(const BodyDesc& b, std::string* why, const std::string& name) {
    std::vector<Piece> pieces;
    if (b.shape.type != ShapeType::Compound) {
        Piece p;
        p.part.name = b.name;
        p.part.shape = b.shape;
        pieces.push_back(p);
    } else {
        for (const PartDesc& part : b.shape.parts) pieces.push_back({part, part.density});
    }
    if (b.motion != Motion::Dynamic) {
        for (Piece& p : pieces) p.density.reset();
        return pieces;
    }
    // The others' density: the body's, or what its mass leaves over their volume.
    double ownMass = 0.0, sharedVolume = 0.0;
    for (const Piece& p : pieces) {
        const auto v = volumeOf(p.part.shape);
        if (!v) {
            if (why)
                *why =
                    name + ": its mesh is not loaded or not closed, so its volume (for its mass) is unknown";
            return std::nullopt;
        }
        if (p.density)
            ownMass += *p.density * *v;
        else
            sharedVolume += *v;
    }
    double shared = b.density.value_or(0.0);
    if (b.mass && sharedVolume > 0.0) shared = (*b.mass - ownMass) / sharedVolume;
    for (Piece& p : pieces)
        if (!p.density) p.density = shared;
    return pieces;
}

// A shape's centre of mass in its frame: its origin, or a closed mesh's own centre.
Vec3 centreOf(const ShapeDesc& s) {
    if (s.type != ShapeType::Mesh || !s.meshData || !isClosed(*s.meshData)) return Vec3::Zero();
    return meshMassProperties(*s.meshData, 1.0).centerOfMass;
}

// `base`, or `base 2`, `base 3` ... : the first not in `taken`.
std::string uniqueName(const std::string& base, const std::set<std::string>& taken) {
    std::string name = base;
    for (int k = 2; taken.count(name); ++k) name = base + " " + std::to_string(k);
    return name;
}

}  // namespace

std::optional<Regrouped> groupBodies(const SceneDesc& scene, std::vector<int> indices, std::string* why) {
    std::sort(indices.begin(), indices.end());
    indices.erase(std::unique(indices.begin(), indices.end()), indices.end());
    auto fail = [&](const std::string& reason) -> std::optional<Regrouped> {
        if (why) *why = reason;
        return std::nullopt;
    };
    if (indices.size() < 2) return fail("select two bodies or more to group");
    for (int i : indices)
        if (i < 0 || i >= static_cast<int>(scene.bodies.size())) return fail("no such body");
    const BodyDesc& first = scene.bodies[static_cast<size_t>(indices.front())];
    Vec3 centre = Vec3::Zero();
    for (int i : indices) {
        const BodyDesc& b = scene.bodies[static_cast<size_t>(i)];
        if (b.shape.type == ShapeType::Plane)
            return fail(who(scene, i) + " is a plane, which cannot be a part");
        if (!b.forces.empty())
            return fail(who(scene, i) + " has forces; remove them, group, and give them to the group");
        if (b.motion != first.motion)
            return fail(who(scene, i) + " is " + toString(b.motion) + " and " + who(scene, indices.front()) +
                        " " + toString(first.motion) + "; group bodies that move alike");
        if (b.motion == Motion::Animated)
            return fail(who(scene, i) + " is animated; group the bodies first, then key the group");
        if (b.motion == Motion::Kinematic &&
            (b.velocity != first.velocity || b.angularVelocity != first.angularVelocity))
            return fail(who(scene, i) + " moves otherwise than " + who(scene, indices.front()) +
                        "; kinematic bodies grouped must move alike");
        centre += b.position / static_cast<double>(indices.size());
    }

    BodyDesc group;
    group.name = first.name + " group";
    group.motion = first.motion;
    group.shape.type = ShapeType::Compound;
    group.position = centre;
    group.restitution = first.restitution;
    group.friction = first.friction;
    double mass = 0.0;
    Vec3 momentum = Vec3::Zero();
    bool sameSpin = true;
    for (int i : indices) {
        const BodyDesc& b = scene.bodies[static_cast<size_t>(i)];
        const auto pieces = piecesOf(b, why, who(scene, i));
        if (!pieces) return std::nullopt;
        const Quat q = b.orientation.normalized();
        for (const Piece& p : *pieces) {
            PartDesc part = p.part;
            if (part.name.empty() || b.shape.type == ShapeType::Compound)
                part.name = part.name.empty() ? b.name : b.name + " " + part.name;
            part.position = q * part.position + b.position - centre;
            part.orientation = (q * part.orientation.normalized()).normalized();
            part.density = p.density;
            if (!part.friction) part.friction = b.friction;
            if (!part.restitution) part.restitution = b.restitution;
            group.shape.parts.push_back(part);
            if (p.density) {
                const double m = *p.density * *volumeOf(part.shape);
                mass += m;
                momentum += m * b.velocity;
            }
        }
        sameSpin = sameSpin && b.angularVelocity == first.angularVelocity;
    }
    if (group.motion == Motion::Dynamic) {
        group.velocity = mass > 0.0 ? Vec3(momentum / mass) : first.velocity;
        group.angularVelocity = sameSpin ? first.angularVelocity : Vec3::Zero();
    } else {
        group.velocity = first.velocity;
        group.angularVelocity = first.angularVelocity;
    }

    std::set<std::string> grouped;
    for (int i : indices) grouped.insert(scene.bodies[static_cast<size_t>(i)].name);
    std::set<std::string> others;  // the names the group's may not take
    for (const BodyDesc& b : scene.bodies)
        if (!grouped.count(b.name)) others.insert(b.name);
    group.name = uniqueName(group.name, others);
    group.collisionGroup = scene.bodies[static_cast<size_t>(indices.front())].collisionGroup;
    Regrouped out;
    out.scene = scene;
    out.scene.bodies.clear();
    for (size_t i = 0; i < scene.bodies.size(); ++i) {
        if (static_cast<int>(i) == indices.front()) {
            out.bodies = {static_cast<int>(out.scene.bodies.size())};
            out.scene.bodies.push_back(group);
        } else if (!grouped.count(scene.bodies[i].name)) {
            out.scene.bodies.push_back(scene.bodies[i]);
        }
    }
    // Joints: those inside the group go; the others' anchors and axes into its frame.
    out.scene.joints.clear();
    auto into = [&](const std::string& body, const Vec3& anchor) {
        for (int i : indices) {
            const BodyDesc& b = scene.bodies[static_cast<size_t>(i)];
            if (b.name == body) return Vec3(b.orientation.normalized() * anchor + b.position - centre);
        }
        return anchor;
    };
    auto turn = [&](const std::string& body, const Vec3& axis) {
        for (int i : indices) {
            const BodyDesc& b = scene.bodies[static_cast<size_t>(i)];
            if (b.name == body) return Vec3(b.orientation.normalized() * axis);
        }
        return axis;
    };
    for (JointDesc j : scene.joints) {
        const bool a = grouped.count(j.bodyA) > 0, bIn = !j.bodyB.empty() && grouped.count(j.bodyB) > 0;
        if (a && bIn) continue;
        if (a) {
            j.anchorA = into(j.bodyA, j.anchorA);
            if (j.axisA) j.axisA = turn(j.bodyA, *j.axisA);
            j.bodyA = group.name;
        }
        if (bIn) {
            j.anchorB = into(j.bodyB, j.anchorB);
            if (j.axisB) j.axisB = turn(j.bodyB, *j.axisB);
            j.bodyB = group.name;
        }
        out.scene.joints.push_back(j);
    }
    // Pairs kept apart: a grouped body's name becomes the group's; a pair inside it goes.
    out.scene.noCollide.clear();
    for (auto pair : scene.noCollide) {
        for (std::string& name : pair)
            if (grouped.count(name)) name = group.name;
        if (pair[0] != pair[1] && std::find(out.scene.noCollide.begin(), out.scene.noCollide.end(), pair) ==
                                      out.scene.noCollide.end())
            out.scene.noCollide.push_back(pair);
    }
    return out;
}

std::optional<Regrouped> ungroupBody(const SceneDesc& scene, int index, std::string* why) {
    auto fail = [&](const std::string& reason) -> std::optional<Regrouped> {
        if (why) *why = reason;
        return std::nullopt;
    };
    if (index < 0 || index >= static_cast<int>(scene.bodies.size())) return fail("no such body");
    const BodyDesc& g = scene.bodies[static_cast<size_t>(index)];
    if (g.shape.type != ShapeType::Compound)
        return fail(who(scene, index) + " is not a compound; nothing to ungroup");
    // (Its parts' own keys would not move them as one: between keys that turn it, each
    // part's straight line is not the arc the group's turn takes it along.)
    if (g.motion == Motion::Animated)
        return fail(who(scene, index) + " is animated; make it dynamic, static or kinematic first");
    for (const JointDesc& j : scene.joints)
        if (j.bodyA == g.name || j.bodyB == g.name)
            return fail(who(scene, index) + " is held by the joint '" + j.name +
                        "'; move it to another body or remove it first");
    const auto pieces = piecesOf(g, why, who(scene, index));
    if (!pieces) return std::nullopt;
    const Quat q = g.orientation.normalized();
    // The compound's centre of mass in the world, for its parts' velocities.
    Vec3 centre = g.position;
    if (g.motion == Motion::Dynamic && !g.angularVelocity.isZero(0.0)) {
        SceneDesc one;
        one.bodies = {g};
        try {
            centre = g.position + q * compile(one).bodies[0].centerOfMass;
        } catch (const SceneError& e) {
            return fail(who(scene, index) + ": " + e.message());
        }
    }
    Regrouped out;
    out.scene = scene;
    out.scene.bodies.erase(out.scene.bodies.begin() + index);
    std::set<std::string> taken;
    for (const BodyDesc& b : out.scene.bodies) taken.insert(b.name);
    std::vector<BodyDesc> made;
    for (size_t k = 0; k < pieces->size(); ++k) {
        const Piece& p = (*pieces)[k];
        BodyDesc b;
        b.name = uniqueName(p.part.name.empty() ? g.name + " " + std::to_string(k + 1) : p.part.name, taken);
        taken.insert(b.name);
        b.motion = g.motion;
        b.shape = p.part.shape;
        b.density = p.density;
        b.position = q * p.part.position + g.position;
        b.orientation = (q * p.part.orientation.normalized()).normalized();
        b.friction = p.part.friction.value_or(g.friction);
        b.restitution = p.part.restitution.value_or(g.restitution);
        b.linearDamping = g.linearDamping;
        b.angularDamping = g.angularDamping;
        b.collisionGroup = g.collisionGroup;
        // The velocity of the compound's point where the part's centre of mass is.
        b.velocity = g.velocity +
                     g.angularVelocity.cross(
                         q * (p.part.position + p.part.orientation.normalized() * centreOf(p.part.shape)) +
                         g.position - centre);
        b.angularVelocity = g.angularVelocity;
        made.push_back(b);
    }
    for (size_t k = 0; k < made.size(); ++k) {
        out.scene.bodies.insert(out.scene.bodies.begin() + index + static_cast<long>(k), made[k]);
        out.bodies.push_back(index + static_cast<int>(k));
    }
    // A pair kept apart with the compound: each of its bodies kept apart from the other.
    out.scene.noCollide.clear();
    for (const auto& pair : scene.noCollide) {
        if (pair[0] != g.name && pair[1] != g.name) {
            out.scene.noCollide.push_back(pair);
            continue;
        }
        const std::string& other = pair[0] == g.name ? pair[1] : pair[0];
        for (const BodyDesc& b : made) out.scene.noCollide.push_back({b.name, other});
    }
    return out;
}

}  // namespace tumble::ui
