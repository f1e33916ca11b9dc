#include "ui/model/echo_path_view.hpp"

namespace sonarsim::ui {

const EchoPath& HoveredPath::update(const RenderResult& shown, std::uint64_t shown_count, int bin, int beam) {
    if (valid_ && count_ == shown_count && bin_ == bin && beam_ == beam) return path_;
    valid_ = true, count_ = shown_count, bin_ = bin, beam_ = beam;
    const auto& f = shown.frame;
    const StrongestContribution* best = f ? f->strongest_ptr.get() : nullptr;
    path_ = best && f->hits_ptr && bin >= 0 && bin < best->bins && beam >= 0 && beam < best->beams
                ? echo_path(*f->hits_ptr, shown.scene, beam, best->at(bin, beam))
                : EchoPath{};
    return path_;
}

std::string echo_source_name(std::int32_t object_id) {
    if (object_id == 0) return "seafloor";
    if (object_id == -2) return "water surface";
    if (object_id > 0) return "object " + std::to_string(object_id - 1);
    return "nothing";
}

std::string echo_path_text(const EchoPath& p) {
    if (p.points_m.empty()) return "";
    if (p.bounces == 0) return "direct echo (" + echo_source_name(p.object_id) + ")";
    return "ghost: " + std::to_string(p.bounces) + (p.bounces == 1 ? " reflection" : " reflections") +
           " (scatterer: " + echo_source_name(p.object_id) + ")";
}

} // namespace sonarsim::ui
