// Subcommands of the sonarsim executable. Each registers its options and returns its exit status.
#pragma once
#include <CLI/CLI.hpp>
#include <functional>
#include <string>
#include <vector>

namespace sonarsim::app {

/// Options shared by the commands that load a scene.
struct SceneOptions {
    std::string scene_file;
    std::string pose;
    std::vector<std::string> sets;
};
void add_scene_options(CLI::App& cmd, SceneOptions& o);

/// Registers `render`; `run` is set to the function that executes it.
void register_render(CLI::App& app, std::function<int()>& run);
void register_batch(CLI::App& app, std::function<int()>& run);
void register_params(CLI::App& app, std::function<int()>& run);
void register_devices(CLI::App& app, std::function<int()>& run);
void register_materials(CLI::App& app, std::function<int()>& run);
void register_study(CLI::App& app, std::function<int()>& run);
void register_view(CLI::App& app, std::function<int()>& run);
void register_compare(CLI::App& app, std::function<int()>& run);
/// `sonarsim` with no arguments: the viewer on the built-in scene.
int run_default_view();

} // namespace sonarsim::app
