// The K distribution's texture: with K speckle, each (range bin, beam) times a Gamma(alpha, 1/alpha)
// variate keyed by the world point the cell stands for (the beam's echo-weighted elevation), on a grid of
// half a range bin (or half the beam spacing across), so a scatterer keeps its texture as the sonar moves.
#include "core/sensor/row_effects.hpp"

#include "core/sensor/keyed_variates.hpp"
#include "core/sensor/speckle_field.hpp"

#include <algorithm>

namespace sonarsim {
namespace {

class KTexture final : public RowEffect {
  public:
    explicit KTexture(const RowContext& c)
        : frame_(c.scene), elevation_(c.inputs->elevation_rad.data()), beams_(c.grid.beams),
          shape_(c.scene.sensor.speckle_k_shape),
          seed_(mix64(std::uint64_t(c.scene.sensor.seed) ^ 0x737065636b6c65ULL)), // "speckle"
          spacing_rad_(c.grid.spacing_rad), bin_m_(c.grid.bin_m) {
        for (int b = 0; b < beams_; ++b) {
            const glm::dvec3 a = frame_.ahead(c.grid.beam_azimuth_rad(b));
            ahead_x_.push_back(a.x), ahead_y_.push_back(a.y), ahead_z_.push_back(a.z);
        }
    }

    void apply(int bin, double r, double* v) const override {
        const int N = beams_;
        if (!std::any_of(v, v + N, [](double x) { return x > 0; })) return;
        struct Scratch {
            std::vector<double> rise, reach, texture;
            std::vector<std::uint32_t> key;
        };
        thread_local Scratch w; // a leaf task's: nothing else runs on this thread while it is in use
        for (auto* a : {&w.rise, &w.reach, &w.texture}) a->resize(size_t(N));
        w.key.resize(size_t(N));
        frame_.raise(r, N, 1, elevation_ + size_t(bin) * size_t(N), w.rise.data(), w.reach.data());
        WorldKeyGrid(seed_, std::min(bin_m_, r * spacing_rad_))
            .keys(N,
                  frame_.points(w.rise.data(), w.reach.data(), ahead_x_.data(), ahead_y_.data(),
                                ahead_z_.data()),
                  w.key.data());
        keyed::gamma_unit_mean(N, w.key.data(), shape_, w.texture.data());
        for (int b = 0; b < N; ++b) v[b] *= w.texture[size_t(b)];
    }

  private:
    SonarFrame frame_;
    const float* elevation_;
    int beams_;
    double shape_;
    std::uint64_t seed_;
    double spacing_rad_, bin_m_;
    std::vector<double> ahead_x_, ahead_y_, ahead_z_;
};

} // namespace

std::unique_ptr<const RowEffect> make_k_texture(const RowContext& c) {
    if (!c.speckle || c.scene.sensor.speckle != Speckle::K) return nullptr;
    return std::make_unique<KTexture>(c);
}

} // namespace sonarsim
