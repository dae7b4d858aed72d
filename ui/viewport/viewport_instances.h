// Many copies of the unit sphere, box, cylinder and plane in one draw call each (instanced
// drawing): every copy has its own model matrix and colours in a per-instance buffer, drawn
// by a small lit material of our own (two fixed directional lights, like the scene's light
// entities, Phong). Qt3D's cost is per entity and per draw, not per triangle, so the
// viewport draws all primitive bodies with four entities whatever their number.
#pragma once

#include <QColor>
#include <QMatrix4x4>

#include <memory>

namespace Qt3DCore {
class QEntity;
}

namespace tumble::ui {

class ViewportInstances {
public:
    enum Kind { Sphere, Box, Cylinder, Plane, KindCount };
    /// How a copy is lit: Phong with these colours (specular: grey level 0..1).
    struct Look {
        QColor diffuse;
        QColor ambient;
        float specular = 0.0f;
    };

    explicit ViewportInstances(Qt3DCore::QEntity* root);
    ~ViewportInstances();
    ViewportInstances(const ViewportInstances&) = delete;
    ViewportInstances& operator=(const ViewportInstances&) = delete;

    /// Starts a new set of copies (what is drawn changes at commit()).
    void clear();
    /// A copy of the unit shape (sphere and cylinder radius 1, cylinder along y of length 1,
    /// box 1 x 1 x 1, plane 1 x 1 in xz) placed by `model` = rotation * scale (+ translation).
    void add(Kind kind, const QMatrix4x4& model, const Look& look);
    /// Hands the copies added since clear() to the renderer.
    void commit();
    /// Copies drawn of a kind (as of the last commit).
    int count(Kind kind) const;
    /// Triangles of the mesh each copy of a kind is drawn with (as of the last commit): spheres
    /// and cylinders get coarser as their copies grow in number (see trianglesPerCopy).
    int drawnTrianglesPerCopy(Kind kind) const;
    /// The triangles of one copy of a kind when `copies` of it are drawn.
    static int trianglesPerCopy(Kind kind, int copies);

private:
    struct Impl;
    std::unique_ptr<Impl> d_;
};

}  // namespace tumble::ui
