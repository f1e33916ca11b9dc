// Adaptive sampling, internal: what one image's trace shares across its passes (the scene, the frame, the
// criteria, the ray budget) and the steps of a pass, each in its own file:
// refine_elevation.cpp (trace and refine a column), refine_azimuth.cpp (split columns where neighbours
// disagree), adaptive_pass.cpp (one pass over some groups of beams: base grid, refinement, cells),
// adaptive_estimate.cpp (the error estimate's shares), adaptive.cpp (the passes, by priority).
#pragma once
#include "core/data/polar_image.hpp"
#include "core/sampling/adaptive_node.hpp"
#include "core/sampling/refine_criteria.hpp"

#include <tbb/enumerable_thread_specific.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <functional>
#include <limits>
#include <deque>
#include <cstdint>

namespace sonarsim {

/// What an adaptive trace's error estimate was made from besides the image's own cells, slot g for group g
/// of its beams (TraceResult::estimate_cells): reestimate_error shades them with another scene's values.
struct AdaptiveEstimateCells {
    std::vector<int> samples; ///< group g's sample beam (-1: none estimated)
    /// Its cells one level coarser, the same with only the triples that are not smooth merged, and (when
    /// `probed`) the azimuth probe's cells as one column and as three; with multipath their ghosts.
    TraceResult coarse, coarse_edges, az_one, az_three;
    bool probed = false;
    double ref_db = 0; ///< the level the estimate's linear sums were taken relative to (Sampler::ref_db)
    int probe_every = 0;
};

} // namespace sonarsim

namespace sonarsim::adaptive {

/// Where Sampler::cells_of puts a column's cells and, with multipath, their ghosts (null: not wanted).
struct CellsOut {
    std::vector<Cell>* cells = nullptr;
    std::vector<GhostCell>* ghosts = nullptr;
    /// When given, the ghosts that do not arrive wholly in the column's own beam go here instead of to
    /// `ghosts` (detail::stays_in_source: the split gather_ghosts takes).
    std::vector<GhostCell>* away = nullptr;
};

/// The first base grid's M + 1 cell edges over the traced aperture phi [rad], top down. A flat pattern:
/// even. A smooth one (gaussian, sinc), traced far into its tails: each triple of cells (and each cell of
/// an incomplete last triple) holds an equal share of the integral of max(kTailDensity, B^kPatternExponent)
/// of the pattern B, so that the main lobe's cells are narrower and the tails' wider (refine_elevation.cpp).
std::vector<double> pattern_grid(const ElevationWeight& pattern, double phi, int M);

struct Sampler {
    const SceneGeometry& g;
    const SceneDesc& s;
    const TraceControl& control;
    detail::RayFrame frame;
    bool multipath; ///< ghosts to find (sampling.bounces and a mirror)
    /// sampling.estimate strict: the sampler acts on its azimuth probe (three ray columns per beam where
    /// azimuth is the larger share of a group's error); fast only reports what the probe sees
    bool strict;
    int probe_every; ///< the azimuth probe's cells: every kProbeEvery-th (strict), kFastProbeEvery-th (fast)
    detail::Multipath mp;
    RefineCriteria criteria;
    double phi; ///< the traced elevation aperture [rad]
    int elevation_levels, azimuth_levels;
    mutable std::atomic<std::uint64_t> rays{0}; ///< rays traced or reserved in this image, all passes
    mutable std::atomic<bool> budget_hit{false};
    /// The budget pays in a fixed order (refine_columns, refine_azimuth): a pass that the budget stopped
    /// first come is traced again so (trace_adaptive), so that it does not depend on the threads.
    bool ordered = false;
    /// A smooth pattern's first base grid's cell edges [rad], top down (sampling.elevation_rays + 1 of them,
    /// denser where the pattern is strong: pattern_grid); empty for the flat pattern's even grid.
    std::vector<double> first_edges;
    std::vector<Angle> base_angles; ///< the base grid's elevations (set_base_grid)
    std::vector<double> base_de;    ///< ... their cells' widths [rad]
    /// ... the narrowest a refined cell of each may get [rad]: its first-grid cell's width / 3^levels
    std::vector<double> base_de_min;
    std::vector<int> traced; ///< the beams traced (TraceControl::beams; all by default)
    /// The beams of the pass being traced (one flag per beam; a pass traces the groups it refines).
    std::vector<char> pass_beams;
    /// The level [dB] linear error sums are taken relative to (the first estimated image's peak; NaN before).
    double ref_db = std::numeric_limits<double>::quiet_NaN();
    /// Sets ref_db to img's peak when not yet set.
    void set_ref_db(const PolarImage& img) {
        if (!std::isnan(ref_db)) return;
        double peak = -std::numeric_limits<double>::infinity();
        for (float v : img.level_db) peak = std::max(peak, double(v));
        if (std::isfinite(peak)) ref_db = peak;
    }
    /// Multipath: the nodes' continuations (Node::via), per thread, in blocks that never move.
    mutable tbb::enumerable_thread_specific<std::deque<Via>> via_store;

    /// Elevations of a pass's base grid of M0 rays (once per pass instead of once per column).
    void set_base_grid(int M0);

    Sampler(const SceneGeometry& geo, const SceneDesc& scene, const TraceControl& c);

    /// Whether beam i is traced in the current pass.
    bool traces(int i) const { return pass_beams.empty() ? control.traces(i) : pass_beams[size_t(i)] != 0; }
    /// Per beam: its base grid's columns, in multiples of sampling.azimuth_rays (1, or 3 for a group whose
    /// estimate found azimuth the larger share of its error); empty: 1 each.
    std::vector<int> column_mult;
    /// The base grid's columns of beam i.
    int columns(int i) const {
        return s.sampling.azimuth_rays * (column_mult.empty() ? 1 : column_mult[size_t(i)]);
    }
    /// Rays of a base grid of M0 elevation rays over n beams (default: every traced beam), at
    /// sampling.azimuth_rays columns each.
    double base_rays(int M0, int n = -1) const {
        return double(M0) * double(n < 0 ? int(traced.size()) : n) * s.sampling.azimuth_rays;
    }

    /// Takes n rays from the image's budget (sampling.max_rays); false (and nothing taken) when it is spent.
    bool reserve(std::uint64_t n) const;
    /// Takes up to n rays (an even number) from the budget; returns how many (0 when it is spent).
    std::uint64_t reserve_up_to(std::uint64_t n) const;

    // refine_elevation.cpp
    /// One ray (a, e) standing for a cell of width de in elevation, with what the criteria read.
    Node trace_node(const Angle& a, const Angle& e, double de, int group) const;
    /// The base grid of one column: base cells [j0, j1) of M0.
    Column trace_column(double a_rad, double da, int M0, int beam, int j0, int j1) const;
    /// A base column at M0 / 3 as one at M0: each cell splits in three, keeping its ray as the middle one.
    void densify_column(Column& col, int M0) const;
    /// Ternary refinement of the columns' cells down to kElevationLevels. `ordered`: level by level over
    /// all columns, each level's rays paid from the budget in the columns' order (where the budget ends
    /// does not depend on the threads); else each column through all its levels at once (faster: its nodes
    /// stay in the cache), the budget paid first come.
    void refine_columns(const std::vector<Column*>& cols, int M0, bool ordered) const;
    /// One column through all its levels, the budget paid first come (refine_columns, not ordered).
    void refine_column(Column& col, int M0) const;

    // refine_azimuth.cpp
    /// Splits columns in azimuth (kAzimuthLevels levels) where neighbours disagree or a cell needs it.
    void refine_azimuth(Beams& beams, int M0, bool ordered) const;

    // adaptive_pass.cpp
    /// Cells of a column at azimuth width da, and their multipath ghosts (with multipath), into up to three
    /// outputs: every node's cell (`fine`); every complete sibling triple merged into its middle cell, one
    /// level up (`all`); only the triples that are not smooth merged (`edges`, smooth_triple; with
    /// `lasting_edges_only`, only those refinement will not split either, refinable_triple). Each cell and
    /// its ghosts are made once, whichever outputs share them. Returns the ghosts' rays.
    std::uint64_t cells_of(const Column& c, double da, CellsOut fine, CellsOut all = {}, CellsOut edges = {},
                           bool lasting_edges_only = false) const;
    /// Whether refinement will split a cell of the sibling triple at nodes [n, n + 3) of c: a pair in it
    /// is discontinuous (significance included, against the base image) or a cell needs to split alone.
    bool refinable_triple(const Column& c, size_t n) const;
    /// Whether the sibling triple at nodes [n, n + 3) of c lies on one smooth surface: every cell hits, no
    /// step between neighbours (RefineCriteria::edge_between) and no reason for the merged cell to split
    /// alone. Merging it changes the image in second order of the cell width; other triples, first order.
    bool smooth_triple(const Column& c, size_t n) const;
    /// The same for the sibling column triple cols[k, k + 3), from their base cells: every one hits, no
    /// edge between neighbouring columns and no specular lobe narrower than the merged column.
    bool smooth_column_triple(const std::vector<Column>& cols, size_t k) const;

  private:
    void trace_continuation(Node& n, const Angle& a) const;
    /// Marks the nodes of `col` to split at this level; returns how many.
    size_t mark_for_split(Column& col, const Angle& a) const;
    /// Replaces each marked node by three of a third its width (the middle one is the node itself).
    void split_marked(Column& col, const Angle& a, size_t marked, int& next_group) const;
};

/// The error estimate's share of one group of beams: its sample beam's image against the same cells one
/// level coarser (adaptive_estimate.cpp). Linear sums are relative to a fixed level (Estimator::ref_db).
struct SampleError {
    /// sum |coarse - fine| and sum fine over the bins, linear, where each bin's |coarse - fine| counts
    /// what merging the triples that are not smooth changes in full and what merging the smooth ones
    /// changes times kSmoothShare (sample_errors)
    double num = 0, den = 0;
    std::vector<float> diffs_db; ///< |coarse - fine| [dB] over bins echoing in both, counted as num is
    /// Sum |three columns - one| over the bins of the azimuth probe (azimuth_probe), times the probe's
    /// stride: the error of a single column per beam across its width, which the coarse image (columns
    /// merge only in split triples) does not see; 0 where the beam has column triples of its own. Strict
    /// acts on it (and diffs_db includes it).
    double az_num = 0;
    /// Fast: the same sum, reported but not acted on (neither the choice of groups nor the stopping rule
    /// counts it: no column is added for it), and per entry of diffs_db what it adds [dB] (from the mean
    /// over the probe_every bins centred on that one, sample_errors).
    double az_seen = 0;
    std::vector<float> seen_inc_db;
    /// Twice the group's estimated error that the sampler acts on (the sums' unit): num plus the azimuth
    /// probe's under strict.
    double share() const { return num + 2 * az_num; }
};

/// What merging a smooth triple changes counts this much in the estimate: the midpoint rule converges in
/// second order on one smooth surface, so the fine cells' error is |fine - coarse| / 8 there, against the
/// |fine - coarse| / 2 the estimate takes for first order (edges, misses, level steps).
constexpr double kSmoothShare = 1.0 / 4;

/// The beams of an image in groups: every stride-th traced beam is a group's sample (the beam whose error
/// is estimated), the traced beams after it up to the next sample belong to its group.
using BeamGroups = std::vector<std::vector<int>>;

/// What one pass over some groups at one base grid leaves.
struct PassCells {
    TraceResult fine;         ///< cells (and ghosts) per beam of the image; empty for beams not refined
    TraceResult coarse;       ///< per group passed in (slot k: group k's sample beam), one level coarser
    TraceResult coarse_edges; ///< the same with only the triples that are not smooth merged
    std::vector<char> bumped; ///< per group passed in: left unrefined, for a denser base grid
    /// The azimuth probe (slot k: group k's sample beam; empty unless probed): the cells it probed (every
    /// probe_every-th of the columns not split in azimuth) as one column and as three, with multipath their
    /// ghosts too (in slot k whatever beam they arrive in: the probe sums their difference).
    TraceResult az_one, az_three;
};

/// Which of some groups' base grids to leave for a denser one, from their base grids' own errors.
using BumpRule = std::function<std::vector<char>(const std::vector<SampleError>& base)>;

/// One pass at base grid M0 elevation rays over `groups`: traces their base grids; when `bump` is given,
/// asks it which to leave unrefined (refinement fixes edges, not the error of every smooth cell, and a
/// denser grid's refinement would redo it); refines the others and collects their cells, fine and (on each
/// group's sample beam, unless previewing) one level coarser. When every group goes denser it returns
/// after the decision, with no cells (and the criteria's base image left as it was).
/// `carried`: beams' base grids at M0 / 3 left by the last pass (kept and split, not traced again); it
/// receives this pass's bumped beams' base grids.
PassCells trace_pass(Sampler& sampler, int M0, const BeamGroups& groups, const BumpRule* bump,
                     Beams* carried);

/// The cells of the refined columns (fine) and, on the `samples` beams (slot k: samples[k]; -1: none)
/// unless previewing, the same cells one level coarser (`coarse`) and the same with only the triples that
/// are not smooth merged (`coarse_edges`); with multipath their ghosts, the coarser images' those arriving
/// in each sample beam. Adds the columns' rays to fine.rays_traced and frees the columns
/// (adaptive_cells.cpp).
void collect_cells(const Sampler& sampler, Beams& beams, const std::vector<int>& samples, TraceResult& fine,
                   TraceResult& coarse, TraceResult& coarse_edges);

/// Images of the same sample beams besides fine and coarse (null: none): the coarse image with only the
/// triples that are not smooth merged, and the azimuth probe's cells (every probe_every-th) as one column
/// and as three. `act_on_azimuth`: strict (fast only reports the probe, SampleError::az_seen).
struct EstimateImages {
    const PolarImage* coarse_edges = nullptr;
    const PolarImage* az_one = nullptr;
    const PolarImage* az_three = nullptr;
    bool act_on_azimuth = true;
    int probe_every = kProbeEvery;
    /// The coarse image with only the triples merged that are neither smooth nor split by refinement (a
    /// bump decision's, with counts_refinable): the other edges' part counts at kRefinableShare.
    const PolarImage* lasting_edges = nullptr;
};

/// Columns `beams` of `img` as an image of their own (-1: an empty column).
PolarImage columns_of(const PolarImage& img, const std::vector<int>& beams);
/// The image of `beams` (-1: an empty column) shaded from the cells (and ghosts, with multipath) of `hits`,
/// as an image of their own (shade_columns).
PolarImage shade_beams(const TraceResult& hits, const SceneDesc& scene, const std::vector<int>& beams);

/// Per sample beam (column k of the images: the same beams), the estimate's share (adaptive_estimate.cpp).
/// Without `coarse_edges`, every triple counts as not smooth; without the probe's images, no azimuth share.
std::vector<SampleError> sample_errors(const PolarImage& coarse, const PolarImage& fine, double ref_db,
                                       const EstimateImages& images = {});

/// The image's error estimated from its groups' shares: fine error ~ |fine - coarse| / 2 (the coarse
/// image's error taken as three times the fine one's: first order at discontinuities, the slowest case;
/// smooth triples count at kSmoothShare). `seen`: with what fast's probe saw but did not act on (az_seen),
/// as reported; without it, what the sampler's choices and stopping rule use.
TraceResult::ErrorEstimate combine_errors(const std::vector<const SampleError*>& errors, bool seen = false);

} // namespace sonarsim::adaptive
