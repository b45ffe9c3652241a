// The name people know this screen by: the machine's host name, as the
// welcome gives it to requesters and a printed field carries it.
#pragma once

#include <string>

namespace umf::provider {

// The host name, or "umf-provider" when the system gives none.
std::string screen_name();

}  // namespace umf::provider
