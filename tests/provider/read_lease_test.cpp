// Read leases (content/read_lease.hpp) and the hashes taken under them
// (content/file_facts.hpp): what the kernel grants, that a writer breaks a
// lease and waits only until it is given back, and which hashes count as
// leased.
#ifdef UMF_PROVIDER_TESTS

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <gtest/gtest.h>

#include <atomic>
#include <chrono>
#include <filesystem>
#include <fstream>
#include <future>
#include <string>
#include <thread>

#include "provider/content/file_facts.hpp"
#include "provider/content/read_lease.hpp"
#include "tests/support/temp_dir.hpp"

namespace {

namespace fs = std::filesystem;
using namespace umf::provider;
using namespace std::chrono_literals;

struct Fd {
    int fd;
    explicit Fd(int f) : fd(f) {}
    ~Fd() {
        if (fd >= 0) ::close(fd);
    }
};

void write_file(const fs::path& path, std::size_t size) {
    std::ofstream out(path, std::ios::binary);
    out << std::string(size, 'u');
}

// Whether this file system grants leases at all (a tmpfs or ext4 does):
// where it does not, the download hashes as before and these tests say so.
bool leases_here(const fs::path& file) {
    Fd fd(::open(file.c_str(), O_RDONLY | O_CLOEXEC));
    return ReadLease(fd.fd).held();
}

TEST(ReadLease, AWriterBreaksItAndWaitsOnlyUntilItIsGivenBack) {
    umf::test::TempDir dir;
    const fs::path file = dir.path / "a.bin";
    write_file(file, 4096);
    if (!leases_here(file)) GTEST_SKIP() << "the file system of " << dir.path << " grants no leases";

    Fd reader(::open(file.c_str(), O_RDONLY | O_CLOEXEC));
    ReadLease lease(reader.fd);
    ASSERT_TRUE(lease.held());
    EXPECT_TRUE(lease.unbroken());
    // Another reader does not break it.
    { Fd other(::open(file.c_str(), O_RDONLY | O_CLOEXEC)); }
    EXPECT_TRUE(lease.unbroken());

    std::atomic<bool> opened{false};
    auto writer = std::async(std::launch::async, [&] {
        Fd w(::open(file.c_str(), O_WRONLY | O_CLOEXEC));
        opened = true;
        return w.fd >= 0;
    });
    const auto deadline = std::chrono::steady_clock::now() + 5s;
    while (lease.unbroken() && std::chrono::steady_clock::now() < deadline) std::this_thread::sleep_for(1ms);
    EXPECT_FALSE(lease.unbroken()) << "an open for writing breaks the lease";
    std::this_thread::sleep_for(50ms);
    EXPECT_FALSE(opened) << "the writer waits while the lease is held";
    const auto released = std::chrono::steady_clock::now();
    lease.release();
    EXPECT_TRUE(writer.get());
    EXPECT_LT(std::chrono::steady_clock::now() - released, 2s) << "and goes on once it is given back";
    EXPECT_FALSE(lease.held());
}

TEST(ReadLease, RefusedWhileTheFileIsOpenForWriting) {
    umf::test::TempDir dir;
    const fs::path file = dir.path / "a.bin";
    write_file(file, 4096);
    if (!leases_here(file)) GTEST_SKIP() << "the file system of " << dir.path << " grants no leases";
    Fd writer(::open(file.c_str(), O_WRONLY | O_CLOEXEC));
    Fd reader(::open(file.c_str(), O_RDONLY | O_CLOEXEC));
    EXPECT_FALSE(ReadLease(reader.fd).held());
    EXPECT_FALSE(ReadLease(-1).held());
}

TEST(FileFacts, AHashTakenUnderAnUnbrokenLeaseOfASettledFileIsLeased) {
    umf::test::TempDir dir;
    const fs::path settled = dir.path / "settled.bin";
    write_file(settled, 3 << 20);
    if (!leases_here(settled)) GTEST_SKIP() << "the file system of " << dir.path << " grants no leases";
    std::this_thread::sleep_for(120ms);
    FileFactsCache cache;
    const FileFacts facts = cache.facts(settled);
    struct stat st {};
    ASSERT_EQ(::stat(settled.c_str(), &st), 0);
    EXPECT_EQ(facts.leased_ctime_ns, std::int64_t{st.st_ctim.tv_sec} * 1000000000 + st.st_ctim.tv_nsec);

    // Open for writing while it is hashed: the hash holds, but not as leased.
    const fs::path open = dir.path / "open.bin";
    write_file(open, 3 << 20);
    std::this_thread::sleep_for(120ms);
    {
        Fd writer(::open(open.c_str(), O_WRONLY | O_CLOEXEC));
        const FileFacts f = cache.facts(open);
        EXPECT_EQ(f.sha256, facts.sha256);
        EXPECT_EQ(f.leased_ctime_ns, 0);
    }
    // Changed just before: its ctime could repeat after the hash.
    const fs::path fresh = dir.path / "fresh.bin";
    write_file(fresh, 1000);
    EXPECT_EQ(cache.facts(fresh).leased_ctime_ns, 0);
}

// A large file hashed while a program opens it for writing: the program
// waits one read of the hash, not all of it, and the hash is not leased.
TEST(FileFacts, AWriterDoesNotWaitForTheHashToEnd) {
    umf::test::TempDir dir;
    const fs::path big = dir.path / "big.bin";
    write_file(big, std::size_t{512} << 20);
    if (!leases_here(big)) GTEST_SKIP() << "the file system of " << dir.path << " grants no leases";
    std::this_thread::sleep_for(120ms);
    FileFactsCache cache;
    const auto started = std::chrono::steady_clock::now();
    auto hashed = std::async(std::launch::async, [&] { return cache.facts(big); });
    // The hash of 512 MiB takes a quarter of a second or more here.
    std::this_thread::sleep_for(30ms);
    const auto opening = std::chrono::steady_clock::now();
    { Fd writer(::open(big.c_str(), O_WRONLY | O_CLOEXEC)); }
    const auto waited = std::chrono::steady_clock::now() - opening;
    const FileFacts facts = hashed.get();
    const auto hash_took = std::chrono::steady_clock::now() - started;
    EXPECT_LT(waited, 100ms) << "the hash took " << std::chrono::duration<double>(hash_took).count() << " s";
    EXPECT_EQ(facts.leased_ctime_ns, 0);
}

}  // namespace

#endif
