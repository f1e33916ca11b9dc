#include "core/base/file_io.hpp"

#include "core/base/errors.hpp"

#include <algorithm>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <memory>

namespace sonarsim {
namespace {

/// Why a read failed, or nothing.
enum class ReadFailure { None, Open, Read, TooLarge };

ReadFailure read_into(const std::string& path, std::uintmax_t max_bytes, std::string& bytes, int& error) {
    std::unique_ptr<std::FILE, int (*)(std::FILE*)> f(std::fopen(path.c_str(), "rb"), &std::fclose);
    if (!f) {
        error = errno;
        return ReadFailure::Open;
    }
    // One read of the size the file has now, then whatever it grew by since.
    std::error_code ec;
    const std::uintmax_t size_now = std::filesystem::file_size(path, ec);
    const std::uintmax_t hint =
        ec ? 0 : std::min(size_now, max_bytes == kAnyFileSize ? size_now : max_bytes + 1);
    bytes.assign(size_t(hint), '\0');
    size_t got = std::fread(bytes.data(), 1, bytes.size(), f.get());
    bytes.resize(got);
    char chunk[65536];
    while (bytes.size() <= max_bytes && (got = std::fread(chunk, 1, sizeof chunk, f.get())) > 0)
        bytes.append(chunk, got);
    if (std::ferror(f.get())) return ReadFailure::Read;
    if (bytes.size() > max_bytes) return ReadFailure::TooLarge;
    return ReadFailure::None;
}

} // namespace

std::string read_file_bytes(const std::string& path, std::uintmax_t max_bytes, const FileReadReport& report) {
    std::string bytes;
    int error = 0;
    const ReadFailure failure = read_into(path, max_bytes, bytes, error);
    if (failure == ReadFailure::None) return bytes;
    std::string reason;
    if (failure == ReadFailure::Open)
        reason = report.cannot_open.empty() ? "cannot be read: " + std::string(std::strerror(error))
                                            : report.cannot_open;
    else if (failure == ReadFailure::Read)
        reason = "read error";
    else
        reason = "file is more than " + std::to_string(max_bytes) + " bytes";
    throw InputError(report.file.empty() ? path : report.file, report.key, report.prefix + reason);
}

std::optional<std::string> try_read_file_bytes(const std::string& path, std::uintmax_t max_bytes) {
    std::string bytes;
    int error = 0;
    if (read_into(path, max_bytes, bytes, error) != ReadFailure::None) return std::nullopt;
    return bytes;
}

} // namespace sonarsim
