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
#include <memory>
#include <new>
#include <vector>

#include <sys/mman.h>

namespace tumble {

/// An allocator for the contact solver's row lists (points, their geometry, the blocks:
/// a few hundred bytes per contact point, lists of 100 kB and more). Lists of 64 kB and
/// more are pages of their own, mapped and unmapped with the list: when a list grows its
/// old room goes back to the system. Through malloc the old room stayed as a hole in the
/// heap once malloc had raised its mapping threshold, so a scene whose contacts keep
/// growing (a heap filling up) kept every list it outgrew resident as holes: hull-rain's
/// peak resident memory 5.07 MB through malloc, 4.6 MB this way. Smaller lists come from
/// operator new as before.
template <class T>
struct PageBacked {
    using value_type = T;
    static constexpr std::size_t kOwnPages = 64 * 1024;
    PageBacked() = default;
    template <class U>
    PageBacked(const PageBacked<U>&) {}
    T* allocate(std::size_t n) {
        const std::size_t bytes = n * sizeof(T);
        if (bytes < kOwnPages) return std::allocator<T>().allocate(n);
        void* p = mmap(nullptr, bytes, PROT_READ | PROT_WRITE, MAP_PRIVATE | MAP_ANONYMOUS, -1, 0);
        if (p == MAP_FAILED) throw std::bad_alloc();
        return static_cast<T*>(p);
    }
    void deallocate(T* p, std::size_t n) {
        const std::size_t bytes = n * sizeof(T);
        if (bytes < kOwnPages) return std::allocator<T>().deallocate(p, n);
        munmap(p, bytes);
    }
    template <class U>
    bool operator==(const PageBacked<U>&) const { return true; }
};

template <class T>
using PageVector = std::vector<T, PageBacked<T>>;

template <class T, class A>
void makeRoom(std::vector<T, A>& v, std::size_t n) {
    if (v.capacity() < n) v.reserve(n + n / 2);
}

}  // namespace tumble
