#include "solver/contact_prepare.h"

#include "common/make_room.h"
#include "common/resting.h"
#include "common/workers.h"
#include "solver/block_regions.h"
#include "solver/contact_rows.h"

#include <bit>
#include <chrono>

namespace tumble {

using collision::Manifold;
using collision::ManifoldList;
using Point = ContactSolverScratch::Point;

namespace {

// Blocks made per chunk on the pool.
constexpr int kBlockGrain = 32;

// First, on one thread: which points of each manifold are solved (s.blockManifold and
// s.blockPoints, in the manifolds' order); only what choosing them needs is computed here,
// the rest is each block's own (makeBlock).
void choosePoints(const Model& model, const ManifoldList& contacts, const ContactSolverSettings& cfg,
                  ContactSolverScratch& s) {
    s.stillMoving.clear();
    s.blockManifold.clear();
    s.blockPoints.clear();
    for (size_t k = 0; k < contacts.size(); ++k) {
        const Manifold& m = contacts[k];
        const SolverBody& A = s.bodies[m.bodyA];
        const SolverBody& B = s.bodies[m.bodyB];
        if (A.invMass == 0.0 && B.invMass == 0.0) continue;  // nothing here can move
        if (isStill(s, m.bodyA) || isStill(s, m.bodyB)) {
            // Taken as last solved. Its bodies are among those the solve moves, as they
            // would be with a point to solve (s.moving: the energy balance's sums).
            for (int i = 0; i < m.count; ++i) {
                if (m.points[i].depth < -cfg.margin) continue;
                for (int b : {m.bodyA, m.bodyB})
                    if (s.bodies[b].invMass > 0.0) s.stillMoving.push_back(b);
                break;
            }
            continue;
        }
        std::uint8_t chosen = 0;
        for (int i = 0; i < m.count; ++i) {
            const collision::ContactPoint& c = m.points[i];
            if (c.depth < -cfg.margin) continue;
            // Apart at the end of the free step and closing fast: an impact of a later step,
            // which its time of impact finds at its moment. As a row here it was a landing
            // placed a step early: gap0 + h vn >= 0 with the end's velocity closes ½ g h² more
            // than the fall does, and a ball 3.8 mm above a stair at the end of a 1/30 s step
            // had its approach cut to what closed the gap, its bounce lost (issue 45).
            if (c.depth < -cfg.touchTolerance) {
                const double vn = m.normal.dot(relativeVelocity(A, c.position - A.x, B, c.position - B.x));
                if (vn < -cfg.restingSpeed * restingShare(model.settings.gravity, m.normal)) continue;
            }
            chosen |= static_cast<std::uint8_t>(1u << i);
        }
        if (chosen == 0) continue;
        s.blockManifold.push_back(static_cast<int>(k));
        s.blockPoints.push_back(chosen);
    }
}

// Then the blocks' order: the manifolds', or region by region when splitBlocks split them
// (each region's blocks side by side in memory, as its thread reads them); s.blockManifold and
// s.blockPoints are put in that order, and s.blockFirst gives each block's first point. The
// lists are sized for them without writing what they hold: each block writes its own entries
// (placeBlock, on the pool); only a list that must grow is made again.
void orderBlocks(ContactSolverScratch& s) {
    const int n = static_cast<int>(s.blockManifold.size());
    if (s.split) {
        auto inRegionOrder = [&](auto& list, auto& spare) {
            spare.resize(n);
            for (int j = 0; j < n; ++j) spare[j] = list[s.regionBlocks[j]];
            list.swap(spare);
        };
        inRegionOrder(s.blockManifold, s.spareManifold);
        inRegionOrder(s.blockPoints, s.sparePoints);
    }
    s.blockFirst.resize(n + 1);
    s.blockFirst[0] = 0;
    for (int j = 0; j < n; ++j) s.blockFirst[j + 1] = s.blockFirst[j] + std::popcount(s.blockPoints[j]);
    auto sizeFor = [](auto& list, size_t size) {
        if (list.capacity() < size) {
            list.clear();
            makeRoom(list, size);
        }
        list.resize(size);
    };
    sizeFor(s.blocks, static_cast<size_t>(n));
    sizeFor(s.points, static_cast<size_t>(s.blockFirst[n]));
    sizeFor(s.geometry, static_cast<size_t>(s.blockFirst[n]));
}

// Block k and its points as chosen: bodies, normal, position, depth, feature.
void placeBlock(const ManifoldList& contacts, ContactSolverScratch& s, int k) {
    const Manifold& m = contacts[s.blockManifold[k]];
    ContactSolverScratch::Block& block = s.blocks[k];
    block = ContactSolverScratch::Block{};
    block.begin = s.blockFirst[k];
    block.count = s.blockFirst[k + 1] - block.begin;
    int at = block.begin;
    for (int i = 0; i < m.count; ++i) {
        if (!(s.blockPoints[k] >> i & 1u)) continue;
        const collision::ContactPoint& c = m.points[i];
        Point p;
        p.a = m.bodyA;
        p.b = m.bodyB;
        p.n = m.normal;
        p.armA = p.armB = p.spinA = p.spinB = Vec3::Zero();  // (makeBlock sets them)
        ContactSolverScratch::PointGeometry g;
        g.localA = g.localB = g.localN = Vec3::Zero();
        g.position = c.position;
        g.depth = c.depth;
        g.feature = c.feature;
        s.points[at] = p;
        s.geometry[at] = g;
        ++at;
    }
}

// Then block k, placed (placeBlock) and its rows made from its manifold: each point's effective
// mass, target and surface points, the block's K and friction frame. Reads the bodies, writes
// block k and its points only.
void makeBlock(const Model& model, const State& state, const State& before, const ManifoldList& contacts,
               const std::vector<double>& sizes, const ContactSolverSettings& cfg, ContactSolverScratch& s,
               int k) {
    const Manifold& m = contacts[s.blockManifold[k]];
    placeBlock(contacts, s, k);
    ContactSolverScratch::Block& block = s.blocks[k];
    const SolverBody& A = s.bodies[m.bodyA];
    const SolverBody& B = s.bodies[m.bodyB];
    const BodyModel& ma = model.bodies[m.bodyA];
    const BodyModel& mb = model.bodies[m.bodyB];
    const double e = std::max(ma.restitutionOf(m.partA), mb.restitutionOf(m.partB));
    const Mat3 RA = state.bodies[m.bodyA].q.toRotationMatrix();
    const Mat3 RB = state.bodies[m.bodyB].q.toRotationMatrix();
    // Each body's orientation at the start: its surface points where they were then
    // (a point's body coordinates turned by it).
    const Mat3 RA0 = before.bodies[m.bodyA].q.toRotationMatrix();
    const Mat3 RB0 = before.bodies[m.bodyB].q.toRotationMatrix();
    block.mu = std::sqrt(ma.frictionOf(m.partA) * mb.frictionOf(m.partB));
    const double roundA = roundness(partShape(ma.collider, m.partA)),
                 roundB = roundness(partShape(mb.collider, m.partB));
    for (int i = 0; i < block.count; ++i) {
        Point& p = s.points[block.begin + i];
        ContactSolverScratch::PointGeometry& g = s.geometry[block.begin + i];
        const Vec3 rA = g.position - A.x, rB = g.position - B.x;
        preparePoint(A, B, rA, rB, p);
        const double vn = p.n.dot(relativeVelocity(A, rA, B, rB));
        const double vn0 = p.n.dot(relativeVelocity(s.start[m.bodyA], rA, s.start[m.bodyB], rB));
        // A's deepest point is half the depth below the midpoint, B's half above.
        const Vec3 sA = rA - 0.5 * g.depth * p.n, sB = rB + 0.5 * g.depth * p.n;
        g.localA = RA.transpose() * sA;
        g.localB = RB.transpose() * sB;
        g.localN = RB.transpose() * p.n;
        // A round body's friction arm reaches its surface point (see prepareBlock).
        g.roundA = roundA > 0.0;
        g.roundB = roundB > 0.0;
        // The gap between those two surface points at the start of the step. The bodies
        // are placed again from there with the solved velocities (redoPoses), so the gap
        // at the end is gap0 + h vn: a gap may close within the step and no more, and an
        // overlap is never pushed apart with velocity (the position pass removes it
        // without kinetic energy). A contact is thus the same constraint whatever the
        // step, resting or landing slowly, and never a source of energy.
        // A round surface (a sphere, a capsule) is its core points grown by a radius:
        // the contact point slides over it as it rolls, so the gap is taken from the core
        // point, which moves with the body, less the radius. (From the surface point
        // turned back, a rolling ball's gap0 was R(1 - cos ωh) and the ball sank by it
        // every step: 0.9 mm at 1/240 s, 7.7 mm at 1/60, and never stopped slipping.)
        const Vec3 coreA = roundA > 0.0 ? Vec3(g.localA + roundA * (RA.transpose() * p.n)) : g.localA;
        const Vec3 coreB = roundB > 0.0 ? Vec3(g.localB - roundB * g.localN) : g.localB;
        const double gap0 = p.n.dot((before.bodies[m.bodyA].x + RA0 * coreA - roundA * p.n) -
                                    (before.bodies[m.bodyB].x + RB0 * coreB + roundB * p.n));
        if (vn < -cfg.restingSpeed && vn0 < -cfg.restingSpeed && gap0 <= cfg.touchTolerance)
            p.target = -e * vn;  // touching and approaching fast: a bounce
        else
            p.target = gap0 > 0.0 ? -gap0 / cfg.h : 0.0;
        // Apart at the start, or meeting fast: the step's velocity change here is a
        // landing's, not that of forces acting all through it (redoPoses).
        block.arriving = block.arriving || gap0 > cfg.touchTolerance || vn0 < -cfg.restingSpeed;
        g.size = std::min(sizes[m.bodyA], sizes[m.bodyB]);
        g.slop = kContactSlop * g.size;
    }
    prepareBlock(A, B, block, s);
}

}  // namespace

void prepareContacts(const Model& model, const State& state, const State& before, const ManifoldList& contacts,
                     const std::vector<double>& sizes, const ContactSolverSettings& cfg, ContactSolverScratch& s) {
    s.subsets.clear();
    loadVelocities(model, before, s.start, s.involved);
    chordVelocities(model, state, before, s.start, s.involved);
    choosePoints(model, contacts, cfg, s);
    splitBlocks(model, contacts, s);
    orderBlocks(s);
    const int n = static_cast<int>(s.blocks.size());
    auto make = [&](int k) { makeBlock(model, state, before, contacts, sizes, cfg, s, k); };
    if (!s.pool || s.pool->threads() == 1 || n <= kBlockGrain) {  // (nothing to time or gate)
        for (int k = 0; k < n; ++k) make(k);
        return;
    }
    const auto start = std::chrono::steady_clock::now();
    const bool pooled = s.prepareGate.worthIt(s.pool, n);
    if (pooled)
        s.pool->run((n + kBlockGrain - 1) / kBlockGrain, [&](int c) {
            for (int k = c * kBlockGrain, end = std::min(n, k + kBlockGrain); k < end; ++k) make(k);
        });
    else
        for (int k = 0; k < n; ++k) make(k);
    s.prepareGate.record(s.pool, n, std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count(),
                         pooled);
}

}  // namespace tumble
