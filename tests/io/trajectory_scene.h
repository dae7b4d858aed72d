// The scene the trajectory writers are tested on: every motion (a static ground, a dynamic
// ball, a dynamic box whose centre of mass is away from its body frame's origin so that
// the written position differs from x, a moving kinematic carousel), a spin, and a ball
// named `ballName` (a name the format must quote or escape). 0.5 s at 20 frames/s.
#pragma once

#include <tumble/scene.h>

#include <string>

namespace tumble::test {

inline SceneDesc trajectoryScene(const std::string& ballName) {
    SceneDesc s;
    s.settings.dt = 0.01;
    s.settings.duration = 0.5;
    s.settings.frameRate = 20;
    s.settings.integrator = "rk4";

    BodyDesc ground;
    ground.name = "ground";
    ground.motion = Motion::Static;
    ground.shape.type = ShapeType::Plane;
    s.bodies.push_back(ground);

    BodyDesc ball;
    ball.name = ballName;
    ball.shape.type = ShapeType::Sphere;
    ball.shape.radius = 0.2;
    ball.mass = 1.5;
    ball.position = Vec3(0, 3, 0);
    ball.velocity = Vec3(2, 5, -1);
    ball.angularVelocity = Vec3(0, 0, 3);
    s.bodies.push_back(ball);

    BodyDesc offset;  // centre of mass away from the body frame's origin
    offset.name = "offset";
    offset.shape.type = ShapeType::Box;
    offset.shape.halfExtents = Vec3(0.5, 0.3, 0.2);
    offset.mass = 2;
    offset.inertia = Vec3(0.2, 0.3, 0.4).asDiagonal();
    offset.centerOfMass = Vec3(0.3, -0.2, 0.1);
    offset.position = Vec3(1, 2, 3);
    offset.orientation = Quat(Eigen::AngleAxisd(0.4, Vec3(0, 0, 1)));
    offset.angularVelocity = Vec3(1, 2, -0.5);
    s.bodies.push_back(offset);

    BodyDesc carousel;
    carousel.name = "carousel";
    carousel.motion = Motion::Kinematic;
    carousel.shape.type = ShapeType::Cylinder;
    carousel.position = Vec3(-1, 0, 0);
    carousel.velocity = Vec3(0.25, 0, 0);
    carousel.angularVelocity = Vec3(0, 1.5, 0);
    s.bodies.push_back(carousel);
    return s;
}

}  // namespace tumble::test
