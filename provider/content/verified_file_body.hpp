// A downloaded file, checked as it goes out (docs/PROTOCOL.md, "Downloads").
// The grab told the phone the file's size and SHA-256; the download sends
// the file only if it is still that file: the same inode, size and mtime
// before the first byte, and the same SHA-256 over the bytes read, computed
// as they are read. A file changed in place without a new mtime is caught at
// the end, and its last piece is never sent: the phone gets a download cut
// short, never bytes other than the ones announced. A resumed download sends
// from an offset and checks the same way: its hasher starts from the
// checkpoint at or before the offset (native/hash_checkpoints.hpp) and reads the
// bytes from there to the offset without sending them. A large download of
// a file hashed under a read lease, and unchanged since, is instead read
// under a lease of its own (verified_file_reader.hpp).
#pragma once

#include <boost/beast/core/error.hpp>
#include <boost/beast/http/message.hpp>
#include <boost/optional.hpp>
#include <cstdint>
#include <filesystem>
#include <memory>
#include <optional>
#include <string>
#include <utility>

#include "native/sha256.hpp"
#include "provider/content/file_facts.hpp"
#include "provider/content/read_lease.hpp"
#include "native/hash_checkpoints.hpp"

namespace umf::provider {

enum class DownloadCheck {
    changed = 1,  // the bytes read are not the ones announced
};
const boost::system::error_category& download_check_category();
inline boost::system::error_code make_error_code(DownloadCheck e) {
    return {static_cast<int>(e), download_check_category()};
}

}  // namespace umf::provider

namespace boost::system {
template <>
struct is_error_code_enum<umf::provider::DownloadCheck> : std::true_type {};
}  // namespace boost::system

namespace umf::provider {

struct VerifiedFileBody {
    class writer;
    class value_type {
    public:
        value_type() = default;
        value_type(value_type&& other) noexcept;
        value_type& operator=(value_type&& other) noexcept;
        ~value_type();

        // Opens the file for sending from `offset` on if it is still the
        // one described by `identity` and hashing to `sha256`; otherwise
        // says why not, in words for the requester. `checkpoints` are the
        // link's (null: none kept); `leased_ctime_ns` is FileFacts's.
        std::optional<std::string> open(const std::filesystem::path& file, const FileIdentity& identity,
                                        std::string sha256, std::uint64_t offset = 0,
                                        std::shared_ptr<native::HashCheckpoints> checkpoints = nullptr,
                                        std::int64_t leased_ctime_ns = 0);
        // The bytes sent: from the offset to the end.
        std::uint64_t size() const { return size_ - offset_; }
        // The first byte sent, and the whole file's size.
        std::uint64_t offset() const { return offset_; }
        std::uint64_t file_size() const { return size_; }

        // The checks, for whoever reads the file (the writer below,
        // verified_file_reader.hpp). Reads up to `size` bytes at `at`:
        // how many, 0 at the end, -1 with `ec`.
        long read_at(std::uint64_t at, char* into, std::size_t size, boost::beast::error_code& ec) const;
        // A hasher that has taken the bytes before `at`, read from the
        // nearest checkpoint on into `buffer`; null with `ec` when the file
        // ended first.
        std::unique_ptr<native::Sha256> hasher_at(std::uint64_t at, char* buffer, std::size_t buffer_size,
                                                  boost::beast::error_code& ec) const;
        // A lease under which the file is still the one announced: held only
        // when its hash was taken under a lease, the kernel grants one now
        // and the file's ctime has not moved since. While it holds unbroken,
        // the bytes read need no hashing (read_lease.hpp).
        ReadLease unchanged_under_lease() const;
        // Hashes the piece of `n` bytes that ends at byte `end` (saving a
        // checkpoint there when one is due); false, with
        // DownloadCheck::changed, when it ends the file and the whole is not
        // the announced SHA-256.
        bool hash_piece(native::Sha256& hash, const char* data, std::size_t n, std::uint64_t end,
                        boost::beast::error_code& ec) const;

    private:
        int fd_ = -1;
        std::uint64_t size_ = 0;  // the whole file's
        std::uint64_t offset_ = 0;
        std::string sha256_;
        std::shared_ptr<native::HashCheckpoints> checkpoints_;
        std::int64_t leased_ctime_ns_ = 0;
    };

    class writer {
    public:
        using const_buffers_type = boost::asio::const_buffer;

        template <bool isRequest, class Fields>
        writer(boost::beast::http::header<isRequest, Fields>&, value_type& body) : body_(body), at_(body.offset()) {}

        void init(boost::beast::error_code& ec) { ec = {}; }
        boost::optional<std::pair<const_buffers_type, bool>> get(boost::beast::error_code& ec);

    private:
        value_type& body_;
        std::uint64_t at_;  // the next byte to send
        std::unique_ptr<native::Sha256> hash_;
        std::unique_ptr<char[]> buffer_;
    };

    static std::uint64_t size(const value_type& body) { return body.size(); }
};

}  // namespace umf::provider
