// Room in the lists that live from step to step (the contact solver's rows, the
// narrowphase's manifolds and its copy for reuse, the parked contacts): sized to what they
// hold and half as much again when they must grow. Not doubled (up to half of a list
// unused: the contact blocks alone held 360 KB of hull-rain's heap peak for 240 blocks of
// 704 bytes), and not less than half: in a scene whose contacts keep growing (a heap
// filling up) each growth leaves the old list freed behind, and an eighth more left so
// many of the allocator's holes that they cost more resident memory than the room saved
// (hull-rain 4.97 MB with an eighth, 4.62-4.68 with a half, 4.73 doubled). Room reserved
// and never written is not resident. The large lists are PageVectors (page_vector.h), so
// what a list outgrows goes back to the system.
#pragma once

#include <cstddef>
#include <vector>

#include <tumble/page_vector.h>

namespace tumble {

template <class T, class A>
void makeRoom(std::vector<T, A>& v, std::size_t n) {
    if (v.capacity() < n) v.reserve(n + n / 2);
}

}  // namespace tumble
