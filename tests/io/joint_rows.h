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
        "drop.json: joints[0].axis_a: a rope joint has no axis (hinge, slider, ball and six_axis joints have one)");
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
    // The six-axis joint's axes.
    row("axes on a hinge", ball, R"("type": "hinge", "axis_a": [0, 1, 0], "axes": {"x": "free"}, "body_a": "crate")",
        "joints[1].axes", "drop.json: joints[1].axes: a hinge joint has none (only six_axis joints do)");
    row("an axis of no mode", ball, R"("type": "six_axis", "axes": {"y": "loose"}, "body_a": "crate")",
        "joints[1].axes.y",
        "drop.json: joints[1].axes.y: must be \"locked\", \"free\" or an object of limits, motor, spring and servo");
    row("an axis that is not one", ball, R"("type": "six_axis", "axes": {"w": "free"}, "body_a": "crate")",
        "joints[1].axes.w", "drop.json: joints[1].axes.w: unknown key");
    row("an angle's limits past pi", ball,
        R"("type": "six_axis", "axes": {"rx": {"limits": [-4, 1]}}, "body_a": "crate")", "joints[1].axes.rx.limits",
        "drop.json: joints[1].axes.rx.limits: must be angles within [-pi, pi] (rad)");
    row("an axis's limits inverted", ball,
        R"("type": "six_axis", "axes": {"y": {"limits": [0.5, -0.5]}}, "body_a": "crate")",
        "joints[1].axes.y.limits", "drop.json: joints[1].axes.y.limits: the lower limit is above the upper one");
    row("a linear axis's motor with a torque", ball,
        R"("type": "six_axis", "axes": {"x": {"motor": {"speed": 1, "max_torque": 2}}}, "body_a": "crate")",
        "joints[1].axes.x.motor.max_torque",
        "drop.json: joints[1].axes.x.motor.max_torque: a linear axis's motor gives a force: max_force");
    row("an angular axis's servo with a force", ball,
        R"("type": "six_axis", "axes": {"rz": {"servo": {"target": 1, "time_constant": 0.1, "max_force": 3}}}, )"
        R"("body_a": "crate")",
        "joints[1].axes.rz.servo.max_force", "drop.json: joints[1].axes.rz.servo.max_force: unknown key");
    row("an axis's negative spring", ball,
        R"("type": "six_axis", "axes": {"y": {"spring": {"stiffness": -3}}}, "body_a": "crate")",
        "joints[1].axes.y.spring.stiffness",
        "drop.json: joints[1].axes.y.spring.stiffness: must be a finite number, at least 0");
    row("an angle's servo target past pi", ball,
        R"("type": "six_axis", "axes": {"rx": {"servo": {"target": 4, "time_constant": 0.1}}}, "body_a": "crate")",
        "joints[1].axes.rx.servo.target",
        "drop.json: joints[1].axes.rx.servo.target: must be an angle within [-pi, pi] (rad)");
    row("six-axis with axis_b", ball, R"("type": "six_axis", "body_a": "crate", "axis_a": [0, 1, 0], "axis_b": [1, 0, 0])",
        "joints[1].axis_b",
        "drop.json: joints[1].axis_b: a six_axis joint's frame on body_b is body_a's as placed: give axis_a only");
    row("limits on a six-axis joint itself", ball, R"("type": "six_axis", "body_a": "crate", "limits": [0, 1])",
        "joints[1].limits", "drop.json: joints[1].limits: a six_axis joint has none (only hinge and slider joints do)");
}

}  // namespace tumble::test
