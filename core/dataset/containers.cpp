#include "core/dataset/containers.hpp"

#include "core/base/errors.hpp"
#include "core/io/aris.hpp"
#include "core/io/ping_output.hpp"
#include "core/io/ros2_sonar.hpp"
#include "core/scene/params.hpp"

#include <stdexcept>

namespace sonarsim {
namespace {

ExportReport aris_frames(const ContainerJob& job, const SceneDesc& scene, const Trajectory& poses,
                         const FrameImageSource& images) {
    check_aris_frame_times(scene, poses, job.origin, job.times_origin);
    return write_aris(job.path, scene, poses, images, job.mapping, job.origin);
}

ExportReport mcap_frames(const ContainerJob& job, const SceneDesc& scene, const Trajectory& poses,
                         const FrameImageSource& images) {
    return write_sonar_mcap(job.path, scene, poses, images, job.type, job.mapping);
}

ExportReport mcap_pings(const ContainerJob& job, std::size_t frames, const PingFrameSource& frames_of) {
    return write_ping_mcap(job.path, frames, frames_of, job.type, job.mapping);
}

} // namespace

const std::vector<DatasetContainer>& dataset_containers() {
    static const std::vector<DatasetContainer> rows = {
        {"--aris", "ARIS recording", false, aris_frames, "frames", nullptr, nullptr, on_aris_samples,
         check_aris_frame_times},
        {"--mcap", "ROS 2 bag in MCAP", true, mcap_frames, "ProjectedSonarImage messages", mcap_pings,
         "RawSonarImage messages, one per ping", nullptr, nullptr},
    };
    return rows;
}

const DatasetContainer& dataset_container(const std::string& option) {
    for (const DatasetContainer& c : dataset_containers())
        if (option == c.option) return c;
    throw std::invalid_argument("no dataset container is written by " + option);
}

bool holds(const DatasetContainer& c, SonarKind kind) {
    return kind == SonarKind::Imaging ? c.write_frames != nullptr : c.write_pings != nullptr;
}

std::string containers_for(SonarKind kind) {
    std::string out;
    for (const DatasetContainer& c : dataset_containers())
        if (holds(c, kind)) out += (out.empty() ? "" : ", ") + std::string(c.option);
    return out;
}

void check_holds(const DatasetContainer& c, const SceneDesc& scene, const std::string& origin) {
    const SonarKind kind = scene.sonar.kind;
    if (holds(c, kind)) return;
    const std::string what =
        kind == SonarKind::Imaging ? "an imaging sonar's frames" : "a " + kind_name(kind) + " sonar's pings";
    std::string own;
    for (const PingOutput& o : ping_outputs())
        if (o.recording_of == kind && (!o.wanted || o.wanted(scene)))
            own = std::string(" (each frame also has its own ") + o.suffix + ")";
    throw InputError(origin, "sonar.kind",
                     std::string("an ") + c.name + " holds " +
                         (c.write_frames ? "an imaging sonar's frames" : "a side-scan's or scan's pings") +
                         ", not " + what + "; allowed: " + containers_for(kind) + own);
}

} // namespace sonarsim
