// The peers are optional (issue 8): a peer_<engine>.cpp built when its library is found
// defines make<Engine>Adapter(). These weak definitions stand in for the ones not built, so
// the benchmark links either way and reports "not built".
#include "engine_adapter.h"

namespace tumble::bench {

__attribute__((weak)) std::unique_ptr<EngineAdapter> makeBulletAdapter() {
    return nullptr;
}
__attribute__((weak)) std::unique_ptr<EngineAdapter> makeOdeAdapter() {
    return nullptr;
}
__attribute__((weak)) std::unique_ptr<EngineAdapter> makeMujocoAdapter() {
    return nullptr;
}
__attribute__((weak)) std::unique_ptr<EngineAdapter> makeJoltAdapter() {
    return nullptr;
}

}  // namespace tumble::bench
