// tst_scene_file's bad-input rows for joints' springs and servos (issue 51 item 1): each a
// change to the base scene's second joint (a ball joint of "crate") and the message that
// names the field.
#pragma once

namespace tumble::test {

template <class Row>
void jointDriveRows(Row row) {
    const char* ball = R"("type": "ball", "body_a": "crate")";
    row("spring on a ball joint", R"("anchor_b": [0, -0.5, 0])",
        R"("anchor_b": [0, -0.5, 0], "spring": {"stiffness": 10})", "joints[1].spring",
        "drop.json: joints[1].spring: a ball joint has none (only hinge and slider joints do)");
    row("negative spring stiffness", ball,
        R"("type": "hinge", "axis_a": [0, 1, 0], "spring": {"stiffness": -1}, "body_a": "crate")",
        "joints[1].spring.stiffness", "drop.json: joints[1].spring.stiffness: must be a finite number, at least 0");
    row("spring without its stiffness", ball,
        R"("type": "slider", "axis_a": [0, 1, 0], "spring": {"damping": 2}, "body_a": "crate")",
        "joints[1].spring.stiffness", "drop.json: joints[1].spring.stiffness: is missing");
    row("spring rest not finite", ball,
        R"("type": "slider", "axis_a": [0, 1, 0], "spring": {"stiffness": 2, "rest": 1e999}, "body_a": "crate")",
        "joints[1].spring.rest", "drop.json: joints[1].spring.rest: must be a finite number");
    row("servo and motor", ball,
        R"("type": "hinge", "axis_a": [0, 1, 0], "motor": {"speed": 1, "max_torque": 2}, )"
        R"("servo": {"target": 1, "time_constant": 0.1}, "body_a": "crate")",
        "joints[1].servo",
        "drop.json: joints[1].servo: a joint has one drive: a motor (a speed) or a servo (a target), not both");
    row("servo without its target", ball,
        R"("type": "hinge", "axis_a": [0, 1, 0], "servo": {"time_constant": 0.1}, "body_a": "crate")",
        "joints[1].servo.target", "drop.json: joints[1].servo.target: is missing");
    row("servo of no torque", ball,
        R"("type": "hinge", "axis_a": [0, 1, 0], "servo": {"target": 1, "time_constant": 0.1, "max_torque": 0}, )"
        R"("body_a": "crate")",
        "joints[1].servo.max_torque",
        "drop.json: joints[1].servo.max_torque: must be greater than 0 (leave it out for no bound)");
    row("servo with a time constant and gains", ball,
        R"("type": "hinge", "axis_a": [0, 1, 0], "servo": {"target": 1, "time_constant": 0.1, "stiffness": 5}, )"
        R"("body_a": "crate")",
        "joints[1].servo.time_constant",
        "drop.json: joints[1].servo.time_constant: give either time_constant or stiffness and damping, not both");
    row("servo without gains", ball,
        R"("type": "slider", "axis_a": [0, 1, 0], "servo": {"target": 1, "damping": 5}, "body_a": "crate")",
        "joints[1].servo.stiffness",
        "drop.json: joints[1].servo.stiffness: must be greater than 0 (or give time_constant instead of "
        "stiffness and damping)");
    row("negative time constant", ball,
        R"("type": "slider", "axis_a": [0, 1, 0], "servo": {"target": 1, "time_constant": -0.1}, "body_a": "crate")",
        "joints[1].servo.time_constant",
        "drop.json: joints[1].servo.time_constant: must be a finite number greater than 0");
    row("slider servo with a torque", ball,
        R"("type": "slider", "axis_a": [0, 1, 0], "servo": {"target": 1, "time_constant": 0.1, "max_torque": 3}, )"
        R"("body_a": "crate")",
        "joints[1].servo.max_torque", "drop.json: joints[1].servo.max_torque: unknown key");
}

}  // namespace tumble::test
