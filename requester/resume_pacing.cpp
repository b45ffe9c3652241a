#include "requester/resume_pacing.hpp"

#include <algorithm>
#include <thread>

namespace umf::requester {

void ResumePacing::wait() {
    std::this_thread::sleep_for(wait_);
    wait_ = std::min(wait_ * 2, kLongest);
}

}  // namespace umf::requester
