// Whole-file reads: one helper for every file the program reads in one piece (scene files, meshes,
// trajectories, viewer scripts, dataset files), with the project's error style.
#pragma once
#include <cstdint>
#include <limits>
#include <optional>
#include <string>

namespace sonarsim {

/// Any size (read_file_bytes' default limit).
inline constexpr std::uintmax_t kAnyFileSize = std::numeric_limits<std::uintmax_t>::max();

/// How a failed read is reported: InputError(file, key, prefix + reason).
struct FileReadReport {
    std::string file;        ///< the InputError's file (empty: the path read)
    std::string key;         ///< its key path (may be empty)
    std::string prefix;      ///< put before the reason, e.g. "mesh \"m.obj\": "
    std::string cannot_open; ///< replaces "cannot be read: <system reason>" when not empty
};

/// The bytes of the file at `path` (fopen/fread: rdbuf() and istreambuf_iterator take ~10x longer on large
/// files; a file that grows while it is read is read to its end). Throws InputError(report.file or path,
/// report.key, report.prefix + reason), where the reason is "cannot be read: <system reason>" (or
/// report.cannot_open) when it cannot be opened, "read error", or "file is more than N bytes" beyond
/// `max_bytes` (nothing beyond max_bytes + 1 bytes is ever held).
std::string read_file_bytes(const std::string& path, std::uintmax_t max_bytes = kAnyFileSize,
                            const FileReadReport& report = {});

/// The bytes of the file at `path`, or nothing when it cannot be opened, read or is larger than
/// `max_bytes`.
std::optional<std::string> try_read_file_bytes(const std::string& path,
                                               std::uintmax_t max_bytes = kAnyFileSize);

} // namespace sonarsim
