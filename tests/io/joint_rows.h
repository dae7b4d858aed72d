// tst_scene_file's bad-input rows for joints' springs, servos, cones and twist limits (issue
// 51 item 1): each a
// change to the base scene's second joint (a ball joint of "crate") and the message that
// names the field.
#pragma once

namespace tumble::test {

template <class Row>
void jointFeatureRows(Row row) {
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
    row("servo keys out of order", ball,
        R"("type": "hinge", "axis_a": [0, 1, 0], "servo": {"time_constant": 0.1, )"
        R"("keys": [{"time": 1, "target": 0}, {"time": 1, "target": 1}]}, "body_a": "crate")",
        "joints[1].servo.keys[1].time", "drop.json: joints[1].servo.keys[1].time: must be later than the key before");
    row("servo target and keys", ball,
        R"("type": "hinge", "axis_a": [0, 1, 0], "servo": {"time_constant": 0.1, "target": 1, )"
        R"("keys": [{"time": 1, "target": 0}]}, "body_a": "crate")",
        "joints[1].servo.target", "drop.json: joints[1].servo.target: give target or keys, not both");
    row("rope with an axis", R"("length": 1.5)", R"("length": 1.5, "axis_a": [0, 1, 0])", "joints[0].axis_a",
        "drop.json: joints[0].axis_a: a rope joint has no axis (hinge, slider and ball joints have one)");
    const char* axis = R"("anchor_b": [0, -0.5, 0])";
    row("swing limit on a hinge", ball,
        R"("type": "hinge", "axis_a": [0, 1, 0], "swing_limit": 0.5, "body_a": "crate")", "joints[1].swing_limit",
        "drop.json: joints[1].swing_limit: a hinge joint has none (only ball joints do)");
    row("swing limit without an axis", axis, R"("anchor_b": [0, -0.5, 0], "swing_limit": 0.5)", "joints[1].axis_a",
        "drop.json: joints[1].axis_a: is missing (a ball joint's swing_limit and twist_limits are about its axis)");
    row("swing limit of 0", axis, R"("anchor_b": [0, -0.5, 0], "axis_a": [0, 1, 0], "swing_limit": [0.5, 0])",
        "joints[1].swing_limit",
        "drop.json: joints[1].swing_limit: must be angles greater than 0 and less than pi (rad)");
    row("swing limit of three angles", axis,
        R"("anchor_b": [0, -0.5, 0], "axis_a": [0, 1, 0], "swing_limit": [0.5, 0.2, 0.1])", "joints[1].swing_limit",
        "drop.json: joints[1].swing_limit: must be an angle or an array of 2 angles");
    row("twist limits past pi", axis, R"("anchor_b": [0, -0.5, 0], "axis_a": [0, 1, 0], "twist_limits": [-4, 1])",
        "joints[1].twist_limits", "drop.json: joints[1].twist_limits: must be angles within [-pi, pi] (rad)");
    row("twist limits inverted", axis, R"("anchor_b": [0, -0.5, 0], "axis_a": [0, 1, 0], "twist_limits": [1, -1])",
        "joints[1].twist_limits", "drop.json: joints[1].twist_limits: the lower limit is above the upper one");
}

}  // namespace tumble::test
