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
            for (const auto& kept : hits_) foreign_.insert(kept.first), unchecked_.insert(kept.first);
            drop_levels([&](const PingKey& key) { return !hits_.count(key); }); // nothing to estimate from
        } else if (s <= Stage::Place) { // the levels too: a preview may have made them from these hits
            hits_.clear(), levels_.clear(), foreign_.clear(), unchecked_.clear();
            hits_bytes_ = levels_bytes_ = 0;
        }
    }
    if (!preview && !keep_placement && !foreign_.empty()) { // placed anew, as `render` places them
        for (const PingKey& key : foreign_)
            if (const auto it = hits_.find(key); it != hits_.end())
                hits_bytes_ -= hits_bytes(*it->second), hits_.erase(it);
        drop_levels([&](const PingKey& key) { return foreign_.count(key) != 0; });
        foreign_.clear(), unchecked_.clear();
    }
    placed_for_ = beam;
}

void PingTraces::drop_levels(const std::function<bool(const PingKey&)>& drop) {
    for (auto it = levels_.begin(); it != levels_.end();) {
        if (!drop(it->first.first)) {
            ++it;
            continue;
        }
        levels_bytes_ -= (it->second->level_db.size() + it->second->ideal_db.size()) * sizeof(float);
        it = levels_.erase(it);
    }
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
        const auto old = hits_.find(key);
        if (old != hits_.end() && (!foreign_.count(key) || old->second == h)) continue;
        const std::size_t bytes = hits_bytes(*h);
        const std::size_t freed = old == hits_.end() ? 0 : hits_bytes(*old->second);
        if (hits_bytes_ - freed + levels_bytes_ + bytes > budget_bytes_) break;
        hits_bytes_ += bytes - freed;
        hits_[key] = std::move(h); // traced for this scene: replaces hits placed for an earlier one
        foreign_.erase(key), unchecked_.erase(key);
    }
}

void PingTraces::keep(const SceneDesc& beam,
                      std::map<PingKey, std::shared_ptr<const TraceResult>> series_hits,
                      std::map<LevelsKey, std::shared_ptr<const PingLevels>> series_levels, bool estimated) {
    // Hits the series took from these (the same object) keep their placement's standing; those it traced
    // are this scene's own. A series that estimated its kept hits anew (full quality) checked them all.
    std::set<PingKey> foreign, unchecked;
    for (const auto& [key, hits] : series_hits) {
        const auto old = hits_.find(key);
        if (old == hits_.end() || old->second != hits) continue;
        if (foreign_.count(key)) foreign.insert(key);
        if (unchecked_.count(key) && !estimated) unchecked.insert(key);
    }
    hits_.clear(), levels_.clear(), hits_bytes_ = levels_bytes_ = 0;
    foreign_.clear(), unchecked_.clear();
    for (auto& [key, hits] : series_hits) {
        const std::size_t bytes = hits_bytes(*hits);
        if (hits_bytes_ + bytes > budget_bytes_) break;
        hits_bytes_ += bytes;
        if (foreign.count(key)) foreign_.insert(key);
        if (unchecked.count(key)) unchecked_.insert(key);
        hits_.emplace(key, std::move(hits));
    }
    for (auto& [key, levels] : series_levels) {
        // Levels made from hits placed for an earlier shading that are no longer held: nothing to check.
        if ((foreign.count(key.first) || unchecked.count(key.first)) && !hits_.count(key.first)) continue;
        const std::size_t bytes = (levels->level_db.size() + levels->ideal_db.size()) * sizeof(float);
        if (hits_bytes_ + levels_bytes_ + bytes > budget_bytes_) break;
        levels_bytes_ += bytes;
        levels_.emplace(key, std::move(levels));
    }
    levels_for_ = beam; // the levels are this series' own
}

} // namespace sonarsim
