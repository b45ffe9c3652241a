// A downloaded file, checked as it goes out (docs/PROTOCOL.md, "Downloads").
// The grab told the phone the file's size and SHA-256; the download sends
// the file only if it is still that file: the same inode, size and mtime
// before the first byte, and the same SHA-256 over the bytes read, computed
// as they are read. A file changed in place without a new mtime is caught at
// the end, and its last piece is never sent: the phone gets a download cut
// short, never bytes other than the ones announced.
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

        // Opens the file for sending if it is still the one described by
        // `identity` and hashing to `sha256`; otherwise says why not, in
        // words for the requester.
        std::optional<std::string> open(const std::filesystem::path& file, const FileIdentity& identity,
                                        std::string sha256);
        std::uint64_t size() const { return size_; }

    private:
        friend class VerifiedFileBody::writer;
        int fd_ = -1;
        std::uint64_t size_ = 0;
        std::string sha256_;
    };

    class writer {
    public:
        using const_buffers_type = boost::asio::const_buffer;

        template <bool isRequest, class Fields>
        writer(boost::beast::http::header<isRequest, Fields>&, value_type& body) : body_(body), remain_(body.size_) {}

        void init(boost::beast::error_code& ec) { ec = {}; }
        boost::optional<std::pair<const_buffers_type, bool>> get(boost::beast::error_code& ec);

    private:
        value_type& body_;
        std::uint64_t remain_;
        native::Sha256 hash_;
        std::unique_ptr<char[]> buffer_;
    };

    static std::uint64_t size(const value_type& body) { return body.size(); }
};

}  // namespace umf::provider
