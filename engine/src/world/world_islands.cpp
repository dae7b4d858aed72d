// World::step's parked islands (the top of world.cpp): the islands without a moment of
// impact keep their free step while the others are cut.
#include "common/make_room.h"
#include "world/world_scratch.h"

#include <algorithm>
#include <iterator>
#include <stdexcept>

namespace tumble {

namespace {

// Each island's own look at the step places every body and updates the broadphase: past
// this many islands with an impact they are cut together (drop-3000's 64 columns landing at
// one moment took 47 ms a step one by one, 11 together).
constexpr size_t kMostGroups = 16;

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
    const int groups = impactIslands(model_, state_, s.islands, s.groupOfRoot, s.groupBodies, s.groupBegin);
    if (s.parkedCount == 0 && groups < 2) {
        s.parked.clear();
        return;
    }
    profile_.parkedBodySteps += s.parkedCount;
    saveStepStart();
    bodyPoses(model_, s.stepStart, d.standFrom);
    d.standing = &s.parked;
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

// Several islands with an impact: cut together, every island is integrated again at every
// island's moments (hull-rain: 7.8 islands with an impact a step, 30 bodies, 5.3 moments).
// Each is cut on its own instead, the others standing as parked islands do: the pending ones
// at the end of their free step, the ones done at their end; the parked islands' machinery
// (leaveParked, the step taken again when a cut body meets a standing one) serves them too.
// The first island is set up; false when there are fewer than two.
bool World::startGroups() {
    Scratch& s = *scratch_;
    const size_t groups = s.groupBegin.empty() ? 0 : s.groupBegin.size() - 1;
    if (groups < 2 || groups > kMostGroups) return false;
    s.parkedIslands = s.parked;
    s.parkedIslandCount = s.parkedCount;
    s.groupContacts.clear();
    s.groupRuns.clear();
    // The other islands stand at the end of their free step until their turn.
    for (int m = s.groupBegin[1]; m < s.groupBegin.back(); ++m) {
        const int i = s.groupBodies[m];
        s.parked[i] = 1;
        state_.asleep[i] = 1;
        ++s.parkedCount;
    }
    setUpGroup(0);
    return true;
}

// Island g from the start of the step, with its own first look and its own cuts.
void World::setUpGroup(int g) {
    Scratch& s = *scratch_;
    s.group = g;
    for (int m = s.groupBegin[g]; m < s.groupBegin[g + 1]; ++m) {
        const int i = s.groupBodies[m];
        if (s.parked[i]) --s.parkedCount;
        s.parked[i] = 0;
        state_.asleep[i] = 0;
        state_.bodies[i] = s.stepStart.bodies[i];
    }
    state_.time = s.stepStart0;
    s.detect.touching = s.touchingAtStart;
    forgetSearches();
}

// The island being cut is done (its contacts solved at its end): its bodies, and the ones it
// woke, stand from now on and its contacts are kept for the end of the step. The next island
// is set up; false when none is left.
bool World::nextGroup() {
    Scratch& s = *scratch_;
    s.groupEnd.resize(model_.bodies.size());
    for (int i : model_.dynamicBodies) {
        if (s.parked[i] || state_.asleep[i]) continue;
        s.groupEnd[i] = s.detect.end[i];  // (the next island's looks place every body again)
        s.realAsleep[i] = 0;
        s.parked[i] = 1;
        state_.asleep[i] = 1;
        ++s.parkedCount;
    }
    s.groupRuns.push_back(s.groupContacts.size());
    s.groupContacts.insert(s.groupContacts.end(), s.detect.contacts.begin(), s.detect.contacts.end());
    if (s.group + 2 >= static_cast<int>(s.groupBegin.size())) return false;
    setUpGroup(s.group + 1);
    return true;
}

// Out of group mode. `unwind`: the step is taken again (unpark(true) follows); else the
// islands' contacts are merged in pair order (each island's are in pair order and no pair
// is in two) and the flags are park()'s again.
void World::endGroups(bool unwind) {
    Scratch& s = *scratch_;
    if (s.group < 0) return;
    s.group = -1;
    if (!unwind) {
        collision::ManifoldList& out = s.detect.contacts;
        out.clear();
        std::vector<std::size_t>& at = s.groupRuns;  // each run's next manifold
        const size_t runs = at.size();
        at.push_back(s.groupContacts.size());
        std::vector<std::size_t>& ends = s.groupRunEnds;
        ends.assign(at.begin() + 1, at.end());
        for (;;) {
            int best = -1;
            for (size_t r = 0; r < runs; ++r) {
                if (at[r] == ends[r]) continue;
                const auto& m = s.groupContacts[at[r]];
                if (best < 0 || std::pair(m.bodyA, m.bodyB) < std::pair(s.groupContacts[at[best]].bodyA,
                                                                       s.groupContacts[at[best]].bodyB))
                    best = static_cast<int>(r);
            }
            if (best < 0) break;
            out.push_back(s.groupContacts[at[best]++]);
        }
        // The islands' poses where their contacts were found, for what the solve moved
        // (settleOverlap) and the flags as they really are.
        for (int i : model_.dynamicBodies)
            if (s.parked[i] && !s.parkedIslands[i]) {
                state_.asleep[i] = s.realAsleep[i];
                s.detect.end[i] = s.groupEnd[i];
            }
    }
    s.groupContacts.clear();
    s.groupRuns.clear();
    s.parked = s.parkedIslands;
    s.parkedCount = s.parkedIslandCount;
    if (!unwind && s.parkedCount == 0) {  // no parked island: the flags are the real ones now
        state_.asleep = s.realAsleep;
        if (!model_.settings.sleeping) state_.asleep.clear();
        s.parked.clear();
        s.detect.standing = nullptr;
    }
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
    d.standing = nullptr;
}

}  // namespace tumble
