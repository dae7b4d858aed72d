// A pair of body indices as one sortable, hashable key.
#pragma once

#include <cstdint>

namespace tumble {

inline std::uint64_t pairKey(int a, int b) {
    return (static_cast<std::uint64_t>(static_cast<std::uint32_t>(a)) << 32) | static_cast<std::uint32_t>(b);
}

}  // namespace tumble
