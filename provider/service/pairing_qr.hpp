// The pairing URL as a QR code a phone can scan off a terminal.
#pragma once

#include <string>
#include <vector>

namespace umf::provider {

// The code's modules, true for dark, with no quiet zone; error correction
// level M. Throws std::runtime_error when the text does not fit a QR code.
std::vector<std::vector<bool>> qr_modules(const std::string& text);

// The code drawn with Unicode half blocks, two module rows per line, dark
// modules as spaces on light blocks (so it reads on dark and light terminals
// alike), with a quiet zone of 2 modules.
std::string qr_text(const std::string& text);

}  // namespace umf::provider
