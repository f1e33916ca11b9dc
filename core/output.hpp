// Files a render writes: PNG, .npy (float32 L_EN), metadata JSON; all written atomically (temp + rename).
#pragma once
#include "image.hpp"
#include "params.hpp"
#include "shade.hpp"

#include <cstdint>
#include <string>
#include <utility>
#include <vector>

namespace sonarsim {

using Bytes = std::vector<std::uint8_t>;

Bytes encode_png(const Image8& image);
/// NumPy .npy v1.0, little-endian float32, C order, shape (bins, beams).
Bytes encode_npy(const PolarImage& image);

/// Writes every (path, bytes) pair to a temporary file beside its target, then renames them all.
/// On any failure the temporaries are removed and no target is created or truncated; throws
/// std::runtime_error.
void write_files_atomically(const std::vector<std::pair<std::string, Bytes>>& files);

Bytes to_bytes(const std::string& text);

} // namespace sonarsim
