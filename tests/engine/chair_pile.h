// The pile of chairs (issue 49): `count` chairs like the one in `chairScene` (the sample
// chair.json: a seat, a back and four legs, one compound body of 4.9 kg) in layers of 5 x 5,
// 0.7 m apart and 1.1 m up, each turned about the vertical, dropped onto its floor; impacts at
// the end of the step, as the peers take them. tumble-bench's chair-pile and the ledger test
// of tst_engine_compound build it here.
#pragma once

#include <tumble/scene.h>

#include <string>

namespace tumble::test {

inline SceneDesc chairPile(const SceneDesc& chairScene, int count) {
    SceneDesc s;
    s.settings = chairScene.settings;
    s.settings.impacts = ImpactTiming::EndOfStep;
    BodyDesc chair;
    for (const BodyDesc& b : chairScene.bodies) {
        if (b.motion == Motion::Static)
            s.bodies.push_back(b);
        else
            chair = b;
    }
    for (int k = 0; k < count; ++k) {
        BodyDesc c = chair;
        c.name = "chair-" + std::to_string(k);
        const int layer = k / 25, i = (k % 25) / 5, j = k % 5;
        c.position = Vec3((i - 2) * 0.7, 0.1 + 1.1 * layer, (j - 2) * 0.7);
        c.orientation = Quat(Eigen::AngleAxisd(k + 0.3 * ((k * 7) % 11 - 5) / 5.0, Vec3::UnitY()));
        s.bodies.push_back(c);
    }
    return s;
}

}  // namespace tumble::test
