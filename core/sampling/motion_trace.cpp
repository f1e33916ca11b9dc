#include "core/sampling/motion_trace.hpp"

#include "core/data/pose.hpp"
#include "core/grid/sonar_grid.hpp"
#include "core/sampling/acquisition.hpp"
#include "core/shading/accumulate.hpp"
#include "core/shading/physics.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

namespace sonarsim {

namespace {

/// Moves a cell's range and its footprint by the same amount.
void shift_range(Cell& c, float d_m) {
    c.range_m += d_m;
    c.range_e_lo_m += d_m, c.range_e_hi_m += d_m;
    c.range_a_lo_m += d_m, c.range_a_hi_m += d_m;
}

/// Half the two-way path minus the receive leg: the transmit leg was |X - p_tx|, not |X - p_rx|.
float two_way_correction(const Cell& c, const glm::dvec3& p_tx) {
    const double tx_leg = glm::length(glm::dvec3(c.point_m) - p_tx);
    return float(0.5 * (tx_leg - double(c.range_m)));
}

/// A slot's estimate and its weights (detail::SlotEstimate): its echo and echoing bins, from its image when
/// its tracer shaded one.
detail::SlotEstimate slot_estimate(const TraceResult& r, const Accumulation* shaded) {
    detail::SlotEstimate x{r.error_estimate, 0, 0};
    if (!shaded || !shaded->image) return x;
    for (float v : shaded->image->level_db)
        if (v > -std::numeric_limits<float>::infinity()) x.echo += std::pow(10.0, 0.1 * v), x.bins += 1;
    return x;
}

} // namespace

TraceResult::ErrorEstimate detail::combine_slot_estimates(const std::vector<SlotEstimate>& v) {
    TraceResult::ErrorEstimate out;
    if (v.empty()) return out;
    out = v.front().e;
    double num = 0, az = 0, den = 0, bins = 0;
    for (const auto& x : v) {
        out.valid = out.valid && x.e.valid;
        out.p95_abs_db = std::max(out.p95_abs_db, x.e.p95_abs_db);
        out.passes = std::max(out.passes, x.e.passes);
        out.budget_reached = out.budget_reached || x.e.budget_reached;
        num += x.e.rel_l1 * x.echo, az += x.e.azimuth_rel_l1 * x.echo, den += x.echo, bins += x.bins;
    }
    if (!(den > 0) || !(bins > 0)) { // no echo to weigh by: the largest
        for (const auto& x : v)
            out.rel_l1 = std::max(out.rel_l1, x.e.rel_l1),
            out.azimuth_rel_l1 = std::max(out.azimuth_rel_l1, x.e.azimuth_rel_l1),
            out.median_abs_db = std::max(out.median_abs_db, x.e.median_abs_db);
        return out;
    }
    out.rel_l1 = num / den, out.azimuth_rel_l1 = az / den;
    std::vector<const detail::SlotEstimate*> by_median;
    for (const auto& x : v) by_median.push_back(&x);
    std::sort(by_median.begin(), by_median.end(),
              [](auto* a, auto* b) { return a->e.median_abs_db < b->e.median_abs_db; });
    double below = 0;
    for (const detail::SlotEstimate* x : by_median)
        if ((below += x->bins) >= 0.5 * bins) {
            out.median_abs_db = x->e.median_abs_db;
            break;
        }
    return out;
}

TraceResult trace_moving(const SceneGeometry& g, const SceneDesc& s, const TraceControl& control) {
    const double c = sound_speed_m_s(s.water.temperature_c, s.water.depth_m);
    const auto slots = acquisition_slots(s.sonar, c);
    const int N = s.sonar.beams, K = s.sonar.range_bins;
    const std::shared_ptr<const SonarGrid> grid = sonar_grid(s.sonar);
    constexpr double kInf = std::numeric_limits<double>::infinity();

    TraceResult out;
    out.beams = N;
    out.cells.resize(size_t(N));
    std::vector<detail::SlotEstimate> estimates;
    for (const AcquisitionSlot& slot : slots) {
        // The slab's own range window on the frame's bin edges, seen from the receive pose; the budget of
        // rays shared between the slots.
        SceneDesc sub = s;
        sub.sonar.pose = pose_at(s.sonar, slot.t_rx_s);
        sub.sonar.velocity_mps = {0, 0, 0}, sub.sonar.angular_rate_dps = {0, 0, 0};
        sub.sonar.range_min_m = grid->range_at_bin_m(slot.bin_begin);
        sub.sonar.range_max_m = slot.bin_end == K ? s.sonar.range_max_m : grid->range_at_bin_m(slot.bin_end);
        sub.sonar.range_bins = slot.bin_end - slot.bin_begin;
        sub.sampling.max_rays = std::max(1000, int(s.sampling.max_rays / std::int64_t(slots.size())));
        // Only this ping's beams (every P-th): the others are fired by other pings, from other poses.
        std::vector<char> fired(size_t(N), 0);
        for (int i = 0; i < N; ++i) fired[size_t(i)] = ping_of_beam(s.sonar, i) == slot.ping;
        TraceControl tc = control;
        tc.beams = s.sonar.pings_per_frame > 1 ? &fired : nullptr;
        tc.keep_placement = false; // the slots' hits are merged: no estimate cells to keep
        ImagePass slot_pass;
        TraceResult r = trace(g, sub, tc, &slot_pass);
        std::shared_ptr<const Accumulation> slot_image = slot_pass.take();
        if (!slot_image && sub.sampling.placement == RayPlacement::Adaptive) { // its estimate's weights
            slot_pass.run(r, sub);
            slot_image = slot_pass.take();
        }

        // Keep the echoes of this ping's beams that arrive in the slab (the first slab keeps everything
        // nearer, the last everything farther), at half their two-way path.
        const glm::dvec3 p_tx = to_glm(pose_at(s.sonar, slot.t_tx_s).position_m);
        const double lo = slot.bin_begin == 0 ? -kInf : sub.sonar.range_min_m;
        const double hi = slot.bin_end == K ? kInf : sub.sonar.range_max_m;
        auto keep = [&](Cell& cell) {
            shift_range(cell, two_way_correction(cell, p_tx));
            return cell.range_m >= lo && cell.range_m < hi;
        };
        if (!r.ghosts.empty() && out.ghosts.empty()) out.ghosts.resize(size_t(N));
        if (r.halves && out.stratum_cells.empty()) out.halves = true, out.stratum_cells.resize(size_t(N));
        for (int i = 0; i < N; ++i) {
            if (ping_of_beam(s.sonar, i) != slot.ping) continue;
            for (Cell& cell : r.cells[size_t(i)])
                if (keep(cell)) out.cells[size_t(i)].push_back(cell);
            if (size_t(i) < r.stratum_cells.size()) // jittered: the estimate's cells, kept alike
                for (Cell& cell : r.stratum_cells[size_t(i)])
                    if (keep(cell)) out.stratum_cells[size_t(i)].push_back(cell);
            if (size_t(i) < r.ghosts.size())
                for (GhostCell& gc : r.ghosts[size_t(i)])
                    if (keep(gc.cell)) out.ghosts[size_t(i)].push_back(gc);
        }
        out.rays_traced += r.rays_traced;
        out.multipath_rays += r.multipath_rays;
        out.preview = out.preview || r.preview;
        estimates.push_back(slot_estimate(r, slot_image.get()));
    }
    out.error_estimate = detail::combine_slot_estimates(estimates);
    return out;
}

} // namespace sonarsim
