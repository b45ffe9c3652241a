#include "requester/upload.hpp"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <boost/asio/ssl.hpp>
#include <boost/beast/core.hpp>
#include <boost/beast/http.hpp>
#include <boost/beast/ssl.hpp>
#include <cerrno>
#include <cstring>
#include <optional>
#include <sstream>
#include <vector>

#include "native/hashing_writer.hpp"
#include "requester/blocking_tls.hpp"
#include "requester/cli.hpp"
#include "requester/grab_failure.hpp"
#include "requester/resume_pacing.hpp"
#include "requester/transfer_text.hpp"
#include "shared/protocol/http_error_body.hpp"

namespace umf::requester {

namespace {

namespace fs = std::filesystem;
namespace net = boost::asio;
namespace beast = boost::beast;
namespace http = beast::http;
namespace p = protocol;

// Read from the file and written to the connection at once.
constexpr std::size_t kPieceBytes = 1 << 20;
// The answer is one short JSON message.
constexpr std::size_t kMaxAnswerBytes = 64 * 1024;
// After a write failed, how long the provider may take to say why.
constexpr std::chrono::milliseconds kLateAnswerWait{3000};

GrabFailure input_failure(const std::string& message) { return {"input", message, kInputError}; }
GrabFailure upload_failure(const std::string& message) { return {"upload", message, kConnection}; }

// What a change to a file moves: a write its ctime (which no program can set
// back) and mtime, a truncation its size.
struct FileState {
    std::uint64_t device = 0, inode = 0;
    std::int64_t size = 0, mtime_ns = 0, ctime_ns = 0;
    bool operator==(const FileState&) const = default;
};

class ReadOnlyFile {
public:
    explicit ReadOnlyFile(const fs::path& path) : path_(path) {
        fd_ = ::open(path.c_str(), O_RDONLY | O_CLOEXEC);
        if (fd_ < 0) throw input_failure("cannot open " + path.string() + ": " + std::strerror(errno));
    }
    ~ReadOnlyFile() { ::close(fd_); }
    ReadOnlyFile(const ReadOnlyFile&) = delete;
    ReadOnlyFile& operator=(const ReadOnlyFile&) = delete;

    FileState state() const {
        struct stat st {};
        if (::fstat(fd_, &st) != 0) throw input_failure("cannot read " + path_.string() + ": " + std::strerror(errno));
        const auto ns = [](const struct timespec& t) { return std::int64_t{t.tv_sec} * 1000000000 + t.tv_nsec; };
        return {static_cast<std::uint64_t>(st.st_dev), static_cast<std::uint64_t>(st.st_ino),
                static_cast<std::int64_t>(st.st_size), ns(st.st_mtim), ns(st.st_ctim)};
    }
    const fs::path& path() const { return path_; }
    // Reading goes on from byte `offset`.
    void seek(std::int64_t offset) {
        if (::lseek(fd_, offset, SEEK_SET) != offset)
            throw input_failure("cannot read " + path_.string() + " from byte " + std::to_string(offset) + ": " +
                                std::strerror(errno));
    }
    // Up to `size` bytes; fewer only at the end of the file.
    std::size_t read(char* data, std::size_t size) {
        std::size_t got = 0;
        while (got < size) {
            const ssize_t n = ::read(fd_, data + got, size - got);
            if (n < 0 && errno == EINTR) continue;
            if (n < 0) throw input_failure("cannot read " + path_.string() + ": " + std::strerror(errno));
            if (n == 0) break;
            got += static_cast<std::size_t>(n);
        }
        return got;
    }

private:
    fs::path path_;
    int fd_ = -1;
};


p::PutStatus interpret(const http::response<http::string_body>& answer) {
    const auto parsed = p::parse_message(answer.body(), p::kRequesterLimits);
    const auto* m = std::get_if<p::Message>(&parsed);
    const unsigned status = answer.result_int();
    if (status == 200) {
        const auto* done = m ? std::get_if<p::PutStatus>(m) : nullptr;
        if (!done || done->status != p::PutState::done)
            throw GrabFailure("protocol", "the provider's answer to the upload is not a put_status done", kConnection);
        return *done;
    }
    const auto error = p::parse_error_body(answer.body());
    const p::Error* e = error ? &*error : nullptr;
    const std::string why = e ? e->message : "HTTP status " + std::to_string(status);
    if (status == 412) throw input_failure("the upload stopped: " + why);
    if (status == 404)
        throw GrabFailure("not_found", "the upload link is unknown, used or expired (" + why + "); put again",
                          kNothing);
    if (e && e->code == p::ErrorCode::too_large)
        throw GrabFailure("too_large", "the screen has no room for the file: " + why, kNothing);
    throw GrabFailure(e ? p::to_string(e->code) : "upload", "the upload failed: " + why, kConnection);
}

// One request of an upload: its answer, or why the connection broke.
struct Sent {
    std::optional<p::PutStatus> done;
    bool awaiting_hash = false;  // 202: every byte is there, the hash not named yet
    std::string why;
};

// A hasher that has taken the file's first `size` bytes: the state kept at
// or before it, and the bytes from there read again.
std::unique_ptr<native::Sha256> prefix_hash(ReadOnlyFile& file, const native::HashCheckpoints& checkpoints,
                                            std::int64_t size) {
    std::vector<char> piece(kPieceBytes);
    const auto read = [&](std::uint64_t at, char* into, std::size_t n) {
        file.seek(static_cast<std::int64_t>(at));
        return static_cast<long>(file.read(into, n));
    };
    auto hash = checkpoints.hasher_at(static_cast<std::uint64_t>(size), read, piece.data(), piece.size());
    if (!hash)
        throw input_failure(file.path().string() + " became shorter than the " + std::to_string(size) +
                            " bytes already sent; put it again");
    return hash;
}

// The SHA-256 of a put that names it after the bytes, taken on a thread
// beside the sending one as the pieces go (native/hashing_writer.hpp, with
// no file). Its states every HashCheckpoints::kStep let a resumed request
// take it up from the bytes the provider holds. A file whose state moved
// while it was sent is hashed again whole, as it is now: the provider's
// check then says whether the bytes it holds are that file.
class RunningHash {
public:
    explicit RunningHash(ReadOnlyFile& file) : file_(file), start_(file.state()) {
        lane_.continue_from(0, std::make_unique<native::Sha256>(), points_.get());
    }

    // A free piece of kPieceBytes to read into and send; then hash() it.
    native::HashingWriter::Piece piece() { return lane_.next(); }
    // The piece's first `size` bytes are the file's next, from at() on.
    void hash(native::HashingWriter::Piece piece, std::size_t size) {
        lane_.submit(piece, size);
        at_ += static_cast<std::int64_t>(size);
    }
    // Taken up again at byte `offset` (a resumed request's start): its
    // SHA-256 there, the Upload-Prefix-SHA256.
    std::string rewind(std::int64_t offset) {
        take_up(offset);
        return lane_.hash_so_far()->hex();
    }
    // Whether the file was found changed (hashed again as it is now).
    bool changed() const { return changed_; }

private:
    void take_up(std::int64_t offset) {
        lane_.drain();
        if (!changed_ && file_.state() != start_) {
            // The states kept are of the file as it was.
            changed_ = true;
            points_ = std::make_unique<native::HashCheckpoints>();
            at_ = -1;
        }
        if (offset == at_) return;
        lane_.continue_from(static_cast<std::uint64_t>(offset), prefix_hash(file_, *points_, offset), points_.get());
        at_ = offset;
    }

    ReadOnlyFile& file_;
    FileState start_;
    std::unique_ptr<native::HashCheckpoints> points_ = std::make_unique<native::HashCheckpoints>();
    native::HashingWriter lane_{-1, kPieceBytes, false, 8};
    std::int64_t at_ = 0;
    bool changed_ = false;
};

// HEAD: how many bytes the provider holds; nullopt when it cannot be asked
// now. Throws GrabFailure when the link is gone.
std::optional<std::int64_t> held_bytes(const p::PairingUrl& provider, const UploadRequest& request,
                                       const NetTimeouts& timeouts) {
    std::optional<PinnedExchange> exchange;
    try {
        exchange.emplace(provider, timeouts);
    } catch (const GrabFailure& f) {
        if (f.code == "certificate") throw;
        return std::nullopt;
    }
    http::request<http::empty_body> req(http::verb::head, request.path, 11);
    PinnedExchange::set_headers(req, provider);
    auto ec = run_step(exchange->io, exchange->stream, timeouts.reply, [&](auto h) {
        http::async_write(exchange->stream, req, h);
    });
    if (ec) return std::nullopt;
    beast::flat_buffer buffer;
    http::response_parser<http::empty_body> parser;
    parser.skip(true);  // a HEAD's answer has no body
    ec = run_step(exchange->io, exchange->stream, timeouts.reply,
                  [&](auto h) { http::async_read_header(exchange->stream, buffer, parser, h); });
    if (ec) return std::nullopt;
    const unsigned status = parser.get().result_int();
    if (status == 404)
        throw GrabFailure("not_found", "the upload broke off and its link was gone when the rest was to be sent; put again",
                          kNothing);
    const std::string text(parser.get()["Upload-Offset"]);
    if (status != 200 || text.empty()) return std::nullopt;
    return std::stoll(text);
}

// The provider's answer to the upload on `tls`: nullopt when none came
// (why says why). `carried` from `used` on: bytes read past the answer
// before it.
std::optional<http::response<http::string_body>> read_answer(BlockingTls& tls, std::string& carried, std::size_t& used,
                                                             std::string& why) {
    http::response_parser<http::string_body> parser;
    parser.body_limit(kMaxAnswerBytes);
    parser.eager(true);
    if (!read_message(tls, parser, [](const auto& p) { return p.is_done(); }, carried, used, why)) return std::nullopt;
    return parser.release();
}

// A final answer as the outcome of one request: another offset is worth
// asking again (HEAD), anything else ends the put (interpret).
Sent answered(const http::response<http::string_body>& answer) {
    if (answer.result() == http::status::conflict) return {std::nullopt, false, "the screen holds other bytes"};
    if (answer.result() == http::status::accepted) return {std::nullopt, true, {}};
    return {interpret(answer), false, {}};
}

// Sends the file from byte `from` (Upload-Offset) to its end and reads the
// answer, with blocking TLS (blocking_tls.hpp): each piece goes out as a
// run of records, so the provider finds many in its socket at once. The
// bytes go through `running` when the hash is named after them (taken up at
// `from`); `named` is that hash, once every byte is sent. Throws GrabFailure
// for an answer that ends the put.
Sent send_from(const p::PairingUrl& provider, const UploadRequest& request, ReadOnlyFile& file, std::int64_t from,
               RunningHash* running, const std::string& named, const UploadProgress& progress,
               const NetTimeouts& timeouts) {
    const auto idle = timeouts.download_idle;
    std::optional<BlockingTls> tls;
    try {
        tls.emplace(provider, timeouts, idle);
    } catch (const GrabFailure& f) {
        if (f.code == "certificate") throw;
        return {std::nullopt, false, f.what()};
    }
    http::request<http::empty_body> req(http::verb::put, request.path, 11);
    PinnedExchange::set_headers(req, provider);
    req.set(http::field::content_type, "application/octet-stream");
    req.set("Upload-Offset", std::to_string(from));
    // The provider checks the bytes it holds before taking more (docs/PROTOCOL.md, "Resuming an upload").
    if (from > 0 && running)
        req.set("Upload-Prefix-SHA256", running->rewind(from));
    else if (from > 0 && request.checkpoints)
        req.set("Upload-Prefix-SHA256", prefix_hash(file, *request.checkpoints, from)->hex());
    if (!named.empty()) req.set("Upload-SHA256", named);
    file.seek(from);
    req.set(http::field::content_length, std::to_string(request.size - from));
    // The body only once the provider agrees: a refusal costs no bytes, and
    // it reads the body straight from the socket (direct_body_receive.hpp).
    const bool has_body = from < request.size;
    if (has_body) req.set(http::field::expect, "100-continue");
    std::ostringstream head_out;
    head_out << req;
    const std::string head = head_out.str();
    if (!tls->write_all(head.data(), head.size())) return {std::nullopt, false, tls->error()};
    // "100 Continue" (a 1xx has no body), or a refusal before any byte of it.
    std::string carried, read_why;
    std::size_t used = 0;
    if (has_body) {
        const auto first = read_answer(*tls, carried, used, read_why);
        if (!first)
            return {std::nullopt, false, tls->timed_out() ? "the provider did not answer the upload's header" : read_why};
        if (first->result() != http::status::continue_) return answered(*first);
    }
    bool written = true;
    std::vector<char> piece(running ? 0 : kPieceBytes);  // the hash's pieces when it runs
    std::int64_t sent = from;
    while (sent < request.size) {
        // Pieces end on multiples of their size, so the hash's checkpoints
        // fall on piece ends wherever the request began.
        constexpr auto kPiece = static_cast<std::int64_t>(kPieceBytes);
        const auto want = static_cast<std::size_t>(std::min<std::int64_t>(kPiece - sent % kPiece, request.size - sent));
        native::HashingWriter::Piece lane_piece;
        char* data = piece.data();
        if (running) data = (lane_piece = running->piece()).data;
        const std::size_t n = file.read(data, want);
        if (n < want)
            throw input_failure(request.file.string() + " became shorter while it was being sent (" +
                                std::to_string(sent + static_cast<std::int64_t>(n)) + " of " +
                                std::to_string(request.size) + " bytes); put it again");
        written = tls->write_all(data, n);
        // Hashed after it went: the hash of this piece runs beside the next one.
        if (running) running->hash(lane_piece, n);
        if (!written) break;
        sent += static_cast<std::int64_t>(n);
        if (progress) progress(sent, request.size);
    }
    const bool write_timed_out = !written && tls->timed_out();
    const std::string write_error = written ? std::string() : tls->error();
    // A provider that refuses early (no room, a used link, another offset)
    // answers and closes while the bytes still flow: its answer says more
    // than the broken write.
    tls->set_idle(written ? idle + std::chrono::seconds(30) : kLateAnswerWait);
    const auto answer = read_answer(*tls, carried, used, read_why);
    if (answer) return answered(*answer);
    if (write_timed_out) return {std::nullopt, false, "the provider took nothing for " + seconds_text(idle)};
    if (!written) return {std::nullopt, false, write_error};
    if (tls->timed_out()) return {std::nullopt, false, "the provider did not answer the upload"};
    return {std::nullopt, false, read_why};
}

}  // namespace

Uploaded upload_file(const protocol::PairingUrl& provider, const UploadRequest& request, const UploadProgress& progress,
                     const NetTimeouts& timeouts, const std::function<void(const std::string&)>& notice) {
    if (request.size < 0) throw input_failure("a negative size cannot be uploaded");
    ReadOnlyFile file(request.file);
    std::optional<RunningHash> running;
    if (request.hash_after) running.emplace(file);
    // A cut connection goes on from what the provider holds (docs/PROTOCOL.md,
    // "Resuming an upload") while that grows now and then.
    std::int64_t from = 0;
    std::string named;  // Upload-SHA256, once every byte is sent
    ResumePacing pacing(timeouts.download_idle);
    for (int resumes = 0;; ++resumes) {
        Sent sent;
        try {
            sent = send_from(provider, request, file, from, running ? &*running : nullptr, named, progress, timeouts);
        } catch (const GrabFailure& f) {
            // The bytes held are the file as it was, not as it is.
            if (running && running->changed() && f.code == "interrupted")
                throw input_failure(request.file.string() + " changed while it was being sent; nothing was kept, put it "
                                    "again (" + f.what() + ")");
            throw;
        }
        if (sent.done) return {*sent.done, named};
        if (sent.awaiting_hash) {
            if (!running || !named.empty())
                throw GrabFailure("protocol", "the provider asks for the upload's SHA-256 again", kConnection);
            named = running->rewind(request.size);
            from = request.size;
            continue;
        }
        // What the provider holds now, asked until it answers.
        std::optional<std::int64_t> held;
        while (!held) {
            pacing.wait();
            held = held_bytes(provider, request, timeouts);
            if (held) pacing.reached(static_cast<std::uint64_t>(*held));
            if (pacing.given_up())
                throw upload_failure("the upload broke off after " + std::to_string(pacing.furthest()) + " of " +
                                     std::to_string(request.size) + " bytes (" + sent.why +
                                     ") and could not go on for " + seconds_text(timeouts.download_idle) + " (" +
                                     std::to_string(resumes + 1) + " tries)");
        }
        from = *held;
        if (running) named = from == request.size ? running->rewind(request.size) : std::string();
        if (notice)
            notice("the connection was lost at " + megabytes(static_cast<std::uint64_t>(from)) + " of " +
                   megabytes(static_cast<std::uint64_t>(request.size)) + " (" + sent.why + "); going on from there");
    }
}

}  // namespace umf::requester
