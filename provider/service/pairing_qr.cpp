#include "provider/service/pairing_qr.hpp"

#include <qrencode.h>

#include <memory>
#include <stdexcept>

namespace umf::provider {

std::vector<std::vector<bool>> qr_modules(const std::string& text) {
    std::unique_ptr<QRcode, decltype(&QRcode_free)> code(QRcode_encodeString(text.c_str(), 0, QR_ECLEVEL_M, QR_MODE_8, 1),
                                                         &QRcode_free);
    if (!code) throw std::runtime_error("the text does not fit a QR code");
    const int n = code->width;
    std::vector<std::vector<bool>> modules(n, std::vector<bool>(n));
    for (int y = 0; y < n; ++y)
        for (int x = 0; x < n; ++x) modules[y][x] = (code->data[y * n + x] & 1) != 0;
    return modules;
}

std::string qr_text(const std::string& text) {
    const auto modules = qr_modules(text);
    constexpr int kQuiet = 2;
    const int n = static_cast<int>(modules.size());
    const int size = n + 2 * kQuiet;
    auto dark = [&](int y, int x) {
        y -= kQuiet;
        x -= kQuiet;
        return y >= 0 && y < n && x >= 0 && x < n && modules[y][x];
    };
    std::string out;
    for (int y = 0; y < size; y += 2) {
        for (int x = 0; x < size; ++x) {
            const bool top = !dark(y, x), bottom = y + 1 < size ? !dark(y + 1, x) : false;  // light halves
            out += top && bottom ? "\u2588" : top ? "\u2580" : bottom ? "\u2584" : " ";
        }
        out += '\n';
    }
    return out;
}

}  // namespace umf::provider
