// sonarsim: acoustic-camera simulator. A thin main: parse the command line, run one subcommand.
#include "commands.hpp"

#include "core/errors.hpp"

#include <iostream>

int main(int argc, char** argv) {
    CLI::App app{"sonarsim: simulated forward-looking imaging sonar (acoustic camera) images"};
    app.require_subcommand(0, 1);
    std::function<int()> run;
    sonarsim::app::register_render(app, run);
    sonarsim::app::register_view(app, run);
    sonarsim::app::register_study(app, run);
    sonarsim::app::register_params(app, run);
    try {
        app.parse(argc, argv);
    } catch (const CLI::CallForHelp& e) {
        return app.exit(e);
    } catch (const CLI::ParseError& e) {
        std::cerr << "sonarsim: error: " << e.what() << " (see sonarsim --help)\n";
        return 2;
    }
    try {
        return run ? run() : sonarsim::app::run_default_view();
    } catch (const sonarsim::InputError& e) {
        std::cerr << "sonarsim: error: " << e.what() << "\n";
        return 2;
    } catch (const std::exception& e) {
        std::cerr << "sonarsim: error: " << e.what() << "\n";
        return 1;
    }
}
