// Which .json files are scene files (for the Open dialog): not the render metadata (`PREFIX.json`) that
// `render` and snapshots write beside the images. GL-free.
#pragma once
#include <string>

namespace sonarsim::ui {

/// True when `path` holds a JSON object whose top-level keys are all scene sections (those of core's
/// parameter table, seafloor, objects). Unreadable, oversized or unparsable files are not scenes.
bool looks_like_scene_file(const std::string& path);

} // namespace sonarsim::ui
