// The pairing QR code as the desktop shows it.
#if defined(UMF_PROVIDER_TESTS) && defined(UMF_PROVIDER_TUNING)

#include <gtest/gtest.h>

#include "provider/service/pairing_qr.hpp"
#include "provider/tuning/desktop_controls.hpp"

namespace {

using namespace umf::provider;

TEST(DesktopControls, PairingQrImageHasTheCodeWithAQuietZone) {
    const std::string url = "https://192.168.1.20:47470/#t=2P8PS1OkkJ6N7t191DIZPnPoi7GaecUS&fp=" + std::string(64, 'a');
    const auto modules = qr_modules(url);
    const int n = static_cast<int>(modules.size());
    const QImage image = pairing_qr_image(url, 5);
    EXPECT_EQ(image.width(), (n + 8) * 5);
    EXPECT_EQ(image.height(), image.width());
    EXPECT_EQ(image.pixel(2, 2), qRgb(255, 255, 255)) << "quiet zone";
    EXPECT_EQ(image.pixel(4 * 5 + 2, 4 * 5 + 2), qRgb(0, 0, 0)) << "finder pattern corner";
    for (int y = 0; y < n; ++y)
        for (int x = 0; x < n; ++x)
            ASSERT_EQ(image.pixel((x + 4) * 5 + 2, (y + 4) * 5 + 2) == qRgb(0, 0, 0), modules[y][x]) << x << "," << y;
}

}  // namespace

#endif
