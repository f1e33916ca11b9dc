// `sonarsim params`: the parameter table (name, unit, default, allowed, help) that scene files, --set and
// the viewer's sliders share, as Markdown.
#include "commands.hpp"

#include "core/scene/params.hpp"

#include <iostream>

namespace sonarsim::app {

void register_params(CLI::App& app, std::function<int()>& run) {
    CLI::App* cmd =
        app.add_subcommand("params", "Print every scene parameter with unit, default and allowed range");
    cmd->callback([&run] {
        run = [] {
            std::cout << params_markdown();
            return 0;
        };
    });
}

} // namespace sonarsim::app
