// A beam table's relative response: each beam's intensity times its gain (SonarGrid::beam_gain).
#include "core/sensor/row_effects.hpp"

namespace sonarsim {
namespace {

class BeamGain final : public RowEffect {
  public:
    explicit BeamGain(const SonarGrid& grid) {
        for (int b = 0; b < grid.beams; ++b) gain_.push_back(grid.beam_gain(b));
    }
    void apply(int, double, double* row) const override {
        for (size_t b = 0; b < gain_.size(); ++b) row[b] *= gain_[b];
    }

  private:
    std::vector<double> gain_;
};

} // namespace

std::unique_ptr<const RowEffect> make_beam_gain(const RowContext& c) {
    if (!c.grid.table()) return nullptr; // an even fan: every beam 1
    return std::make_unique<BeamGain>(c.grid);
}

} // namespace sonarsim
