#include <tumble/state.h>

#include <cstdio>
#include <cstring>

namespace tumble {

namespace {

struct Fnv1a {
    std::uint64_t h = 14695981039346656037ull;
    void add(double d) {
        unsigned char bytes[sizeof d];
        std::memcpy(bytes, &d, sizeof d);
        for (unsigned char b : bytes) {
            h ^= b;
            h *= 1099511628211ull;
        }
    }
    void add(const Vec3& v) {
        for (int i = 0; i < 3; ++i) add(v[i]);
    }
};

}  // namespace

std::uint64_t hashState(const State& state) {
    Fnv1a f;
    f.add(state.time);
    for (const BodyState& b : state.bodies) {
        f.add(b.x);
        f.add(b.q.w());
        f.add(b.q.vec());
        f.add(b.P);
        f.add(b.L);
    }
    return f.h;
}

std::string hashHex(std::uint64_t hash) {
    char buf[17];
    std::snprintf(buf, sizeof buf, "%016llx", static_cast<unsigned long long>(hash));
    return buf;
}

}  // namespace tumble
