#include "core/io/xtf_read.hpp"

#include "core/base/errors.hpp"

#include <algorithm>
#include <cstring>

namespace sonarsim {
namespace {

/// Little-endian fields of a byte buffer, bounds-checked against the whole file.
class Reader {
  public:
    Reader(const std::vector<std::uint8_t>& b, std::string path) : b_(b), path_(std::move(path)) {}
    template <class T> T at(size_t offset, const char* field) const {
        if (offset + sizeof(T) > b_.size()) throw InputError(path_, field, "the file ends inside this field");
        T v;
        std::memcpy(&v, b_.data() + offset, sizeof v);
        return v;
    }
    std::string text(size_t offset, size_t width, const char* field) const {
        if (offset + width > b_.size()) throw InputError(path_, field, "the file ends inside this field");
        const char* p = reinterpret_cast<const char*>(b_.data() + offset);
        return std::string(p, strnlen(p, width));
    }
    size_t size() const { return b_.size(); }
    const std::string& path() const { return path_; }
    const std::uint8_t* data(size_t offset) const { return b_.data() + offset; }

  private:
    const std::vector<std::uint8_t>& b_;
    std::string path_;
};

XtfPing read_ping(const Reader& r, size_t at, const XtfFile& file) {
    XtfPing p;
    p.year = r.at<std::uint16_t>(at + 14, "Year");
    p.month = r.at<std::uint8_t>(at + 16, "Month");
    p.day = r.at<std::uint8_t>(at + 17, "Day");
    p.hour = r.at<std::uint8_t>(at + 18, "Hour");
    p.minute = r.at<std::uint8_t>(at + 19, "Minute");
    p.second = r.at<std::uint8_t>(at + 20, "Second");
    p.hundredths = r.at<std::uint8_t>(at + 21, "HSeconds");
    p.julian_day = r.at<std::uint16_t>(at + 22, "JulianDay");
    p.ping_number = r.at<std::uint32_t>(at + 28, "PingNumber");
    p.sound_velocity = r.at<float>(at + 32, "SoundVelocity");
    p.computed_sound_velocity = r.at<float>(at + 72, "ComputedSoundVelocity");
    p.sensor_y = r.at<double>(at + 160, "SensorYcoordinate");
    p.sensor_x = r.at<double>(at + 168, "SensorXcoordinate");
    p.depth_m = r.at<float>(at + 192, "SensorDepth");
    p.altitude_m = r.at<float>(at + 196, "SensorPrimaryAltitude");
    p.pitch_deg = r.at<float>(at + 204, "SensorPitch");
    p.roll_deg = r.at<float>(at + 208, "SensorRoll");
    p.heading_deg = r.at<float>(at + 212, "SensorHeading");
    const int channels = r.at<std::uint16_t>(at + 4, "NumChansToFollow");
    size_t c = at + 256;
    for (int k = 0; k < channels; ++k) {
        XtfChannelPing ch;
        ch.channel = r.at<std::uint16_t>(c, "ChannelNumber");
        ch.slant_range_m = r.at<float>(c + 4, "SlantRange");
        ch.ground_range_m = r.at<float>(c + 8, "GroundRange");
        ch.time_delay_s = r.at<float>(c + 12, "TimeDelay");
        ch.time_duration_s = r.at<float>(c + 16, "TimeDuration");
        ch.seconds_per_ping = r.at<float>(c + 20, "SecondsPerPing");
        ch.samples = r.at<std::uint32_t>(c + 42, "NumSamples");
        if (ch.channel >= int(file.channel_info.size()))
            throw InputError(r.path(), "ChannelNumber",
                             "channel " + std::to_string(ch.channel) + " has no ChanInfo");
        const size_t bytes =
            size_t(ch.samples) * size_t(file.channel_info[size_t(ch.channel)].bytes_per_sample);
        c += 64;
        if (c + bytes > r.size())
            throw InputError(r.path(), "NumSamples", "the samples run past the file's end");
        ch.data.assign(r.data(c), r.data(c) + bytes);
        ch.near_first = ch.data;
        const XtfChannelInfo& info = file.channel_info[size_t(ch.channel)];
        if (info.type == 1) // port: whole samples in reverse order, each sample's bytes as they are
            for (size_t k = 0; k < ch.samples; ++k)
                std::copy_n(ch.data.begin() +
                                std::ptrdiff_t((ch.samples - 1 - k) * size_t(info.bytes_per_sample)),
                            info.bytes_per_sample,
                            ch.near_first.begin() + std::ptrdiff_t(k * size_t(info.bytes_per_sample)));
        c += bytes;
        p.channels.push_back(std::move(ch));
    }
    return p;
}

} // namespace

XtfFile read_xtf(const std::vector<std::uint8_t>& bytes, const std::string& path) {
    const Reader r(bytes, path);
    XtfFile f;
    if (r.at<std::uint8_t>(0, "FileFormat") != 0x7B)
        throw InputError(path, "FileFormat", "not an XTF file (its first byte is not 0x7B)");
    f.recording_program = r.text(2, 8, "RecordingProgramName");
    f.sonar_name = r.text(18, 16, "SonarName");
    f.note = r.text(36, 64, "NoteString");
    f.nav_units = r.at<std::uint16_t>(164, "NavUnits");
    f.sonar_channels = r.at<std::uint16_t>(166, "NumberOfSonarChannels");
    if (f.sonar_channels > 6)
        throw InputError(path, "NumberOfSonarChannels", "more than 6 channels are not read");
    for (int ch = 0; ch < f.sonar_channels; ++ch) {
        const size_t c = 256 + size_t(ch) * 128;
        XtfChannelInfo info;
        info.type = r.at<std::uint8_t>(c, "TypeOfChannel");
        info.bytes_per_sample = r.at<std::uint16_t>(c + 6, "BytesPerSample");
        info.name = r.text(c + 12, 16, "ChannelName");
        info.frequency_khz = r.at<float>(c + 32, "Frequency");
        info.horizontal_beam_deg = r.at<float>(c + 36, "HorizBeamAngle");
        info.tilt_deg = r.at<float>(c + 40, "TiltAngle");
        info.beam_width_deg = r.at<float>(c + 44, "BeamWidth");
        f.channel_info.push_back(info);
    }
    size_t at = 1024; // a multiple of 1024 with up to 6 channels
    while (at < bytes.size()) {
        if (r.at<std::uint16_t>(at, "MagicNumber") != 0xFACE)
            throw InputError(path, "MagicNumber",
                             "a record at byte " + std::to_string(at) + " does not start with 0xFACE");
        const std::uint32_t record = r.at<std::uint32_t>(at + 10, "NumBytesThisRecord");
        if (record < 256 || at + record > bytes.size())
            throw InputError(path, "NumBytesThisRecord",
                             "record at byte " + std::to_string(at) + " runs past the file's end");
        if (r.at<std::uint8_t>(at + 2, "HeaderType") == 0) f.pings.push_back(read_ping(r, at, f));
        at += record;
    }
    return f;
}

} // namespace sonarsim
