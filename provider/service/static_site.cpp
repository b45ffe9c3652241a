#include "provider/service/static_site.hpp"

#include <fstream>
#include <sstream>
#include <stdexcept>

#include "provider/content/file_facts.hpp"

namespace umf::provider {

namespace {

// No inline style: the pages are served with a Content-Security-Policy of
// style-src 'self' (site_route.cpp).
const char* kBuiltInPage = R"(<!doctype html>
<html lang="en"><head><meta charset="utf-8"><meta name="viewport" content="width=device-width, initial-scale=1">
<title>umf</title><link rel="stylesheet" href="/umf-provider.css"></head>
<body>
<h1>umf provider</h1>
<p>This provider serves its content to paired requesters. Point the webcam requester at the screen:</p>
<pre>umf-requester grab --url 'PAIRING URL' --camera 0</pre>
<p>The pairing URL comes from <code>umf-provider pair</code> on the desktop.</p>
</body></html>
)";

const char* kBuiltInStyle = "body { font-family: sans-serif; max-width: 36em; margin: 2em auto; padding: 0 1em }\n";

std::string mime_with_charset(const std::filesystem::path& file) {
    std::string mime = mime_for(file);
    const std::string ext = file.extension().string();
    if (ext == ".js" || ext == ".mjs") mime = "text/javascript";
    if (ext == ".wasm") mime = "application/wasm";
    if (ext == ".css") mime = "text/css";
    if (ext == ".webmanifest") mime = "application/manifest+json";
    if (ext == ".ico") mime = "image/x-icon";
    if (ext == ".map") mime = "application/json";
    if (mime.rfind("text/", 0) == 0 || mime == "application/json") mime += "; charset=utf-8";
    return mime;
}

}  // namespace

StaticSite::StaticSite() {
    files_["/index.html"] = {"text/html; charset=utf-8", std::make_shared<const std::string>(kBuiltInPage), {}};
    files_["/umf-provider.css"] = {"text/css; charset=utf-8", std::make_shared<const std::string>(kBuiltInStyle), {}};
}

StaticSite StaticSite::from_folder(const std::filesystem::path& root) {
    namespace fs = std::filesystem;
    StaticSite site;
    site.files_.clear();
    std::size_t total = 0;
    std::error_code ec;
    fs::recursive_directory_iterator it(root, fs::directory_options::none, ec), end;
    if (ec) throw std::runtime_error("cannot read the web folder " + root.string() + ": " + ec.message());
    for (; it != end; it.increment(ec)) {
        if (ec) throw std::runtime_error("cannot read the web folder " + root.string() + ": " + ec.message());
        const fs::path rel = fs::relative(it->path(), root);
        if (!rel.empty() && rel.begin()->string().front() == '.') {
            if (it->is_directory()) it.disable_recursion_pending();
            continue;
        }
        if (!it->is_regular_file()) continue;
        if (site.files_.size() >= kMaxFiles) throw std::runtime_error("the web folder holds too many files");
        std::ifstream in(it->path(), std::ios::binary);
        std::ostringstream bytes;
        bytes << in.rdbuf();
        if (!in && !in.eof()) throw std::runtime_error("cannot read " + it->path().string());
        total += bytes.str().size();
        if (total > kMaxTotalBytes) throw std::runtime_error("the web folder is larger than 64 MiB");
        site.files_["/" + rel.generic_string()] = {mime_with_charset(it->path()),
                                                   std::make_shared<const std::string>(std::move(bytes).str()), {}};
    }
    if (!site.files_.count("/index.html")) {
        // A web client still being built (the detector alone): "/" keeps the
        // built-in page.
        for (auto& [path, file] : StaticSite().files_) site.files_.emplace(path, file);
    }
    return site;
}

std::optional<StaticFile> StaticSite::find(std::string_view target) const {
    target = target.substr(0, target.find_first_of("?#"));
    if (target == "/") target = "/index.html";
    auto it = files_.find(target);
    if (it == files_.end()) return std::nullopt;
    return it->second;
}

}  // namespace umf::provider
