#include "core/io/output.hpp"

#include "core/sensor/sensor.hpp"

#include "core/pipeline/simulator.hpp"

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <mutex>
#include <random>
#include <stdexcept>
#include <unistd.h>

namespace sonarsim {

Bytes to_bytes(const std::string& t) {
    return Bytes(t.begin(), t.end());
}

Bytes encode_npy_array(const void* data, std::size_t bytes, const std::string& descr,
                       const std::vector<std::size_t>& shape) {
    std::string dims;
    for (std::size_t d : shape) dims += (dims.empty() ? "" : ", ") + std::to_string(d);
    if (shape.size() == 1) dims += ","; // a one-axis shape is written (3,)
    std::string header = "{'descr': '" + descr + "', 'fortran_order': False, 'shape': (" + dims + "), }";
    const size_t total = 10 + header.size() + 1;
    header.append((64 - total % 64) % 64, ' ');
    header += '\n';
    Bytes out = {0x93, 'N', 'U', 'M', 'P', 'Y', 1, 0};
    out.push_back(std::uint8_t(header.size() & 0xff));
    out.push_back(std::uint8_t(header.size() >> 8));
    out.insert(out.end(), header.begin(), header.end());
    const size_t off = out.size();
    out.resize(off + bytes);
    if (bytes) std::memcpy(out.data() + off, data, bytes); // x86/ARM: little-endian
    return out;
}

Bytes encode_npy(const PolarImage& img) {
    static_assert(sizeof(float) == 4, "float32");
    return encode_npy_array(img.level_db.data(), img.level_db.size() * 4, "<f4",
                            {std::size_t(img.bins), std::size_t(img.beams)});
}

namespace {

/// Throws unless `path` can be replaced by a rename: its directory exists and is writable and it is not
/// itself a directory.
void check_target(const std::string& path) {
    namespace fs = std::filesystem;
    const fs::path p(path);
    const fs::path dir = p.parent_path().empty() ? fs::path(".") : p.parent_path();
    std::error_code ec;
    if (!fs::is_directory(dir, ec))
        throw std::runtime_error("cannot write " + path + ": directory " + dir.string() + " does not exist");
    if (::access(dir.c_str(), W_OK | X_OK) != 0)
        throw std::runtime_error("cannot write " + path + ": directory " + dir.string() +
                                 " is not writable: " + std::strerror(errno));
    if (fs::is_directory(p, ec)) throw std::runtime_error("cannot write " + path + ": it is a directory");
}

/// A random hexadecimal tag for temporary file names.
std::string temp_tag() {
    static std::mt19937_64 rng{std::random_device{}()};
    static std::mutex m;
    std::lock_guard<std::mutex> lock(m);
    char b[20];
    std::snprintf(b, sizeof b, "%012llx", static_cast<unsigned long long>(rng() >> 16));
    return b;
}

Bytes sector_png(const SceneDesc&, const Frame& f, const json&) {
    return encode_png(f.sector());
}
Bytes polar_png(const SceneDesc&, const Frame& f, const json&) {
    return encode_png(polar_gray_image(f.polar(), f.display));
}
Bytes level_npy(const SceneDesc&, const Frame& f, const json&) {
    return encode_npy(f.polar());
}
Bytes ideal_npy(const SceneDesc&, const Frame& f, const json&) {
    return encode_npy(f.ideal());
}
bool sensor_applied(const SceneDesc& s) {
    return !sensor_is_ideal(s);
}
/// The metadata with `more`'s keys added (ground_truth_maps_metadata: what only some writers add).
Bytes metadata_json(const SceneDesc& s, const Frame& f, const json& more) {
    json j = frame_metadata(s, f);
    if (more.is_object()) j.update(more);
    return to_bytes(j.dump(2) + "\n");
}

} // namespace

const std::vector<RenderOutput>& render_outputs() {
    static const std::vector<RenderOutput> table = {
        {".png", "sector image", sector_png},
        {"_polar.png", "polar image, gray", polar_png},
        {".npy", "the image level dB, float32 (range bins, beams): L_EN through the sensor", level_npy,
         nullptr, "the image level dB, float32 (range bins, beams): L_EN (the ideal sensor)"},
        {".json", "metadata", metadata_json},
        {"_ideal.npy", "L_EN dB before the sensor stage (only when the sensor is not ideal)", ideal_npy,
         sensor_applied}};
    return table;
}

const char* RenderOutput::what_for(const SceneDesc* scene) const {
    return scene && what_ideal && sensor_is_ideal(*scene) ? what_ideal : what;
}

std::vector<std::string> render_output_paths(const std::string& prefix, const SceneDesc& scene) {
    std::vector<std::string> paths;
    for (auto& o : render_outputs())
        if (o.written_for(scene)) paths.push_back(prefix + o.suffix);
    return paths;
}

std::string render_outputs_text(const std::string& prefix, const SceneDesc* scene) {
    std::string text;
    for (auto& o : render_outputs())
        if (!scene || o.written_for(*scene))
            text += (text.empty() ? "" : ", ") + prefix + o.suffix + " (" + o.what_for(scene) + ")";
    return text;
}

void write_render_files(const std::string& prefix, const SceneDesc& scene, const Frame& frame,
                        std::vector<std::pair<std::string, Bytes>> extra, const json& metadata_more) {
    std::vector<std::pair<std::string, Bytes>> files;
    for (auto& o : render_outputs())
        if (o.written_for(scene))
            files.emplace_back(prefix + o.suffix, o.encode(scene, frame, metadata_more));
    for (auto& e : extra) files.push_back(std::move(e));
    write_files_atomically(files);
}

AtomicFile::AtomicFile(std::string path) : path_(std::move(path)) {
    check_target(path_);
    tmp_ = path_ + ".tmp-" + std::to_string(::getpid()) + "-" + temp_tag();
    f_ = std::fopen(tmp_.c_str(), "wb");
    if (!f_) throw std::runtime_error("cannot write " + path_ + ": " + std::strerror(errno));
}

AtomicFile::~AtomicFile() {
    if (f_) {
        std::fclose(f_);
        std::remove(tmp_.c_str());
    }
}

void AtomicFile::write(const void* data, size_t bytes) {
    if (bytes && std::fwrite(data, 1, bytes, f_) != bytes)
        throw std::runtime_error("cannot write " + path_ + ": " + std::strerror(errno ? errno : EIO));
    size_ += bytes;
}

void AtomicFile::commit() {
    const bool ok = std::fflush(f_) == 0;
    const int err = errno;
    std::fclose(f_);
    f_ = nullptr;
    if (!ok || std::rename(tmp_.c_str(), path_.c_str()) != 0) {
        const int e = ok ? errno : err;
        std::remove(tmp_.c_str());
        throw std::runtime_error("cannot write " + path_ + ": " + std::strerror(e));
    }
}

namespace {

/// The header of an .npy v1.0 float32 C-order file and where its data start; throws otherwise.
std::string npy_f32_header(const Bytes& b, const std::string& path, size_t& data_at) {
    auto bad = [&](const std::string& why) {
        return std::runtime_error(path + ": not a float32 .npy image: " + why);
    };
    if (b.size() < 10 || std::memcmp(b.data(), "\x93NUMPY\x01\x00", 8) != 0) throw bad("no .npy v1.0 magic");
    const size_t hlen = size_t(b[8]) | size_t(b[9]) << 8;
    if (10 + hlen > b.size()) throw bad("truncated header");
    const std::string header(b.begin() + 10, b.begin() + long(10 + hlen));
    if (header.find("'descr': '<f4'") == std::string::npos ||
        header.find("'fortran_order': False") == std::string::npos)
        throw bad("expected '<f4' in C order");
    data_at = 10 + hlen;
    return header;
}

} // namespace

PolarImage decode_npy(const Bytes& b, const std::string& path) {
    size_t at = 0;
    const std::string header = npy_f32_header(b, path, at);
    PolarImage img;
    const size_t shape = header.find("'shape': (");
    if (shape == std::string::npos ||
        std::sscanf(header.c_str() + shape, "'shape': (%d, %d)", &img.bins, &img.beams) != 2 ||
        img.bins < 1 || img.beams < 1)
        throw std::runtime_error(path + ": not a float32 .npy image: expected a 2-D shape");
    img.level_db = decode_npy_values(b, path, size_t(img.bins) * size_t(img.beams));
    return img;
}

std::vector<float> decode_npy_values(const Bytes& b, const std::string& path, std::size_t count) {
    size_t at = 0;
    npy_f32_header(b, path, at);
    if (b.size() != at + 4 * count)
        throw std::runtime_error(path + ": not a float32 .npy array of " + std::to_string(count) +
                                 " values: its size differs");
    std::vector<float> v(count);
    std::memcpy(v.data(), b.data() + at, 4 * count);
    return v;
}

void write_files_atomically(const std::vector<std::pair<std::string, Bytes>>& files) {
    for (auto& f : files) check_target(f.first);
    std::vector<std::string> temps;
    auto cleanup = [&] {
        for (auto& t : temps) std::remove(t.c_str());
    };
    for (auto& [path, bytes] : files) {
        // Unique per process and call: concurrent writers (batch shards on several hosts) never share one.
        const std::string tmp = path + ".tmp-" + std::to_string(::getpid()) + "-" + temp_tag();
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
    for (auto& f : files) { // once more: a target may have turned into a directory meanwhile
        try {
            check_target(f.first);
        } catch (...) {
            cleanup();
            throw;
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
