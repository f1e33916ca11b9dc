// sonarsim: acoustic-camera simulator. A thin main: parse the command line, run one subcommand.
#include "commands.hpp"

#include "core/base/errors.hpp"

#include <iostream>
#include <new>

int main(int argc, char** argv) {
    CLI::App app{"sonarsim: simulated forward-looking imaging sonar (acoustic camera) images"};
    app.require_subcommand(0, 1);
    std::function<int()> run;
    sonarsim::app::register_render(app, run);
    sonarsim::app::register_view(app, run);
    sonarsim::app::register_study(app, run);
    sonarsim::app::register_batch(app, run);
    sonarsim::app::register_params(app, run);
    sonarsim::app::register_devices(app, run);
    sonarsim::app::register_materials(app, run);
    sonarsim::app::register_compare(app, run);
    // Exit status: 0 done, 2 bad input (command line, scene file, mesh), 1 anything else (I/O, memory).
    // Every error is one line on stderr.
    using sonarsim::InputError;
    try {
        app.parse(argc, argv);
    } catch (const CLI::ParseError& e) {
        if (e.get_exit_code() == 0) return app.exit(e); // --help and the like
        if (argc > 1 && argv[1][0] != '-' &&
            !app.get_subcommands().size()) { // a first word that is no command
            std::string commands;
            for (const CLI::App* c : app.get_subcommands({}))
                commands += (commands.empty() ? "" : ", ") + c->get_name();
            std::cerr << "sonarsim: error: unknown command \"" << InputError::printable(argv[1])
                      << "\"; the commands are " << commands << " (see sonarsim --help)\n";
            return 2;
        }
        std::cerr << "sonarsim: error: " << InputError::printable(e.what()) << " (see sonarsim --help)\n";
        return 2;
    }
    try {
        return run ? run() : sonarsim::app::run_default_view();
    } catch (const InputError& e) {
        std::cerr << "sonarsim: error: " << e.what() << "\n";
        return 2;
    } catch (const std::bad_alloc&) {
        std::cerr << "sonarsim: error: out of memory\n";
        return 1;
    } catch (const std::exception& e) {
        std::cerr << "sonarsim: error: " << InputError::printable(e.what()) << "\n";
        return 1;
    }
}
