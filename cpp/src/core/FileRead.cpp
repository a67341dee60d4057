#include "core/FileRead.h"

#include <cerrno>
#include <cstring>
#include <filesystem>
#include <fstream>

#include <weft/Error.h>

namespace weft {

namespace fs = std::filesystem;

uint64_t checkInputFile(const std::string& path, const std::string& what, uint64_t maxBytes) {
    const std::string name = what + " '" + path + "'";
    if (path.empty()) throw IoError("cannot open " + what + ": the path is empty");
    std::error_code ec;
    const fs::file_status st = fs::status(path, ec);
    if (ec || !fs::exists(st))
        throw IoError("cannot open " + name + ": " +
                      (ec ? ec.message() : std::string("no such file")));
    if (fs::is_directory(st)) throw IoError("cannot open " + name + ": it is a directory");
    if (!fs::is_regular_file(st))
        throw IoError("cannot open " + name + ": not a regular file (a device, pipe or socket)");
    const uintmax_t size = fs::file_size(path, ec);
    if (ec) throw IoError("cannot read " + name + ": " + ec.message());
    if (size > maxBytes)
        throw IoError(name + " has " + std::to_string(size) + " bytes, more than the " +
                      std::to_string(maxBytes) + " a " + what + " may have");
    return uint64_t(size);
}

std::vector<uint8_t> readInputFile(const std::string& path, const std::string& what,
                                   uint64_t maxBytes) {
    const uint64_t size = checkInputFile(path, what, maxBytes);
    std::ifstream in(path, std::ios::binary);
    if (!in) throw IoError("cannot open " + what + " '" + path + "': " + std::strerror(errno));
    std::vector<uint8_t> bytes(static_cast<size_t>(size));
    if (size > 0 && !in.read(reinterpret_cast<char*>(bytes.data()), std::streamsize(size)))
        throw IoError("cannot read " + what + " '" + path + "': it ended after " +
                      std::to_string(in.gcount()) + " of " + std::to_string(size) + " bytes");
    return bytes;
}

} // namespace weft
