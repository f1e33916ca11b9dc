// Datasets: shards reproduce a single run, --resume completes a killed run, the index lists every frame.
#include "support.hpp"

#include "core/dataset/batch.hpp"
#include "core/base/errors.hpp"
#include "core/shading/ground_truth.hpp"
#include "core/io/output.hpp"
#include "core/scene/params.hpp"

#include <catch2/catch.hpp>
#include <nlohmann/json.hpp>

using namespace sonarsim;
using namespace sonarsim::test;

namespace {

const Trajectory& path5() {
    static const Trajectory t = line_trajectory("0.2,2.3,0.9,0.5,2.1,0.8,5", {-1, 30, -39}, 10, "test");
    return t;
}

/// Every file of frame k equal in both datasets; the metadata JSON apart from its timings.
void check_same_frame(const std::string& a, const std::string& b, size_t k) {
    for (auto& o : render_outputs()) {
        if (o.wanted) continue; // not written for this scene's ideal sensor
        const std::string fa = frame_prefix(a, k) + o.suffix, fb = frame_prefix(b, k) + o.suffix;
        INFO(fa << " vs " << fb);
        auto x = file_bytes(fa), y = file_bytes(fb);
        REQUIRE(!x.empty());
        if (std::string(o.suffix) == ".json") {
            auto ja = nlohmann::json::parse(x), jb = nlohmann::json::parse(y);
            ja.erase("time_ms"), jb.erase("time_ms");
            CHECK(ja == jb);
        } else {
            CHECK(x == y);
        }
    }
}

std::vector<std::string> index_rows(const std::string& dir) {
    std::ifstream in(dir + "/index.csv");
    std::vector<std::string> rows;
    for (std::string line; std::getline(in, line);) rows.push_back(line);
    return rows;
}

} // namespace

TEST_CASE("the union of shards equals a single run byte for byte", "[batch]") {
    const SceneDesc scene = small_scene();
    const std::string single = batch_out("single"), sharded = batch_out("sharded");
    prepare_dataset(single, scene, path5());
    const BatchSummary all = run_batch(single, {});
    CHECK(all.rendered == 5);
    CHECK(all.indexed == 5);
    prepare_dataset(sharded, scene, path5());
    BatchOptions o;
    o.frames = shard_frames("1/2", 5, "--shard");
    CHECK(o.frames == std::vector<size_t>{1, 3});
    CHECK(run_batch(sharded, o).indexed == 2);
    o.frames = shard_frames("0/2", 5, "--shard");
    CHECK(run_batch(sharded, o).indexed == 5);
    for (size_t k = 0; k < 5; ++k) check_same_frame(single, sharded, k);
    // Frames differ from each other: the pose did change.
    CHECK(file_bytes(frame_prefix(single, 0) + ".npy") != file_bytes(frame_prefix(single, 4) + ".npy"));

    const auto rows = index_rows(sharded);
    REQUIRE(rows.size() == 6);
    CHECK(rows[0] == "frame,t,x,y,z,roll_deg,pitch_deg,yaw_deg,files,ms,error_median_db,error_p95_db,rays");
    CHECK(rows[3].rfind("2,0.2,0.35,2.2,0.85,-1,30,-39,frames/000002.png;frames/000002_polar.png;"
                        "frames/000002.npy;frames/000002.json,",
                        0) == 0);
}

TEST_CASE("shards of a speckled device sensor reproduce a single run byte for byte", "[batch][sensor]") {
    SceneDesc scene = small_scene();
    apply_setting(scene, "sensor.model", "device", "test");
    const Trajectory still = line_trajectory("0.3,2.4,0.9,0.3,2.4,0.9,3", {-1, 30, -39}, 10, "test");
    const std::string single = batch_out("speckle_single"), sharded = batch_out("speckle_sharded");
    prepare_dataset(single, scene, still);
    run_batch(single, {});
    prepare_dataset(sharded, scene, still);
    for (const char* shard : {"1/2", "0/2"}) {
        BatchOptions o;
        o.frames = shard_frames(shard, 3, "--shard");
        run_batch(sharded, o);
    }
    for (size_t k = 0; k < 3; ++k)
        for (const char* suffix : {".npy", "_ideal.npy", ".png"}) {
            INFO("frame " << k << suffix);
            const auto x = file_bytes(frame_prefix(single, k) + suffix);
            REQUIRE(!x.empty());
            CHECK(x == file_bytes(frame_prefix(sharded, k) + suffix));
        }
    // The pose is the same for every frame: the ideal images agree, and each frame has its own speckle.
    CHECK(file_bytes(frame_prefix(single, 0) + "_ideal.npy") ==
          file_bytes(frame_prefix(single, 2) + "_ideal.npy"));
    CHECK(file_bytes(frame_prefix(single, 0) + ".npy") != file_bytes(frame_prefix(single, 2) + ".npy"));
}

TEST_CASE("batch writes each frame's ground truth on request", "[batch][ground_truth]") {
    const std::string dir = batch_out("ground_truth");
    prepare_dataset(dir, small_scene(), path5());
    BatchOptions o;
    o.frames = {1};
    o.ground_truth = true;
    run_batch(dir, o);
    for (const std::string& name : ground_truth_names()) {
        const auto bytes = file_bytes(frame_prefix(dir, 1) + "_gt_" + name + ".npy");
        INFO(name);
        CHECK(bytes.size() > 96 * 48 * 4); // (bins, beams) of 4-byte values after the header
    }
    CHECK(file_bytes(frame_prefix(dir, 0) + "_gt_object_id.npy").empty()); // frame 0 was not rendered
}

TEST_CASE("resume after a killed run completes the set", "[batch]") {
    const SceneDesc scene = small_scene();
    const std::string ref = batch_out("resume_ref"), dir = batch_out("resume");
    prepare_dataset(ref, scene, path5());
    run_batch(ref, {});
    prepare_dataset(dir, scene, path5());
    BatchOptions first;
    first.frames = {0, 1, 2, 3};
    run_batch(dir, first);
    // The kill: frame 3 in flight, two of its files renamed, the others left as temporaries; frame 4 never
    // started.
    std::filesystem::rename(frame_prefix(dir, 3) + ".json", frame_prefix(dir, 3) + ".json.tmp-1-abc");
    std::filesystem::remove(frame_prefix(dir, 3) + ".npy");
    SceneDesc base;
    Trajectory stored;
    load_dataset(dir, base, stored);
    CHECK_FALSE(frame_complete(dir, 3, base));
    CHECK(frame_complete(dir, 2, base));

    BatchOptions resume;
    resume.resume = true;
    std::vector<size_t> seen;
    resume.progress = [&](const BatchProgress& p) { seen.push_back(p.rendered); };
    const BatchSummary r = run_batch(dir, resume);
    CHECK(r.rendered == 2); // frames 3 and 4
    CHECK(r.skipped == 3);
    CHECK(seen == std::vector<size_t>{0, 0, 0, 1, 2});
    CHECK(r.indexed == 5);
    for (size_t k = 0; k < 5; ++k) check_same_frame(ref, dir, k);
    CHECK(index_rows(dir).size() == 6);
}

TEST_CASE("a dataset directory of another scene or trajectory is refused", "[batch]") {
    const SceneDesc scene = small_scene();
    const std::string dir = batch_out("other");
    prepare_dataset(dir, scene, path5());
    prepare_dataset(dir, scene, path5()); // the same again: fine (shards, resume)
    SceneDesc other = scene;
    other.sonar.range_max_m = 4;
    CHECK_THROWS_AS(prepare_dataset(dir, other, path5()), InputError);
    Trajectory shorter = path5();
    shorter.pop_back();
    CHECK_THROWS_AS(prepare_dataset(dir, scene, shorter), InputError);
    SceneDesc loaded;
    Trajectory t;
    load_dataset(dir, loaded, t);
    CHECK(t.size() == 5);
    CHECK(loaded.sonar.beams == 48);
    CHECK_THROWS_WITH(shard_frames("2/2", 5, "--shard"),
                      "--shard: \"2/2\": expected i/n with 0 <= i < n, e.g. 0/4");
    CHECK_THROWS_AS(dataset_images(dir, 5, "--aris"), InputError); // nothing rendered yet
}
