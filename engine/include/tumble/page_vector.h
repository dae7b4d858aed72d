// Lists whose large rooms are pages of their own (PageVector): for the engine's lists that
// live from step to step and grow with the contacts, so that a list that outgrows its room
// gives the old room back to the system instead of leaving it as a hole in the heap.
#pragma once

#include <cstddef>
#include <memory>
#include <vector>

namespace tumble {

/// Maps `bytes` of zeroed pages (throws std::bad_alloc when the system has none) and
/// gives them back.
void* mapPages(std::size_t bytes);
void unmapPages(void* p, std::size_t bytes);

/// An allocator whose rooms of 64 kB and more are pages of their own, mapped and unmapped
/// with the room. Through malloc the old room of a grown list stays as a hole in the heap
/// once malloc has raised its mapping threshold (it does at the first large room freed),
/// so a scene whose contacts keep growing (a heap filling up) kept every room it outgrew
/// resident: hull-rain's peak resident memory 5.07 MB through malloc, 4.6 MB with the
/// contact solver's rows in pages (make_room.h). Smaller rooms come from operator new.
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
        return static_cast<T*>(mapPages(bytes));
    }
    void deallocate(T* p, std::size_t n) {
        const std::size_t bytes = n * sizeof(T);
        if (bytes < kOwnPages) return std::allocator<T>().deallocate(p, n);
        unmapPages(p, bytes);
    }
    template <class U>
    bool operator==(const PageBacked<U>&) const { return true; }
};

template <class T>
using PageVector = std::vector<T, PageBacked<T>>;

}  // namespace tumble
