// ARIS headers a vendor tool would believe: the mode (PingMode, FrequencyHiLow, TheSystemType) from the
// device and the frequency, never from the beam count alone, and the scenes no ARIS mode holds refused.
#include "support.hpp"

#include "core/base/errors.hpp"
#include "core/io/aris.hpp"

#include <catch2/catch.hpp>

using namespace sonarsim;
using namespace sonarsim::test;

namespace {

SceneDesc with(SceneDesc s, std::initializer_list<const char*> sets) {
    for (const char* set : sets) apply_setting_text(s, set, "test");
    return s;
}

} // namespace

TEST_CASE("ARIS files hold only the beam counts and frequencies ARIS modes have", "[aris]") {
    const SceneDesc s = small_aris_scene();
    CHECK_THROWS_WITH(check_aris(with(s, {"sonar.beams=100"}), "scene.json"),
                      "scene.json: sonar.beams: an ARIS file holds 48, 64, 96 or 128 beams, got 100");
    for (const char* ok : {"sonar.beams=48", "sonar.frequency_khz=700", "sonar.frequency_khz=1100"})
        CHECK_NOTHROW(check_aris(with(s, {ok}), "scene.json"));
    CHECK_NOTHROW(check_aris(with(s, {"sonar.beams=64", "sonar.frequency_khz=1800"}), "s"));
    CHECK_NOTHROW(check_aris(with(s, {"sonar.beams=96", "sonar.frequency_khz=1800"}), "s"));
    CHECK_NOTHROW(check_aris(with(s, {"sonar.beams=128", "sonar.frequency_khz=3000"}), "s"));
    // 64 beams are ARIS 3000 LF: 3000 kHz is 67 % off its 1800 kHz.
    CHECK_THROWS_WITH(check_aris(with(s, {"sonar.beams=64", "sonar.frequency_khz=3000"}), "scene.json"),
                      "scene.json: sonar.frequency_khz: 3000 kHz is no ARIS mode of 64 beams: they are the "
                      "ARIS 3000 LF mode at 1800 kHz (allowed within 25 %); set sonar.frequency_khz=1800 or "
                      "sonar.device=aris3000-lf");
    CHECK_THROWS_WITH(
        check_aris(with(s, {"sonar.beams=128", "sonar.frequency_khz=1200"}), "--aris"),
        Catch::Contains("--aris: sonar.frequency_khz: 1200 kHz is no ARIS mode of 128 beams: they "
                        "are the ARIS 3000 HF mode at 3000 kHz"));
    // 2300 kHz is 28 % above 1800; 2200 kHz 22 %.
    CHECK_THROWS_AS(check_aris(with(s, {"sonar.beams=96", "sonar.frequency_khz=2300"}), "s"), InputError);
    CHECK_NOTHROW(check_aris(with(s, {"sonar.beams=96", "sonar.frequency_khz=2200"}), "s"));
    // An ARIS preset fixes the system: the ARIS 3000 has no 96-beam mode.
    CHECK_THROWS_WITH(
        check_aris(with(s, {"sonar.device=aris3000-hf", "sonar.beams=96"}), "scene.json"),
        "scene.json: sonar.beams: an ARIS file of the aris3000-hf preset holds 128 or 64 beams, got 96");
}
