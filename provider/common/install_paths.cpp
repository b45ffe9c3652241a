#include "provider/common/install_paths.hpp"

#include <stdexcept>

namespace umf::provider {

namespace fs = std::filesystem;

namespace {

// The installed place when `probe` is there, else the build's.
std::optional<fs::path> installed_or_built(const fs::path& installed, const char* built, const fs::path& probe) {
    std::error_code ec;
    if (!installed.empty() && fs::exists(installed / probe, ec)) return installed;
    if (built && fs::exists(fs::path(built) / probe, ec)) return fs::path(built);
    return std::nullopt;
}

const char* built_fields_dir() {
#ifdef UMF_DATA_DIR
    return UMF_DATA_DIR "/fields";
#else
    return nullptr;
#endif
}

const char* built_web_site_dir() {
#ifdef UMF_WEB_SITE_DIR
    return UMF_WEB_SITE_DIR;
#else
    return nullptr;
#endif
}

const char* built_browser_extension_dir() {
#ifdef UMF_BROWSER_EXTENSION_DIR
    return UMF_BROWSER_EXTENSION_DIR;
#else
    return nullptr;
#endif
}

fs::path share_subdir(const char* name) {
    const fs::path share = installed_share_dir();
    return share.empty() ? fs::path() : share / name;
}

std::string place(const std::optional<fs::path>& dir) { return dir ? dir->string() : std::string("(none)"); }

}  // namespace

fs::path program_path() {
    std::error_code ec;
    const auto self = fs::read_symlink("/proc/self/exe", ec);
    return ec ? fs::path() : self;
}

fs::path program_dir() { return program_path().parent_path(); }

fs::path installed_share_dir() {
    const fs::path bin = program_dir();
    return bin.empty() ? fs::path() : bin.parent_path() / "share" / "umf";
}

fs::path shipped_fields_dir() {
    const fs::path installed = share_subdir("fields");
    const char* built = built_fields_dir();
    // b4-64x36.json is the field every screen size falls back to.
    if (auto dir = installed_or_built(installed, built, "b4-64x36.json")) return *dir;
    throw std::runtime_error("the shipped fields are missing: looked in " +
                             (installed.empty() ? std::string("PREFIX/share/umf/fields") : installed.string()) +
                             (built ? std::string(" and ") + built : std::string()));
}

std::optional<fs::path> web_site_dir() {
    return installed_or_built(share_subdir("web"), built_web_site_dir(), "index.html");
}

std::optional<fs::path> browser_extension_dir() {
    return installed_or_built(share_subdir("browser-extension"), built_browser_extension_dir(), "manifest.json");
}

std::string install_paths_report() {
    std::optional<fs::path> fields;
    try {
        fields = shipped_fields_dir();
    } catch (const std::runtime_error&) {
    }
    return "program: " + program_dir().string() + "\nfields: " + place(fields) + "\nphone page: " +
           place(web_site_dir()) + "\nbrowser extension: " + place(browser_extension_dir()) + "\n";
}

}  // namespace umf::provider
