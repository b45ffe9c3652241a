// A preset's settings on the command line, over the chosen preset:
// `umf-provider --preset subtle --opacity-max 0.25 --period 3`.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include "shared/cli/args.hpp"
#include "shared/overlay/preset.hpp"

namespace umf::provider {

// The preset --preset names (`kiosk` for a board, else `balanced`): a
// built-in one, or one of `config_dir`/presets.json, which wins over a
// built-in of the same name. UsageError listing the names when none is called so.
overlay::Preset preset_option(const cli::Args& args, const std::filesystem::path& config_dir, bool board);

// --opacity-min, --opacity-max, --period, --waveform, --module-px, --blur,
// --region, --focus-radius, --activation, --fade, --palette.
const std::vector<std::string>& preset_setting_options();

// The preset with the settings given in `args` applied; UsageError naming
// the option when a value is malformed or the result is not a valid preset.
overlay::Preset apply_preset_options(overlay::Preset preset, const cli::Args& args);

}  // namespace umf::provider
