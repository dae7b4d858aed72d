// World::step's parked islands (the top of world.cpp): the islands without a moment of
// impact keep their free step while the others are cut.
#include "make_room.h"
#include "world_scratch.h"

#include <algorithm>
#include <iterator>

namespace tumble {

// After the first look at the step: the islands without an impact keep their free step.
void World::park() {
    Scratch& s = *scratch_;
    DetectScratch& d = s.detect;
    s.parkedCount = parkIslandsWithoutImpact(model_, state_, d.broadphase.pairs(), d.impacts, s.islands, s.parked);
    if (s.parkedCount == 0) {
        s.parked.clear();
        return;
    }
    profile_.parkedBodySteps += s.parkedCount;
    s.stepStart = state_;  // the contact memory and touching pairs of the step's start: unchanged so far
    copyMotion(s.before, s.stepStart);
    s.touchingAtStart = d.touching;
    s.ledgerAtStart = ledger_;
    s.realAsleep = state_.asleep;
    s.realAsleep.resize(model_.bodies.size(), 0);
    state_.asleep = s.realAsleep;
    for (int i : model_.dynamicBodies) {
        if (!s.parked[i]) continue;
        state_.asleep[i] = 1;
        s.before.bodies[i] = state_.bodies[i];  // a cut goes back to s.before: they stay at the end
    }
    // Their contacts wait for the end of the step.
    auto it = std::stable_partition(d.contacts.begin(), d.contacts.end(), [&](const collision::Manifold& m) {
        return !s.parked[m.bodyA] && !s.parked[m.bodyB];
    });
    s.parkedContacts.assign(it, d.contacts.end());
    d.contacts.erase(it, d.contacts.end());
}

// After each look at the cut bodies: false when one pairs with a parked body (its new path
// may reach it); else the contacts and impacts found with parked bodies (a moving kinematic
// body still pairs with them) are dropped: theirs are the ones of the free step.
bool World::leaveParked() {
    Scratch& s = *scratch_;
    DetectScratch& d = s.detect;
    auto parked = [&](int b) { return s.parked[b] != 0; };
    auto cut = [&](int b) { return model_.bodies[b].motion == Motion::Dynamic && !parked(b) && !state_.isAsleep(b); };
    for (const auto& [a, b] : d.broadphase.pairs())
        if ((parked(a) && cut(b)) || (parked(b) && cut(a))) return false;
    dropParked();
    return true;
}

void World::dropParked() {
    Scratch& s = *scratch_;
    DetectScratch& d = s.detect;
    auto parked = [&](int b) { return s.parked[b] != 0; };
    std::erase_if(d.contacts, [&](const collision::Manifold& m) { return parked(m.bodyA) || parked(m.bodyB); });
    std::erase_if(d.impacts, [&](const collision::ImpactEvent& e) { return parked(e.bodyA) || parked(e.bodyB); });
}

// Ends the parking: `unwind` takes the world back to the start of the step; else the sleep
// flags are the real ones again and the contacts of both sets are merged in pair order.
void World::unpark(bool unwind) {
    Scratch& s = *scratch_;
    DetectScratch& d = s.detect;
    if (unwind) {
        state_ = s.stepStart;
        ledger_ = s.ledgerAtStart;
        d.touching = s.touchingAtStart;
        s.impacts.clear();
    } else {
        state_.asleep = s.realAsleep;
        if (!model_.settings.sleeping) state_.asleep.clear();
        // In place (a second list for the merge stayed as large as the contacts between steps).
        const auto cut = static_cast<std::ptrdiff_t>(d.contacts.size());
        makeRoom(d.contacts, d.contacts.size() + s.parkedContacts.size());
        d.contacts.insert(d.contacts.end(), s.parkedContacts.begin(), s.parkedContacts.end());
        std::inplace_merge(d.contacts.begin(), d.contacts.begin() + cut, d.contacts.end(),
                           [](const collision::Manifold& a, const collision::Manifold& b) {
                               return std::pair(a.bodyA, a.bodyB) < std::pair(b.bodyA, b.bodyB);
                           });
    }
    s.parkedContacts.clear();
    s.parked.clear();
    s.parkedCount = 0;
}

}  // namespace tumble
