// The derived columns of a row: the viewer's label and slider range, section titles, and a material row's
// accessors.
#include "core/scene/param_spec.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace sonarsim {

const char* section_title(Section section) {
    switch (section) {
    case Section::None:
        return "";
    case Section::Pose:
        return "Pose";
    case Section::Sonar:
        return "Sonar";
    case Section::Water:
        return "Water";
    case Section::Material:
    case Section::Object:
        return "Object / material";
    case Section::Display:
        return "Display";
    case Section::Sensor:
        return "Sensor";
    case Section::Sampling:
        return "Sampling";
    case Section::Motion:
        return "Motion during a frame";
    }
    return "";
}

std::string ValueSpec::label_text() const {
    std::string name = label;
    if (name.empty()) {
        const size_t dot = key.find('.');
        name = dot == std::string::npos ? key : key.substr(dot + 1);
        for (const char* suffix : {"_khz", "_deg", "_db", "_m", "_c"}) {
            const std::string x(suffix);
            if (name.size() > x.size() && name.compare(name.size() - x.size(), x.size(), x) == 0) {
                name.resize(name.size() - x.size());
                break;
            }
        }
        std::replace(name.begin(), name.end(), '_', ' ');
    }
    return unit.empty() ? name : name + " [" + unit + "]";
}

SliderRange ValueSpec::slider_range() const {
    return slider.lo < slider.hi ? slider : SliderRange{min, max, false};
}

double MaterialSpec::value_of(const json& v) const {
    return v.is_null() ? std::numeric_limits<double>::infinity() : v.get<double>();
}

json MaterialSpec::get(const Material& m) const {
    const double v = m.*field;
    return std::isfinite(v) ? json(v) : json(nullptr);
}

} // namespace sonarsim
