// World::step's parked islands (the top of world.cpp): the islands without a moment of
// impact keep their free step while the others are cut.
#include "common/make_room.h"
#include "world/world_scratch.h"

#include <algorithm>
#include <iterator>
#include <stdexcept>

namespace tumble {

namespace {

// `to` made `from` but for the contact memory and the touching pairs, which neither copies:
// each keeps its own (a pile's are large, and a cut changes little of them).
void assignAllButMemory(State& to, State& from) {
    std::vector<ContactMemory> fromContacts = std::move(from.contacts), toContacts = std::move(to.contacts);
    std::vector<std::uint64_t> fromTouching = std::move(from.touching), toTouching = std::move(to.touching);
    to = from;
    from.contacts = std::move(fromContacts);
    from.touching = std::move(fromTouching);
    to.contacts = std::move(toContacts);
    to.touching = std::move(toTouching);
}

}  // namespace

// After the first look at the step: the islands without an impact keep their free step.
void World::park() {
    Scratch& s = *scratch_;
    DetectScratch& d = s.detect;
    s.parkedCount =
        parkIslandsWithoutImpact(model_, state_, d.broadphase.pairs(), d.impacts, s.islands, s.parked);
    if (s.parkedCount == 0) {
        s.parked.clear();
        return;
    }
    profile_.parkedBodySteps += s.parkedCount;
    saveStepStart();
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
    // Their contacts wait for the end of the step (split in one pass: std::stable_partition
    // took a buffer as large as the contacts for it).
    const auto parkedPair = [&](const collision::Manifold& m) {
        return s.parked[m.bodyA] || s.parked[m.bodyB];
    };
    const auto n = static_cast<size_t>(std::count_if(d.contacts.begin(), d.contacts.end(), parkedPair));
    s.parkedContacts.clear();
    makeRoom(s.parkedContacts, n);  // (grown by half, as rememberPairs' list and for the same reason)
    size_t cut = 0;
    for (size_t k = 0; k < d.contacts.size(); ++k) {
        const collision::Manifold& m = d.contacts[k];
        if (parkedPair(m)) {
            s.parkedContacts.push_back(m);
        } else if (cut++ != k) {
            d.contacts[cut - 1] = m;
        }
    }
    d.contacts.resize(cut);
}

// What an unwind goes back to (unpark): the state at the start of the step but its contact
// memory and touching pairs, which are large in a pile and which a cut changes little. The
// touching pairs change only at the end of the step. Of the memory, the piece solves of the
// cuts (impactAt) drop and remake the points with a body that is neither parked (asleep to
// them) nor standing still, and keep every other as it is, in order: those points alone are
// kept here, with their places. (A copy of the whole memory was 76 KB of hull-rain's peak.)
void World::saveStepStart() {
    Scratch& s = *scratch_;
    assignAllButMemory(s.stepStart, state_);
    copyMotion(s.before, s.stepStart);
    s.cutMemory.clear();
    s.cutMemoryAt.clear();
    s.memoryAtStart = state_.contacts.size();
    for (size_t k = 0; k < state_.contacts.size(); ++k) {
        const ContactMemory& c = state_.contacts[k];
        if (parkedOrStill(c.bodyA) && parkedOrStill(c.bodyB)) continue;
        s.cutMemory.push_back(c);
        s.cutMemoryAt.push_back(k);
    }
}

bool World::parkedOrStill(int body) const {
    return scratch_->parked[body] != 0 || model_.bodies[body].standsStill();
}

void World::restoreStepStart() {
    Scratch& s = *scratch_;
    assignAllButMemory(state_, s.stepStart);
    // The points kept as they were, in order, then the saved ones back in their places.
    std::vector<ContactMemory>& m = state_.contacts;
    std::erase_if(
        m, [&](const ContactMemory& c) { return !(parkedOrStill(c.bodyA) && parkedOrStill(c.bodyB)); });
    if (m.size() + s.cutMemory.size() != s.memoryAtStart)  // (a cut changed a point it keeps: a bug)
        throw std::logic_error("World: the contact memory a cut kept is not the step's start's");
    putBackInPlaces(m, s.cutMemory, s.cutMemoryAt);
}

// After each look at the cut bodies: false when one pairs with a parked body (its new path
// may reach it); else the contacts and impacts found with parked bodies (a moving kinematic
// body still pairs with them) are dropped: theirs are the ones of the free step.
bool World::leaveParked() {
    Scratch& s = *scratch_;
    DetectScratch& d = s.detect;
    auto parked = [&](int b) { return s.parked[b] != 0; };
    auto cut = [&](int b) {
        return model_.bodies[b].motion == Motion::Dynamic && !parked(b) && !state_.isAsleep(b);
    };
    for (const auto& [a, b] : d.broadphase.pairs())
        if ((parked(a) && cut(b)) || (parked(b) && cut(a))) return false;
    dropParked();
    return true;
}

void World::dropParked() {
    Scratch& s = *scratch_;
    DetectScratch& d = s.detect;
    auto parked = [&](int b) { return s.parked[b] != 0; };
    std::erase_if(d.contacts,
                  [&](const collision::Manifold& m) { return parked(m.bodyA) || parked(m.bodyB); });
    std::erase_if(d.impacts,
                  [&](const collision::ImpactEvent& e) { return parked(e.bodyA) || parked(e.bodyB); });
}

// Ends the parking: `unwind` takes the world back to the start of the step; else the sleep
// flags are the real ones again and the contacts of both sets are merged in pair order.
void World::unpark(bool unwind) {
    Scratch& s = *scratch_;
    DetectScratch& d = s.detect;
    if (unwind) {
        restoreStepStart();
        ledger_ = s.ledgerAtStart;
        d.touching = s.touchingAtStart;
        s.impacts.clear();
    } else {
        state_.asleep = s.realAsleep;
        if (!model_.settings.sleeping) state_.asleep.clear();
        // In place, from the back, the cut pairs' first among equals as in a stable merge (a
        // second list for the merge stayed as large as the contacts between steps, and
        // std::inplace_merge takes a buffer for it).
        auto after = [](const collision::Manifold& a, const collision::Manifold& b) {
            return std::pair(a.bodyA, a.bodyB) > std::pair(b.bodyA, b.bodyB);
        };
        size_t cut = d.contacts.size(), parked = s.parkedContacts.size();
        makeRoom(d.contacts, cut + parked);
        d.contacts.resize(cut + parked);
        for (size_t k = cut + parked; parked > 0;) {
            --k;
            if (cut > 0 && after(d.contacts[cut - 1], s.parkedContacts[parked - 1])) {
                d.contacts[k] = d.contacts[--cut];
            } else {
                d.contacts[k] = s.parkedContacts[--parked];
            }
        }
    }
    s.parkedContacts.clear();
    s.parked.clear();
    s.parkedCount = 0;
}

}  // namespace tumble
