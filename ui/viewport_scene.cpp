// Every body is an entity with its pose as a transform, over one or more parts (a capsule
// is a cylinder and two spheres) that scale shared unit meshes. Meshes and materials are
// shared: one unit sphere, box, cylinder and plane for the whole scene, one material per
// motion kind plus one for the selection, so hundreds of bodies cost hundreds of small
// transforms and nothing more. Imported meshes get one geometry per TriangleMesh, shared
// by every body that uses the same loaded mesh.
#include "viewport_scene.h"

#include "viewport_overlay.h"
#include "viewport_wire.h"

#include <tumble/mass.h>

#include <Qt3DCore/QAttribute>
#include <Qt3DCore/QBuffer>
#include <Qt3DCore/QEntity>
#include <Qt3DCore/QGeometry>
#include <Qt3DCore/QTransform>
#include <Qt3DExtras/QCuboidMesh>
#include <Qt3DExtras/QCylinderMesh>
#include <Qt3DExtras/QPerVertexColorMaterial>
#include <Qt3DExtras/QPhongMaterial>
#include <Qt3DExtras/QPlaneMesh>
#include <Qt3DExtras/QSphereMesh>
#include <Qt3DRender/QDirectionalLight>
#include <Qt3DRender/QGeometryRenderer>
#include <Qt3DRender/QMaterial>

#include <QColor>
#include <QQuaternion>
#include <QVector3D>

#include <algorithm>
#include <cstring>
#include <map>
#include <vector>

namespace tumble::ui {

namespace {

constexpr float kPlaneSize = 40.0f;  // drawn extent of an (infinite) plane, m
constexpr int kGridHalf = 10;        // grid lines from -10 m to 10 m, every metre
constexpr float kGridLift = 0.002f;  // above y = 0 so the ground plane does not hide it
constexpr double kWireLift = 1.004;  // collision wireframes, scaled about the body origin

QVector3D toQt(const Vec3& v) {
    return QVector3D(float(v.x()), float(v.y()), float(v.z()));
}

QQuaternion toQt(const Quat& q) {
    const Quat n = q.normalized();
    return QQuaternion(float(n.w()), float(n.x()), float(n.y()), float(n.z()));
}

Qt3DExtras::QPhongMaterial* makeMaterial(const QColor& diffuse, Qt3DCore::QNode* parent) {
    auto* m = new Qt3DExtras::QPhongMaterial(parent);
    m->setDiffuse(diffuse);
    m->setAmbient(diffuse.darker(350));
    m->setSpecular(QColor(40, 40, 40));
    m->setShininess(20.0f);
    return m;
}

// A renderer over interleaved float vertices: `components` floats per attribute, in order.
Qt3DRender::QGeometryRenderer* makeRenderer(const std::vector<float>& data,
                                            const std::vector<std::pair<QString, int>>& layout,
                                            Qt3DRender::QGeometryRenderer::PrimitiveType type,
                                            Qt3DCore::QNode* parent) {
    int stride = 0;
    for (const auto& a : layout) stride += a.second;
    const int count = static_cast<int>(data.size()) / stride;
    auto* renderer = new Qt3DRender::QGeometryRenderer(parent);
    auto* geometry = new Qt3DCore::QGeometry(renderer);
    auto* buffer = new Qt3DCore::QBuffer(geometry);
    QByteArray bytes(static_cast<qsizetype>(data.size() * sizeof(float)), Qt::Uninitialized);
    std::memcpy(bytes.data(), data.data(), static_cast<size_t>(bytes.size()));
    buffer->setData(bytes);
    int offset = 0;
    for (const auto& [name, n] : layout) {
        auto* attr =
            new Qt3DCore::QAttribute(buffer, name, Qt3DCore::QAttribute::Float, uint(n), uint(count),
                                     uint(offset * sizeof(float)), uint(stride * sizeof(float)), geometry);
        attr->setAttributeType(Qt3DCore::QAttribute::VertexAttribute);
        geometry->addAttribute(attr);
        offset += n;
    }
    renderer->setGeometry(geometry);
    renderer->setPrimitiveType(type);
    renderer->setVertexCount(count);
    return renderer;
}

}  // namespace

struct ViewportScene::Impl {
    Qt3DCore::QEntity* root = nullptr;
    // Shared unit meshes.
    Qt3DExtras::QSphereMesh* sphere = nullptr;
    Qt3DExtras::QCuboidMesh* box = nullptr;
    Qt3DExtras::QCylinderMesh* cylinder = nullptr;
    Qt3DExtras::QPlaneMesh* plane = nullptr;
    // Shared materials.
    Qt3DExtras::QPhongMaterial* dynamicMat = nullptr;
    Qt3DExtras::QPhongMaterial* staticMat = nullptr;
    Qt3DExtras::QPhongMaterial* kinematicMat = nullptr;
    Qt3DExtras::QPhongMaterial* selectedMat = nullptr;
    Qt3DExtras::QPhongMaterial* groundMat = nullptr;         // planes: dark and matte, under the grid
    Qt3DExtras::QPerVertexColorMaterial* wireMat = nullptr;  // collision shapes
    bool showWire = false;
    // One wireframe per loaded mesh and collision kind, like the render meshes.
    std::map<std::pair<const TriangleMesh*, MeshCollision>,
             std::pair<std::shared_ptr<const TriangleMesh>, Qt3DRender::QGeometryRenderer*>>
        meshWires;
    // One geometry per loaded mesh (the shared_ptr keeps the key alive).
    std::map<const TriangleMesh*,
             std::pair<std::shared_ptr<const TriangleMesh>, Qt3DRender::QGeometryRenderer*>>
        meshes;

    struct Body {
        Qt3DCore::QEntity* entity = nullptr;
        Qt3DCore::QTransform* transform = nullptr;
        std::vector<Qt3DCore::QEntity*> parts;
        Qt3DExtras::QPhongMaterial* material = nullptr;  // the one in use
        Qt3DCore::QEntity* wire = nullptr;               // the collision shape, when shown
        ShapeDesc shape;                                 // what the parts draw
        Motion motion = Motion::Dynamic;
        bool plane = false;
        bool selected = false;
    };
    std::vector<Body> bodies;

    Qt3DExtras::QPhongMaterial* materialFor(const Body& b) const {
        if (b.selected) return selectedMat;
        if (b.plane) return groundMat;
        switch (b.motion) {
            case Motion::Static: return staticMat;
            case Motion::Kinematic: return kinematicMat;
            case Motion::Dynamic: break;
        }
        return dynamicMat;
    }

    Qt3DRender::QGeometryRenderer* meshRenderer(const std::shared_ptr<const TriangleMesh>& mesh) {
        auto it = meshes.find(mesh.get());
        if (it != meshes.end()) return it->second.second;
        // Flat shading: three vertices per triangle, each with the face normal.
        std::vector<float> data;
        data.reserve(mesh->triangles.size() * 18);
        for (const auto& tri : mesh->triangles) {
            const Vec3& a = mesh->vertices[size_t(tri[0])];
            const Vec3& b = mesh->vertices[size_t(tri[1])];
            const Vec3& c = mesh->vertices[size_t(tri[2])];
            Vec3 n = (b - a).cross(c - a);
            if (n.norm() > 0) n.normalize();
            for (const Vec3* p : {&a, &b, &c}) {
                for (int i = 0; i < 3; ++i) data.push_back(float((*p)[i]));
                for (int i = 0; i < 3; ++i) data.push_back(float(n[i]));
            }
        }
        auto* r = makeRenderer(data,
                               {{Qt3DCore::QAttribute::defaultPositionAttributeName(), 3},
                                {Qt3DCore::QAttribute::defaultNormalAttributeName(), 3}},
                               Qt3DRender::QGeometryRenderer::Triangles, root);
        meshes.emplace(mesh.get(), std::make_pair(mesh, r));
        return r;
    }

    Qt3DCore::QEntity* addPart(Body& b, Qt3DCore::QComponent* mesh, const QVector3D& scale,
                               const QVector3D& translation = QVector3D(),
                               const QQuaternion& rotation = QQuaternion()) {
        auto* part = new Qt3DCore::QEntity(b.entity);
        auto* t = new Qt3DCore::QTransform(part);
        t->setScale3D(scale);
        t->setTranslation(translation);
        t->setRotation(rotation);
        part->addComponent(mesh);
        part->addComponent(t);
        part->addComponent(b.material);
        b.parts.push_back(part);
        return part;
    }

    Body make(const BodyDesc& desc, bool selected) {
        Body b;
        b.entity = new Qt3DCore::QEntity(root);
        b.transform = new Qt3DCore::QTransform(b.entity);
        b.entity->addComponent(b.transform);
        b.motion = desc.motion;
        b.plane = desc.shape.type == ShapeType::Plane;
        b.selected = selected;
        b.material = materialFor(b);
        fill(b, desc);
        return b;
    }

    static bool sameShape(const ShapeDesc& a, const ShapeDesc& b) {
        return a == b && a.meshData == b.meshData;
    }

    void pose(Body& b, const BodyDesc& desc) {
        b.transform->setTranslation(toQt(desc.position));
        b.transform->setRotation(toQt(desc.orientation));
    }

    Qt3DRender::QGeometryRenderer* wireRenderer(const ShapeDesc& s, Qt3DCore::QNode* owner) {
        auto build = [](const ShapeDesc& shape) {
            std::vector<float> data;
            const QColor c(70, 235, 200);
            // A hair outside the surface, so the lines on it win the depth test and the ones
            // behind it stay hidden.
            for (const Vec3& q : collisionWire(shape)) {
                const Vec3 p = q * kWireLift;
                data.insert(data.end(), {float(p.x()), float(p.y()), float(p.z()), float(c.redF()),
                                         float(c.greenF()), float(c.blueF())});
            }
            return data;
        };
        if (s.type != ShapeType::Mesh) {
            return makeColouredRenderer(build(s), Qt3DRender::QGeometryRenderer::Lines, owner);
        }
        const auto key = std::make_pair(s.meshData.get(), s.collision);
        auto it = meshWires.find(key);
        if (it != meshWires.end()) return it->second.second;
        auto* r = makeColouredRenderer(build(s), Qt3DRender::QGeometryRenderer::Lines, root);
        meshWires.emplace(key, std::make_pair(s.meshData, r));
        return r;
    }

    void setWire(Body& b) {
        delete b.wire;
        b.wire = nullptr;
        if (!showWire || b.shape.type == ShapeType::Plane) return;
        if (b.shape.type == ShapeType::Mesh && !b.shape.meshData) return;
        b.wire = new Qt3DCore::QEntity(b.entity);
        b.wire->addComponent(wireRenderer(b.shape, b.wire));
        b.wire->addComponent(wireMat);
    }

    // Pose and parts from the description (parts are rebuilt: the shape may have changed).
    void fill(Body& b, const BodyDesc& desc) {
        for (auto* p : b.parts) delete p;
        b.parts.clear();
        pose(b, desc);
        b.shape = desc.shape;
        setWire(b);
        const ShapeDesc& s = desc.shape;
        const float r = float(s.radius);
        const float h = float(s.halfHeight);
        switch (s.type) {
            case ShapeType::Sphere: addPart(b, sphere, QVector3D(r, r, r)); break;
            case ShapeType::Box: addPart(b, box, 2.0f * toQt(s.halfExtents)); break;
            case ShapeType::Cylinder: addPart(b, cylinder, QVector3D(r, 2 * h, r)); break;
            case ShapeType::Capsule:
                addPart(b, cylinder, QVector3D(r, 2 * h, r));
                addPart(b, sphere, QVector3D(r, r, r), QVector3D(0, h, 0));
                addPart(b, sphere, QVector3D(r, r, r), QVector3D(0, -h, 0));
                break;
            case ShapeType::Plane: {
                QVector3D n = toQt(s.normal);
                if (n.isNull()) n = QVector3D(0, 1, 0);
                n.normalize();
                addPart(b, plane, QVector3D(kPlaneSize, 1, kPlaneSize), n * float(s.distance),
                        QQuaternion::rotationTo(QVector3D(0, 1, 0), n));
                break;
            }
            case ShapeType::Mesh:
                if (s.meshData) addPart(b, meshRenderer(s.meshData), QVector3D(1, 1, 1));
                break;
        }
    }

    void setMaterial(Body& b, Qt3DExtras::QPhongMaterial* m) {
        if (b.material == m) return;
        for (auto* p : b.parts) {
            p->removeComponent(b.material);
            p->addComponent(m);
        }
        b.material = m;
    }

    void buildGridAndAxes() {
        std::vector<float> grid;
        auto line = [](std::vector<float>& v, QVector3D a, QVector3D b, QColor c) {
            for (const QVector3D& p : {a, b}) {
                v.insert(v.end(),
                         {p.x(), p.y(), p.z(), float(c.redF()), float(c.greenF()), float(c.blueF())});
            }
        };
        const float e = float(kGridHalf);
        for (int i = -kGridHalf; i <= kGridHalf; ++i) {
            if (i == 0) continue;  // the axes take these
            const QColor c = (i % 5 == 0) ? QColor(150, 152, 162) : QColor(112, 114, 124);
            line(grid, QVector3D(float(i), kGridLift, -e), QVector3D(float(i), kGridLift, e), c);
            line(grid, QVector3D(-e, kGridLift, float(i)), QVector3D(e, kGridLift, float(i)), c);
        }
        // The axes: x red, y green, z blue, the negative halves dimmer.
        line(grid, QVector3D(0, kGridLift, 0), QVector3D(e, kGridLift, 0), QColor(220, 60, 60));
        line(grid, QVector3D(-e, kGridLift, 0), QVector3D(0, kGridLift, 0), QColor(110, 50, 50));
        line(grid, QVector3D(0, kGridLift, 0), QVector3D(0, kGridLift, e), QColor(70, 110, 230));
        line(grid, QVector3D(0, kGridLift, -e), QVector3D(0, kGridLift, 0), QColor(50, 60, 110));
        line(grid, QVector3D(0, 0, 0), QVector3D(0, 2, 0), QColor(70, 200, 70));

        auto* entity = new Qt3DCore::QEntity(root);
        entity->addComponent(makeRenderer(grid,
                                          {{Qt3DCore::QAttribute::defaultPositionAttributeName(), 3},
                                           {Qt3DCore::QAttribute::defaultColorAttributeName(), 3}},
                                          Qt3DRender::QGeometryRenderer::Lines, entity));
        entity->addComponent(new Qt3DExtras::QPerVertexColorMaterial(entity));
    }

    void buildLights() {
        auto light = [this](QVector3D dir, float intensity) {
            auto* e = new Qt3DCore::QEntity(root);
            auto* l = new Qt3DRender::QDirectionalLight(e);
            l->setWorldDirection(dir);
            l->setIntensity(intensity);
            l->setColor(Qt::white);
            e->addComponent(l);
        };
        light(QVector3D(-0.4f, -1.0f, -0.6f), 0.9f);  // key, from above
        light(QVector3D(0.6f, -0.3f, 0.5f), 0.35f);   // fill, from the other side
    }
};

ViewportScene::ViewportScene(Qt3DCore::QEntity* root) : d_(std::make_unique<Impl>()) {
    Impl& d = *d_;
    d.root = root;
    d.sphere = new Qt3DExtras::QSphereMesh(root);
    d.sphere->setRadius(1.0f);
    d.sphere->setRings(24);
    d.sphere->setSlices(32);
    d.box = new Qt3DExtras::QCuboidMesh(root);  // 1 x 1 x 1
    d.cylinder = new Qt3DExtras::QCylinderMesh(root);
    d.cylinder->setRadius(1.0f);
    d.cylinder->setLength(1.0f);
    d.cylinder->setRings(2);
    d.cylinder->setSlices(32);
    d.plane = new Qt3DExtras::QPlaneMesh(root);
    d.plane->setWidth(1.0f);
    d.plane->setHeight(1.0f);
    d.dynamicMat = makeMaterial(QColor(214, 140, 70), root);
    d.staticMat = makeMaterial(QColor(140, 144, 150), root);
    d.kinematicMat = makeMaterial(QColor(90, 140, 215), root);
    d.selectedMat = makeMaterial(QColor(255, 214, 60), root);
    d.selectedMat->setAmbient(QColor(110, 90, 20));
    d.groundMat = makeMaterial(QColor(78, 80, 88), root);
    d.groundMat->setSpecular(QColor(0, 0, 0));
    d.groundMat->setAmbient(QColor(40, 41, 46));
    d.wireMat = new Qt3DExtras::QPerVertexColorMaterial(root);
    d.buildLights();
    d.buildGridAndAxes();
}

ViewportScene::~ViewportScene() = default;  // the entities belong to the root

void ViewportScene::rebuild(const SceneDesc& scene) {
    for (auto& b : d_->bodies) delete b.entity;
    d_->bodies.clear();
    for (auto& [key, value] : d_->meshes) delete value.second;
    d_->meshes.clear();
    for (auto& [key, value] : d_->meshWires) delete value.second;
    d_->meshWires.clear();
    for (const BodyDesc& desc : scene.bodies) d_->bodies.push_back(d_->make(desc, false));
}

void ViewportScene::insert(int index, const BodyDesc& body) {
    if (index < 0 || index > count()) index = count();
    d_->bodies.insert(d_->bodies.begin() + index, d_->make(body, false));
}

void ViewportScene::update(int index, const BodyDesc& body) {
    if (index < 0 || index >= count()) return;
    Impl::Body& b = d_->bodies[size_t(index)];
    b.motion = body.motion;
    b.plane = body.shape.type == ShapeType::Plane;
    if (Impl::sameShape(b.shape, body.shape)) {  // a move or a turn (a drag): keep the parts
        d_->setMaterial(b, d_->materialFor(b));
        d_->pose(b, body);
        return;
    }
    b.material = d_->materialFor(b);
    d_->fill(b, body);
}

void ViewportScene::remove(int index) {
    if (index < 0 || index >= count()) return;
    delete d_->bodies[size_t(index)].entity;
    d_->bodies.erase(d_->bodies.begin() + index);
}

void ViewportScene::setSelection(const QList<int>& indices) {
    for (int i = 0; i < count(); ++i) {
        Impl::Body& b = d_->bodies[size_t(i)];
        b.selected = indices.contains(i);
        d_->setMaterial(b, d_->materialFor(b));
    }
}

int ViewportScene::count() const {
    return static_cast<int>(d_->bodies.size());
}

void ViewportScene::setShowCollisionShapes(bool show) {
    if (show == d_->showWire) return;
    d_->showWire = show;
    for (auto& b : d_->bodies) d_->setWire(b);
}

bool ViewportScene::showCollisionShapes() const {
    return d_->showWire;
}

int ViewportScene::collisionShapeCount() const {
    return int(
        std::count_if(d_->bodies.begin(), d_->bodies.end(), [](const Impl::Body& b) { return b.wire; }));
}

}  // namespace tumble::ui
