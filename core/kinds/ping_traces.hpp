// The hits of pings traced earlier, kept between render_pings calls by channel and transducer pose: a ping
// heard again from the same pose, in a scene whose geometry and ray placement are unchanged, is shaded from
// them and traces nothing (a slider of the mission, a still side-scan's repeated pings). While nothing but
// the poses changes, the pings' levels are kept too: a ping heard again with the same noise draw is copied
// (a waterfall scrolling along a played trajectory makes only its new pings).
#pragma once
#include "core/data/hits.hpp"
#include "core/data/scene.hpp"

#include <array>
#include <cstddef>
#include <cstdint>
#include <functional>
#include <map>
#include <memory>
#include <optional>
#include <set>
#include <utility>
#include <vector>

namespace sonarsim {

/// One channel's transducer pose, bit for bit: the key of a ping's hits.
struct PingKey {
    int channel = 0;
    std::array<double, 6> pose{}; ///< position [m], then orientation [deg]
    PingKey(int channel, const Pose& p);
    Pose as_pose() const;
    bool operator<(const PingKey& o) const;
};

/// One ping's and channel's levels as a series made them.
struct PingLevels {
    std::vector<float> level_db; ///< through the sensor [dB]
    std::vector<float> ideal_db; ///< L_EN
    bool preview = false;        ///< from a preview's hits
};

class PingTraces {
  public:
    /// What the hits of one series may hold at most; past it the later pings are not kept (they are traced
    /// again next time).
    static constexpr std::size_t kDefaultBudgetBytes = std::size_t(512) << 20;
    explicit PingTraces(std::size_t budget_bytes = kDefaultBudgetBytes) : budget_bytes_(budget_bytes) {}

    /// Before a series of `beam` (the one-beam imaging sonar, render_pings): drops the hits that cannot serve
    /// it. Geometry or anything the tracer reads changed: all. Ray placement changed (a value the adaptive
    /// sampler steers by, Stage::Place): a preview re-shades them; a full-quality series drops them all, or
    /// with `keep_placement` (PingControl::keep_placement) keeps them as placed for an earlier shading
    /// (placed_earlier), for the series to re-estimate.
    void prepare(const SceneDesc& beam, bool preview, bool keep_placement = false);
    /// Whether the kept hits of `key` were placed for an earlier shading than the prepared scene's (kept by
    /// prepare with keep_placement): a series of the scene's own bytes (without keep_placement) drops them.
    bool placed_earlier(const PingKey& key) const { return foreign_.count(key) != 0; }
    /// Whether they are yet to be estimated anew with the prepared scene's shading before they serve it.
    bool needs_estimate(const PingKey& key) const { return unchecked_.count(key) != 0; }
    /// The kept hits of `key` that a series of the prepared scene may shade, or null. A full-quality series
    /// does not take a preview's hits.
    std::shared_ptr<const TraceResult> find(const PingKey& key, bool preview) const;
    /// The levels of `key` with noise draw `draw` kept from a series of the prepared scene itself (only the
    /// poses and display values may differ), or null; a full-quality series does not take a preview's.
    std::shared_ptr<const PingLevels> find_levels(const PingKey& key, std::uint64_t draw, bool preview) const;
    using LevelsKey = std::pair<PingKey, std::uint64_t>;
    /// After the series of `beam`: its hits and levels replace the kept ones, as many as the budget holds
    /// (hits first). `estimated`: the series made the estimate of every kept hits that needed it
    /// (needs_estimate; a full-quality series does, a preview does not).
    void keep(const SceneDesc& beam, std::map<PingKey, std::shared_ptr<const TraceResult>> series_hits,
              std::map<LevelsKey, std::shared_ptr<const PingLevels>> series_levels, bool estimated);

    /// Hits of the prepared scene traced by a series that did not finish (cancelled): kept beside the others
    /// (replacing those placed for an earlier shading), as many as the budget holds.
    void add(std::map<PingKey, std::shared_ptr<const TraceResult>> hits);

    std::size_t kept_bytes() const { return hits_bytes_ + levels_bytes_; }
    std::size_t kept_pings() const { return hits_.size(); }
    std::size_t budget_bytes() const { return budget_bytes_; }

  private:
    std::size_t budget_bytes_;
    std::size_t hits_bytes_ = 0, levels_bytes_ = 0;
    std::optional<SceneDesc> placed_for_; ///< the beam scene the kept hits were placed for
    std::optional<SceneDesc> levels_for_; ///< the beam scene the kept levels were made with
    std::map<PingKey, std::shared_ptr<const TraceResult>> hits_;
    std::map<LevelsKey, std::shared_ptr<const PingLevels>> levels_;
    std::set<PingKey> foreign_;   ///< kept hits placed for an earlier shading (placed_earlier)
    std::set<PingKey> unchecked_; ///< ... not yet estimated anew with the prepared scene (needs_estimate)
    /// Drops the kept levels of the keys `drop` says.
    void drop_levels(const std::function<bool(const PingKey&)>& drop);
};

} // namespace sonarsim
