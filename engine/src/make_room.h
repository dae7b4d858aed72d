// Room in the contact solver's lists, which live from step to step: sized to what they
// hold and half as much again when they must grow. Not doubled (up to half of a list
// unused: the contact blocks alone held 360 KB of hull-rain's heap peak for 240 blocks of
// 704 bytes), and not less than half: in a scene whose contacts keep growing (a heap
// filling up) each growth leaves the old list freed behind, and an eighth more left so
// many of the allocator's holes that they cost more resident memory than the room saved
// (hull-rain 4.97 MB with an eighth, 4.62-4.68 with a half, 4.73 doubled). Room reserved
// and never written is not resident. (Made for the narrowphase's copy of the manifolds
// and the parked step's copy of the state too, it cost hull-rain 0.3 MB more: left out.)
#pragma once

#include <cstddef>
#include <vector>

namespace tumble {

template <class T>
void makeRoom(std::vector<T>& v, std::size_t n) {
    if (v.capacity() < n) v.reserve(n + n / 2);
}

}  // namespace tumble
