// The hashing writer of large transfers: pieces of every size and
// alignment arrive in the file in order with the SHA-256 of all of them,
// directly or through the page cache; a restart begins again from nothing;
// a failing disk is reported, not lost. Without a file it only hashes,
// keeping its states every checkpoint step and going on from one.
#if defined(UMF_PROVIDER_TESTS)

#include <fcntl.h>
#include <gtest/gtest.h>
#include <unistd.h>

#include <cstring>
#include <memory>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <string>

#include "native/hashing_writer.hpp"
#include "native/sha256.hpp"
#include "tests/support/temp_dir.hpp"

namespace {

using umf::native::HashingWriter;

std::string sha256_of(const std::string& bytes) {
    umf::native::Sha256 sha;
    sha.update(bytes.data(), bytes.size());
    return sha.hex();
}

std::string file_text(const std::filesystem::path& path) {
    std::ifstream in(path, std::ios::binary);
    std::ostringstream out;
    out << in.rdbuf();
    return out.str();
}

// Sends `bytes` through `writer` in pieces of the sizes given, over and over.
void send(HashingWriter& writer, const std::string& bytes, std::initializer_list<std::size_t> sizes) {
    std::size_t at = 0;
    for (auto size = sizes.begin(); at < bytes.size(); ++size) {
        if (size == sizes.end()) size = sizes.begin();
        HashingWriter::Piece piece = writer.next();
        const std::size_t n = std::min({*size, piece.capacity, bytes.size() - at});
        std::memcpy(piece.data, bytes.data() + at, n);
        writer.submit(piece, n);
        at += n;
    }
}

TEST(HashingWriter, PiecesOfAnySizeArriveInOrderWithTheirHash) {
    umf::test::TempDir dir;
    std::string bytes(9 * 65536 + 123, '\0');
    for (std::size_t i = 0; i < bytes.size(); ++i) bytes[i] = static_cast<char>((i * 2654435761u) >> 13);
    for (const bool direct : {false, true}) {
        const auto path = dir.path / (direct ? "direct.bin" : "cached.bin");
        const int fd = ::open(path.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0600);
        ASSERT_GE(fd, 0);
        {
            HashingWriter writer(fd, 65536, direct, 3);
            // Whole aligned pieces, a short one that leaves the offset unaligned, and back.
            send(writer, bytes, {65536, 65536, 1000, 3096, 65536, 7});
            writer.drain();
            EXPECT_EQ(writer.hex(), sha256_of(bytes));
        }
        ::close(fd);
        EXPECT_TRUE(file_text(path) == bytes) << (direct ? "direct" : "through the cache");
    }
}

TEST(HashingWriter, ARestartBeginsTheFileAndTheHashAgain) {
    umf::test::TempDir dir;
    const auto path = dir.path / "again.bin";
    const int fd = ::open(path.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0600);
    ASSERT_GE(fd, 0);
    const std::string first(200000, 'a'), second(150000, 'b');
    {
        HashingWriter writer(fd, 65536, false);
        send(writer, first, {65536});
        writer.drain();
        writer.restart();
        send(writer, second, {40000});
        writer.drain();
        EXPECT_EQ(writer.hex(), sha256_of(second));
    }
    ::close(fd);
    EXPECT_TRUE(file_text(path) == second);
}

TEST(HashingWriter, AWriteThatFailsIsReported) {
    umf::test::TempDir dir;
    const auto path = dir.path / "readonly.bin";
    std::ofstream(path) << "";
    const int fd = ::open(path.c_str(), O_RDONLY | O_CLOEXEC);  // every write fails (EBADF)
    ASSERT_GE(fd, 0);
    {
        HashingWriter writer(fd, 4096, false, 2);
        const std::string bytes(64 * 1024, 'x');
        try {
            send(writer, bytes, {4096});
            writer.drain();
            ADD_FAILURE() << "no error for a file that cannot be written";
        } catch (const std::runtime_error& e) {
            EXPECT_NE(std::string(e.what()).find("cannot write the file"), std::string::npos) << e.what();
        }
    }
    ::close(fd);
}

// The requester's put: no file, the hash's states saved at each step, and a
// resumed transfer's hash taken up from the nearest one.
TEST(HashingWriter, WithoutAFileItHashesAndKeepsCheckpoints) {
    using umf::native::HashCheckpoints;
    const std::size_t piece = 1 << 20;
    std::string bytes(2 * HashCheckpoints::kStep + 3 * piece + 77, '\0');
    for (std::size_t i = 0; i < bytes.size(); ++i) bytes[i] = static_cast<char>((i * 40503u) >> 11);
    HashCheckpoints points;
    HashingWriter writer(-1, piece, false, 4);
    writer.continue_from(0, std::make_unique<umf::native::Sha256>(), &points);
    send(writer, bytes, {piece});
    writer.drain();
    EXPECT_EQ(writer.hash_so_far()->hex(), sha256_of(bytes));
    EXPECT_EQ(points.nearest(bytes.size()).first, 2 * HashCheckpoints::kStep) << "a state at each step";

    // Taken up at an offset past the first step, from the state kept there.
    const std::size_t resume = HashCheckpoints::kStep + 5 * piece;
    const auto read = [&](std::uint64_t at, char* into, std::size_t n) {
        const std::size_t got = std::min<std::size_t>(n, bytes.size() - at);
        std::memcpy(into, bytes.data() + at, got);
        return static_cast<long>(got);
    };
    std::string buffer(piece, '\0');
    auto state = points.hasher_at(resume, read, buffer.data(), buffer.size());
    ASSERT_TRUE(state);
    HashingWriter again(-1, piece, false, 4);
    again.continue_from(resume, std::move(state), &points);
    send(again, bytes.substr(resume), {piece});
    again.drain();
    EXPECT_EQ(again.hex(), sha256_of(bytes));
}

}  // namespace

#endif
