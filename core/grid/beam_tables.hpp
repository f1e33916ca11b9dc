// Per-beam angle tables of real devices (assets/devices/beam_tables/NAME.csv, compiled in like the presets):
// each beam's centre and edges [deg, positive = port], in sonarsim's order (beam 0 port-most), the device's
// own number of each beam and an optional relative gain. `sonar.beam_table` names one; `uniform` is none.
#pragma once
#include <string>
#include <vector>

namespace sonarsim {

struct BeamTable {
    std::string name;                       ///< file name without .csv
    std::string title;                      ///< the file's first comment line
    std::vector<double> centre_deg;         ///< per beam, beam 0 port-most [deg]
    std::vector<double> port_edge_deg;      ///< per beam: its port (upper) edge [deg]
    std::vector<double> starboard_edge_deg; ///< per beam: its starboard (lower) edge [deg]
    std::vector<double> gain;               ///< per beam: relative response (1 = none)
    std::vector<int> device_beam;           ///< per beam: the device's number of it
    int beams() const { return int(centre_deg.size()); }
};

/// The value of `sonar.beam_table` that means evenly spaced beams (eq. 10).
inline const char* const kUniformBeams = "uniform";

/// Every table's name, sorted (without "uniform").
const std::vector<std::string>& beam_table_names();
/// The table of that name, or null.
const BeamTable* find_beam_table(const std::string& name);

} // namespace sonarsim
