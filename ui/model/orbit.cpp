#include "ui/model/orbit.hpp"

#include "core/data/pose.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numeric>

namespace sonarsim::ui {

Orbiter::Orbiter(const SceneDesc& s) : start_(s.sonar.pose) {
    const glm::dvec3 pos = to_glm(s.sonar.pose.position_m);
    const glm::dvec3 bore = rotation_matrix(s.sonar.pose.orientation_deg) * glm::dvec3(1, 0, 0);
    double reach = 0.4 * s.sonar.range_max_m;
    if (s.seafloor && bore.z < -1e-3) reach = (pos.z - s.seafloor->height_m) / -bore.z;
    centre_ = pos + reach * bore;
    radius_ = std::hypot(pos.x - centre_.x, pos.y - centre_.y);
    phi0_ = std::atan2(pos.y - centre_.y, pos.x - centre_.x);
}

Pose Orbiter::at(int frame) const {
    const double dphi = deg2rad(1.5 * frame);
    Pose p = start_;
    p.position_m[0] = centre_.x + radius_ * std::cos(phi0_ + dphi);
    p.position_m[1] = centre_.y + radius_ * std::sin(phi0_ + dphi);
    const double yaw = std::fmod(start_.orientation_deg[2] + rad2deg(dphi) + 180.0, 360.0);
    p.orientation_deg[2] = (yaw < 0 ? yaw + 360.0 : yaw) - 180.0;
    return p;
}

std::string FrameStats::json_line(size_t skip) const {
    const std::vector<double> f(frame_ms.begin() + long(std::min(skip, frame_ms.size())), frame_ms.end());
    auto mean = [](const std::vector<double>& v) {
        return v.empty() ? 0.0 : std::accumulate(v.begin(), v.end(), 0.0) / double(v.size());
    };
    auto p95 = [](std::vector<double> v) { // nearest rank
        std::sort(v.begin(), v.end());
        return v.empty() ? 0.0 : v[size_t(std::ceil(0.95 * double(v.size()))) - 1];
    };
    char buf[256];
    std::snprintf(buf, sizeof buf,
                  "{\"frames\":%zu,\"frame_ms_mean\":%.2f,\"frame_ms_p95\":%.2f,\"image_ms_mean\":%.2f,"
                  "\"image_ms_p95\":%.2f,\"images\":\"%s\"",
                  f.size(), mean(f), p95(f), mean(image_ms), p95(image_ms), preview ? "preview" : "full");
    std::string out = buf;
    if (!estimate_median_db.empty()) {
        size_t met = 0;
        for (size_t k = 0; k < estimate_median_db.size(); ++k)
            met += estimate_median_db[k] <= screen_median_db[k];
        std::snprintf(
            buf, sizeof buf,
            ",\"estimate_median_db_mean\":%.4f,\"screen_median_db_mean\":%.4f,\"at_screen_precision\":%.3f",
            mean(estimate_median_db), mean(screen_median_db),
            double(met) / double(estimate_median_db.size()));
        out += buf;
    }
    if (full_image_ms >= 0) {
        std::snprintf(buf, sizeof buf, ",\"full_image_ms\":%.2f", full_image_ms);
        out += buf;
    }
    return out + "}";
}

} // namespace sonarsim::ui
