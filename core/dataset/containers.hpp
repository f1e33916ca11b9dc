// The files that pack a whole dataset for practitioners' tools (`batch --aris`, `--mcap`): one row each, with
// the batch option that asks for it, what it holds and its writers (in io/). A new container is a row of
// dataset_containers().
#pragma once
#include "core/data/scene.hpp"
#include "core/data/trajectory.hpp"
#include "core/io/byte_mapping.hpp"
#include "core/io/ros2_pings.hpp"

#include <string>
#include <vector>

namespace sonarsim {

/// What a container's writer is given: the dataset's scene (export keys of the command line) and poses,
/// the data type and, for bytes, the mapping chosen once for the whole dataset.
struct ContainerJob {
    std::string path;         ///< the file to write
    std::string origin;       ///< what errors name ("--aris", a scene file)
    std::string times_origin; ///< where the frame times came from (the dataset's trajectory.csv)
    SonarDataType type = SonarDataType::Uint8;
    ByteMapping mapping;
};

struct DatasetContainer {
    const char* option; ///< the batch option that asks for it ("--aris")
    const char* name;   ///< what batch calls the file ("ARIS recording")
    bool holds_float32; ///< can hold levels in dB (--mcap-dtype float32); else bytes under one mapping
    /// An imaging sonar's frames, and how batch counts them ("frames"); null: it holds none.
    ExportReport (*write_frames)(const ContainerJob& job, const SceneDesc& scene, const Trajectory& poses,
                                 const FrameImageSource& images);
    const char* frame_items;
    /// A side-scan's or scan's pings, and how batch counts them (one per ping); null: it holds none.
    ExportReport (*write_pings)(const ContainerJob& job, std::size_t frames,
                                const PingFrameSource& frames_of);
    const char* ping_items;
    /// Before an imaging dataset is rendered for it: the scene as the file records it (ARIS: on its samples;
    /// `note` says what moved); null: the scene as it is.
    SceneDesc (*prepare)(const SceneDesc& scene, const std::string& origin, std::string& note);
    /// Throws an InputError naming `times_origin` when the poses' times do not fit the file (ARIS: frames
    /// faster than the device images them); null: any times do. Its writer checks it again.
    void (*check_times)(const SceneDesc& scene, const Trajectory& poses, const std::string& origin,
                        const std::string& times_origin);
};

/// Every container, one row each.
const std::vector<DatasetContainer>& dataset_containers();
/// The row of a batch option ("--aris"); throws std::invalid_argument for none.
const DatasetContainer& dataset_container(const std::string& option);
/// Whether `c` holds the data of a `kind` sonar.
bool holds(const DatasetContainer& c, SonarKind kind);
/// The options of the containers that hold a `kind` sonar's data ("--mcap"; "--aris, --mcap").
std::string containers_for(SonarKind kind);
/// Throws InputError(origin, "sonar.kind", ...) unless `c` holds the data of `scene`'s kind of sonar, naming
/// those that do and the recording file each frame of this scene has besides (XTF, a Ping Viewer log).
void check_holds(const DatasetContainer& c, const SceneDesc& scene, const std::string& origin);

} // namespace sonarsim
