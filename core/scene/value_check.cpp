// Checks of one value against its row: type, bounds (exclusive where flagged), choices; the text of what a
// row allows, for errors and the docs.
#include "core/scene/params.hpp"

#include "core/base/errors.hpp"

#include <cmath>
#include <cstdlib>
#include <sstream>

namespace sonarsim {
namespace {

std::string type_name(const json& v) {
    if (v.is_null()) return "null";
    if (v.is_boolean()) return "a boolean";
    if (v.is_number()) return "a number";
    if (v.is_string()) {
        // "nan", "inf", "1e999": a number's text that is no finite number.
        const std::string& t = v.get_ref<const std::string&>();
        char* end = nullptr;
        const double x = t.empty() ? 0.0 : std::strtod(t.c_str(), &end);
        if (!t.empty() && end && *end == '\0' && !std::isfinite(x))
            return "\"" + t + "\", not a finite number";
        return "a string";
    }
    if (v.is_array()) return "an array";
    return "an object";
}

void check_number(const ValueSpec& spec, double x, const std::string& file, const std::string& key) {
    const bool below = spec.min_exclusive ? !(x > spec.min) : !(x >= spec.min);
    const bool above = spec.max_exclusive ? !(x < spec.max) : !(x <= spec.max);
    if (!std::isfinite(x) || below || above)
        throw InputError(file, key,
                         "value " + number_text(x) + " is out of range; allowed: " + allowed_text(spec));
}

} // namespace

std::string number_text(double v) {
    std::ostringstream s;
    if (std::isfinite(v) && v == std::floor(v) && std::abs(v) < 1e15)
        s << static_cast<long long>(v); // whole numbers in plain digits: 50000000, not 5e+07
    else
        s << v;
    return s.str();
}

std::string allowed_text(const ValueSpec& spec) {
    if (spec.type == ParamType::Enum) {
        std::string s = "one of";
        for (size_t i = 0; i < spec.choices.size(); ++i) s += (i ? ", \"" : " \"") + spec.choices[i] + "\"";
        return s;
    }
    std::string range = std::string(spec.min_exclusive ? "(" : "[") + number_text(spec.min) + ", " +
                        number_text(spec.max) + (spec.max_exclusive ? ")" : "]");
    std::string unit = spec.unit.empty() ? "" : " " + spec.unit;
    if (spec.type == ParamType::Bool) return "true or false";
    if (spec.type == ParamType::String) return "a string";
    if (spec.type == ParamType::Integer) return "an integer in " + range;
    if (spec.type == ParamType::Vec3) return "an array of 3 finite numbers in " + range + unit;
    return "a finite number in " + range + unit + (spec.optional ? ", or null (absent)" : "");
}

json validate_value(const ValueSpec& spec, const json& v, const std::string& file, const std::string& key) {
    if (spec.optional && v.is_null()) return v;
    switch (spec.type) {
    case ParamType::Number:
        if (!v.is_number())
            throw InputError(file, key, "expected " + allowed_text(spec) + ", got " + type_name(v));
        check_number(spec, v.get<double>(), file, key);
        return json(v.get<double>());
    case ParamType::Integer: {
        if (!v.is_number())
            throw InputError(file, key, "expected " + allowed_text(spec) + ", got " + type_name(v));
        const double x = v.get<double>();
        if (!std::isfinite(x) || x != std::floor(x))
            throw InputError(
                file, key, "value " + number_text(x) + " is not an integer; allowed: " + allowed_text(spec));
        check_number(spec, x, file, key);
        return json(int(x));
    }
    case ParamType::Vec3: {
        if (!v.is_array() || v.size() != 3)
            throw InputError(file, key,
                             "expected " + allowed_text(spec) + ", got " +
                                 (v.is_array() ? "an array of " + std::to_string(v.size()) : type_name(v)));
        Vec3d out{};
        for (size_t i = 0; i < 3; ++i) {
            const std::string ki = key + "[" + std::to_string(i) + "]";
            if (!v[i].is_number()) throw InputError(file, ki, "expected a number, got " + type_name(v[i]));
            check_number(spec, v[i].get<double>(), file, ki);
            out[i] = v[i].get<double>();
        }
        return json(out);
    }
    case ParamType::String:
        if (!v.is_string()) throw InputError(file, key, "expected a string, got " + type_name(v));
        return v;
    case ParamType::Bool:
        if (!v.is_boolean()) throw InputError(file, key, "expected true or false, got " + type_name(v));
        return v;
    case ParamType::Enum:
        if (v.is_string())
            for (auto& c : spec.choices)
                if (c == v.get<std::string>()) return v;
        throw InputError(file, key,
                         "got " + (v.is_string() ? "\"" + v.get<std::string>() + "\"" : type_name(v)) +
                             "; allowed: " + allowed_text(spec));
    }
    return v;
}

} // namespace sonarsim
