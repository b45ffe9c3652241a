#include "requester/download.hpp"

#include <fcntl.h>
#include <stdio.h>
#include <sys/stat.h>
#include <unistd.h>

#include <boost/asio/ssl.hpp>
#include <boost/beast/core.hpp>
#include <boost/beast/http.hpp>
#include <boost/beast/ssl.hpp>
#include <cerrno>
#include <cstring>
#include <memory>
#include <optional>
#include <sstream>

#include "native/hashing_writer.hpp"
#include "requester/blocking_tls.hpp"
#include "requester/cli.hpp"
#include "requester/grab_failure.hpp"
#include "requester/resume_pacing.hpp"
#include "requester/transfer_text.hpp"
#include "shared/io/store_file.hpp"
#include "shared/protocol/http_error_body.hpp"
#include "shared/protocol/messages.hpp"

namespace umf::requester {

namespace {

namespace fs = std::filesystem;
namespace net = boost::asio;
namespace beast = boost::beast;
namespace http = beast::http;

// The piece of the body hashed and written at once.
constexpr std::size_t kPieceBytes = 1 << 20;

// Files this large are written past the page cache (hashing_writer.hpp).
constexpr std::int64_t kDirectFromBytes = std::int64_t{64} << 20;

// Error bodies are a short JSON message; anything longer is cut off.
constexpr std::size_t kMaxErrorBodyBytes = 64 * 1024;

GrabFailure output_failure(const std::string& message) { return {"output", message, kInputError}; }
GrabFailure download_failure(const std::string& message) { return {"download", message, kConnection}; }

std::string errno_text() { return std::strerror(errno); }

// The private file the bytes land in first: 0600, in the target directory
// (so the final link stays on one file system), removed unless kept.
class TempFile {
public:
    explicit TempFile(const fs::path& dir) {
        std::string tmpl = (dir / ".umf-download-XXXXXX").string();
        fd_ = mkostemp(tmpl.data(), O_CLOEXEC);
        if (fd_ < 0) throw output_failure("cannot create a file in " + dir.string() + ": " + errno_text());
        path_ = tmpl;
    }
    ~TempFile() {
        if (fd_ >= 0) ::close(fd_);
        if (!kept_) ::unlink(path_.c_str());
    }
    TempFile(const TempFile&) = delete;
    TempFile& operator=(const TempFile&) = delete;

    int fd() const { return fd_; }
    // Flushed to disk and given the permissions of a file the user saved:
    // 0600 only kept strangers out while it was incomplete.
    void finish() {
        const mode_t mask = ::umask(0);
        ::umask(mask);
        if (::fchmod(fd_, 0666 & ~mask) != 0 || ::fsync(fd_) != 0 || ::close(fd_) != 0) {
            fd_ = -1;
            throw output_failure("cannot finish " + path_.string() + ": " + errno_text());
        }
        fd_ = -1;
    }
    void keep() { kept_ = true; }
    const fs::path& path() const { return path_; }

private:
    fs::path path_;
    int fd_ = -1;
    bool kept_ = false;
};


}  // namespace

std::string store_without_overwriting(const fs::path& temp, const fs::path& dir, const std::string& name) {
    try {
        return io::store_under_free_name(temp, dir, name);
    } catch (const std::runtime_error& e) {
        throw output_failure(e.what());
    }
}

namespace {

// "bytes FIRST-LAST/SIZE" naming exactly the rest from `from`.
bool names_the_rest(beast::string_view content_range, std::uint64_t from, std::uint64_t size) {
    return content_range ==
           "bytes " + std::to_string(from) + "-" + std::to_string(size - 1) + "/" + std::to_string(size);
}

// The state of one download across its attempts: the bytes kept so far,
// hashed and written as they came, and the validator the rest is asked for
// with.
struct Transfer {
    Transfer(const protocol::PairingUrl& url, const DownloadRequest& what, const NetTimeouts& limits, TempFile& into)
        : provider(url),
          request(what),
          timeouts(limits),
          file(into),
          writer(into.fd(), kPieceBytes, what.size >= kDirectFromBytes, 16) {}

    const protocol::PairingUrl& provider;
    const DownloadRequest& request;
    const NetTimeouts& timeouts;
    TempFile& file;
    native::HashingWriter writer;
    std::uint64_t received = 0;
    std::string etag;

    std::uint64_t expected() const { return static_cast<std::uint64_t>(request.size); }

    // Starts again from the first byte (the provider sent the whole file).
    void restart() {
        finish_writing();
        writer.restart();
        received = 0;
    }
    // Everything received is hashed and on its way to disk.
    void finish_writing() {
        try {
            writer.drain();
        } catch (const std::runtime_error& e) {
            throw output_failure(std::string(e.what()) + " (" + file.path().string() + ")");
        }
    }
    native::HashingWriter::Piece next_piece() {
        try {
            return writer.next();
        } catch (const std::runtime_error& e) {
            throw output_failure(std::string(e.what()) + " (" + file.path().string() + ")");
        }
    }

    // One request, for the whole file or the rest of it. True when the
    // file is complete; false with `why` when the connection broke (worth
    // asking again); throws GrabFailure for an answer that ends it.
    bool attempt(std::string& why);
    [[noreturn]] void refused(unsigned status, const std::string& error_body) const;
};

void Transfer::refused(unsigned status, const std::string& error_body) const {
    const auto error = protocol::parse_error_body(error_body);
    const protocol::Error* e = error ? &*error : nullptr;
    const std::string why = e ? e->message : "HTTP status " + std::to_string(status);
    if (status == 404 && received > 0)
        throw GrabFailure("not_found",
                          "the download broke off after " + std::to_string(received) + " of " +
                              std::to_string(request.size) + " bytes and its link was gone when the rest was asked for (" +
                              why + "); nothing was kept; grab again",
                          kNothing);
    if (status == 404)
        throw GrabFailure("not_found", "the download link is unknown, used or expired (" + why + "); grab again",
                          kNothing);
    throw GrabFailure(e ? protocol::to_string(e->code) : "download", "the download failed: " + why, kConnection);
}

bool Transfer::attempt(std::string& why) {
    std::optional<BlockingTls> tls;
    try {
        tls.emplace(provider, timeouts, timeouts.download_idle);
    } catch (const GrabFailure& f) {
        if (f.code == "certificate") throw;
        why = f.what();
        return false;
    }
    http::request<http::empty_body> req(http::verb::get, request.path, 11);
    PinnedExchange::set_headers(req, provider);
    // The link is bound to the session's pairing token (docs/PROTOCOL.md, "Downloads").
    req.set(http::field::authorization, "Bearer " + provider.token);
    if (received > 0) {
        req.set(http::field::range, "bytes=" + std::to_string(received) + "-");
        if (!etag.empty()) req.set(http::field::if_range, etag);
    }
    std::ostringstream out;
    out << req;
    const std::string head_out = out.str();
    if (!tls->write_all(head_out.data(), head_out.size())) {
        why = "cannot request " + request.path + ": " + tls->error();
        return false;
    }
    http::response_parser<http::empty_body> parser;
    parser.skip(true);  // the body is read here, not by the parser
    std::string head;
    std::size_t used = 0;
    if (!read_message(*tls, parser, [](const auto& p) { return p.is_header_done(); }, head, used, why)) {
        if (tls->timed_out()) why = "the provider sent no answer within " + seconds_text(timeouts.download_idle);
        return false;
    }
    const unsigned status = parser.get().result_int();
    const bool body = status == 200 || status == 206;
    if (status == 206 && (received == 0 || !names_the_rest(parser.get()[http::field::content_range], received, expected())))
        throw download_failure("the provider resumed the download at another place (" +
                               std::string(parser.get()[http::field::content_range]) + ") than the " +
                               std::to_string(received) + " bytes it had");
    if (status == 200) {
        if (received > 0) restart();  // the file as a whole, again
        etag = std::string(parser.get()[http::field::etag]);
    }
    const auto length = parser.content_length();
    if (body) {
        if (!length)
            throw download_failure("the provider's download has no Content-Length; it must announce the size");
        if (*length != expected() - received)
            throw download_failure("the provider announced " + std::to_string(request.size) +
                                   " bytes but the download has " + std::to_string(received + *length));
    }
    // The body: what came with the header, then large reads straight into
    // the piece that is hashed and written.
    std::uint64_t left = body ? *length : std::min<std::uint64_t>(length.value_or(kMaxErrorBodyBytes), kMaxErrorBodyBytes);
    const std::size_t early = static_cast<std::size_t>(std::min<std::uint64_t>(head.size() - used, left));
    if (!body) {
        std::string error_body = head.substr(used, early);
        char piece[16 * 1024];
        for (left -= early; left > 0;) {
            const long n = tls->read_some(piece, static_cast<std::size_t>(std::min<std::uint64_t>(sizeof piece, left)));
            if (n <= 0) break;  // an error body ends with its length or with the connection
            error_body.append(piece, static_cast<std::size_t>(n));
            left -= static_cast<std::uint64_t>(n);
        }
        refused(status, error_body);
    }
    // Each piece is filled from the network and handed to the writer; a
    // piece cut short by the connection is kept, and the rest asked for.
    const char* carried = head.data() + used;
    std::size_t carried_left = early;
    while (left > 0) {
        const native::HashingWriter::Piece piece = next_piece();
        std::size_t want = static_cast<std::size_t>(std::min<std::uint64_t>(piece.capacity, left));
        // After a cut, a short first piece brings the file back to where
        // whole pieces can be written directly.
        if (const std::size_t off = received % native::HashingWriter::kDirectAlign; off != 0)
            want = std::min(want, native::HashingWriter::kDirectAlign - off);
        const std::size_t from_head = std::min(carried_left, want);
        std::memcpy(piece.data, carried, from_head);
        carried += from_head;
        carried_left -= from_head;
        std::size_t filled = from_head;
        long n = 1;
        while (filled < want && (n = tls->read_some(piece.data + filled, want - filled)) > 0)
            filled += static_cast<std::size_t>(n);
        writer.submit(piece, filled);
        received += filled;
        left -= filled;
        if (n > 0) continue;
        why = tls->timed_out() ? "nothing arrived for " + seconds_text(timeouts.download_idle)
                               : n == 0 ? std::string("the provider closed the connection") : tls->error();
        return false;
    }
    return true;
}

}  // namespace

SavedFile download_file(const protocol::PairingUrl& provider, const DownloadRequest& request, const fs::path& dir_in,
                        const NetTimeouts& timeouts, const std::function<void(const std::string&)>& progress) {
    std::error_code fec;
    fs::path dir = fs::absolute(dir_in, fec);
    if (fec) throw output_failure("cannot use " + dir_in.string() + ": " + fec.message());
    fs::create_directories(dir, fec);
    if (fec) throw output_failure("cannot create " + dir.string() + ": " + fec.message());
    if (!fs::is_directory(dir, fec)) throw output_failure(dir.string() + " is not a directory");
    if (request.size < 0) throw download_failure("the provider announced a negative size");
    const std::string name = protocol::safe_file_name(request.name);

    TempFile file(dir);
    Transfer transfer(provider, request, timeouts, file);
    // A cut connection is asked again for the rest (docs/PROTOCOL.md,
    // "Resuming a download") while it still brings new bytes now and then.
    ResumePacing pacing(timeouts.download_idle);
    for (int resumes = 0;; ++resumes) {
        std::string why;
        if (transfer.attempt(why)) break;
        pacing.reached(transfer.received);
        if (pacing.given_up())
            throw download_failure("the download broke off after " + std::to_string(transfer.received) + " of " +
                                   std::to_string(request.size) + " bytes (" + why + ") and brought nothing more for " +
                                   seconds_text(timeouts.download_idle) + " of asking again (" + std::to_string(resumes + 1) +
                                   " times), so its SHA-256 could not be checked and nothing was kept");
        if (progress)
            progress("the connection was lost at " + megabytes(transfer.received) + " of " + megabytes(transfer.expected()) +
                     " (" + why + "); resuming in " + std::to_string(pacing.next_wait().count()) + " ms");
        pacing.wait();
    }

    transfer.finish_writing();
    const std::string digest = transfer.writer.hex();
    if (request.sha256 && *request.sha256 != digest)
        throw download_failure("the downloaded file's SHA-256 is " + digest + ", the provider announced " +
                               *request.sha256 + "; it was not kept");

    file.finish();
    SavedFile saved;
    saved.name = store_without_overwriting(file.path(), dir, name);
    file.keep();
    saved.path = dir / saved.name;
    saved.size = request.size;
    saved.sha256 = digest;
    return saved;
}

}  // namespace umf::requester
