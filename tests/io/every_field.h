// A scene that sets every field of the scene format to something other than its default
// (tst_scene_file's round trips): bodies of every shape, forces of every kind, joints of
// every type with limits, a motor, springs, servos and a breaking force.
#pragma once

#include <tumble/scene.h>

namespace tumble::test {

inline Mat3 mat(double a, double b, double c, double d, double e, double f, double g, double h, double i) {
    Mat3 m;
    m << a, b, c, d, e, f, g, h, i;
    return m;
}

inline SceneDesc everyField() {
    SceneDesc s;
    s.settings.gravity = Vec3(0.5, -3.7, 1.25);
    s.settings.dt = 0.002;
    s.settings.duration = 2.5;
    s.settings.integrator = "symplectic-euler";
    s.settings.frameRate = 50;
    s.settings.sleeping = false;
    s.settings.solverIterations = 7;
    s.settings.impacts = ImpactTiming::EndOfStep;
    s.settings.collisionGroups = {"debris", "default", "fence"};
    s.settings.groupsApart = {{"debris", "fence"}, {"debris", "debris"}};

    BodyDesc ground;
    ground.name = "ground";
    ground.motion = Motion::Static;
    ground.shape.type = ShapeType::Plane;
    ground.shape.normal = Vec3(1, 2, 2) / 3.0;
    ground.shape.distance = -0.25;
    ground.restitution = 0.9;
    ground.friction = 0.8;
    s.bodies.push_back(ground);

    BodyDesc ball;
    ball.name = "ball, \"the\" first";
    ball.shape.type = ShapeType::Sphere;
    ball.shape.radius = 0.3;
    ball.mass = 2.5;
    ball.position = Vec3(0.1, 2, -0.3);
    ball.orientation = Quat(Eigen::AngleAxisd(0.7, Vec3(1, 2, 3).normalized()));
    ball.velocity = Vec3(1, 2, 3);
    ball.angularVelocity = Vec3(-0.5, 0.25, 4);
    ball.restitution = 0.25;
    ball.friction = 1.5;
    ball.linearDamping = 0.1;
    ball.angularDamping = 0.05;
    ForceDesc push;
    push.type = ForceType::Force;
    push.vector = Vec3(1, 0, -2);
    push.point = Vec3(0, 0.3, 0);
    push.frame = Frame::Body;
    push.start = 0.5;
    push.end = 1.5;
    ball.forces.push_back(push);
    ForceDesc thrust;  // at the centre of mass, world frame, always
    thrust.type = ForceType::Force;
    thrust.vector = Vec3(0, 3, 0);
    ball.forces.push_back(thrust);
    ForceDesc twist;
    twist.type = ForceType::Torque;
    twist.vector = Vec3(0, 0, 0.125);
    twist.frame = Frame::World;
    twist.start = 1.0;
    ball.forces.push_back(twist);
    ForceDesc spring;
    spring.type = ForceType::Spring;
    spring.anchor = Vec3(0, 4, 0);
    spring.point = Vec3(0.1, 0.2, 0);
    spring.stiffness = 40;
    spring.restLength = 1.25;
    spring.damping = 0.75;
    spring.end = 2.0;
    ball.forces.push_back(spring);
    s.bodies.push_back(ball);

    BodyDesc crate;
    crate.name = "crate";
    crate.shape.type = ShapeType::Box;
    crate.shape.halfExtents = Vec3(0.5, 0.25, 0.125);
    crate.density = 750;
    crate.inertia = mat(2, 0.1, 0, 0.1, 3, -0.2, 0, -0.2, 4);
    crate.centerOfMass = Vec3(0.01, -0.02, 0.03);
    crate.position = Vec3(3, 1, 0);
    s.bodies.push_back(crate);

    BodyDesc pill;
    pill.name = "pill";
    pill.motion = Motion::Kinematic;
    pill.shape.type = ShapeType::Capsule;
    pill.shape.radius = 0.2;
    pill.shape.halfHeight = 0.6;
    pill.position = Vec3(-2, 1, 0);
    pill.orientation = Quat(0.5, -0.5, 0.5, 0.5);
    pill.velocity = Vec3(0.5, 0, 0);
    pill.angularVelocity = Vec3(0, 1, 0);
    s.bodies.push_back(pill);

    BodyDesc can;
    can.name = "can";
    can.shape.type = ShapeType::Cylinder;
    can.shape.radius = 0.1;
    can.shape.halfHeight = 0.2;
    can.mass = 0.33;
    can.inertia = mat(0.01, 0, 0, 0, 0.002, 0, 0, 0, 0.01);
    s.bodies.push_back(can);

    BodyDesc bunny;
    bunny.name = "bunny";
    bunny.shape.type = ShapeType::Mesh;
    bunny.shape.file = "meshes/bunny.obj";
    bunny.shape.scale = Vec3(1, 2, 0.5);
    bunny.shape.collision = MeshCollision::Triangles;
    bunny.density = 500;
    s.bodies.push_back(bunny);

    BodyDesc post;
    post.name = "post";
    post.motion = Motion::Static;
    post.shape.type = ShapeType::Box;
    post.shape.halfExtents = Vec3(0.1, 1, 0.1);
    post.position = Vec3(0, 1, 5);
    post.collisionGroup = "fence";
    s.bodies.push_back(post);

    BodyDesc cart;  // a compound: every part field, a mesh part among them
    cart.name = "cart";
    cart.shape.type = ShapeType::Compound;
    PartDesc deck;
    deck.name = "deck";
    deck.shape.type = ShapeType::Box;
    deck.shape.halfExtents = Vec3(0.5, 0.05, 0.3);
    deck.position = Vec3(0, 0.2, 0);
    deck.orientation = Quat(Eigen::AngleAxisd(0.3, Vec3::UnitY()));
    deck.density = 600;
    deck.friction = 0.3;
    deck.restitution = 0.1;
    cart.shape.parts.push_back(deck);
    PartDesc lump;  // no name, no own density or material: the body's
    lump.shape.type = ShapeType::Mesh;
    lump.shape.file = "meshes/bunny.obj";
    lump.shape.scale = Vec3(0.5, 0.5, 0.5);
    lump.shape.collision = MeshCollision::ConvexParts;  // with both of its options
    lump.shape.maxParts = 4;
    lump.shape.partsTolerance = 0.01;
    lump.position = Vec3(0.2, 0.4, -0.1);
    cart.shape.parts.push_back(lump);
    cart.mass = 50.0;  // more than the deck's own 36 kg (0.06 m³ at 600 kg/m³): the lump takes the rest
    cart.position = Vec3(4, 0.5, 4);
    s.bodies.push_back(cart);

    BodyDesc paddle;  // animated: keys of every field, smooth
    paddle.name = "paddle";
    paddle.motion = Motion::Animated;
    paddle.shape.type = ShapeType::Box;
    paddle.shape.halfExtents = Vec3(0.05, 0.3, 0.4);
    paddle.position = Vec3(-1, 0.5, 2);
    paddle.interpolation = KeyInterpolation::Smooth;
    paddle.keys = {{0.25, Vec3(-1, 0.5, 2), Quat::Identity()},
                   {1.5, Vec3(0.5, 0.75, 2), Quat(0.5, 0.5, -0.5, 0.5)},
                   {2.0, Vec3(1, 0.5, 2.5), Quat(0, 0, 1, 0)}};
    s.bodies.push_back(paddle);

    JointDesc rope;  // to the world, with its length
    rope.name = "string";
    rope.type = JointType::Rope;
    rope.bodyA = ball.name;
    rope.anchorA = Vec3(0, 0.3, 0);
    rope.anchorB = Vec3(0.1, 4, -0.3);
    rope.length = 1.75;
    s.joints.push_back(rope);
    JointDesc rod;  // between two bodies, its length from the scene
    rod.name = "rod";
    rod.type = JointType::Distance;
    rod.bodyA = "crate";
    rod.anchorA = Vec3(0.5, 0, 0);
    rod.bodyB = "can";
    rod.anchorB = Vec3(0, 0.2, 0);
    s.joints.push_back(rod);
    JointDesc hinge;
    hinge.name = "pin";
    hinge.type = JointType::Ball;
    hinge.bodyA = "crate";
    hinge.anchorA = Vec3(-0.5, 0.25, 0);
    hinge.bodyB = "post";
    hinge.anchorB = Vec3(0, 1, 0);
    hinge.axisA = Vec3(0, -1, 0);  // a shoulder: an elliptical cone and a twist range
    hinge.axisB = Vec3(0, -1, 0.5);
    hinge.swingLimit = std::array<double, 2>{0.75, 0.25};
    hinge.twistLimits = std::array<double, 2>{-0.5, 0.25};
    s.joints.push_back(hinge);
    JointDesc door;  // a hinge with both axes given
    door.name = "door";
    door.type = JointType::Hinge;
    door.bodyA = "can";
    door.anchorA = Vec3(0, 0.2, 0);
    door.axisA = Vec3(0, 1, 0);
    door.bodyB = "post";
    door.anchorB = Vec3(0.1, 0.5, 0);
    door.axisB = Vec3(0, 2, 0);
    door.limits = std::array<double, 2>{-1.25, 0.5};
    door.motor = JointDesc::Motor{0.75, 12.5};
    door.spring = JointDesc::Spring{3.5, 0.25, 0.125};
    s.joints.push_back(door);
    JointDesc rail;  // a slider to the world, its world axis from the start
    rail.name = "rail";
    rail.type = JointType::Slider;
    rail.bodyA = "bunny";
    rail.axisA = Vec3(1, 0, 0);
    rail.limits = std::array<double, 2>{-0.5, 2};
    rail.motor = JointDesc::Motor{-0.25, 40};
    s.joints.push_back(rail);
    JointDesc shock;  // a slider's servo by gains, unbounded; a spring at rest at 0
    shock.name = "shock";
    shock.type = JointType::Slider;
    shock.bodyA = "can";
    shock.bodyB = "post";
    shock.axisA = Vec3(0, 1, 0);
    shock.spring = JointDesc::Spring{400, 0, 0};
    shock.servo = JointDesc::Servo{-0.25, HUGE_VAL, 400, 20, 0, {}};
    s.joints.push_back(shock);
    JointDesc arm;  // a hinge's servo by its time constant, bounded
    arm.name = "arm";
    arm.type = JointType::Hinge;
    arm.bodyA = "crate";
    arm.axisA = Vec3(0, 0, 1);
    arm.servo = JointDesc::Servo{0.5, 30, 0, 0, 0.2, {{0.0, 0.5}, {1.5, -0.25}, {2.0, 0.125}}};
    s.joints.push_back(arm);
    JointDesc weld;
    weld.name = "weld";
    weld.type = JointType::Fixed;
    weld.bodyA = "crate";
    weld.bodyB = "can";
    weld.breakForce = 1500;
    weld.collideConnected = true;
    s.joints.push_back(weld);
    JointDesc six;  // every kind of axis: locked, free, limited, driven, sprung, servoed
    six.name = "six";
    six.type = JointType::SixAxis;
    six.bodyA = "crate";
    six.bodyB = "can";
    six.axisA = Vec3(0, 1, 0);
    six.axes[1].free = true;
    six.axes[1].limits = std::array<double, 2>{-0.125, 0.25};
    six.axes[1].spring = JointDesc::Spring{500, 12.5, 0.0625};
    six.axes[2].free = true;
    six.axes[2].motor = JointDesc::Motor{0.5, 75};
    six.axes[3].free = true;
    six.axes[4].free = true;
    six.axes[4].servo = JointDesc::Servo{0.25, 8, 0, 0, 0.125, {}};
    six.axes[5].free = true;
    six.axes[5].limits = std::array<double, 2>{-1.5, 0.75};
    s.joints.push_back(six);
    s.noCollide = {{"pill", "bunny"}};
    return s;
}

}  // namespace tumble::test
