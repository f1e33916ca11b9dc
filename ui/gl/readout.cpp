#include "ui/gl/readout.hpp"

#include "core/display/display_range.hpp"

#include "core/pipeline/memory_report.hpp"
#include "core/shading/physics.hpp"

#include <imgui.h>

#include <cstdio>
#include <string>

namespace sonarsim::ui {
namespace {

void estimate_tooltip(const SceneDesc& s, const TraceResult::ErrorEstimate& est) {
    if (s.sampling.placement == RayPlacement::Jittered) {
        ImGui::SetTooltip(
            "The jittered grid's estimate of this image's error: rel L1 of the linear image and "
            "median |dB| over echoing bins,\nagainst sampling.tolerance_rel_l1 (%.2f %%) and "
            "tolerance_db (%.3f dB): its two independent halves' difference (%.2f %%) and\nits "
            "footprint's bias (%.2f %%), added in quadrature bin by bin (docs/model.md). The grid "
            "does not refine: more rays lower it.",
            100 * s.sampling.tolerance_rel_l1, s.sampling.tolerance_db, 100 * est.variance_rel_l1,
            100 * est.footprint_rel_l1);
        return;
    }
    ImGui::SetTooltip("The sampler's estimate of this image's error: rel L1 of the linear image and median "
                      "|dB| over echoing bins,\nagainst sampling.tolerance_rel_l1 (%.2f %%) and tolerance_db "
                      "(%.3f dB); %.2f %% of it is one ray column's error across a beam's\nwidth, which "
                      "sampling.estimate fast reports and does not refine (strict adds ray columns for it; "
                      "docs/model.md).",
                      100 * s.sampling.tolerance_rel_l1, s.sampling.tolerance_db, 100 * est.azimuth_rel_l1);
}

/// The sampler's estimate of the shown image's error (adaptive, jittered), against its tolerances (none for
/// a plain grid or a preview).
void estimate_line(const SceneDesc& s, const TraceResult::ErrorEstimate& est) {
    if (!est.valid) return;
    const bool met = est.meets(s.sampling);
    // Short enough for the panel's narrowest width; the tooltip says the rest.
    const char* mode = est.strict ? " strict" : "";
    if (met)
        ImGui::TextDisabled("estimate %.2f %% %.3f dB%s", 100 * est.rel_l1, est.median_abs_db, mode);
    else
        ImGui::TextColored(ImVec4(1.0f, 0.65f, 0.3f, 1.0f), "estimate %.2f %% %.3f dB%s, %s",
                           100 * est.rel_l1, est.median_abs_db, mode,
                           est.budget_reached ? "budget" : "> tol.");
    // Fast stops once what it refines meets the tolerances; what its probe sees across the beams it reports.
    const bool azimuth_left = !met && !est.budget_reached && est.azimuth_rel_l1 > 0;
    if (azimuth_left) {
        if (ImGui::IsItemHovered()) estimate_tooltip(s, est);
        ImGui::TextColored(ImVec4(1.0f, 0.65f, 0.3f, 1.0f), "  %.2f %% of it across beams",
                           100 * est.azimuth_rel_l1);
    }
    if (ImGui::IsItemHovered()) estimate_tooltip(s, est);
}

} // namespace

void draw_readout(Session& session, double frame_ms) {
    const SceneDesc& s = session.scene();
    ImGui::Text("alpha = %.3f dB/m",
                absorption_db_per_m(s.sonar.frequency_khz, s.water.temperature_c, s.water.depth_m));
    if (ImGui::IsItemHovered())
        ImGui::SetTooltip("Absorption (eq. 7) at f, T, D; the paper's Table II gives 3.04 dB/m");
    ImGui::Text("frame %.1f ms", frame_ms);
    if (const RenderResult* r = session.shown(); r && r->pings) { // a side-scan's or scan's pings
        const PingSeries& p = *r->pings;
        ImGui::SameLine();
        ImGui::Text("  image %.1f ms%s", r->wall_ms, r->preview() ? " (preview)" : "");
        ImGui::TextDisabled("%d %s x %d bins, every %.1f ms", p.pings, p.channels == 2 ? "pings" : "steps",
                            p.bins, 1e3 * p.ping_interval_s);
        ImGui::TextDisabled("%d traced, %d shaded, %d kept", p.traced_profiles, p.shaded_profiles,
                            p.copied_profiles);
        if (ImGui::IsItemHovered())
            ImGui::SetTooltip(
                "Each ping's channels: traced anew (%llu rays), shaded from hits traced before "
                "from the same pose, or kept from the last image (only the pose changed).\n%d of "
                "them from rays placed for earlier values of a slider that steers the sampler,\nkept "
                "where their error estimate, made anew, meets the tolerances (or stays within\none "
                "tolerance of what their trace reached); a snapshot places them anew",
                static_cast<unsigned long long>(p.rays_traced), p.kept_placement_profiles);
    } else if (r) {
        const Frame& f = *r->frame;
        ImGui::SameLine();
        ImGui::Text("  image %.1f ms%s", r->wall_ms, f.preview() ? " (preview)" : "");
        // This image's own work per stage: a stage it shares with the image before is "kept"; an adaptive
        // trace shades its cells itself.
        auto stage_ms = [](double ms, const char* none) {
            char b[32];
            if (ms > 0) std::snprintf(b, sizeof b, "%.1f", ms);
            return ms > 0 ? std::string(b) : std::string(none);
        };
        ImGui::TextDisabled("trace %s  shade %s  map %s ms", stage_ms(f.trace_ms, "kept").c_str(),
                            stage_ms(f.shade_ms, f.trace_ms > 0 ? "in trace" : "kept").c_str(),
                            stage_ms(f.image_ms, "kept").c_str());
        const MemoryReport m = memory_report();
        ImGui::TextDisabled("%llu rays  kept %s MiB", static_cast<unsigned long long>(f.hits().rays_traced),
                            mib_text(m.mesh_bytes + m.kept_bytes).c_str());
        if (ImGui::IsItemHovered()) ImGui::SetTooltip("Kept between images: %s", to_string(m).c_str());
        if (f.preview() && f.hits().halves && f.error_estimate.valid) { // at the screen's precision
            const double screen = half_grey_level_db(f.display);
            ImGui::TextDisabled("preview %.3f dB, screen %.3f dB", f.error_estimate.median_abs_db, screen);
            if (ImGui::IsItemHovered())
                ImGui::SetTooltip(
                    "A preview at the screen's precision: a jittered grid whose median |dB| "
                    "error over echoing bins\nis estimated at %.3f dB (rel L1 %.2f %%), against "
                    "half a grey level of the display range, %.3f dB.\nThe full-quality image "
                    "follows when the pose rests.",
                    f.error_estimate.median_abs_db, 100 * f.error_estimate.rel_l1, screen);
        } else {
            estimate_line(s, f.error_estimate);
            if (f.placement_kept) {
                ImGui::TextDisabled("rays kept, re-shaded");
                if (ImGui::IsItemHovered())
                    ImGui::SetTooltip("A slider that steers the sampler changed: the last image's rays were "
                                      "re-shaded\nand their error estimate made anew with the new values "
                                      "(above). They are kept where it\nmeets the tolerances (or stays "
                                      "within one tolerance of what the trace reached),\nso no ray was "
                                      "traced. sonarsim render and a snapshot place the rays anew.");
            }
        }
    } else {
        ImGui::SameLine();
        ImGui::TextDisabled("  image: rendering...");
    }
}

} // namespace sonarsim::ui
