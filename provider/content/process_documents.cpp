#include "provider/content/process_documents.hpp"

#include <pwd.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <array>
#include <cstdlib>
#include <fstream>
#include <optional>
#include <set>
#include <string_view>
#include <system_error>
#include <utility>

#include "provider/content/recent_files.hpp"

namespace umf::provider {

namespace fs = std::filesystem;

namespace {

// More than the kernel lets a command line be (ARG_MAX), and than any
// process holds files open that we would look at.
constexpr std::size_t kMaxCmdlineBytes = 4 * 1024 * 1024;
constexpr std::size_t kMaxDescriptors = 4096;

bool starts_with(std::string_view text, std::string_view prefix) { return text.substr(0, prefix.size()) == prefix; }
bool ends_with(std::string_view text, std::string_view suffix) {
    return text.size() >= suffix.size() && text.substr(text.size() - suffix.size()) == suffix;
}

// Programs whose first operand is their program (a script), not a document.
bool is_interpreter(std::string_view arg0) {
    const std::string name = fs::path(arg0).filename().string();
    static constexpr std::array<std::string_view, 9> shells{"sh", "bash", "dash", "zsh", "ksh",
                                                             "mksh", "fish", "csh", "tcsh"};
    static constexpr std::array<std::string_view, 11> families{"python", "perl", "ruby", "node", "lua", "php",
                                                               "java", "tclsh", "wish", "gjs", "Rscript"};
    if (std::find(shells.begin(), shells.end(), name) != shells.end()) return true;
    return std::any_of(families.begin(), families.end(), [&](std::string_view f) { return starts_with(name, f); });
}

// Kernel interfaces look like regular files in /proc and /sys.
bool in_pseudo_file_system(const fs::path& path) {
    const auto first = std::next(path.begin());
    if (first == path.end()) return false;
    return *first == "proc" || *first == "sys" || *first == "dev";
}

bool is_readable_regular_file(const fs::path& path) {
    struct stat info {};
    if (::stat(path.c_str(), &info) != 0 || !S_ISREG(info.st_mode)) return false;
    return ::access(path.c_str(), R_OK) == 0 && !in_pseudo_file_system(path);
}

std::optional<fs::path> argument_path(const std::string& arg, const fs::path& cwd) {
    if (starts_with(arg, "file:")) return file_url_to_path(arg);
    if (arg.find('\0') != std::string::npos) return std::nullopt;
    const fs::path path(arg);
    if (path.is_absolute()) return path.lexically_normal();
    if (cwd.empty() || !cwd.is_absolute()) return std::nullopt;
    return (cwd / path).lexically_normal();
}

// Two names of one file (a symlink, "./a" and "a") count once.
std::string identity_of(const fs::path& path) {
    std::error_code ec;
    const fs::path canonical = fs::weakly_canonical(path, ec);
    return ec ? path.string() : canonical.string();
}

// Collects paths in order, each file once.
class UniquePaths {
public:
    explicit UniquePaths(std::set<std::string> excluded = {}) : seen_(std::move(excluded)) {}
    void add(const fs::path& path) {
        if (seen_.insert(identity_of(path)).second) paths_.push_back(path);
    }
    std::vector<fs::path> take() { return std::move(paths_); }

private:
    std::set<std::string> seen_;
    std::vector<fs::path> paths_;
};

bool is_library_or_state_file(const std::string& name) {
    static constexpr std::array<std::string_view, 16> suffixes{
        ".so", ".lock", ".log", ".tmp", ".swp", ".db", ".sqlite", ".sqlite3", "-journal", "-wal", "-shm",
        ".pyc", ".o", ".a", "~", ".part"};
    if (std::any_of(suffixes.begin(), suffixes.end(), [&](std::string_view s) { return ends_with(name, s); }))
        return true;
    return name.find(".so.") != std::string::npos || name == "lock" || name == "LOCK";
}

bool owned_by_us(const fs::path& process_dir) {
    struct stat info {};
    return ::stat(process_dir.c_str(), &info) == 0 && info.st_uid == ::geteuid();
}

fs::path read_link_or_empty(const fs::path& link) {
    std::error_code ec;
    fs::path target = fs::read_symlink(link, ec);
    return ec ? fs::path() : target;
}

std::vector<std::pair<long, fs::path>> descriptor_targets(const fs::path& fd_dir) {
    std::vector<std::pair<long, fs::path>> targets;
    std::error_code ec;
    for (fs::directory_iterator it(fd_dir, ec), end; !ec && it != end && targets.size() < kMaxDescriptors;
         it.increment(ec)) {
        const std::string name = it->path().filename().string();
        char* rest = nullptr;
        const long fd = std::strtol(name.c_str(), &rest, 10);
        if (rest == name.c_str() || *rest != '\0') continue;
        fs::path target = read_link_or_empty(it->path());
        // Sockets, pipes and anonymous inodes read "socket:[123]" and the like.
        if (target.is_absolute()) targets.emplace_back(fd, std::move(target));
    }
    std::sort(targets.begin(), targets.end());
    return targets;
}

}  // namespace

fs::path user_home() {
    if (const char* home = std::getenv("HOME"); home && *home && fs::path(home).is_absolute()) return home;
    long size = ::sysconf(_SC_GETPW_R_SIZE_MAX);
    std::string buffer(size > 0 ? static_cast<std::size_t>(size) : 16384, '\0');
    struct passwd entry {};
    struct passwd* found = nullptr;
    if (::getpwuid_r(::geteuid(), &entry, buffer.data(), buffer.size(), &found) != 0 || !found || !found->pw_dir)
        return {};
    return found->pw_dir;
}

std::vector<std::string> process_arguments(int pid, const fs::path& proc_root) {
    std::ifstream in(proc_root / std::to_string(pid) / "cmdline", std::ios::binary);
    if (!in) return {};
    std::string text;
    std::array<char, 8192> chunk{};
    while (text.size() < kMaxCmdlineBytes) {
        in.read(chunk.data(), chunk.size());
        if (in.gcount() <= 0) break;
        text.append(chunk.data(), static_cast<std::size_t>(in.gcount()));
    }
    std::vector<std::string> arguments;
    for (std::size_t start = 0; start < text.size();) {
        const std::size_t end = std::min(text.find('\0', start), text.size());
        arguments.emplace_back(text, start, end - start);
        start = end + 1;
    }
    return arguments;
}

std::vector<fs::path> documents_in_arguments(const std::vector<std::string>& arguments, const fs::path& cwd,
                                             const fs::path& executable) {
    if (arguments.empty()) return {};
    std::set<std::string> excluded;
    if (!executable.empty()) excluded.insert(identity_of(executable));
    if (auto self = argument_path(arguments[0], cwd)) excluded.insert(identity_of(*self));
    UniquePaths documents(std::move(excluded));
    bool options_ended = false;
    bool script_pending = is_interpreter(arguments[0]);
    for (std::size_t i = 1; i < arguments.size(); ++i) {
        const std::string& arg = arguments[i];
        if (!options_ended && arg == "--") {
            options_ended = true;
            continue;
        }
        if (arg.empty() || (!options_ended && arg.size() > 1 && arg[0] == '-')) continue;
        if (std::exchange(script_pending, false)) continue;
        const auto path = argument_path(arg, cwd);
        if (path && is_readable_regular_file(*path)) documents.add(*path);
    }
    return documents.take();
}

bool looks_like_user_document(const fs::path& path, const fs::path& home) {
    if (home.empty() || !path.is_absolute()) return false;
    const fs::path relative = path.lexically_normal().lexically_relative(home.lexically_normal());
    if (relative.empty() || *relative.begin() == "..") return false;
    for (const auto& part : relative)
        if (part.string().empty() || part.string()[0] == '.') return false;
    return !is_library_or_state_file(path.filename().string());
}

std::vector<fs::path> open_documents(int pid, const ProcessDocumentOptions& options) {
    const fs::path home = options.home.empty() ? user_home() : options.home;
    if (home.empty() || pid <= 0) return {};
    UniquePaths documents;
    for (const auto& [fd, target] : descriptor_targets(options.proc_root / std::to_string(pid) / "fd"))
        if (looks_like_user_document(target, home) && is_readable_regular_file(target)) documents.add(target);
    return documents.take();
}

std::vector<fs::path> process_documents(int pid, const ProcessDocumentOptions& options) {
    if (pid <= 0) return {};
    const fs::path dir = options.proc_root / std::to_string(pid);
    if (options.same_user_only && !owned_by_us(dir)) return {};
    const auto arguments = process_arguments(pid, options.proc_root);
    UniquePaths documents;
    for (const auto& path : documents_in_arguments(arguments, read_link_or_empty(dir / "cwd"),
                                                   read_link_or_empty(dir / "exe")))
        documents.add(path);
    if (options.open_files)
        for (const auto& path : open_documents(pid, options)) documents.add(path);
    return documents.take();
}

}  // namespace umf::provider
