#include "shared/io/atomic_file.hpp"

#include <cstdio>
#include <fstream>

namespace umf {

void write_file_atomically(const std::string& path, const std::string& bytes) {
    const std::string tmp = path + ".tmp";
    {
        std::ofstream out(tmp, std::ios::binary | std::ios::trunc);
        if (!out) throw FileWriteError(path + ": cannot write (" + tmp + " cannot be created)");
        out.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
        out.flush();
        if (!out) {
            std::remove(tmp.c_str());
            throw FileWriteError(path + ": writing failed");
        }
    }
    if (std::rename(tmp.c_str(), path.c_str()) != 0) {
        std::remove(tmp.c_str());
        throw FileWriteError(path + ": cannot replace the file");
    }
}

}  // namespace umf
