#include "provider/trust/certificate_keeper.hpp"

#include "provider/trust/tls_identity_store.hpp"

namespace umf::provider {

namespace {

// The certificate's end is far (kServingRenewBefore ahead): looking once an
// hour is plenty, and costs a file read.
constexpr auto kExpiryCheckInterval = std::chrono::hours(1);

}  // namespace

CertificateKeeper::CertificateKeeper(Settings settings, ServingNames served)
    : settings_(std::move(settings)),
      served_(std::move(served)),
      next_expiry_check_(std::chrono::system_clock::now() + kExpiryCheckInterval),
      thread_([this] { run(); }) {}

CertificateKeeper::~CertificateKeeper() {
    {
        std::lock_guard lock(mutex_);
        stopping_ = true;
    }
    wake_.notify_all();
    thread_.join();
}

void CertificateKeeper::run() {
    std::unique_lock lock(mutex_);
    while (!wake_.wait_for(lock, settings_.interval, [this] { return stopping_; })) {
        lock.unlock();
        check(std::chrono::system_clock::now());
        lock.lock();
    }
}

void CertificateKeeper::check(std::chrono::system_clock::time_point now) {
    const ServingNames names = settings_.names();
    // Addresses that went away stay in the certificate until it is issued
    // again for another reason: naming them does no harm.
    if (names == served_ && now < next_expiry_check_) return;
    try {
        const LoadedIdentity loaded = load_or_issue_tls_identity(settings_.config_dir, names, now);
        served_ = names;
        next_expiry_check_ = now + kExpiryCheckInterval;
        last_failure_.clear();
        if (!loaded.issued_because.empty() && settings_.issued) settings_.issued(loaded.identity, loaded.issued_because);
    } catch (const std::exception& e) {
        // Said once per kind of failure, not every interval.
        if (e.what() != last_failure_ && settings_.failed) settings_.failed(e.what());
        last_failure_ = e.what();
    }
}

}  // namespace umf::provider
