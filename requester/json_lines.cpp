#include "requester/json_lines.hpp"

#include <cerrno>
#include <cstring>
#include <string>

#include "requester/cli.hpp"

namespace umf::requester {

void write_line(std::FILE* out, const Json& j) {
    const std::string line = j.dump(-1, ' ', false, Json::error_handler_t::replace) + "\n";
    if (std::fwrite(line.data(), 1, line.size(), out) != line.size() || std::fflush(out) != 0)
        throw InputError(std::string("cannot write the output: ") + std::strerror(errno));
}

}  // namespace umf::requester
