// Non-GL: the slider ranges of the viewer. Bounds, units and help come from core's parameter table; this
// only narrows each slider to the values worth sweeping (typing a value with Ctrl+click still allows any
// value the table accepts).
#pragma once
#include "core/scene/params.hpp"

#include <string>

namespace sonarsim::ui {

struct SliderRange {
    double lo = 0, hi = 1;
    bool logarithmic = false;
};

/// Range of a scene parameter ("sonar.beams") or material parameter ("nu_db"); always inside the table's
/// bounds.
SliderRange slider_range(const ValueSpec& spec);

/// Section of a scene parameter in the controls panel: "Sonar", "Water", "Sampling", "Display", or "Pose".
std::string param_section(const ParamSpec& spec);

/// A short label "key [unit]" without the section prefix.
std::string param_label(const ValueSpec& spec);

} // namespace sonarsim::ui
