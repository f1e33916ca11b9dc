// `sonarsim view`: placeholder until the viewer lands (issue 3).
#include "commands.hpp"

#include <iostream>

namespace sonarsim::app {

void register_view(CLI::App&, std::function<int()>&) {}

int run_default_view() {
    std::cerr << "sonarsim: the viewer is not built yet; use `sonarsim render --out PREFIX`\n";
    return 1;
}

} // namespace sonarsim::app
