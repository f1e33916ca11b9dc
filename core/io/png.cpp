// PNG encoding with zlib (see png.hpp). The container (PNG specification, ISO/IEC 15948): the signature,
// then chunks of length, type, data and the CRC-32 of type and data: IHDR, one IDAT, IEND.
#include "core/io/png.hpp"

#include <cstring>
#include <stdexcept>
#include <string>
#include <zlib.h>

namespace sonarsim {
namespace {

void append_be32(Bytes& out, std::uint32_t v) {
    for (int s = 24; s >= 0; s -= 8) out.push_back(std::uint8_t(v >> s));
}

void append_chunk(Bytes& out, const char (&type)[5], const std::uint8_t* data, size_t n) {
    append_be32(out, std::uint32_t(n));
    const size_t at = out.size();
    out.insert(out.end(), type, type + 4);
    if (n) out.insert(out.end(), data, data + n);
    uLong crc = ::crc32(0, out.data() + at, 4);
    if (n) crc = ::crc32_z(crc, data, n); // zlib's crc32 of a null buffer is its initial value, 0
    append_be32(out, std::uint32_t(crc));
}

/// The scanlines as PNG filters them: a filter byte (1, Sub) before each row, each byte less the byte one
/// pixel to its left (modulo 256; the first pixel as it is).
std::vector<std::uint8_t> sub_filtered(const Image8& img) {
    const size_t c = size_t(img.channels), stride = size_t(img.width) * c;
    std::vector<std::uint8_t> raw((stride + 1) * size_t(img.height));
    for (size_t y = 0; y < size_t(img.height); ++y) {
        const std::uint8_t* row = img.pixels.data() + y * stride;
        std::uint8_t* out = raw.data() + y * (stride + 1);
        out[0] = 1;
        std::memcpy(out + 1, row, c);
        for (size_t i = c; i < stride; ++i) out[1 + i] = std::uint8_t(row[i] - row[i - c]);
    }
    return raw;
}

} // namespace

Bytes encode_png(const Image8& img) {
    if (img.width <= 0 || img.height <= 0)
        throw std::invalid_argument("PNG encoding: the image is empty (" + std::to_string(img.width) + " x " +
                                    std::to_string(img.height) + ")");
    if (img.channels != 1 && img.channels != 3 && img.channels != 4)
        throw std::invalid_argument("PNG encoding: " + std::to_string(img.channels) +
                                    " channels (allowed: 1, 3 or 4)");
    if (img.pixels.size() != size_t(img.width) * size_t(img.height) * size_t(img.channels))
        throw std::invalid_argument("PNG encoding: " + std::to_string(img.pixels.size()) + " bytes for " +
                                    std::to_string(img.width) + " x " + std::to_string(img.height) + " x " +
                                    std::to_string(img.channels));
    const std::vector<std::uint8_t> raw = sub_filtered(img);
    uLongf packed_n = compressBound(uLong(raw.size()));
    std::vector<std::uint8_t> packed(packed_n);
    if (compress2(packed.data(), &packed_n, raw.data(), uLong(raw.size()), kPngDeflateLevel) != Z_OK)
        throw std::runtime_error("PNG encoding: zlib could not compress " + std::to_string(raw.size()) +
                                 " bytes");

    Bytes out = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n'};
    out.reserve(out.size() + packed_n + 64);
    Bytes ihdr;
    append_be32(ihdr, std::uint32_t(img.width));
    append_be32(ihdr, std::uint32_t(img.height));
    const std::uint8_t colour_type = img.channels == 1 ? 0 : img.channels == 3 ? 2 : 6;
    // bit depth 8, colour type, deflate, adaptive filtering (per-row filter bytes), no interlace
    ihdr.insert(ihdr.end(), {8, colour_type, 0, 0, 0});
    append_chunk(out, "IHDR", ihdr.data(), ihdr.size());
    append_chunk(out, "IDAT", packed.data(), packed_n);
    append_chunk(out, "IEND", nullptr, 0);
    return out;
}

} // namespace sonarsim
