#include "provider/content/verified_file_body.hpp"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>

namespace umf::provider {

namespace {

// Large enough that a 1 GiB file is 16,384 reads, not the 262,144 of 4 KiB.
constexpr std::size_t kReadBytes = 64 * 1024;

class DownloadCheckCategory : public boost::system::error_category {
public:
    const char* name() const noexcept override { return "umf.download"; }
    std::string message(int) const override { return "the file's bytes are not the ones its grab announced"; }
};

}  // namespace

const boost::system::error_category& download_check_category() {
    static const DownloadCheckCategory category;
    return category;
}

VerifiedFileBody::value_type::value_type(value_type&& other) noexcept
    : fd_(std::exchange(other.fd_, -1)),
      size_(other.size_),
      offset_(other.offset_),
      sha256_(std::move(other.sha256_)),
      checkpoints_(std::move(other.checkpoints_)),
      leased_ctime_ns_(other.leased_ctime_ns_) {}

VerifiedFileBody::value_type& VerifiedFileBody::value_type::operator=(value_type&& other) noexcept {
    if (this != &other) {
        if (fd_ >= 0) ::close(fd_);
        fd_ = std::exchange(other.fd_, -1);
        size_ = other.size_;
        offset_ = other.offset_;
        sha256_ = std::move(other.sha256_);
        checkpoints_ = std::move(other.checkpoints_);
        leased_ctime_ns_ = other.leased_ctime_ns_;
    }
    return *this;
}

VerifiedFileBody::value_type::~value_type() {
    if (fd_ >= 0) ::close(fd_);
}

std::optional<std::string> VerifiedFileBody::value_type::open(const std::filesystem::path& file,
                                                              const FileIdentity& identity, std::string sha256,
                                                              std::uint64_t offset,
                                                              std::shared_ptr<native::HashCheckpoints> checkpoints,
                                                              std::int64_t leased_ctime_ns) {
    if (fd_ >= 0) ::close(fd_);
    fd_ = ::open(file.c_str(), O_RDONLY | O_CLOEXEC);
    if (fd_ < 0) return std::string("the file can no longer be read: ") + std::strerror(errno);
    struct stat st {};
    if (::fstat(fd_, &st) != 0 || !S_ISREG(st.st_mode)) return std::string("the file can no longer be read");
    const FileIdentity now{static_cast<std::uint64_t>(st.st_dev), static_cast<std::uint64_t>(st.st_ino),
                           static_cast<std::int64_t>(st.st_size),
                           static_cast<std::int64_t>(st.st_mtim.tv_sec) * 1000000000 + st.st_mtim.tv_nsec};
    if (now != identity) return std::string("the file changed since it was offered; grab it again");
    if (sha256.size() != 64) return std::string("the file was offered without its SHA-256");
    size_ = static_cast<std::uint64_t>(identity.size);
    if (offset > size_) return std::string("the download cannot resume past the file's end");
    offset_ = offset;
    sha256_ = std::move(sha256);
    checkpoints_ = checkpoints ? std::move(checkpoints) : std::make_shared<native::HashCheckpoints>();
    leased_ctime_ns_ = leased_ctime_ns;
    return std::nullopt;
}

long VerifiedFileBody::value_type::read_at(std::uint64_t at, char* into, std::size_t size,
                                           boost::beast::error_code& ec) const {
    ssize_t n;
    do {
        n = ::pread(fd_, into, size, static_cast<off_t>(at));
    } while (n < 0 && errno == EINTR);
    if (n < 0) ec = boost::system::error_code(errno, boost::system::system_category());
    return static_cast<long>(n);
}

std::unique_ptr<native::Sha256> VerifiedFileBody::value_type::hasher_at(std::uint64_t at, char* buffer,
                                                                       std::size_t buffer_size,
                                                                       boost::beast::error_code& ec) const {
    auto hash = checkpoints_->hasher_at(
        at, [&](std::uint64_t at, char* into, std::size_t size) { return read_at(at, into, size, ec); }, buffer,
        buffer_size);
    if (!hash && !ec) ec = DownloadCheck::changed;
    return hash;
}

ReadLease VerifiedFileBody::value_type::unchanged_under_lease() const {
    if (leased_ctime_ns_ == 0 || fd_ < 0) return {};
    ReadLease lease(fd_);
    struct stat st {};
    // Taken first, the lease covers every change after the ctime read here.
    if (!lease.held() || ::fstat(fd_, &st) != 0 ||
        std::int64_t{st.st_ctim.tv_sec} * 1000000000 + st.st_ctim.tv_nsec != leased_ctime_ns_)
        return {};
    return lease;
}

bool VerifiedFileBody::value_type::hash_piece(native::Sha256& hash, const char* data, std::size_t n,
                                              std::uint64_t end, boost::beast::error_code& ec) const {
    hash.update(data, n);
    if (end % native::HashCheckpoints::kStep == 0) checkpoints_->save(end, hash);
    // The last piece goes out only when the whole is what was announced.
    if (end == size_ && hash.hex() != sha256_) {
        ec = DownloadCheck::changed;
        return false;
    }
    return true;
}

boost::optional<std::pair<VerifiedFileBody::writer::const_buffers_type, bool>> VerifiedFileBody::writer::get(
    boost::beast::error_code& ec) {
    ec = {};
    if (!buffer_) buffer_ = std::make_unique_for_overwrite<char[]>(kReadBytes);
    // At most a checkpoint step of bytes read and not sent.
    if (!hash_ && !(hash_ = body_.hasher_at(body_.offset(), buffer_.get(), kReadBytes, ec))) return boost::none;
    // An empty file of the same identity is the empty file that was hashed.
    if (at_ >= body_.file_size()) return boost::none;
    // Reads end on multiples of kReadBytes, so the checkpoints' offsets are
    // reached exactly wherever the transfer began.
    const auto want = static_cast<std::size_t>(
        std::min<std::uint64_t>(body_.file_size() - at_, kReadBytes - at_ % kReadBytes));
    const long n = body_.read_at(at_, buffer_.get(), want, ec);
    if (n < 0) return boost::none;
    if (n == 0) {
        // Shorter than when it was offered.
        ec = DownloadCheck::changed;
        return boost::none;
    }
    at_ += static_cast<std::uint64_t>(n);
    if (!body_.hash_piece(*hash_, buffer_.get(), static_cast<std::size_t>(n), at_, ec)) return boost::none;
    return {{boost::asio::const_buffer(buffer_.get(), static_cast<std::size_t>(n)), at_ < body_.file_size()}};
}

}  // namespace umf::provider
