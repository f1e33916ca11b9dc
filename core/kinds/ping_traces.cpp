#include "core/kinds/ping_traces.hpp"

#include "core/sampling/trace.hpp"
#include "core/scene/params.hpp"

#include <cstring>

namespace sonarsim {

PingKey::PingKey(int ch, const Pose& p) : channel(ch) {
    for (int i = 0; i < 3; ++i)
        pose[size_t(i)] = p.position_m[size_t(i)], pose[size_t(i) + 3] = p.orientation_deg[size_t(i)];
}

Pose PingKey::as_pose() const {
    Pose p;
    for (size_t i = 0; i < 3; ++i) p.position_m[i] = pose[i], p.orientation_deg[i] = pose[i + 3];
    return p;
}

bool PingKey::operator<(const PingKey& o) const {
    if (channel != o.channel) return channel < o.channel;
    // Bit for bit: a pose is the same ping's only when it is the same number (-0 and 0 are two poses here,
    // which costs a trace at most).
    return std::memcmp(pose.data(), o.pose.data(), sizeof pose) < 0;
}

namespace {

/// What changed from `before` to `beam` besides the pose and noise draw (each ping's own).
Stage changed_but_pings(SceneDesc before, const SceneDesc& beam) {
    before.sonar.pose = beam.sonar.pose;
    before.sensor.noise_draw = beam.sensor.noise_draw;
    return changed_stage(before, beam);
}

} // namespace

void PingTraces::prepare(const SceneDesc& beam, bool preview, bool keep_placement) {
    // A display value (colour map, display range) does not touch the levels.
    if (levels_for_ && changed_but_pings(*levels_for_, beam) < Stage::Display)
        levels_.clear(), levels_bytes_ = 0;
    if (placed_for_) {
        const Stage s = changed_but_pings(*placed_for_, beam);
        if (s == Stage::Place && preview) return; // re-shaded as placed for the earlier scene
        if (s == Stage::Place && keep_placement) {
            for (const auto& kept : hits_) earlier_.insert(kept.first); // the series re-estimates them
        } else if (s <= Stage::Place) { // the levels too: a preview may have made them from these hits
            hits_.clear(), earlier_.clear(), levels_.clear(), hits_bytes_ = levels_bytes_ = 0;
        }
    }
    placed_for_ = beam;
}

std::shared_ptr<const TraceResult> PingTraces::find(const PingKey& key, bool preview) const {
    const auto it = hits_.find(key);
    if (it == hits_.end() || (it->second->preview && !preview)) return nullptr;
    return it->second;
}

std::shared_ptr<const PingLevels> PingTraces::find_levels(const PingKey& key, std::uint64_t draw,
                                                          bool preview) const {
    const auto it = levels_.find({key, draw});
    if (it == levels_.end() || (it->second->preview && !preview)) return nullptr;
    return it->second;
}

void PingTraces::add(std::map<PingKey, std::shared_ptr<const TraceResult>> hits) {
    for (auto& [key, h] : hits) {
        if (hits_.count(key)) continue;
        const std::size_t bytes = hits_bytes(*h);
        if (hits_bytes_ + levels_bytes_ + bytes > budget_bytes_) break;
        hits_bytes_ += bytes;
        hits_.emplace(key, std::move(h));
    }
}

void PingTraces::keep(const SceneDesc& beam,
                      std::map<PingKey, std::shared_ptr<const TraceResult>> series_hits,
                      std::map<LevelsKey, std::shared_ptr<const PingLevels>> series_levels) {
    hits_.clear(), levels_.clear(), earlier_.clear(), hits_bytes_ = levels_bytes_ = 0;
    for (auto& [key, hits] : series_hits) { // each serves `beam`: traced for it, or estimated anew with it
        const std::size_t bytes = hits_bytes(*hits);
        if (hits_bytes_ + bytes > budget_bytes_) break;
        hits_bytes_ += bytes;
        hits_.emplace(key, std::move(hits));
    }
    for (auto& [key, levels] : series_levels) {
        const std::size_t bytes = (levels->level_db.size() + levels->ideal_db.size()) * sizeof(float);
        if (hits_bytes_ + levels_bytes_ + bytes > budget_bytes_) break;
        levels_bytes_ += bytes;
        levels_.emplace(key, std::move(levels));
    }
    levels_for_ = beam; // the levels are this series' own
}

} // namespace sonarsim
