#include "core/sensor/row_effects.hpp"

namespace sonarsim {

// Each defined in its own file.
std::unique_ptr<const RowEffect> make_beam_gain(const RowContext& context);
std::unique_ptr<const RowEffect> make_k_texture(const RowContext& context);
std::unique_ptr<const RowEffect> make_noise(const RowContext& context);

const std::vector<RowEffectEntry>& row_effects() {
    static const std::vector<RowEffectEntry> table = {
        {"beam gain", make_beam_gain}, // a beam table's relative response per beam (beam_gain.cpp)
        {"K texture", make_k_texture}, // the K distribution's texture per resolution cell (k_texture.cpp)
        {"noise", make_noise},         // |sqrt(I) + n|^2 keyed by the pose (noise.cpp)
    };
    return table;
}

} // namespace sonarsim
