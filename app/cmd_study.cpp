// `sonarsim study`: work-precision report (issue 4, in progress).
#include "commands.hpp"

namespace sonarsim::app {
void register_study(CLI::App&, std::function<int()>&) {}
} // namespace sonarsim::app
