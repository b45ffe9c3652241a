// The documents a process likely shows, from what Linux tells about it in
// /proc: the files its command line names and, optionally, the user's files
// it holds open. Every function takes the /proc root so tests can fake one.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

namespace umf::provider {

struct ProcessDocumentOptions {
    std::filesystem::path proc_root = "/proc";
    // Open files count only under this directory; empty: the user's home.
    std::filesystem::path home;
    bool open_files = true;
    // Only processes of the user the provider runs as: a window's PID comes
    // from the window itself, and a PID from another user (or another PID
    // namespace) names someone else's process.
    bool same_user_only = true;
};

// $HOME, else the password database's; empty when neither is known.
std::filesystem::path user_home();

// The arguments of /proc/PID/cmdline; empty when the process is gone or its
// command line cannot be read.
std::vector<std::string> process_arguments(int pid, const std::filesystem::path& proc_root);

// Existing, readable regular files among the arguments, in order, without
// duplicates: relative ones resolved against `cwd` (skipped when cwd is
// empty), file: URLs decoded. Skipped: argv[0] and `executable`, options
// (arguments from '-' up to a "--"), and an interpreter's script ("python3
// tool.py report.pdf" shows report.pdf).
std::vector<std::filesystem::path> documents_in_arguments(const std::vector<std::string>& arguments,
                                                          const std::filesystem::path& cwd,
                                                          const std::filesystem::path& executable = {});

// Whether an open file looks like something the user works on: under
// `home`, in no hidden directory (so not ~/.cache, ~/.config, browser
// profiles), not a library, lock, log, journal or database file.
bool looks_like_user_document(const std::filesystem::path& path, const std::filesystem::path& home);

// Files open per /proc/PID/fd that look like user documents (see above) and
// are existing, readable regular files, in descriptor order.
std::vector<std::filesystem::path> open_documents(int pid, const ProcessDocumentOptions& options);

// documents_in_arguments, then open_documents when asked, without
// duplicates. Empty for a gone, foreign (same_user_only) or unreadable
// process; never throws for the process's state.
std::vector<std::filesystem::path> process_documents(int pid, const ProcessDocumentOptions& options = {});

}  // namespace umf::provider
