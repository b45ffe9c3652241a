// Window classes: codes that are rotations of one another form one class, and
// a field is 4-orientable when every window has a class of its own and no
// window is self-symmetric. The generator asks these questions millions of
// times a second, so small code spaces are tabulated once.
#pragma once

#include <cstdint>
#include <unordered_set>
#include <vector>

#include "shared/field/window_code.hpp"

namespace umf {

class WindowClasses {
public:
    // Code spaces up to this size get a lookup table (16 MB at most).
    static constexpr std::uint64_t kTableLimit = 1u << 22;

    explicit WindowClasses(const WindowCodec& codec);

    struct Class {
        std::uint64_t id;     // the canonical code
        bool self_symmetric;  // never allowed in a field
    };
    Class of(std::uint64_t code) const {
        if (!table_.empty()) {
            std::uint32_t e = table_[code];
            return {e & 0x7fffffffu, (e >> 31) != 0};
        }
        return {codec_.canonical(code), codec_.self_symmetric(code)};
    }
    const WindowCodec& codec() const { return codec_; }

private:
    const WindowCodec& codec_;
    std::vector<std::uint32_t> table_;
};

// The set of classes in use: a bitmap when the code space is small, a hash
// set otherwise.
class ClassSet {
public:
    explicit ClassSet(std::uint64_t code_space);
    bool contains(std::uint64_t id) const {
        return dense_ ? (bits_[id >> 6] >> (id & 63)) & 1u : sparse_.count(id) != 0;
    }
    void insert(std::uint64_t id) {
        if (dense_)
            bits_[id >> 6] |= std::uint64_t{1} << (id & 63);
        else
            sparse_.insert(id);
    }
    void erase(std::uint64_t id) {
        if (dense_)
            bits_[id >> 6] &= ~(std::uint64_t{1} << (id & 63));
        else
            sparse_.erase(id);
    }

private:
    bool dense_;
    std::vector<std::uint64_t> bits_;
    std::unordered_set<std::uint64_t> sparse_;
};

}  // namespace umf
