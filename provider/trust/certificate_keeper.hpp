// Keeps the served certificate fitting the machine while the provider runs:
// it looks at the machine's names and addresses every few seconds and,
// when one is new (another network, a DHCP lease) or the certificate nears
// its end, issues it again from the screen's root and hands it over. Paired
// requesters pin the root, so they keep connecting without a new pairing.
#pragma once

#include <chrono>
#include <condition_variable>
#include <filesystem>
#include <functional>
#include <mutex>
#include <string>
#include <thread>

#include "provider/trust/serving_names.hpp"
#include "provider/trust/tls_identity.hpp"

namespace umf::provider {

class CertificateKeeper {
public:
    struct Settings {
        std::filesystem::path config_dir;
        std::chrono::milliseconds interval{2000};
        std::function<ServingNames()> names = current_serving_names;
        // Called on the keeper's thread with the new identity and why it was issued.
        std::function<void(const TlsIdentity&, const std::string& why)> issued;
        // Called on the keeper's thread when issuing failed (the old one serves on).
        std::function<void(const std::string& error)> failed;
    };

    // Starts looking at once; `served` is what the provider serves now.
    CertificateKeeper(Settings settings, ServingNames served);
    ~CertificateKeeper();  // stops and joins
    CertificateKeeper(const CertificateKeeper&) = delete;
    CertificateKeeper& operator=(const CertificateKeeper&) = delete;

private:
    void run();
    void check(std::chrono::system_clock::time_point now);

    Settings settings_;
    ServingNames served_;
    std::chrono::system_clock::time_point next_expiry_check_;
    std::string last_failure_;
    std::mutex mutex_;
    std::condition_variable wake_;
    bool stopping_ = false;
    std::thread thread_;
};

}  // namespace umf::provider
