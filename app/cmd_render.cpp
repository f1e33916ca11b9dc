// `sonarsim render`: one image of a scene, written as PNG, .npy and metadata JSON.
#include "commands.hpp"
#include "load.hpp"

#include "core/errors.hpp"
#include "core/simulator.hpp"

#include <filesystem>
#include <iostream>
#include <memory>

namespace sonarsim::app {
namespace {

struct RenderOptions {
    SceneOptions scene;
    std::string out;
};

int run_render(const RenderOptions& o) {
    const SceneDesc scene = load_scene_from_options(o.scene);
    const std::filesystem::path prefix(o.out);
    const auto dir = prefix.parent_path().empty() ? std::filesystem::path(".") : prefix.parent_path();
    std::error_code ec;
    if (!std::filesystem::is_directory(dir, ec))
        throw InputError("--out", "", "directory \"" + dir.string() + "\" does not exist");

    Simulator sim(scene);
    const Frame& f = sim.render();
    write_render_files(o.out, scene, f);
    std::cout << "wrote " << o.out << ".png (sector image " << f.sector.width << "x" << f.sector.height
              << "), " << o.out << "_polar.png, " << o.out << ".npy (L_EN dB, " << f.polar.bins << " x "
              << f.polar.beams << "), " << o.out << ".json\n"
              << "rays " << f.hits.rays_traced << ", trace " << f.trace_ms << " ms, shade " << f.shade_ms
              << " ms, image " << f.image_ms << " ms\n";
    return 0;
}

} // namespace

void register_render(CLI::App& app, std::function<int()>& run) {
    auto o = std::make_shared<RenderOptions>();
    CLI::App* cmd = app.add_subcommand("render", "Render one sonar image headless (PNG, .npy, .json)");
    add_scene_options(*cmd, o->scene);
    cmd->add_option("--out", o->out,
                    "Output prefix: writes PREFIX.png, PREFIX_polar.png, PREFIX.npy, PREFIX.json")
        ->required();
    cmd->callback([o, &run] { run = [o] { return run_render(*o); }; });
}

} // namespace sonarsim::app
