// The file of a large download read and hashed on a thread of its own, a
// few pieces ahead of the connection that encrypts and sends them. Hashing
// is the costliest step of a download (SHA-256 takes about twice as long as
// AES-GCM on the same bytes); done inline, it makes the connection's thread
// the transfer's bottleneck, here it runs beside the encryption. The checks
// are VerifiedFileBody's (same identity, the hasher started from the
// nearest checkpoint, checkpoints saved on the way), and the last piece is
// handed out only once the whole file hashed to the announced SHA-256: the
// phone never gets bytes other than the announced ones.
//
// A file hashed under a read lease and unchanged since is read under a
// lease of its own instead, and not hashed: while the lease holds, its bytes
// are the hashed ones. That halves the provider's work for a download. If
// someone opens the file for writing meanwhile, the lease is given back
// within a few milliseconds, the bytes sent so far are hashed from the
// file again, and the rest goes out checked as above.
#pragma once

#include <boost/beast/core/error.hpp>
#include <condition_variable>
#include <cstddef>
#include <cstdint>
#include <deque>
#include <functional>
#include <memory>
#include <mutex>
#include <optional>
#include <thread>
#include <vector>

#include "provider/content/verified_file_body.hpp"

namespace umf::provider {

class VerifiedFileReader {
public:
    struct Piece {
        const char* data = nullptr;
        std::size_t size = 0;
    };
    enum class Next {
        piece,    // the next piece is ready
        waiting,  // not yet: `ready` will be called once it is (or the reading failed)
        end,      // every piece was taken
        failed,   // the reading failed: DownloadCheck::changed, or the system's error
    };

    // Starts reading `body` (opened; it must outlive this reader). `ready`
    // is called on the reader's thread after take() said `waiting`, once
    // there is something new to take: it must only hand the news on (post
    // to the connection's strand), never take or destroy this reader there.
    VerifiedFileReader(const VerifiedFileBody::value_type& body, std::function<void()> ready);
    // Stops the reading (the piece being read is finished first) and waits for it.
    ~VerifiedFileReader();
    VerifiedFileReader(const VerifiedFileReader&) = delete;
    VerifiedFileReader& operator=(const VerifiedFileReader&) = delete;

    // The next piece in the file's order, valid until release(); `ec` is set for `failed`.
    Next take(Piece& piece, boost::beast::error_code& ec);
    // The piece take() gave is done with: its buffer is read into again.
    void release();

private:
    struct Free {
        void operator()(char* p) const;
    };

    void run();
    // Reads the pieces from `at` on without hashing them while `lease`
    // holds: where it stopped (the file's end, or where the lease broke and
    // was given back), or nothing when stopping or failed (published).
    std::optional<std::uint64_t> read_leased(ReadLease& lease, std::uint64_t at);
    // Reads and hashes the pieces from `at` on until the end, a failure or a stop.
    void read_hashed(std::uint64_t at);
    // Reads the piece at `at` into `buffer`: its size, or 0 or less with the
    // failure published.
    long read_piece(std::uint64_t at, char* buffer);
    // Waits for a free buffer; null when stopping. A `lease` is looked at
    // while waiting, and given back as soon as it is broken.
    char* free_buffer(ReadLease* lease = nullptr);
    void give_back(char* buffer);
    // Queues a piece (or a failure, or the end) and wakes a waiting taker.
    void publish(const Piece* piece, boost::beast::error_code ec, bool end);

    const VerifiedFileBody::value_type& body_;
    std::function<void()> ready_;
    std::vector<std::unique_ptr<char, Free>> buffers_;

    std::mutex mutex_;
    std::condition_variable freed_;
    std::vector<char*> free_;
    std::deque<Piece> ready_pieces_;  // oldest first
    const char* taken_ = nullptr;     // the buffer take() gave out
    boost::beast::error_code failure_;
    bool read_all_ = false;
    bool taker_waits_ = false;
    bool stopping_ = false;
    std::thread thread_;
};

}  // namespace umf::provider
