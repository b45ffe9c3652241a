#include "requester/download.hpp"

#include <fcntl.h>
#include <stdio.h>
#include <sys/stat.h>
#include <unistd.h>

#include <vector>
#include <boost/asio/ssl.hpp>
#include <boost/beast/core.hpp>
#include <boost/beast/http.hpp>
#include <boost/beast/ssl.hpp>
#include <cerrno>
#include <cstring>
#include <memory>
#include <optional>

#include "native/sha256.hpp"
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

// What one read of the body takes at most.
constexpr std::size_t kPieceBytes = 64 << 10;

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

    void write(const char* data, std::size_t size) {
        while (size > 0) {
            const ssize_t n = ::write(fd_, data, size);
            if (n < 0 && errno == EINTR) continue;
            if (n <= 0) throw output_failure("cannot write " + path_.string() + ": " + errno_text());
            data += n;
            size -= static_cast<std::size_t>(n);
        }
    }
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
    // Empty again, for a download that starts over.
    void truncate() {
        if (::ftruncate(fd_, 0) != 0 || ::lseek(fd_, 0, SEEK_SET) != 0)
            throw output_failure("cannot empty " + path_.string() + ": " + errno_text());
    }
    void keep() { kept_ = true; }
    const fs::path& path() const { return path_; }

private:
    fs::path path_;
    int fd_ = -1;
    bool kept_ = false;
};

std::string seconds(std::chrono::milliseconds ms) { return std::to_string(ms.count() / 1000) + " s"; }

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
// hashed as they came, and the validator the rest is asked for with.
struct Transfer {
    Transfer(const protocol::PairingUrl& url, const DownloadRequest& what, const NetTimeouts& limits, TempFile& into)
        : provider(url), request(what), timeouts(limits), file(into) {}

    const protocol::PairingUrl& provider;
    const DownloadRequest& request;
    const NetTimeouts& timeouts;
    TempFile& file;
    std::unique_ptr<native::Sha256> sha = std::make_unique<native::Sha256>();
    std::uint64_t received = 0;
    std::string etag;

    std::uint64_t expected() const { return static_cast<std::uint64_t>(request.size); }

    // Starts again from the first byte (the provider sent the whole file).
    void restart() {
        file.truncate();
        sha = std::make_unique<native::Sha256>();
        received = 0;
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
    std::optional<PinnedExchange> exchange;
    try {
        exchange.emplace(provider, timeouts);
    } catch (const GrabFailure& f) {
        if (f.code == "certificate") throw;
        why = f.what();
        return false;
    }
    net::io_context& io = exchange->io;
    TlsStream& stream = exchange->stream;
    http::request<http::empty_body> req(http::verb::get, request.path, 11);
    PinnedExchange::set_headers(req, provider);
    if (received > 0) {
        req.set(http::field::range, "bytes=" + std::to_string(received) + "-");
        if (!etag.empty()) req.set(http::field::if_range, etag);
    }
    auto ec = run_step(io, stream, timeouts.download_idle, [&](auto h) { http::async_write(stream, req, h); });
    if (ec) {
        why = "cannot request " + request.path + ": " + ec.message();
        return false;
    }
    beast::flat_buffer buffer;
    http::response_parser<http::buffer_body> parser;
    parser.body_limit(std::max<std::uint64_t>(expected() - received, kMaxErrorBodyBytes));
    ec = run_step(io, stream, timeouts.download_idle, [&](auto h) { http::async_read_header(stream, buffer, parser, h); });
    if (ec == beast::error::timeout) {
        why = "the provider sent no answer within " + seconds(timeouts.download_idle);
        return false;
    }
    if (ec) {
        why = "cannot read the answer: " + ec.message();
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
    if (body) {
        const auto length = parser.content_length();
        if (!length)
            throw download_failure("the provider's download has no Content-Length; it must announce the size");
        if (*length != expected() - received)
            throw download_failure("the provider announced " + std::to_string(request.size) +
                                   " bytes but the download has " + std::to_string(received + *length));
    }
    // Large pieces: fewer writes and fewer turns of the I/O loop per GiB.
    std::vector<char> chunk(kPieceBytes);
    std::string error_body;
    while (!parser.is_done()) {
        parser.get().body().data = chunk.data();
        parser.get().body().size = chunk.size();
        ec = run_step(io, stream, timeouts.download_idle, [&](auto h) { http::async_read(stream, buffer, parser, h); });
        if (ec == http::error::need_buffer) ec = {};
        const std::size_t n = chunk.size() - parser.get().body().size;
        if (body) {
            file.write(chunk.data(), n);
            sha->update(chunk.data(), n);
            received += n;
        } else if (error_body.size() < kMaxErrorBodyBytes) {
            error_body.append(chunk.data(), std::min(n, kMaxErrorBodyBytes - error_body.size()));
        }
        if (ec == http::error::body_limit)
            throw download_failure("the download is longer than the announced " + std::to_string(request.size) +
                                   " bytes");
        if (ec == beast::error::timeout) {
            why = "nothing arrived for " + seconds(timeouts.download_idle);
            return false;
        }
        if (ec) {
            why = ec.message();
            return false;
        }
    }
    beast::error_code ignored;
    beast::get_lowest_layer(stream).socket().close(ignored);
    if (!body) refused(status, error_body);
    if (received != expected())
        throw download_failure("the download ended after " + std::to_string(received) + " of " +
                               std::to_string(request.size) + " bytes");
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
                                   seconds(timeouts.download_idle) + " of asking again (" + std::to_string(resumes + 1) +
                                   " times), so its SHA-256 could not be checked and nothing was kept");
        if (progress)
            progress("the connection was lost at " + megabytes(transfer.received) + " of " + megabytes(transfer.expected()) +
                     " (" + why + "); resuming in " + std::to_string(pacing.next_wait().count()) + " ms");
        pacing.wait();
    }

    const std::string digest = transfer.sha->hex();
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
