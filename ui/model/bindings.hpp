// Every mouse and key binding of the viewer, in one table: Help -> Controls lists it, README.md documents it
// (tests/ui checks that README names each one).
#pragma once
#include <vector>

namespace sonarsim::ui {

struct Binding {
    const char* where; ///< "3D view", "Sonar image", "Keys", "Sliders"
    const char* input; ///< e.g. "Ctrl+Z"
    const char* action;
};

const std::vector<Binding>& bindings();

} // namespace sonarsim::ui
