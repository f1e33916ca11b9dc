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
/// pixel (`c` bytes) to its left (modulo 256; the first pixel as it is).
std::vector<std::uint8_t> sub_filtered(const std::uint8_t* pixels, int width, int height, size_t c) {
    const size_t stride = size_t(width) * c;
    std::vector<std::uint8_t> raw((stride + 1) * size_t(height));
    for (size_t y = 0; y < size_t(height); ++y) {
        const std::uint8_t* row = pixels + y * stride;
        std::uint8_t* out = raw.data() + y * (stride + 1);
        out[0] = 1;
        std::memcpy(out + 1, row, c);
        for (size_t i = c; i < stride; ++i) out[1 + i] = std::uint8_t(row[i] - row[i - c]);
    }
    return raw;
}

/// The PNG of filtered scanlines `raw`: IHDR (bit depth, colour type), tEXt chunks, one IDAT, IEND.
Bytes assemble(int width, int height, std::uint8_t bit_depth, std::uint8_t colour_type,
               const std::vector<std::uint8_t>& raw,
               const std::vector<std::pair<std::string, std::string>>& text) {
    uLongf packed_n = compressBound(uLong(raw.size()));
    std::vector<std::uint8_t> packed(packed_n);
    if (compress2(packed.data(), &packed_n, raw.data(), uLong(raw.size()), kPngDeflateLevel) != Z_OK)
        throw std::runtime_error("PNG encoding: zlib could not compress " + std::to_string(raw.size()) +
                                 " bytes");
    Bytes out = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n'};
    out.reserve(out.size() + packed_n + 64);
    Bytes ihdr;
    append_be32(ihdr, std::uint32_t(width));
    append_be32(ihdr, std::uint32_t(height));
    // bit depth, colour type, deflate, adaptive filtering (per-row filter bytes), no interlace
    ihdr.insert(ihdr.end(), {bit_depth, colour_type, 0, 0, 0});
    append_chunk(out, "IHDR", ihdr.data(), ihdr.size());
    for (const auto& [keyword, value] : text) { // keyword, a NUL, the text (Latin-1)
        Bytes t(keyword.begin(), keyword.end());
        t.push_back(0);
        t.insert(t.end(), value.begin(), value.end());
        append_chunk(out, "tEXt", t.data(), t.size());
    }
    append_chunk(out, "IDAT", packed.data(), packed_n);
    append_chunk(out, "IEND", nullptr, 0);
    return out;
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
    const std::uint8_t colour_type = img.channels == 1 ? 0 : img.channels == 3 ? 2 : 6;
    return assemble(img.width, img.height, 8, colour_type,
                    sub_filtered(img.pixels.data(), img.width, img.height, size_t(img.channels)), {});
}

Bytes encode_png_gray16(int width, int height, const std::vector<std::uint16_t>& values,
                        const std::vector<std::pair<std::string, std::string>>& text) {
    if (width <= 0 || height <= 0)
        throw std::invalid_argument("PNG encoding: the image is empty (" + std::to_string(width) + " x " +
                                    std::to_string(height) + ")");
    if (values.size() != size_t(width) * size_t(height))
        throw std::invalid_argument("PNG encoding: " + std::to_string(values.size()) + " values for " +
                                    std::to_string(width) + " x " + std::to_string(height));
    // tEXt (PNG specification 11.3.4.3): a keyword of 1-79 printable Latin-1 characters, no leading, trailing
    // or double space; text of printable Latin-1 and newlines.
    auto printable = [](unsigned char c) { return (c >= 32 && c <= 126) || c >= 161; };
    for (const auto& [keyword, value] : text) {
        bool ok = !keyword.empty() && keyword.size() <= 79 && keyword.front() != ' ' &&
                  keyword.back() != ' ' && keyword.find("  ") == std::string::npos;
        for (unsigned char c : keyword) ok = ok && printable(c);
        for (unsigned char c : value) ok = ok && (printable(c) || c == '\n');
        if (!ok)
            throw std::invalid_argument("PNG encoding: tEXt keyword '" + keyword +
                                        "' or its text is not what PNG allows (printable Latin-1; a keyword "
                                        "of 1-79 characters, no leading, trailing or double space)");
    }
    std::vector<std::uint8_t> be(values.size() * 2); // PNG samples are big-endian
    for (size_t i = 0; i < values.size(); ++i)
        be[2 * i] = std::uint8_t(values[i] >> 8), be[2 * i + 1] = std::uint8_t(values[i]);
    return assemble(width, height, 16, 0, sub_filtered(be.data(), width, height, 2), text);
}

} // namespace sonarsim
