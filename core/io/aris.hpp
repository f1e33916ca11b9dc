// Sound Metrics ARIS recordings (.aris, docs/formats.md; the vendor file SDK's FileHeader.h, FrameHeader.h):
// a 1024-byte file header, then per frame a 1024-byte frame header and BeamCount x SamplesPerBeam bytes,
// sample-major, beam 0 the starboard-most. Packed little-endian.
#pragma once
#include "core/data/polar_image.hpp"
#include "core/data/scene.hpp"
#include "core/data/trajectory.hpp"
#include "core/io/aris_grid.hpp"
#include "core/io/byte_mapping.hpp"

#include <cstdint>
#include <string>
#include <vector>

namespace sonarsim {

/// Throws the InputError write_aris would (naming the scene key) unless the scene can be an ARIS file: a
/// mode of its beam count (of the system an ARIS preset fixes) within 25 % of its frequency, and a range
/// grid whose header fields lie in the documented ranges (aris_grid.hpp).
void check_aris(const SceneDesc& scene, const std::string& origin);

/// Throws an InputError naming `times_origin` (where the frame times came from: "--rate", a trajectory file)
/// when a frame of `frames` follows the one before sooner than the scene's ARIS mode images one (its pings
/// per frame, 3, 4, 6 or 8 of 16 beams, times the CyclePeriod of its range grid, and at most 15 frames/s): a
/// recording faster than the device. Throws what check_aris throws (naming `origin`) first.
void check_aris_frame_times(const SceneDesc& scene, const Trajectory& frames, const std::string& origin,
                            const std::string& times_origin);

/// The scene with its range window and bins on the samples its ARIS file would hold (on_samples of
/// aris_timing), so that the file holds the rendered samples rather than a resampling; `note` says what moved
/// (empty when the bins are the samples already). Throws what check_aris throws.
SceneDesc on_aris_samples(const SceneDesc& scene, const std::string& origin, std::string& note);

/// Writes every frame of `trajectory` as one .aris file (atomically: a temporary, then a rename) on the
/// device's grid (aris_timing; the image itself when its bins are the samples, else resampled onto them by
/// aris_resample, which `notes` then says), each sample the byte of its
/// image level (the frame's .npy: the sensor's output, TVG and gain included; with
/// the ideal sensor, L_EN) under `mapping`, whose levels of bytes 0 and 255 go into every frame header's
/// UserValue1 and UserValue2 [dB]. Pose and time go into the frame headers (SonarX/Y/Z,
/// SonarPan/Tilt/Roll = yaw/pitch/roll, FrameTime = scene.exports.start_time_s + t, in us). Returns what the
/// mapping clipped (of the file's samples). Throws what check_aris throws.
ExportReport write_aris(const std::string& path, const SceneDesc& scene, const Trajectory& trajectory,
                        const FrameImageSource& image, const ByteMapping& mapping, const std::string& origin);

} // namespace sonarsim
