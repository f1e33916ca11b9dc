#include "core/grid/beam_tables.hpp"

#include "core/base/embedded_files.hpp"

#include <algorithm>
#include <cstdlib>
#include <map>
#include <sstream>
#include <stdexcept>

namespace sonarsim {
namespace detail {
extern const char* const kBeamTableFiles[][2];
extern const int kBeamTableFileCount;
} // namespace detail

namespace {

/// One compiled-in table. Its rows are checked here: a malformed file is a build-time asset error, so it
/// throws std::logic_error naming the file (the tests load every table).
BeamTable parse_table(const std::string& file_name, const std::string& text) {
    BeamTable t;
    t.name = file_name.substr(0, file_name.size() - 4);
    const std::string where = "assets/devices/beam_tables/" + file_name;
    std::istringstream in(text);
    std::string line;
    bool header = false;
    while (std::getline(in, line)) {
        if (!line.empty() && line.back() == '\r') line.pop_back();
        if (line.empty()) continue;
        if (line[0] == '#') {
            if (t.title.empty()) t.title = line.substr(std::min(line.size(), line.find(':') + 2));
            continue;
        }
        if (!header) {
            if (line != "beam,device_beam,centre_deg,port_edge_deg,starboard_edge_deg,gain")
                throw std::logic_error(where + ": unexpected header '" + line + "'");
            header = true;
            continue;
        }
        std::vector<double> v;
        std::istringstream row(line);
        for (std::string cell; std::getline(row, cell, ',');) {
            char* end = nullptr;
            v.push_back(std::strtod(cell.c_str(), &end));
            if (end == cell.c_str() || *end) throw std::logic_error(where + ": bad number '" + cell + "'");
        }
        if (v.size() != 6 || int(v[0]) != t.beams())
            throw std::logic_error(where + ": row '" + line + "' is not beam " + std::to_string(t.beams()));
        t.device_beam.push_back(int(v[1]));
        t.centre_deg.push_back(v[2]), t.port_edge_deg.push_back(v[3]), t.starboard_edge_deg.push_back(v[4]);
        t.gain.push_back(v[5]);
    }
    for (int i = 0; i < t.beams(); ++i) {
        const size_t k = size_t(i);
        const bool ordered = t.port_edge_deg[k] > t.starboard_edge_deg[k] &&
                             (i == 0 || t.centre_deg[k] < t.centre_deg[k - 1]) &&
                             (i == 0 || t.port_edge_deg[k] <= t.port_edge_deg[k - 1]);
        if (!ordered) throw std::logic_error(where + ": beam " + std::to_string(i) + " is out of order");
    }
    if (t.beams() < 2) throw std::logic_error(where + ": fewer than two beams");
    return t;
}

const std::map<std::string, BeamTable>& tables() {
    static const std::map<std::string, BeamTable> all = [] {
        std::map<std::string, BeamTable> out;
        for (int i = 0; i < detail::kBeamTableFileCount; ++i) {
            const std::string name = detail::kBeamTableFiles[i][0];
            if (name.size() > 4 && name.substr(name.size() - 4) == ".csv") {
                BeamTable t = parse_table(name, detail::kBeamTableFiles[i][1]);
                out.emplace(t.name, std::move(t));
            }
        }
        return out;
    }();
    return all;
}

} // namespace

const std::vector<std::string>& beam_table_names() {
    // From the file names alone: the parameter table lists them at start-up, before any table is needed.
    static const std::vector<std::string> names =
        EmbeddedFiles{detail::kBeamTableFiles, detail::kBeamTableFileCount}.names(".csv");
    return names;
}

const BeamTable* find_beam_table(const std::string& name) {
    const auto it = tables().find(name);
    return it == tables().end() ? nullptr : &it->second;
}

} // namespace sonarsim
