#include "shared/field/window_classes.hpp"

namespace umf {

WindowClasses::WindowClasses(const WindowCodec& codec) : codec_(codec) {
    if (codec.code_space() > kTableLimit) return;
    table_.resize(codec.code_space());
    for (std::uint64_t code = 0; code < codec.code_space(); ++code)
        table_[code] = static_cast<std::uint32_t>(codec.canonical(code)) |
                       (codec.self_symmetric(code) ? 0x80000000u : 0u);
}

ClassSet::ClassSet(std::uint64_t code_space) : dense_(code_space <= (std::uint64_t{1} << 30)) {
    if (dense_) bits_.assign((code_space + 63) / 64, 0);
}

}  // namespace umf
