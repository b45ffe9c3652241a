// Where accepted files land by default (`serve --put-dir DIR` overrides it):
// the user's download folder as the XDG user directories name it
// (XDG_DOWNLOAD_DIR in $XDG_CONFIG_HOME/user-dirs.dirs, which is what
// `xdg-user-dir DOWNLOAD` reads), else ~/Downloads.
#pragma once

#include <filesystem>
#include <optional>
#include <string>

namespace umf::provider {

// XDG_DOWNLOAD_DIR from the text of a user-dirs.dirs file, "$HOME" expanded
// to `home`; nullopt when the file does not set it to an absolute path
// ("$HOME/..." or "/..."), or sets it to the home folder itself (which the
// XDG spec uses to switch a directory off).
std::optional<std::filesystem::path> download_dir_from_user_dirs(const std::string& text,
                                                                 const std::filesystem::path& home);

// The default put folder, from the environment ($HOME, $XDG_CONFIG_HOME) and
// the user-dirs.dirs file; not created here.
std::filesystem::path default_put_folder();

}  // namespace umf::provider
