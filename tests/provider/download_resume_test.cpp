// Resuming downloads on the provider's side, piece by piece: which part a
// Range asks for (content/resume_range.hpp), how long a link lives
// (content/download_table.hpp), and a file sent from an offset still checked
// whole through the hash checkpoints (content/verified_file_body.hpp, and
// content/verified_file_reader.hpp for large bodies). The
// HTTPS side with curl is tests/provider/provider_http_test.cpp.
#ifdef UMF_PROVIDER_TESTS

#include <gtest/gtest.h>

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <boost/beast/http/message.hpp>
#include <chrono>
#include <condition_variable>
#include <functional>
#include <filesystem>
#include <fstream>
#include <mutex>
#include <string>
#include <thread>

#include "provider/content/download_table.hpp"
#include "provider/content/file_facts.hpp"
#include "provider/content/read_lease.hpp"
#include "provider/content/resume_range.hpp"
#include "provider/content/verified_file_body.hpp"
#include "provider/content/verified_file_reader.hpp"
#include "tests/support/temp_dir.hpp"

namespace {

namespace fs = std::filesystem;
using namespace umf::provider;
using umf::native::HashCheckpoints;
using Kind = ResumeRange::Kind;

TEST(ResumeRange, TheRestFromAnOffsetAndNothingElse) {
    const std::string etag = download_etag("ab12");
    EXPECT_EQ(etag, "\"sha256-ab12\"");
    struct Case {
        const char* range;
        const char* if_range;
        Kind kind;
        std::uint64_t offset;
    };
    const Case cases[] = {
        {"", "", Kind::whole, 0},
        {"bytes=100-", "", Kind::rest, 100},
        {"bytes=100-", "\"sha256-ab12\"", Kind::rest, 100},
        {" bytes=0-", "", Kind::rest, 0},
        {"bytes=100-999", "", Kind::rest, 100},   // to the end, spelled out
        {"bytes=100-5000", "", Kind::rest, 100},  // past the end is the end
        {"bytes=-300", "", Kind::rest, 700},
        {"bytes=-5000", "", Kind::rest, 0},
        {"bytes=100-", "\"sha256-ffff\"", Kind::whole, 0},                  // another version
        {"bytes=100-", "Sat, 28 Nov 2026 10:00:00 GMT", Kind::whole, 0},  // a date: not trusted
        {"bytes=100-200", "", Kind::whole, 0},                             // ends before the file does
        {"bytes=0-10,20-", "", Kind::whole, 0},
        {"bytes=abc-", "", Kind::whole, 0},
        {"bytes=-0", "", Kind::whole, 0},
        {"bytes=+5-", "", Kind::whole, 0},
        {"items=100-", "", Kind::whole, 0},
        {"bytes=99999999999999999999999-", "", Kind::whole, 0},
        {"bytes=1000-", "", Kind::unsatisfiable, 0},
        {"bytes=5000-", "", Kind::unsatisfiable, 0},
    };
    for (const auto& c : cases) {
        const ResumeRange r = resume_range(c.range, c.if_range, etag, 1000);
        EXPECT_EQ(r.kind, c.kind) << c.range << " / " << c.if_range;
        if (r.kind == Kind::rest) {
            EXPECT_EQ(r.offset, c.offset) << c.range;
        }
    }
    EXPECT_EQ(resume_range("bytes=0-", "", etag, 0).kind, Kind::whole) << "an empty file is sent whole";
}

TEST(DownloadTable, ALinkLivesUntilADownloadOfItCompletes) {
    using namespace std::chrono_literals;
    DownloadTable table(60s);
    const auto t0 = DownloadTable::Clock::time_point{} + 1000s;
    DownloadEntry entry;
    entry.name = "a.bin";
    const std::string link = table.add(entry, t0);
    EXPECT_FALSE(table.begin("/dl/unknown", t0));
    EXPECT_FALSE(table.begin("/up/" + link.substr(4), t0));

    auto first = table.begin(link + "?x=1", t0);
    ASSERT_TRUE(first);
    EXPECT_EQ(first->entry->name, "a.bin");
    // A transfer that runs longer than the lifetime keeps its link.
    table.add(DownloadEntry{}, t0 + 120s);  // sweeps expired links
    EXPECT_EQ(table.size(), 2u);
    table.end(*first, false, t0 + 120s);  // broken: the rest may be asked for
    auto second = table.begin(link, t0 + 170s);
    ASSERT_TRUE(second) << "a broken download's link lives on from its end";
    EXPECT_EQ(second->checkpoints, first->checkpoints) << "transfers of a link share its checkpoints";
    table.end(*second, true, t0 + 171s);
    EXPECT_FALSE(table.begin(link, t0 + 172s)) << "a completed download ends the link";

    const std::string idle = table.add(entry, t0);
    EXPECT_FALSE(table.begin(idle, t0 + 61s)) << "a link nobody used expires";
}

class ResumedFile : public ::testing::Test {
protected:
    umf::test::TempDir dir;
    fs::path file;
    std::string bytes;
    std::string sha256;
    FileIdentity identity;

    // Past two checkpoint steps, so a resume starts from a checkpoint.
    void SetUp() override {
        file = dir.path / "big.bin";
        bytes.resize(2 * HashCheckpoints::kStep + 300000);
        for (std::size_t i = 0; i < bytes.size(); ++i) bytes[i] = static_cast<char>((i * 131) >> 7);
        std::ofstream(file, std::ios::binary) << bytes;
        FileFactsCache cache;
        const FileFacts facts = cache.facts(file);
        sha256 = facts.sha256;
        identity = facts.identity;
    }
    // Sends from `offset` until `stop` bytes have gone out; what was sent,
    // and the error that ended it.
    std::pair<std::string, boost::beast::error_code> send(std::uint64_t offset, std::shared_ptr<HashCheckpoints> points,
                                                          std::uint64_t stop = ~0ull) {
        VerifiedFileBody::value_type body;
        EXPECT_FALSE(body.open(file, identity, sha256, offset, points));
        EXPECT_EQ(body.size(), bytes.size() - offset);
        boost::beast::http::response_header<> header;
        VerifiedFileBody::writer writer(header, body);
        boost::beast::error_code ec;
        writer.init(ec);
        std::string sent;
        while (sent.size() < stop) {
            auto piece = writer.get(ec);
            if (ec || !piece) break;
            sent.append(static_cast<const char*>(piece->first.data()), piece->first.size());
            if (!piece->second) break;
        }
        return {sent, ec};
    }
    // The same through a VerifiedFileReader, as a large body is sent;
    // `leased_ctime_ns` as FileFacts has it, `on_piece` called after each
    // piece taken with the bytes taken so far.
    std::pair<std::string, boost::beast::error_code> read(std::uint64_t offset, std::shared_ptr<HashCheckpoints> points,
                                                          std::uint64_t stop = ~0ull, std::int64_t leased_ctime_ns = 0,
                                                          const std::function<void(std::size_t)>& on_piece = {},
                                                          const std::string& announced = {}) {
        VerifiedFileBody::value_type body;
        EXPECT_FALSE(body.open(file, identity, announced.empty() ? sha256 : announced, offset, points,
                               leased_ctime_ns));
        std::mutex mutex;
        std::condition_variable woken;
        bool ready = false;
        VerifiedFileReader reader(body, [&] {
            std::lock_guard lock(mutex);
            ready = true;
            woken.notify_all();
        });
        std::string sent;
        boost::beast::error_code ec;
        while (sent.size() < stop) {
            VerifiedFileReader::Piece piece;
            const auto next = reader.take(piece, ec);
            if (next == VerifiedFileReader::Next::waiting) {
                std::unique_lock lock(mutex);
                woken.wait(lock, [&] { return ready; });
                ready = false;
                continue;
            }
            if (next != VerifiedFileReader::Next::piece) break;
            sent.append(piece.data, piece.size);
            reader.release();
            if (on_piece) on_piece(sent.size());
        }
        return {sent, ec};
    }
};

TEST_F(ResumedFile, TheRestIsSentAndTheWholeChecked) {
    auto points = std::make_shared<HashCheckpoints>();
    const std::uint64_t cut = HashCheckpoints::kStep + 12345 * 7;
    const auto [head, ec1] = send(0, points, cut);
    ASSERT_FALSE(ec1) << ec1.message();
    ASSERT_GE(head.size(), cut);
    EXPECT_EQ(points->nearest(cut).first, HashCheckpoints::kStep) << "the first step's state was saved";
    const auto [rest, ec2] = send(cut, points);
    EXPECT_FALSE(ec2) << ec2.message();
    EXPECT_TRUE(bytes.substr(0, cut) + rest == bytes);
    // Without checkpoints the resumed transfer hashes from the start.
    const auto [again, ec3] = send(cut + 1, nullptr);
    EXPECT_FALSE(ec3) << ec3.message();
    EXPECT_TRUE(again == bytes.substr(cut + 1));
}

// A byte changed before the offset, the identity kept (the modification
// time restored): the resumed transfer never sends its last piece.
TEST_F(ResumedFile, AByteChangedBeforeTheOffsetCutsTheRest) {
    auto points = std::make_shared<HashCheckpoints>();
    const std::uint64_t cut = HashCheckpoints::kStep + 500000;
    (void)send(0, points, cut);
    const auto mtime = fs::last_write_time(file);
    {
        std::fstream f(file, std::ios::binary | std::ios::in | std::ios::out);
        f.seekp(static_cast<std::streamoff>(HashCheckpoints::kStep + 100));
        f.put('\x55' ^ bytes[HashCheckpoints::kStep + 100]);
    }
    fs::last_write_time(file, mtime);
    const auto [rest, ec] = send(cut, points);
    EXPECT_EQ(ec, DownloadCheck::changed);
    EXPECT_LT(rest.size(), bytes.size() - cut);
}

// The reader of large bodies: the same checks, a resume from a checkpoint,
// a reader dropped half-way, and a changed byte that holds back the end.
TEST_F(ResumedFile, TheReaderSendsTheRestAndChecksTheWhole) {
    auto points = std::make_shared<HashCheckpoints>();
    const std::uint64_t cut = HashCheckpoints::kStep + 12345 * 7;
    const auto [head, ec1] = read(0, points, cut);  // the reader stops with pieces still ahead
    ASSERT_FALSE(ec1) << ec1.message();
    ASSERT_GE(head.size(), cut);
    EXPECT_TRUE(head == bytes.substr(0, head.size()));
    EXPECT_EQ(points->nearest(cut).first, HashCheckpoints::kStep);
    const auto [rest, ec2] = read(cut, points);
    EXPECT_FALSE(ec2) << ec2.message();
    EXPECT_TRUE(bytes.substr(0, cut) + rest == bytes);
    const auto [again, ec3] = read(cut + 1, nullptr);
    EXPECT_FALSE(ec3) << ec3.message();
    EXPECT_TRUE(again == bytes.substr(cut + 1));
}

TEST_F(ResumedFile, TheReaderHoldsBackTheEndOfAChangedFile) {
    const auto mtime = fs::last_write_time(file);
    {
        std::fstream f(file, std::ios::binary | std::ios::in | std::ios::out);
        f.seekp(static_cast<std::streamoff>(bytes.size() - 1000));
        f.put('\x55' ^ bytes[bytes.size() - 1000]);
    }
    fs::last_write_time(file, mtime);
    const auto [sent, ec] = read(0, nullptr);
    EXPECT_EQ(ec, DownloadCheck::changed);
    EXPECT_LT(sent.size(), bytes.size());
    EXPECT_TRUE(sent == bytes.substr(0, sent.size()));
}

// A file hashed under a lease and unchanged since (content/read_lease.hpp).
class LeasedFile : public ResumedFile {
protected:
    std::int64_t ctime_ns = 0;
    void SetUp() override {
        ResumedFile::SetUp();
        struct stat st {};
        ASSERT_EQ(::stat(file.c_str(), &st), 0);
        ctime_ns = std::int64_t{st.st_ctim.tv_sec} * 1000000000 + st.st_ctim.tv_nsec;
        const int fd = ::open(file.c_str(), O_RDONLY | O_CLOEXEC);
        const bool leases = ReadLease(fd).held();
        ::close(fd);
        if (!leases) GTEST_SKIP() << "the file system of " << dir.path << " grants no leases";
    }
    // Opens the file for writing, writes `byte` at `at` unless it is -1,
    // and says how long the open waited.
    std::chrono::steady_clock::duration write_at(std::uint64_t at, int byte) {
        const auto start = std::chrono::steady_clock::now();
        const int fd = ::open(file.c_str(), O_WRONLY | O_CLOEXEC);
        const auto waited = std::chrono::steady_clock::now() - start;
        EXPECT_GE(fd, 0);
        if (byte >= 0) {
            const char c = static_cast<char>(byte);
            EXPECT_EQ(::pwrite(fd, &c, 1, static_cast<off_t>(at)), 1);
        }
        ::close(fd);
        return waited;
    }
};

TEST_F(LeasedFile, IsSentWithoutBeingHashedAgain) {
    // Announced with another hash: only a transfer that does not hash
    // sends it whole. With a ctime that moved, it is hashed and held back.
    const std::string other(64, '0');
    const auto [sent, ec] = read(0, nullptr, ~0ull, ctime_ns, {}, other);
    EXPECT_FALSE(ec) << ec.message();
    EXPECT_TRUE(sent == bytes);
    const auto [resumed, ec2] = read(HashCheckpoints::kStep + 7, nullptr, ~0ull, ctime_ns, {}, other);
    EXPECT_FALSE(ec2) << ec2.message();
    EXPECT_TRUE(resumed == bytes.substr(HashCheckpoints::kStep + 7));
    const auto [held_back, ec3] = read(0, nullptr, ~0ull, ctime_ns + 1, {}, other);
    EXPECT_EQ(ec3, DownloadCheck::changed);
    EXPECT_LT(held_back.size(), bytes.size());
}

// A program saving the file while a slow phone takes it: its open waits
// milliseconds, and the transfer goes on checked by the hash from there.
TEST_F(LeasedFile, AWriterWaitsMillisecondsAndTheRestIsChecked) {
    std::chrono::steady_clock::duration waited{};
    const auto [sent, ec] = read(0, nullptr, ~0ull, ctime_ns, [&](std::size_t taken) {
        // The phone stops taking after the first piece; the reader's
        // buffers are full when the writer opens the file.
        if (taken != (1u << 20)) return;
        std::this_thread::sleep_for(std::chrono::milliseconds(200));
        waited = write_at(0, -1);
    });
    EXPECT_FALSE(ec) << ec.message();
    EXPECT_TRUE(sent == bytes) << "opened, not changed: the whole file, checked";
    EXPECT_LT(waited, std::chrono::milliseconds(500));

    // Changed ahead of the transfer: the end is held back. (A change of
    // bytes already read and hashed again changes nothing sent.)
    const std::size_t near_end = bytes.size() - 1000;
    const auto [cut, ec2] = read(0, nullptr, ~0ull, ctime_ns, [&](std::size_t taken) {
        if (taken == (1u << 20)) waited = write_at(near_end, static_cast<unsigned char>(bytes[near_end] ^ 0x55));
    });
    EXPECT_EQ(ec2, DownloadCheck::changed);
    EXPECT_LT(cut.size(), bytes.size());
    EXPECT_LT(waited, std::chrono::milliseconds(500));
}

}  // namespace

#endif
