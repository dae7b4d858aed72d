#include "document/placement.h"

#include "document/body_presets.h"

#include <tumble/errors.h>
#include <tumble/model.h>
#include <tumble/placement.h>

#include <algorithm>
#include <cmath>

namespace tumble::ui {

namespace {

constexpr double kFarthestDrop = 1e4;  // m: a drop looks this far down

// The scene compiled with its bodies at their scene poses; nothing when it cannot be (a
// body whose mesh is not loaded, an impossible value the panels have not refused yet).
struct Compiled {
    Model model;
    State state;
};
std::optional<Compiled> compiled(const SceneDesc& scene) {
    try {
        Compiled c{compile(scene), {}};
        c.state = initialState(c.model, scene);
        return c;
    } catch (const std::exception&) {
        return std::nullopt;
    }
}

}  // namespace

Vec3 downOf(const SceneDesc& scene) {
    const Vec3& g = scene.settings.gravity;
    return g.norm() > 0.0 ? Vec3(g.normalized()) : Vec3(-Vec3::UnitY());
}

Quat uprightFor(const Vec3& down) {
    return Quat::FromTwoVectors(-Vec3::UnitY(), down.normalized());
}

std::vector<std::optional<double>> dropDistances(const SceneDesc& scene, const std::vector<int>& indices) {
    std::vector<std::optional<double>> falls(indices.size());
    std::optional<Compiled> c = compiled(scene);  // once for all of them
    if (!c) return falls;
    const Vec3 down = downOf(scene);
    for (std::size_t k = 0; k < indices.size(); ++k) {
        const int i = indices[k];
        if (i < 0 || i >= static_cast<int>(scene.bodies.size()) || scene.bodies[i].shape.type == ShapeType::Plane)
            continue;
        falls[k] = travelToTouch(c->model, c->state, i, down, kFarthestDrop);
        if (falls[k]) c->state.bodies[i].x += *falls[k] * down;  // where the next ones meet it
    }
    return falls;
}

BodyDesc setDownAt(const SceneDesc& scene, BodyDesc body, const Vec3& point) {
    if (body.shape.type == ShapeType::Plane) return body;
    const Vec3 down = downOf(scene);
    const double size = std::max(boundingRadius(body.shape), 1e-3);
    // Its frame's origin over the point by its size (with room to spare): the whole body is
    // then above the point; lowered from there onto the first body it meets.
    SceneDesc with = scene;
    with.bodies.push_back(body);
    BodyDesc& placed = with.bodies.back();
    placed.name = "\x01placing";  // (a name no body of the scene has)
    const int index = static_cast<int>(with.bodies.size()) - 1;
    for (double rise = 1.01 * size;; rise *= 2.0) {
        placed.position = point - rise * down;
        const std::optional<Compiled> c = compiled(with);
        if (!c) break;
        const std::optional<double> fall = travelToTouch(c->model, c->state, index, down, rise + kFarthestDrop);
        if (!fall) {
            body.position = point;  // nothing below to rest on: where the user looks
            return body;
        }
        // Starting inside another body (an overhang over the point): raised and tried again.
        if (*fall > 0.0 || rise > kFarthestDrop) {
            body.position = placed.position + *fall * down;
            return body;
        }
    }
    body.position = point;
    return body;
}

struct Settler::Impl {
    SceneDesc scene;  // without the body's joints
    int index = -1;
    BodyDesc start;   // the body as compiled
    std::optional<Compiled> compiled;
    Vec3 startCentre = Vec3::Zero();  // its centre of mass in the compiled state
};

Settler::Settler(const SceneDesc& scene, int index) : d_(std::make_unique<Impl>()) {
    if (index < 0 || index >= static_cast<int>(scene.bodies.size())) return;
    d_->scene = scene;
    d_->index = index;
    d_->start = scene.bodies[static_cast<std::size_t>(index)];
    const std::string& name = d_->start.name;
    std::erase_if(d_->scene.joints, [&](const JointDesc& j) { return j.bodyA == name || j.bodyB == name; });
    d_->compiled = compiled(d_->scene);
    if (d_->compiled) d_->startCentre = d_->compiled->state.bodies[static_cast<std::size_t>(index)].x;
}

Settler::~Settler() = default;

BodyDesc Settler::settle(const BodyDesc& moved) const {
    if (d_->index < 0 || moved.shape.type == ShapeType::Plane) return moved;
    if (!(moved.orientation.coeffs() == d_->start.orientation.coeffs()) || !(moved.shape == d_->start.shape)) {
        SceneDesc with = d_->scene;
        with.bodies[static_cast<std::size_t>(d_->index)] = moved;
        return Settler(with, d_->index).settle(moved);
    }
    BodyDesc body = moved;
    if (!d_->compiled) return body;  // (setDownAt's answer when the scene cannot be compiled)
    // setDownAt's steps, the body moved in the compiled state instead of compiled again.
    const Vec3 down = downOf(d_->scene);
    const double size = std::max(boundingRadius(body.shape), 1e-3);
    State& state = d_->compiled->state;
    Vec3& centre = state.bodies[static_cast<std::size_t>(d_->index)].x;
    const Vec3 fromOrigin = d_->startCentre - d_->start.position;
    for (double rise = 1.01 * size;; rise *= 2.0) {
        const Vec3 origin = moved.position - rise * down;
        centre = origin + fromOrigin;
        const std::optional<double> fall =
            travelToTouch(d_->compiled->model, state, d_->index, down, rise + kFarthestDrop);
        if (!fall) return body;  // nothing below to rest on: where it was dragged
        if (*fall > 0.0 || rise > kFarthestDrop) {
            body.position = origin + *fall * down;
            return body;
        }
    }
}

BodyDesc settledAt(const SceneDesc& scene, int index, const BodyDesc& moved) {
    if (index < 0 || index >= static_cast<int>(scene.bodies.size())) return moved;
    SceneDesc with = scene;
    with.bodies[static_cast<std::size_t>(index)] = moved;
    return Settler(with, index).settle(moved);
}

std::vector<int> lowestFirst(const SceneDesc& scene, std::vector<int> indices) {
    const Vec3 down = downOf(scene);
    std::stable_sort(indices.begin(), indices.end(), [&](int a, int b) {
        return scene.bodies[a].position.dot(down) > scene.bodies[b].position.dot(down);
    });
    return indices;
}

long layoutCount(const LayoutSpec& spec) {
    const long n = std::max(spec.count, 0);
    switch (spec.kind) {
        case Layout::Stack: return n;
        case Layout::Pyramid: return spec.square ? n * (n + 1) * (2 * n + 1) / 6 : n * (n + 1) / 2;
        case Layout::Wall: return n * std::max(spec.rows, 0);
    }
    return 0;
}

std::vector<Vec3> layoutCentres(const LayoutSpec& spec) {
    std::vector<Vec3> out;
    const long total = layoutCount(spec);
    if (total <= 0 || total > kMostLaidOut) return out;
    out.reserve(static_cast<std::size_t>(total));
    const Vec3& h = spec.halfExtents;
    const double pitchX = 2.0 * h.x() + spec.gap, pitchZ = 2.0 * h.z() + spec.gap;
    auto row = [&](int n, double y, double shift, double z) {
        for (int i = 0; i < n; ++i) out.emplace_back((i - 0.5 * (n - 1)) * pitchX + shift, y, z);
    };
    switch (spec.kind) {
        case Layout::Stack:
            for (int k = 0; k < spec.count; ++k) out.emplace_back(0.0, h.y() * (2 * k + 1), 0.0);
            break;
        case Layout::Pyramid:
            for (int layer = 0; layer < spec.count; ++layer) {
                const int n = spec.count - layer;
                const double y = h.y() * (2 * layer + 1);
                if (!spec.square) {
                    row(n, y, 0.0, 0.0);
                    continue;
                }
                for (int k = 0; k < n; ++k) row(n, y, 0.0, (k - 0.5 * (n - 1)) * pitchZ);
            }
            break;
        case Layout::Wall:
            for (int r = 0; r < spec.rows; ++r)
                row(spec.count, h.y() * (2 * r + 1), spec.staggered && r % 2 == 1 ? 0.5 * pitchX : 0.0, 0.0);
            break;
    }
    return out;
}

std::vector<Vec3> arrayPlaces(const Vec3& start, const std::array<int, 3>& counts, const std::array<Vec3, 3>& steps) {
    std::vector<Vec3> out;
    long total = 1;
    for (int n : counts) {
        if (n < 1) return out;
        total *= n;
        if (total > kMostLaidOut) return {};
    }
    out.reserve(static_cast<std::size_t>(total));
    for (int k = 0; k < counts[2]; ++k)
        for (int j = 0; j < counts[1]; ++j)
            for (int i = 0; i < counts[0]; ++i) out.push_back(start + i * steps[0] + j * steps[1] + k * steps[2]);
    return out;
}

}  // namespace tumble::ui
