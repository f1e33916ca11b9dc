// The adaptive sampler's error estimate per sample beam (adaptive::sample_errors) against closed forms: how
// the merged images' differences are weighted, and how fast reports its azimuth probe per bin.
#include "core/sampling/adaptive_sampler.hpp"

#include <catch2/catch.hpp>
#include <cmath>
#include <vector>

using namespace sonarsim;
using namespace sonarsim::adaptive;

namespace {

/// One beam of levels [dB] (-inf: no echo).
PolarImage column(const std::vector<float>& db) {
    PolarImage img;
    img.bins = int(db.size()), img.beams = 1;
    img.level_db = db;
    return img;
}

double db_of(double ratio) {
    return 10 * std::log10(ratio);
}

} // namespace

TEST_CASE("sample_errors: edges in full, smooth triples at 1/4, edges refinement will split at 1/3",
          "[estimate]") {
    // Linear levels (reference 0 dB): 1, 10 and 100. Bin 0: an edge refinement will split (u = f, m != u);
    // bin 1: an edge it will not (u = m) and a smooth merge (a against m); bin 2: no echo.
    const float none = -INFINITY;
    const PolarImage f = column({0, 0, none}), u = column({0, 10, none}), m = column({10, 10, none}),
                     a = column({10, 20, none});
    EstimateImages without{&m};
    const SampleError e = sample_errors(a, f, 0.0, without).front();
    CHECK(e.den == Approx(2).epsilon(1e-12));
    CHECK(e.num == Approx(9 + (9 + 90 / 4.0)).epsilon(1e-12));
    EstimateImages with{&m};
    with.lasting_edges = &u;
    const SampleError l = sample_errors(a, f, 0.0, with).front();
    CHECK(l.num == Approx(9 * kRefinableShare + (9 + 90 / 4.0)).epsilon(1e-12));
    REQUIRE(l.diffs_db.size() == 2); // bins echoing in both
    CHECK(l.diffs_db[0] == Approx(db_of(1 + 9 * kRefinableShare)).epsilon(1e-6));
    CHECK(l.diffs_db[1] == Approx(db_of(1 + 9 + 90 / 4.0)).epsilon(1e-6));
}

TEST_CASE("sample_errors: fast reports its probe per bin as the mean over the probe_every bins around it",
          "[estimate]") {
    // Thirty bins at 0 dB, the same coarse (no elevation error); the probe saw one cell, in bin 15, whose
    // three columns echo twice what one does: scaled by the probe's stride, 9 x 1.
    const int K = 30, P = 9;
    const float none = -INFINITY;
    const PolarImage f = column(std::vector<float>(K, 0.0f));
    std::vector<float> one_db(K, none), three_db(K, none);
    one_db[15] = 0, three_db[15] = float(db_of(2));
    const PolarImage one = column(one_db), three = column(three_db);
    EstimateImages fast{&f, &one, &three, false, P};
    const SampleError e = sample_errors(f, f, 0.0, fast).front();
    CHECK(e.az_seen == Approx(P).epsilon(1e-6));
    CHECK(e.az_num == 0);
    REQUIRE(e.seen_inc_db.size() == size_t(K));
    for (int b = 0; b < K; ++b) {
        INFO("bin " << b);
        CHECK(e.diffs_db[size_t(b)] == 0);
        // Each of the nine bins centred on bin 15 takes 9 / 9: twice that against the fine level 1.
        const bool near = b >= 15 - P / 2 && b <= 15 + P / 2;
        CHECK(e.seen_inc_db[size_t(b)] == Approx(near ? db_of(1 + 2.0) : 0.0).margin(1e-6));
    }
    // Strict acts on it where it lies: its own bin, in full.
    EstimateImages strict{&f, &one, &three, true, 3};
    const SampleError s = sample_errors(f, f, 0.0, strict).front();
    CHECK(s.az_num == Approx(3).epsilon(1e-6));
    CHECK(s.seen_inc_db.empty());
    CHECK(s.diffs_db[15] == Approx(db_of(1 + 2 * 3.0)).epsilon(1e-6));
    CHECK(s.diffs_db[14] == 0);
}
