// Bodies of the primitive shapes (sphere, box, cylinder, capsule, plane) are drawn by
// instancing (viewport_instances.h): one draw per shape kind, whatever the number of bodies,
// each body a copy of a shared unit mesh with its own matrix and colours. Qt3D's cost is per
// entity (its jobs, a draw call and a uniform upload each), so one entity per body made a
// frame cost about a millisecond a body on a software renderer. Changes are gathered and
// handed to the renderer once per pass of the event loop. Imported meshes keep an entity
// each (a renderer of their own over one vertex buffer per TriangleMesh, shared by every
// body that uses it, with Qt3D's Phong materials), and so do collision wireframes while
// shown.
#include "viewport/viewport_scene.h"

#include "viewport/viewport_grid.h"
#include "viewport/viewport_instances.h"
#include "viewport/viewport_overlay.h"
#include "viewport/viewport_wire.h"

#include <tumble/mass.h>

#include <Qt3DCore/QAttribute>
#include <Qt3DCore/QBuffer>
#include <Qt3DCore/QEntity>
#include <Qt3DCore/QGeometry>
#include <Qt3DCore/QTransform>
#include <Qt3DExtras/QPerVertexColorMaterial>
#include <Qt3DExtras/QPhongMaterial>
#include <Qt3DRender/QDirectionalLight>
#include <Qt3DRender/QGeometryRenderer>
#include <Qt3DRender/QMaterial>

#include <QColor>
#include <QMatrix4x4>
#include <QQuaternion>
#include <QTimer>
#include <QVector3D>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <map>
#include <vector>

namespace tumble::ui {

namespace {

constexpr float kPlaneSize = 40.0f;  // drawn extent of an (infinite) plane, m
constexpr int kGridHalf = 20;        // grid lines from -20 m to 20 m, every metre (fading out)
constexpr float kGridLift = 0.002f;  // above y = 0 (the grid's shader pulls it nearer still)
constexpr double kWireLift = 1.004;  // collision wireframes, scaled about the body origin

QVector3D toQt(const Vec3& v) {
    return QVector3D(float(v.x()), float(v.y()), float(v.z()));
}

QQuaternion toQt(const Quat& q) {
    const Quat n = q.normalized();
    return QQuaternion(float(n.w()), float(n.x()), float(n.y()), float(n.z()));
}

// Phong colours; the ambient is the diffuse's, darker, unless given.
ViewportInstances::Look look(const QColor& diffuse, const QColor& specular,
                             const QColor& ambient = QColor()) {
    return {diffuse, ambient.isValid() ? ambient : diffuse.darker(350), float(specular.redF())};
}

Qt3DExtras::QPhongMaterial* makeMaterial(const ViewportInstances::Look& look, Qt3DCore::QNode* parent) {
    auto* m = new Qt3DExtras::QPhongMaterial(parent);
    m->setDiffuse(look.diffuse);
    m->setAmbient(look.ambient);
    const int grey = int(std::lround(look.specular * 255.0f));
    m->setSpecular(QColor(grey, grey, grey));
    m->setShininess(20.0f);
    return m;
}

// A renderer over interleaved float vertices: `components` floats per attribute, in order.
Qt3DCore::QBuffer* makeBuffer(const std::vector<float>& data, Qt3DCore::QNode* parent) {
    auto* buffer = new Qt3DCore::QBuffer(parent);
    QByteArray bytes(static_cast<qsizetype>(data.size() * sizeof(float)), Qt::Uninitialized);
    std::memcpy(bytes.data(), data.data(), static_cast<size_t>(bytes.size()));
    buffer->setData(bytes);
    return buffer;
}

// A renderer of `buffer` (made by makeBuffer, shared or its own) with the attributes of
// `layout` (name, floats) interleaved in that order.
Qt3DRender::QGeometryRenderer* rendererOf(Qt3DCore::QBuffer* buffer, int floats,
                                          const std::vector<std::pair<QString, int>>& layout,
                                          Qt3DRender::QGeometryRenderer::PrimitiveType type,
                                          Qt3DCore::QNode* parent) {
    int stride = 0;
    for (const auto& a : layout) stride += a.second;
    const int count = floats / stride;
    auto* renderer = new Qt3DRender::QGeometryRenderer(parent);
    auto* geometry = new Qt3DCore::QGeometry(renderer);
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

Qt3DRender::QGeometryRenderer* makeRenderer(const std::vector<float>& data,
                                            const std::vector<std::pair<QString, int>>& layout,
                                            Qt3DRender::QGeometryRenderer::PrimitiveType type,
                                            Qt3DCore::QNode* parent) {
    Qt3DCore::QBuffer* buffer = makeBuffer(data, nullptr);
    auto* renderer = rendererOf(buffer, int(data.size()), layout, type, parent);
    buffer->setParent(renderer->geometry());  // its own
    return renderer;
}

}  // namespace

struct ViewportScene::Impl {
    Qt3DCore::QEntity* root = nullptr;
    Qt3DCore::QEntity* gridEntity = nullptr;  // the grid and the axes
    // The primitive bodies, drawn by instancing.
    std::unique_ptr<ViewportInstances> instances;
    ViewportInstances::Look dynamicLook, staticLook, kinematicLook, selectedLook, groundLook, selectedGroundLook,
        asleepLook;
    // Mesh bodies: shared materials, the same colours as the looks.
    Qt3DExtras::QPhongMaterial* dynamicMat = nullptr;
    Qt3DExtras::QPhongMaterial* staticMat = nullptr;
    Qt3DExtras::QPhongMaterial* kinematicMat = nullptr;
    Qt3DExtras::QPhongMaterial* selectedMat = nullptr;
    Qt3DExtras::QPhongMaterial* asleepMat = nullptr;
    Qt3DExtras::QPerVertexColorMaterial* wireMat = nullptr;  // collision shapes
    bool showWire = false;
    // One vertex buffer per loaded mesh (the shared_ptr keeps the key alive), and one for
    // its wireframe per collision kind.
    struct MeshBuffer {
        Qt3DCore::QBuffer* buffer = nullptr;
        int floats = 0;
    };
    std::map<const TriangleMesh*, std::pair<std::shared_ptr<const TriangleMesh>, MeshBuffer>> meshes;
    std::map<std::pair<const TriangleMesh*, MeshCollision>, std::pair<std::shared_ptr<const TriangleMesh>, MeshBuffer>>
        meshWires;

    struct Body {
        Qt3DCore::QEntity* entity = nullptr;  // a mesh body's entity (others are instances)
        Qt3DCore::QTransform* transform = nullptr;
        Qt3DCore::QEntity* part = nullptr;               // its mesh
        Qt3DExtras::QPhongMaterial* material = nullptr;  // the one in use
        // A compound's mesh parts (under `entity`, each with its pose in the body's frame):
        // the entity, the part's index, the material in use.
        struct MeshPart {
            Qt3DCore::QEntity* entity = nullptr;
            int index = -1;
            Qt3DExtras::QPhongMaterial* material = nullptr;
        };
        std::vector<MeshPart> meshParts;
        Qt3DCore::QEntity* wire = nullptr;               // the collision shape, when shown
        Qt3DCore::QTransform* wireTransform = nullptr;
        ShapeDesc shape;     // what is drawn
        QVector3D position;  // drawn (the document's, or a recorded frame's)
        QQuaternion orientation;
        QVector3D docPosition;  // the document's
        QQuaternion docOrientation;
        bool shown = false;  // drawn at a recorded frame's pose, not the document's
        Motion motion = Motion::Dynamic;
        bool plane = false;
        bool selected = false;
        int selectedPart = -1;  // a compound's part drawn selected instead of the whole body
        bool asleep = false;
    };
    std::vector<Body> bodies;

    // The instances are rebuilt from `bodies` once per pass of the event loop after a change.
    QObject timerContext;
    bool flushPending = false;

    void changed() {
        if (flushPending) return;
        flushPending = true;
        QTimer::singleShot(0, &timerContext, [this] { flush(); });
    }

    const ViewportInstances::Look& lookFor(const Body& b) const {
        if (b.plane) return b.selected ? selectedGroundLook : groundLook;
        if (b.selected && b.selectedPart < 0) return selectedLook;
        if (b.asleep) return asleepLook;
        switch (b.motion) {
            case Motion::Static: return staticLook;
            case Motion::Kinematic:
            case Motion::Animated: return kinematicLook;
            case Motion::Dynamic: break;
        }
        return dynamicLook;
    }

    Qt3DExtras::QPhongMaterial* materialFor(const Body& b, int part = -1) const {
        if (b.selected && (b.selectedPart < 0 || b.selectedPart == part)) return selectedMat;
        if (b.asleep) return asleepMat;
        switch (b.motion) {
            case Motion::Static: return staticMat;
            case Motion::Kinematic:
            case Motion::Animated: return kinematicMat;
            case Motion::Dynamic: break;
        }
        return dynamicMat;
    }

    void flush() {
        flushPending = false;
        using K = ViewportInstances::Kind;
        instances->clear();
        for (const Body& b : bodies) {
            const ShapeDesc& s = b.shape;
            if (s.type == ShapeType::Mesh) continue;
            QMatrix4x4 pose;
            pose.translate(b.position);
            pose.rotate(b.orientation);
            // A shape drawn in the frame `frame` (the body's, or a compound's part's in it).
            auto draw = [&](const ShapeDesc& shape, const QMatrix4x4& frame,
                            const ViewportInstances::Look& look, auto& self) -> void {
                auto part = [&](K kind, const QVector3D& scale, const QVector3D& translation = QVector3D(),
                                const QQuaternion& rotation = QQuaternion()) {
                    QMatrix4x4 m = frame;
                    m.translate(translation);
                    m.rotate(rotation);
                    m.scale(scale);
                    instances->add(kind, m, look);
                };
                const float r = float(shape.radius);
                const float h = float(shape.halfHeight);
                switch (shape.type) {
                    case ShapeType::Sphere: part(K::Sphere, QVector3D(r, r, r)); break;
                    case ShapeType::Box: part(K::Box, 2.0f * toQt(shape.halfExtents)); break;
                    case ShapeType::Cylinder: part(K::Cylinder, QVector3D(r, 2 * h, r)); break;
                    case ShapeType::Capsule:
                        part(K::Cylinder, QVector3D(r, 2 * h, r));
                        part(K::Sphere, QVector3D(r, r, r), QVector3D(0, h, 0));
                        part(K::Sphere, QVector3D(r, r, r), QVector3D(0, -h, 0));
                        break;
                    case ShapeType::Plane: {
                        QVector3D n = toQt(shape.normal);
                        if (n.isNull()) n = QVector3D(0, 1, 0);
                        n.normalize();
                        part(K::Plane, QVector3D(kPlaneSize, 1, kPlaneSize), n * float(shape.distance),
                             QQuaternion::rotationTo(QVector3D(0, 1, 0), n));
                        break;
                    }
                    case ShapeType::Mesh: break;  // (a compound's mesh parts are not drawn yet)
                    case ShapeType::Compound:
                        for (size_t k = 0; k < shape.parts.size(); ++k) {
                            const PartDesc& p = shape.parts[k];
                            if (p.shape.type == ShapeType::Compound) continue;  // refused by validate
                            QMatrix4x4 m = frame;
                            m.translate(toQt(p.position));
                            m.rotate(toQt(p.orientation.normalized()));
                            const bool picked = b.selected && b.selectedPart == static_cast<int>(k);
                            self(p.shape, m, picked ? selectedLook : look, self);
                        }
                        break;
                }
            };
            draw(s, pose, lookFor(b), draw);
        }
        instances->commit();
    }

    // A mesh body's renderer, its own, of its mesh's vertices (one buffer per mesh, shared
    // by every body that uses it). The renderer is made under the body's own entity: one made
    // elsewhere (under the root, shared by the bodies) drew nothing when the mesh came after
    // the view was up (a scene opened, a mesh imported: issue 21), under Qt 6.4's RHI backend.
    Qt3DRender::QGeometryRenderer* meshRenderer(const std::shared_ptr<const TriangleMesh>& mesh,
                                                Qt3DCore::QNode* owner) {
        auto it = meshes.find(mesh.get());
        if (it == meshes.end()) {
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
            it = meshes.emplace(mesh.get(), std::make_pair(mesh, MeshBuffer{makeBuffer(data, root), int(data.size())}))
                     .first;
        }
        const MeshBuffer& m = it->second.second;
        return rendererOf(m.buffer, m.floats,
                          {{Qt3DCore::QAttribute::defaultPositionAttributeName(), 3},
                           {Qt3DCore::QAttribute::defaultNormalAttributeName(), 3}},
                          Qt3DRender::QGeometryRenderer::Triangles, owner);
    }

    Body make(const BodyDesc& desc, bool selected) {
        Body b;
        b.motion = desc.motion;
        b.plane = desc.shape.type == ShapeType::Plane;
        b.selected = selected;
        fill(b, desc);
        return b;
    }

    static bool sameShape(const ShapeDesc& a, const ShapeDesc& b) {
        return a == b && a.meshData == b.meshData;
    }

    void pose(Body& b, const BodyDesc& desc) {
        b.docPosition = toQt(desc.position);
        b.docOrientation = toQt(desc.orientation);
        // While a recorded frame is drawn the body stays there: the edit shows at frame 0.
        if (b.shown) {
            place(b, b.position, b.orientation);
        } else {
            place(b, b.docPosition, b.docOrientation);
        }
    }

    void place(Body& b, const QVector3D& position, const QQuaternion& orientation) {
        b.position = position;
        b.orientation = orientation;
        for (auto* t : {b.transform, b.wireTransform}) {
            if (!t) continue;
            t->setTranslation(b.position);
            t->setRotation(b.orientation);
        }
        if (b.shape.type != ShapeType::Mesh) changed();
    }

    Qt3DRender::QGeometryRenderer* wireRenderer(const ShapeDesc& s, Qt3DCore::QNode* owner) {
        auto build = [](const ShapeDesc& shape) {
            std::vector<float> data;
            // Each piece (a compound's part, a mesh's convex part) in its own colour. A hair
            // outside the surface, so the lines on it win the depth test and the ones behind
            // it stay hidden.
            std::vector<int> pieces;
            const std::vector<Vec3> wire = collisionWire(shape, &pieces);
            for (size_t i = 0; i < wire.size(); ++i) {
                const Vec3 p = wire[i] * kWireLift;
                const auto c = pieceColour(pieces[i / 2]);
                data.insert(data.end(), {float(p.x()), float(p.y()), float(p.z()), c[0], c[1], c[2]});
            }
            return data;
        };
        // (Convex parts are drawn as made, each time: parts made anew under the same mesh
        // must not find the old ones' buffer.)
        if (s.type != ShapeType::Mesh || s.collision == MeshCollision::ConvexParts) {
            return makeColouredRenderer(build(s), Qt3DRender::QGeometryRenderer::Lines, owner);
        }
        // A mesh's wire: one buffer per mesh and collision kind, a renderer per body (as
        // meshRenderer, and for the same reason).
        const auto key = std::make_pair(s.meshData.get(), s.collision);
        auto it = meshWires.find(key);
        if (it == meshWires.end()) {
            const std::vector<float> data = build(s);
            it = meshWires.emplace(key, std::make_pair(s.meshData, MeshBuffer{makeBuffer(data, root), int(data.size())}))
                     .first;
        }
        const MeshBuffer& m = it->second.second;
        return rendererOf(m.buffer, m.floats,
                          {{Qt3DCore::QAttribute::defaultPositionAttributeName(), 3},
                           {Qt3DCore::QAttribute::defaultColorAttributeName(), 3}},
                          Qt3DRender::QGeometryRenderer::Lines, owner);
    }

    void setWire(Body& b) {
        delete b.wire;
        b.wire = nullptr;
        b.wireTransform = nullptr;
        if (!showWire || b.shape.type == ShapeType::Plane) return;
        if (b.shape.type == ShapeType::Mesh && !b.shape.meshData) return;
        b.wire = new Qt3DCore::QEntity(root);
        b.wireTransform = new Qt3DCore::QTransform(b.wire);
        b.wireTransform->setTranslation(b.position);
        b.wireTransform->setRotation(b.orientation);
        b.wire->addComponent(b.wireTransform);
        b.wire->addComponent(wireRenderer(b.shape, b.wire));
        b.wire->addComponent(wireMat);
    }

    static void drop(Body& b) {
        delete b.entity;
        delete b.wire;
        b.entity = nullptr;
        b.transform = nullptr;
        b.part = nullptr;
        b.meshParts.clear();
        b.wire = nullptr;
        b.wireTransform = nullptr;
    }

    // Pose and drawing from the description (rebuilt: the shape may have changed).
    void fill(Body& b, const BodyDesc& desc) {
        const bool wasInstanced = b.shape.type != ShapeType::Mesh;
        drop(b);
        b.shape = desc.shape;
        const ShapeDesc& s = desc.shape;
        if (s.type == ShapeType::Mesh) {
            b.entity = new Qt3DCore::QEntity(root);
            b.transform = new Qt3DCore::QTransform(b.entity);
            b.entity->addComponent(b.transform);
            b.material = materialFor(b);
            if (s.meshData) {
                b.part = new Qt3DCore::QEntity(b.entity);
                b.part->addComponent(meshRenderer(s.meshData, b.part));
                b.part->addComponent(b.material);
            }
            if (wasInstanced) changed();  // it leaves the instances
        } else if (s.type == ShapeType::Compound) {
            // Its primitives are instances (flush); its meshes entities of their own.
            for (size_t k = 0; k < s.parts.size(); ++k) {
                const PartDesc& p = s.parts[k];
                if (p.shape.type != ShapeType::Mesh || !p.shape.meshData) continue;
                if (!b.entity) {
                    b.entity = new Qt3DCore::QEntity(root);
                    b.transform = new Qt3DCore::QTransform(b.entity);
                    b.entity->addComponent(b.transform);
                }
                Body::MeshPart m{new Qt3DCore::QEntity(b.entity), int(k), materialFor(b, int(k))};
                auto* at = new Qt3DCore::QTransform(m.entity);
                at->setTranslation(toQt(p.position));
                at->setRotation(toQt(p.orientation.normalized()));
                m.entity->addComponent(at);
                m.entity->addComponent(meshRenderer(p.shape.meshData, m.entity));
                m.entity->addComponent(m.material);
                b.meshParts.push_back(m);
            }
        }
        pose(b, desc);
        setWire(b);
    }

    // The materials of a mesh body, or of a compound's mesh parts, as its state now says.
    void refreshMaterials(Body& b) {
        auto swap = [](Qt3DCore::QEntity* e, Qt3DExtras::QPhongMaterial*& in, Qt3DExtras::QPhongMaterial* m) {
            if (in == m) return;
            if (e) {
                e->removeComponent(in);
                e->addComponent(m);
            }
            in = m;
        };
        swap(b.part, b.material, materialFor(b));
        for (Body::MeshPart& m : b.meshParts) swap(m.entity, m.material, materialFor(b, m.index));
    }

    void buildGridAndAxes() {
        std::vector<float> grid;
        // In pieces of at most 1 m (the grid's shader sets each vertex's depth by the slope
        // of the ground there: viewport_grid.cpp).
        auto line = [](std::vector<float>& v, QVector3D a, QVector3D b, QColor c) {
            const int pieces = std::max(1, int(std::ceil((b - a).length())));
            for (int k = 0; k < pieces; ++k) {
                for (const QVector3D& p : {a + (b - a) * float(k) / float(pieces), a + (b - a) * float(k + 1) / float(pieces)})
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

        gridEntity = new Qt3DCore::QEntity(root);
        gridEntity->addComponent(makeRenderer(grid,
                                              {{Qt3DCore::QAttribute::defaultPositionAttributeName(), 3},
                                               {Qt3DCore::QAttribute::defaultColorAttributeName(), 3}},
                                              Qt3DRender::QGeometryRenderer::Lines, gridEntity));
        gridEntity->addComponent(makeGridMaterial(gridEntity, e));
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
    d.instances = std::make_unique<ViewportInstances>(root);
    const QColor specular(40, 40, 40);
    d.dynamicLook = look(QColor(214, 140, 70), specular);
    d.staticLook = look(QColor(140, 144, 150), specular);
    d.kinematicLook = look(QColor(90, 140, 215), specular);
    d.selectedLook = look(QColor(255, 214, 60), specular, QColor(110, 90, 20));
    // The colour the ground had as a Phong-lit QPlaneMesh, (79, 81, 91) on screen.
    d.groundLook = look(QColor(42, 43, 48), QColor(0, 0, 0), QColor(35, 36, 40));
    // A selected ground is tinted, not lit up: the whole floor in the selection's yellow
    // drowned the bodies on it.
    d.selectedGroundLook = look(QColor(58, 54, 34), QColor(0, 0, 0), QColor(48, 44, 26));
    d.dynamicMat = makeMaterial(d.dynamicLook, root);
    d.staticMat = makeMaterial(d.staticLook, root);
    d.kinematicMat = makeMaterial(d.kinematicLook, root);
    d.selectedMat = makeMaterial(d.selectedLook, root);
    // Asleep (the Sleeping overlay): a cold, dim blue grey.
    d.asleepLook = look(QColor(96, 118, 150), specular);
    d.asleepMat = makeMaterial(d.asleepLook, root);
    d.wireMat = new Qt3DExtras::QPerVertexColorMaterial(root);
    d.buildLights();
    d.buildGridAndAxes();
}

ViewportScene::~ViewportScene() = default;  // the entities belong to the root

Qt3DCore::QEntity* ViewportScene::grid() const {
    return d_->gridEntity;
}

void ViewportScene::rebuild(const SceneDesc& scene) {
    for (auto& b : d_->bodies) Impl::drop(b);
    d_->bodies.clear();
    for (auto& [key, value] : d_->meshes) delete value.second.buffer;
    d_->meshes.clear();
    for (auto& [key, value] : d_->meshWires) delete value.second.buffer;
    d_->meshWires.clear();
    d_->bodies.reserve(scene.bodies.size());
    for (const BodyDesc& desc : scene.bodies) d_->bodies.push_back(d_->make(desc, false));
    d_->changed();
}

void ViewportScene::insert(int index, const BodyDesc& body) {
    if (index < 0 || index > count()) index = count();
    d_->bodies.insert(d_->bodies.begin() + index, d_->make(body, false));
    d_->changed();
}

void ViewportScene::update(int index, const BodyDesc& body) {
    if (index < 0 || index >= count()) return;
    Impl::Body& b = d_->bodies[size_t(index)];
    b.motion = body.motion;
    b.plane = body.shape.type == ShapeType::Plane;
    if (Impl::sameShape(b.shape, body.shape)) {  // a move or a turn (a drag): keep the entities
        d_->refreshMaterials(b);
        d_->pose(b, body);
        return;
    }
    d_->fill(b, body);
    d_->changed();
}

void ViewportScene::remove(int index) {
    if (index < 0 || index >= count()) return;
    Impl::drop(d_->bodies[size_t(index)]);
    d_->bodies.erase(d_->bodies.begin() + index);
    d_->changed();
}

void ViewportScene::setSelection(const QList<int>& indices, int part) {
    bool any = false;
    for (int i = 0; i < count(); ++i) {
        Impl::Body& b = d_->bodies[size_t(i)];
        const bool selected = indices.contains(i);
        const int selectedPart = selected && indices.size() == 1 ? part : -1;
        if (selected == b.selected && selectedPart == b.selectedPart) continue;
        b.selected = selected;
        b.selectedPart = selectedPart;
        d_->refreshMaterials(b);
        if (b.shape.type != ShapeType::Mesh) any = true;
    }
    if (any) d_->changed();
}

int ViewportScene::count() const {
    return static_cast<int>(d_->bodies.size());
}

void ViewportScene::setShownPose(int index, const QVector3D& position, const QQuaternion& orientation) {
    if (index < 0 || index >= count()) return;
    Impl::Body& b = d_->bodies[size_t(index)];
    if (b.shown && b.position == position && b.orientation == orientation) return;
    b.shown = true;
    d_->place(b, position, orientation);
}

void ViewportScene::clearShownPoses() {
    for (Impl::Body& b : d_->bodies) {
        if (!b.shown) continue;
        b.shown = false;
        d_->place(b, b.docPosition, b.docOrientation);
    }
}

void ViewportScene::setAsleep(int index, bool asleep) {
    if (index < 0 || index >= count()) return;
    Impl::Body& b = d_->bodies[size_t(index)];
    if (b.asleep == asleep) return;
    b.asleep = asleep;
    d_->refreshMaterials(b);
    if (b.shape.type != ShapeType::Mesh) d_->changed();
}

int ViewportScene::asleepCount() const {
    return int(std::count_if(d_->bodies.begin(), d_->bodies.end(),
                             [](const Impl::Body& b) { return b.asleep && !b.plane; }));
}

QMatrix4x4 ViewportScene::drawnTransform(int index) const {
    QMatrix4x4 m;
    if (index < 0 || index >= count()) return m;
    const Impl::Body& b = d_->bodies[size_t(index)];
    m.translate(b.position);
    m.rotate(b.orientation);
    return m;
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
