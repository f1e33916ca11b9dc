#include "output.hpp"

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <stdexcept>
#include <stb/stb_image_write.h>
#include <unistd.h>

namespace sonarsim {

Bytes to_bytes(const std::string& t) {
    return Bytes(t.begin(), t.end());
}

Bytes encode_png(const Image8& img) {
    Bytes out;
    auto sink = [](void* ctx, void* data, int size) {
        auto* o = static_cast<Bytes*>(ctx);
        o->insert(o->end(), static_cast<std::uint8_t*>(data), static_cast<std::uint8_t*>(data) + size);
    };
    if (!stbi_write_png_to_func(sink, &out, img.width, img.height, img.channels, img.pixels.data(),
                                img.width * img.channels))
        throw std::runtime_error("PNG encoding failed");
    return out;
}

Bytes encode_npy(const PolarImage& img) {
    std::string header = "{'descr': '<f4', 'fortran_order': False, 'shape': (" + std::to_string(img.bins) +
                         ", " + std::to_string(img.beams) + "), }";
    const size_t total = 10 + header.size() + 1;
    header.append((64 - total % 64) % 64, ' ');
    header += '\n';
    Bytes out = {0x93, 'N', 'U', 'M', 'P', 'Y', 1, 0};
    out.push_back(std::uint8_t(header.size() & 0xff));
    out.push_back(std::uint8_t(header.size() >> 8));
    out.insert(out.end(), header.begin(), header.end());
    const size_t off = out.size();
    out.resize(off + img.level_db.size() * 4);
    static_assert(sizeof(float) == 4, "float32");
    std::memcpy(out.data() + off, img.level_db.data(), img.level_db.size() * 4); // x86/ARM: little-endian
    return out;
}

void write_files_atomically(const std::vector<std::pair<std::string, Bytes>>& files) {
    std::vector<std::string> temps;
    auto cleanup = [&] {
        for (auto& t : temps) std::remove(t.c_str());
    };
    for (auto& [path, bytes] : files) {
        const std::string tmp = path + ".tmp-" + std::to_string(::getpid());
        temps.push_back(tmp);
        errno = 0;
        std::ofstream f(tmp, std::ios::binary | std::ios::trunc);
        int err = f ? 0 : errno; // the reason the open failed, before anything else can change errno
        if (f) {
            f.write(reinterpret_cast<const char*>(bytes.data()), std::streamsize(bytes.size()));
            f.close();
            if (!f) err = errno ? errno : EIO;
        }
        if (err || !f) {
            cleanup();
            throw std::runtime_error("cannot write " + path + ": " + std::strerror(err ? err : EIO));
        }
    }
    for (size_t i = 0; i < files.size(); ++i)
        if (std::rename(temps[i].c_str(), files[i].first.c_str()) != 0) {
            const int err = errno;
            cleanup();
            throw std::runtime_error("cannot rename into " + files[i].first + ": " + std::strerror(err));
        }
}

} // namespace sonarsim
