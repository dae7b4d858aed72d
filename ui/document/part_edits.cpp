#include "document/part_edits.h"

#include "document/body_presets.h"

#include <tumble/errors.h>
#include <tumble/model.h>

#include <algorithm>
#include <set>

namespace tumble::ui {

namespace {

// How far a part reaches above its own frame's origin along the body's y axis (a bound:
// a turned part is taken by its bounding sphere).
double reachUp(const PartDesc& p) {
    BodyDesc asBody;
    asBody.shape = p.shape;
    asBody.orientation = p.orientation;
    return halfHeightAboveOrigin(asBody);
}

// Why the scene holding only `body` would be refused, or "" if it would not.
std::string refusal(const BodyDesc& body) {
    SceneDesc check;
    check.bodies.push_back(body);
    try {
        validate(check);
    } catch (const SceneError& e) {
        std::string path = e.path();
        const auto dot = path.find('.');
        path = dot == std::string::npos ? std::string() : path.substr(dot + 1);
        return (path.empty() ? std::string() : path + ": ") + e.message();
    }
    return {};
}

}  // namespace

std::string partLabel(const PartDesc& part, int index) {
    return part.name.empty() ? "part " + std::to_string(index + 1) : part.name;
}

std::optional<BodyDesc> withPartAdded(const BodyDesc& body, ShapeType type, std::string* why) {
    auto refuse = [&](std::string reason) -> std::optional<BodyDesc> {
        if (why) *why = std::move(reason);
        return std::nullopt;
    };
    if (type != ShapeType::Sphere && type != ShapeType::Box && type != ShapeType::Capsule &&
        type != ShapeType::Cylinder)
        return refuse(std::string("a part added here is a sphere, box, capsule or cylinder, not a ") +
                      toString(type));
    if (body.shape.type == ShapeType::Plane) return refuse("a plane cannot have parts");
    BodyDesc out = body;
    if (out.shape.type != ShapeType::Compound) {
        PartDesc base;
        base.name = "base";
        base.shape = body.shape;
        base.shape.parts.clear();
        out.shape = ShapeDesc{};
        out.shape.type = ShapeType::Compound;
        out.shape.parts.push_back(std::move(base));
    }
    PartDesc part;
    part.shape = presetBody(type, SceneDesc{}).shape;
    part.shape.radius /= 2;
    part.shape.halfHeight /= 2;
    part.shape.halfExtents /= 2;
    std::set<std::string> names;
    for (const PartDesc& p : out.shape.parts) names.insert(p.name);
    part.name = toString(type);
    for (int k = 2; names.count(part.name); ++k)
        part.name = std::string(toString(type)) + "-" + std::to_string(k);
    double top = 0.0;
    for (const PartDesc& p : out.shape.parts) top = std::max(top, p.position.y() + reachUp(p));
    part.position = Vec3(0.0, top + reachUp(part), 0.0);
    out.shape.parts.push_back(std::move(part));
    if (std::string problem = refusal(out); !problem.empty()) return refuse(std::move(problem));
    return out;
}

std::optional<BodyDesc> withoutPart(const BodyDesc& body, int part, std::string* why) {
    auto refuse = [&](std::string reason) -> std::optional<BodyDesc> {
        if (why) *why = std::move(reason);
        return std::nullopt;
    };
    const int count = body.shape.type == ShapeType::Compound ? static_cast<int>(body.shape.parts.size()) : 0;
    if (part < 0 || part >= count) return refuse("the body has no such part");
    if (count == 1) return refuse("a compound keeps at least one part: delete the body, or Ungroup it");
    BodyDesc out = body;
    out.shape.parts.erase(out.shape.parts.begin() + part);
    if (std::string problem = refusal(out); !problem.empty()) return refuse(std::move(problem));
    return out;
}

}  // namespace tumble::ui
