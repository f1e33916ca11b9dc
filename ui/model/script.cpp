#include "ui/model/script.hpp"

#include "core/base/errors.hpp"
#include "core/base/file_io.hpp"

#include <algorithm>
#include <cctype>
#include <map>
#include <sstream>

namespace sonarsim::ui {
namespace {

const std::map<std::string, int>& key_names() {
    static const std::map<std::string, int> names = {
        {"escape", key::Escape},     {"esc", key::Escape},    {"enter", key::Enter},
        {"space", key::Space},       {"delete", key::Delete}, {"shift", key::LeftShift},
        {"ctrl", key::LeftControl},  {"alt", key::LeftAlt},   {"rshift", key::RightShift},
        {"rctrl", key::RightControl}};
    return names;
}

int modifier_bit(int k) {
    if (k == key::LeftShift || k == key::RightShift) return mods::Shift;
    if (k == key::LeftControl || k == key::RightControl) return mods::Control;
    if (k == key::LeftAlt || k == key::RightAlt) return mods::Alt;
    return 0;
}

int button_of(const std::string& s) {
    if (s == "left") return button::Left;
    if (s == "right") return button::Right;
    if (s == "middle") return button::Middle;
    return -1;
}

size_t arg_count(const std::string& c) {
    static const std::map<std::string, size_t> n = {{"move", 2},
                                                    {"press", 1},
                                                    {"release", 1},
                                                    {"click", 2},
                                                    {"wheel", 1},
                                                    {"key", 1},
                                                    {"keydown", 1},
                                                    {"keyup", 1},
                                                    {"screenshot", 1},
                                                    {"state", 1},
                                                    {"layout", 1},
                                                    {"snapshot", 1},
                                                    {"quit", 0},
                                                    {"open", 1},
                                                    {"move_to", 3},
                                                    {"move_by", 2},
                                                    {"trajectory_save", 1},
                                                    {"trajectory_load", 1},
                                                    {"trajectory_snapshots", 1},
                                                    {"ground_truth", 1}};
    auto it = n.find(c);
    return it == n.end() ? size_t(-1) : it->second;
}

double number(const std::string& s, const std::string& file, int line) {
    try {
        size_t used = 0;
        const double v = std::stod(s, &used);
        if (used == s.size()) return v;
    } catch (const std::exception&) {
    }
    throw InputError(file, "line " + std::to_string(line), "\"" + s + "\" is not a number");
}

} // namespace

KeyChord parse_key_chord(const std::string& text, const std::string& file, int line) {
    KeyChord k;
    std::string t = text;
    std::transform(t.begin(), t.end(), t.begin(), [](unsigned char c) { return char(std::tolower(c)); });
    std::stringstream ss(t);
    std::string part;
    std::vector<std::string> parts;
    while (std::getline(ss, part, '+')) parts.push_back(part);
    for (size_t i = 0; i < parts.size(); ++i) {
        const std::string& p = parts[i];
        int code = 0;
        if (p.size() == 1 && std::isalnum(static_cast<unsigned char>(p[0])))
            code = std::toupper(static_cast<unsigned char>(p[0]));
        else if (auto it = key_names().find(p); it != key_names().end())
            code = it->second;
        else
            throw InputError(file, "line " + std::to_string(line),
                             "unknown key \"" + p + "\" in \"" + text + "\"");
        if (i + 1 < parts.size()) {
            if (!modifier_bit(code))
                throw InputError(file, "line " + std::to_string(line), "\"" + p + "\" is not a modifier");
            k.mods |= modifier_bit(code);
        } else {
            k.key = code;
        }
    }
    return k;
}

bool is_input_command(const std::string& c) {
    return c == "move" || c == "move_to" || c == "move_by" || c == "press" || c == "release" ||
           c == "click" || c == "wheel" || c == "key" || c == "keydown" || c == "keyup";
}

std::vector<ScriptStep> parse_script(const std::string& text, const std::string& file) {
    std::vector<ScriptStep> steps;
    std::istringstream in(text);
    std::string row;
    int line = 0, last_frame = 0;
    while (std::getline(in, row)) {
        ++line;
        row = row.substr(0, row.find('#'));
        std::istringstream words(row);
        std::vector<std::string> w;
        for (std::string s; words >> s;) w.push_back(s);
        if (w.empty()) continue;
        const std::string where = "line " + std::to_string(line);
        if (w.size() < 2) throw InputError(file, where, "expected FRAME COMMAND ARGS...");
        ScriptStep st;
        st.line = line;
        const double f = number(w[0], file, line);
        if (f < 0 || f != int(f) || f < last_frame)
            throw InputError(file, where, "the frame must be a whole number, not below the line before");
        st.frame = last_frame = int(f);
        st.command = w[1];
        st.args.assign(w.begin() + 2, w.end());
        const size_t n = arg_count(st.command);
        if (n == size_t(-1)) throw InputError(file, where, "unknown command \"" + st.command + "\"");
        if (st.args.size() != n)
            throw InputError(file, where, st.command + " takes " + std::to_string(n) + " argument(s)");
        if (st.command == "move" || st.command == "click" || st.command == "wheel" || st.command == "move_by")
            for (auto& a : st.args) number(a, file, line);
        if (st.command == "move_to") number(st.args[1], file, line), number(st.args[2], file, line);
        if ((st.command == "press" || st.command == "release") && button_of(st.args[0]) < 0)
            throw InputError(file, where, "expected left, right or middle");
        if (st.command == "key" || st.command == "keydown" || st.command == "keyup")
            parse_key_chord(st.args[0], file, line);
        steps.push_back(std::move(st));
    }
    return steps;
}

std::vector<ScriptStep> load_script(const std::string& path) {
    return parse_script(read_file_bytes(path, kAnyFileSize, {path, "", "", "cannot read the script"}), path);
}

std::vector<InputEvent> step_events(const ScriptStep& st, glm::dvec2& pos, int& held) {
    using T = InputEvent::Type;
    std::vector<InputEvent> out;
    auto ev = [&](T type) {
        InputEvent e;
        e.type = type;
        e.pos = pos;
        e.mods = held;
        return e;
    };
    auto key_event = [&](int code, bool press) {
        // GLFW on X11 reports the modifiers held before the event.
        InputEvent e = ev(T::Key);
        e.key = code;
        e.key_down = press;
        out.push_back(e);
        const int bit = modifier_bit(code);
        held = press ? (held | bit) : (held & ~bit);
    };
    const std::string& c = st.command;
    if (c == "move" || c == "click") {
        pos = {std::stod(st.args[0]), std::stod(st.args[1])};
        out.push_back(ev(T::Move));
    }
    if (c == "move_by") {
        pos += glm::dvec2(std::stod(st.args[0]), std::stod(st.args[1]));
        out.push_back(ev(T::Move));
    }
    if (c == "press" || c == "click") {
        InputEvent e = ev(T::Press);
        e.button = c == "click" ? button::Left : button_of(st.args[0]);
        out.push_back(e);
    }
    if (c == "release" || c == "click") {
        InputEvent e = ev(T::Release);
        e.button = c == "click" ? button::Left : button_of(st.args[0]);
        out.push_back(e);
    }
    if (c == "wheel") {
        InputEvent e = ev(T::Wheel);
        e.wheel = std::stod(st.args[0]);
        out.push_back(e);
    }
    if (c == "key" || c == "keydown" || c == "keyup") {
        const KeyChord k = parse_key_chord(st.args[0], "script", st.line);
        const int mod_keys[3][2] = {
            {mods::Control, key::LeftControl}, {mods::Shift, key::LeftShift}, {mods::Alt, key::LeftAlt}};
        if (c != "keyup")
            for (auto& m : mod_keys)
                if (k.mods & m[0]) key_event(m[1], true);
        if (c != "keyup") key_event(k.key, true);
        if (c != "keydown") key_event(k.key, false);
        if (c != "keydown")
            for (auto& m : mod_keys)
                if (k.mods & m[0]) key_event(m[1], false);
    }
    return out;
}

} // namespace sonarsim::ui
