// Plain data describing a scene: sonar, water, sampling, display, seafloor and objects.
// Every field with a unit carries it in its name. Defaults are the paper's (Tables I-II, ARIS Explorer 3000).
#pragma once
#include <cstdint>
#include <array>
#include <limits>
#include <optional>
#include <string>
#include <vector>

namespace sonarsim {

using Vec3d = std::array<double, 3>;

/// GSAB backscatter parameters (paper eq. 9). mu is linear, nu in dB (10 log10 nu).
struct Material {
    double nu_db = -45.0; ///< 10 log10 nu [dB]
    double q = 2.0;       ///< Lambert exponent [-]
    double mu = 0.0;      ///< specular amplitude [linear]; 0 turns the specular term off
    double h_deg = 5.0;   ///< specular lobe width [deg]
    /// Energy lost per specular reflection, -10 log10 |R|^2 [dB]; infinite (absent in a scene file): not a
    /// mirror. Multipath only (sampling.bounces > 0).
    double reflection_db = std::numeric_limits<double>::infinity();
    /// Seabed texture (shading/texture.hpp), fixed to the surface: rms of a random level [dB]; 0: off.
    double texture_rms_db = 0.0;
    double texture_correlation_m = 0.5; ///< lag at which the texture's autocorrelation falls to 1/e [m]
    double ripple_amplitude_db = 0.0;   ///< peak amplitude of the ripples' level sinusoid [dB]; 0: off
    double ripple_wavelength_m = 0.5;   ///< ripple crest spacing [m]
    double ripple_direction_deg = 0.0;  ///< ripples' wave vector, from the surface frame's x toward y [deg]
    double slope_rms_deg = 0.0;         ///< rms facet tilt in the plane of incidence [deg]; 0: off
    /// The material preset applied before the explicit keys (assets/materials/NAME.json); "none": none.
    std::string preset = "none";
    bool is_mirror() const { return reflection_db < std::numeric_limits<double>::infinity(); }
};

/// A sonar pose; the default is the paper's Fig. 9 pose 1.
struct Pose {
    Vec3d position_m{0.34, 2.42, 0.90};          ///< [m]
    Vec3d orientation_deg{-0.97, 29.79, -38.96}; ///< roll, pitch, yaw [deg]; R = Rz(yaw) Ry(pitch) Rx(roll)
};

/// The paper's Fig. 9 pose 2 (the viewer's button; assets/scenes/fig9_pose2.json holds it, tested).
inline const Pose kFig9Pose2{{0.84, 2.42, 0.90}, {6.88, 28.07, -41.25}};

/// What kind of sonar (sonar.kind): a forward-looking imaging sonar's fan of beams; a side-scan sonar's two
/// channels (port and starboard) pinging together; a mechanically scanned sonar's one beam stepped by its
/// head.
enum class SonarKind { Imaging, Sidescan, Scanning };
/// The rows of a side-scan waterfall (sidescan.range): by slant range as recorded, or by ground range over a
/// flat bottom at the altitude of each ping's first bottom return.
enum class SidescanRange { Slant, Ground };

struct SonarParams {
    std::string device = "none"; ///< device preset (assets/devices/NAME.json) its values came from
    SonarKind kind = SonarKind::Imaging;
    Pose pose;
    double frequency_khz = 3000.0;
    double azimuth_fov_deg = 32.0;
    double elevation_fov_deg = 14.0;
    int beams = 128;
    /// Beam angles: "uniform" (eq. 10) or a device's table (assets/devices/beam_tables/NAME.csv).
    std::string beam_table = "uniform";
    double range_min_m = 0.5;
    double range_max_m = 5.0;
    int range_bins = 512;
    double source_level_db = 230.0;
    double noise_level_db = 10.0;
    /// Motion during a frame (sampling/acquisition.hpp): velocity in the sonar's frame at the frame's first
    /// transmit [m/s] and body rates about the sonar's x, y, z axes [deg/s]. Zero: each frame a snapshot.
    Vec3d velocity_mps{0, 0, 0};
    Vec3d angular_rate_dps{0, 0, 0};
    /// Pings that build one frame: ping k fires every P-th beam (ARIS: beams / 16, device beam
    /// c x P + k). 1: every beam from one ping.
    int pings_per_frame = 1;
    /// `batch`: each frame's velocity and rates from its trajectory (the poses before and after it).
    bool motion_from_trajectory = false;
};

/// A side-scan sonar (sonar.kind "sidescan"): two transducers, port and starboard, each one beam
/// sonar.azimuth_fov_deg wide along track and sonar.elevation_fov_deg wide across it, tilted down.
struct SidescanParams {
    double depression_deg = 20; ///< each transducer's axis below the horizontal [deg]
    int pings = 200;            ///< pings of one waterfall (its rows)
    SidescanRange range = SidescanRange::Slant;
    double ping_overhead_ms = 0; ///< time between pings beyond the listening window 2 r_max / c [ms]
    /// The first bottom return (the altitude of the ground-range correction): the first bin whose echo level
    /// over the noise (L_EN) reaches this [dB]
    double bottom_threshold_db = 10;
};

/// A mechanically scanned sonar (sonar.kind "scanning"): one beam turned by the head's motor in steps, one
/// ping per step. Head angles from the sonar's x axis (forward) toward y (port).
struct ScanningParams {
    double sector_start_deg = -180; ///< the first step's head angle [deg]
    double sector_end_deg = 180;    ///< the sweep ends at this head angle [deg]
    double step_deg = 0.9;          ///< head angle between pings (Ping360: 1 gradian = 0.9 deg) [deg]
    double step_overhead_ms = 25;   ///< time of a step beyond the listening window 2 r_max / c [ms]
};

struct WaterParams {
    double temperature_c = 10.0;
    double depth_m = 3.0;
    /// The water surface: the plane z = surface_height_m [m], a pressure-release mirror (R = -1) that also
    /// backscatters (surface_material). Absent: no surface.
    std::optional<double> surface_height_m;
    double surface_roughness_m = 0.0; ///< rms height sigma: coherent |R|^2 = exp(-(2 k sigma cos theta)^2)
    Material surface_material{-50.0, 2.0, 0.0, 5.0};
};

enum class NormalSource { Mesh, Paper };
/// Where rays go: the regular grid (trace.cpp), or the grid refined where the error needs it (adaptive.cpp).
enum class RayPlacement { Grid, Adaptive, Jittered };
/// Where a ray's echo goes: the bin of its range, or spread over its cell's range footprint (shade.cpp).
enum class EchoBinning { Point, Footprint };
/// How the adaptive sampler estimates its error (adaptive_estimate.cpp, docs/model.md): fast counts every
/// coarse-to-fine difference at first order and does not see the error of one ray column across a beam;
/// strict tells smooth cells (second order) from edges and measures that azimuth error with a probe.
enum class ErrorEstimate { Fast, Strict };
/// The named combinations of placement and binning (sampling.scheme; see scene/sampling_scheme.hpp).
enum class SamplingScheme { Uniform, Spread, Adaptive, Jittered };

struct SamplingParams {
    int elevation_rays = 101; ///< adaptive: rays of the base grid; grid: all rays (paper: 281)
    int azimuth_rays = 1;
    NormalSource normals = NormalSource::Mesh;
    RayPlacement placement = RayPlacement::Adaptive;
    EchoBinning binning = EchoBinning::Footprint;
    double tolerance_db = 0.1;      ///< adaptive placement's target median |dB error|
    double tolerance_rel_l1 = 0.01; ///< ... and its target relative L1 error of the linear image
    int max_rays = 2000000;         ///< adaptive placement's budget of rays per image, refinement included
    ErrorEstimate estimate = ErrorEstimate::Fast; ///< adaptive placement's error estimate
    int bounces = 0; ///< specular reflections followed per leg (multipath); 0: direct paths only
};

enum class Colormap { Gray, Viridis, Copper, Hot };

struct DisplayParams {
    double lo_db = 80.0;
    double hi_db = 120.0;
    Colormap colormap = Colormap::Gray;
    bool auto_range = false; ///< lo/hi from the image's 5th and 99.5th percentiles instead of lo_db/hi_db
};

/// The 8-bit exports (.aris, MCAP uint8): the image levels bytes 0 and 255 stand for (io/byte_mapping.hpp).
struct ExportParams {
    bool auto_range = true;  ///< chosen from the levels of the exported frames instead of lo_db/hi_db
    double lo_db = 0;        ///< level of byte 0 (and below)
    double hi_db = 80;       ///< level of byte 255 (and above)
    double start_time_s = 0; ///< UNIX time of t = 0 (ARIS FrameTime); 0: the dataset's (dataset.json)
};

enum class SensorModel { Ideal, Device };
enum class AzimuthWindow { None, Rect, Hann, Taylor };
enum class Beamformer { Lens, Array };
enum class ElevationPattern { Flat, Gaussian, Sinc };
enum class Pulse { Cw, Chirp };
enum class Speckle { Off, Rayleigh, K };
enum class Tvg { Off, Log20, Log30, Log40 };

/// The sensor stage: what a device does to the ideal echo image (sensor.cpp). Every effect off is the ideal
/// sensor. Formulas and sources: docs/model.md (The sensor), core/sensor/README.md.
struct SensorParams {
    SensorModel model = SensorModel::Ideal;
    AzimuthWindow azimuth_window = AzimuthWindow::None;
    double azimuth_beamwidth_deg = 0; ///< -3 dB width of the receive beam; 0: the beam spacing
    double taylor_sidelobe_db = -30;  ///< design sidelobe level of the "taylor" window
    Beamformer beamformer = Beamformer::Lens;
    ElevationPattern elevation_pattern = ElevationPattern::Flat;
    double elevation_beamwidth_deg = 0; ///< -3 dB two-way width; 0: sonar.elevation_fov_deg
    double range_resolution_m = 0;      ///< c tau / 2 (cw) or c / 2B (chirp); 0: ideal
    Pulse pulse = Pulse::Cw;
    Speckle speckle = Speckle::Off;
    double speckle_k_shape = 4; ///< K-distribution shape alpha (scintillation index 1 + 2 / alpha)
    int seed = 1;
    bool noise = false; ///< additive complex Gaussian noise at L_N
    Tvg tvg = Tvg::Off;
    double gain_db = 0;
    /// Not a parameter (no key): which transmit the noise is drawn for, besides the pose; a side-scan's or
    /// scan's ping number + 1 (render_pings), so that pings from one pose get their own noise; 0 an image.
    std::uint64_t noise_draw = 0;
};

struct Seafloor {
    double height_m = 0.0;
    Material material;
};

/// A scene object: a mesh file or an axis-aligned box (before rotation), placed by
/// position/orientation/scale.
struct ObjectDesc {
    std::string mesh;           ///< path as written in the scene file (empty for a box)
    std::string mesh_resolved;  ///< absolute or scene-relative-resolved path used for loading
    std::optional<Vec3d> box_m; ///< box size dx, dy, dz [m]
    Vec3d position_m{0, 0, 0};  ///< box centre / mesh origin [m]
    Vec3d orientation_deg{0, 0, 0};
    Vec3d scale{1, 1, 1};
    /// Shading normals interpolated from corner normals that average the faces within this angle of each
    /// other (shading_normals.hpp); 0: face normals [deg]
    double crease_angle_deg = 60.0;
    /// Phong tessellation's shape factor: hits on a smooth object's bent faces move onto the curved surface
    /// through its vertices and corner normals (phong_surface.hpp); 0: on the flat faces [none, 0..1]
    double phong_alpha = 0.0;
    Material material;
    std::string name; ///< a label (not written to the metadata)
};

struct SceneDesc {
    std::string source_file; ///< where it was read from ("" for built-in / in-memory)
    SonarParams sonar;
    SidescanParams sidescan;
    ScanningParams scanning;
    WaterParams water;
    SamplingParams sampling;
    DisplayParams display;
    SensorParams sensor;
    ExportParams exports;
    std::optional<Seafloor> seafloor = Seafloor{};
    std::vector<ObjectDesc> objects;
};

} // namespace sonarsim
