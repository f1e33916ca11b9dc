// Adaptive sampling, internal (adaptive*.cpp, refine_*.cpp, tests): the cells of a column as the sampler
// refines them, and the columns of a beam.
#pragma once
#include "core/base/fast_math.hpp"
#include "core/sampling/multipath.hpp"
#include "core/sampling/trace_detail.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <optional>
#include <vector>

namespace sonarsim::adaptive {

using detail::Angle;

constexpr int kElevationLevels = 5; // ternary splits: cells down to 1/243 of the base width
constexpr int kAzimuthLevels = 3; // columns split in three locally: down to 1/27 of the base width (specular)
constexpr int kEdgeAzimuthLevels = 2; // ... and down to 1/9 where neighbouring columns see different surfaces
constexpr int kMaxPasses = 3;         // base grids a group may have: elevation_rays x 1, 3, 9 (adaptive.cpp)
/// A smooth elevation pattern's base grid (pattern_grid, refine_elevation.cpp): cells dense as
/// max(kTailDensity, B^kPatternExponent) of the pattern B, in equal shares: fewer rays in the pattern's
/// tails, whose echo counts little, while every device row's estimate stays at or above its error (the
/// settings measured: bench/NOTEBOOK.md).
constexpr double kTailDensity = 0.45;
constexpr double kPatternExponent = 0.25;
/// Before refining, a pass sends the groups with the largest shares of its base grid's own estimated error
/// to the next base grid unrefined (refinement at edges does not close such a gap), until the rest would
/// meet kSkipFactor x each tolerance.
constexpr double kSkipFactor = 1;
/// Past the first base grid, fast's bump decision counts the error of the triples that refinement will
/// split (a pair discontinuous and significant against the base image, or a cell that splits alone) at this
/// share: refinement closes most of it, so it is a weaker reason for a denser grid. Strict counts it in
/// full. A smaller share leaves wide sonars' wrecks coarser than their estimate says (bench/NOTEBOOK.md).
constexpr double kRefinableShare = 2.0 / 3;
/// Cells whose errors may add up in one bin: a pair is worth refining when its possible error exceeds
/// 1 / kErrorsPerBin of what the tolerance allows the bin.
constexpr double kErrorsPerBin = 3;
/// A pair of cells is not refined when the error it can cause is below kCellShare of one base cell's even
/// share of the error sampling.tolerance_rel_l1 allows the whole image: however many such pairs there are,
/// together they leave at most kCellShare of that tolerance. It spares the many small edges of a wide
/// terrain image (half its rays on the benchmark's Oculus scene); small enough that bins 50 dB below the
/// image's peak (strong absorption, grazing floors) are still refined by the per-bin test.
constexpr double kCellShare = 1.0 / 32;
/// The azimuth probe traces beside every kProbeEvery-th cell of a sample beam's unsplit columns (strict,
/// which acts on it), every kFastProbeEvery-th with fast (which only reports it: 2 rays per 36 cells of
/// an image's columns, about 5 % more rays).
constexpr int kProbeEvery = 3;
constexpr int kFastProbeEvery = 9;
/// The error estimate looks at every kEstimateStride-th beam of images with 8 x that many beams or more,
/// and at every kWideEstimateStride-th of images with kWideBeams or more (64 sample beams at least): wide
/// images cost less to estimate for the same error, while narrower ones keep enough sample beams for the
/// estimate to stay at or above the error (bench/NOTEBOOK.md).
constexpr int kEstimateStride = 4;
constexpr int kWideEstimateStride = 8;
constexpr int kWideBeams = 512;
constexpr double kLn10Over10 = 0.23025850929940458;
constexpr double kLog2_10Over10 = 0.33219280948873623; ///< log2(10) / 10: dB to a power of 2
constexpr double kDbPerOctave = 3.0102999566398120;    ///< 10 log10(2): a power of 2 to dB
/// An azimuth split covers the base cells where neighbouring columns disagree and this many on each side
/// (what differs between columns often moves in elevation from one to the next).
constexpr int kRunMargin = 1;

/// Multipath: what the specular continuation of a mirror hit meets, its echo per steradian as a double
/// path (reflection losses aside) and |d range / d elevation| there.
struct Via : detail::Multipath::Continuation {
    double density_db = 0, dr_de = 0;
};
/// A node's continuation when it has none (no hit, or no multipath).
inline const Via kNoVia{};

/// One elevation cell of a column. Kept small (it is copied and moved as columns are refined): what only
/// multipath reads lives beside the nodes (Via, stored by the Sampler).
struct Node {
    double de = 0; ///< width [rad] (the centre: angle)
    std::optional<Hit> hit;
    glm::dvec3 p_m{0};       ///< the hit point [m, world]
    double density_db = 0;   ///< echo level per steradian (cell_echo_db with dOmega = B_v(e), the pattern)
    double dr_de = 0;        ///< |d range / d elevation| on the hit plane [m/rad]
    double footprint_m = 0;  ///< dr_de * de: the range the cell spans [m]
    double per_metre_db = 0; ///< echo per metre of range when the footprint spans bins (see set_width)
    bool fresh = true;       ///< created or resized since its neighbours were last compared
    int group = 0;           ///< siblings of one split (or base triples) share a group
    int j = 0;               ///< the base cell it lies in
    bool refine = false;
    bool alone_checked = false; ///< needs_split_alone() depends on the node only: evaluate it once
    Angle angle;                ///< the centre [rad] with its sine and cosine
    const Via* via = &kNoVia;   ///< multipath: the continuation (never null)
};

/// Sets the cell width of a node that hit and what follows from it for the neighbour comparisons (bin_m:
/// the range bin width [m]).
inline void set_width(Node& n, double de, double bin_m) {
    n.de = de, n.fresh = true;
    n.footprint_m = n.dr_de * de;
    n.per_metre_db =
        n.density_db + kDbPerOctave * fast::log2_positive(n.angle.c * de / std::max(n.footprint_m, bin_m));
}

/// Neighbouring cells whose echo density steps by more than kJumpPerToleranceDb x tolerance_db [dB], or whose
/// echo per metre of range (on one plane, footprints spanning bins) steps by more than
/// kRangeJumpPerToleranceDb x tolerance_db, are not smooth between them (RefineCriteria).
constexpr double kJumpPerToleranceDb = 10;
constexpr double kRangeJumpPerToleranceDb = 4;
/// The error estimate takes a merged triple to converge in second order only where its neighbours' levels
/// step by less than they would at this tolerance_db (the default), however loose the tolerance: a step
/// that a loose tolerance leaves unrefined is still a kink that converges in first order (at 3 % and
/// 0.3 dB the estimate said 0.50x the measured error on the benchmark's Oculus scene, 0.84x on Monterey).
constexpr double kSmoothToleranceDb = 0.1;
/// A neighbour whose echo per metre of range differs from a cell's by more than this [dB] gives it no trend:
/// such a step is a kink or an edge, the density step the estimate's smooth test takes as an edge (1 dB).
/// Without it, the device bench's terrains lost accuracy (ARIS 3000 HF 0.84 -> 1.08 %, Oculus M1200d HF
/// 0.70 -> 1.03 % with its estimate below); with it every device row is at or better than without trends.
constexpr double kTrendStepDb = kJumpPerToleranceDb * kSmoothToleranceDb;

/// The trend of the echo per metre of range [1/m] (Cell::spread_slope_per_m) at nodes[k] of a column,
/// limited as in MUSCL schemes (minmod): of the one-sided differences of ln(echo per metre) to its
/// neighbours k - reach and k + reach, the smaller where they agree in sign; 0 where they do not (a kink: a
/// facet edge, a crest), where either steps by more than kTrendStepDb, or where a neighbour is missing or
/// on another surface, so that no trend is carried across an edge. reach 3: a merged triple's, from the
/// neighbouring triples (adaptive_cells.cpp). log_pm: each node's ln(echo per metre), when the caller has
/// them (null: computed here).
double spread_slope(const std::vector<Node>& nodes, size_t k, size_t reach, double bin_m,
                    const double* log_pm = nullptr);

/// One azimuth column of a beam: its elevation cells.
struct Column {
    double a = 0, da = 0;
    int beam = 0;
    int j0 = 0, j1 = 0;      ///< the base cells [j0, j1) it covers (a split refines only where it is needed)
    bool sibling = false;    ///< made by the last azimuth split, beside its siblings (same group)
    bool unrefined = false;  ///< traced beside a split, its elevation refinement still to come
    int group = 0;           ///< sibling columns of one split (or base triples) share a group
    std::vector<Node> nodes; ///< ordered by decreasing elevation
    std::vector<Node> base;  ///< the base grid as first traced (for comparing neighbouring columns)
    std::uint64_t rays = 0;
};

/// The columns of each beam.
using Beams = std::vector<std::vector<Column>>;

} // namespace sonarsim::adaptive
