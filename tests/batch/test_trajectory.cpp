// Trajectory files and generated paths.
#include "core/base/errors.hpp"
#include "core/data/pose.hpp"
#include "core/data/trajectory.hpp"

#include <catch2/catch.hpp>

using namespace sonarsim;

namespace {
std::string error_of(const std::string& text) {
    try {
        parse_trajectory_csv(text, "T.csv");
    } catch (const InputError& e) {
        return e.what();
    }
    return "no error";
}
} // namespace

TEST_CASE("a trajectory file gives one pose per row", "[trajectory]") {
    const Trajectory t =
        parse_trajectory_csv("# a comment\nt,x,y,z,roll_deg,pitch_deg,yaw_deg\r\n0,1,2,3,4,5,6\n\n0.5, -1, "
                             "2.5e-1, 3, 0, 30, -90\n",
                             "T.csv");
    REQUIRE(t.size() == 2);
    CHECK(t[1].t_s == 0.5);
    CHECK(t[1].pose.position_m == Vec3d{-1, 0.25, 3});
    CHECK(t[1].pose.orientation_deg == Vec3d{0, 30, -90});
    const Trajectory again = parse_trajectory_csv(trajectory_to_csv(t), "again");
    REQUIRE(again.size() == 2);
    CHECK(again[0].pose.orientation_deg == Vec3d{4, 5, 6});
}

TEST_CASE("bad trajectory files name the file and the line and the column", "[trajectory]") {
    const std::string header = "t,x,y,z,roll_deg,pitch_deg,yaw_deg\n";
    CHECK(error_of(header + "0,0,0,0,0,0,0\n1,0,0,0,0,abc,0\n") ==
          "T.csv:3: pitch_deg: \"abc\" is not a finite number");
    CHECK(error_of(header + "0,0,0,0,0,0\n") == "T.csv:2: expected 7 columns, got 6");
    CHECK(error_of("t,x,y,z\n") == "T.csv:1: expected the header \"t,x,y,z,roll_deg,pitch_deg,yaw_deg\"");
    CHECK(error_of(header) == "T.csv: no frames after the header");
    CHECK(error_of(header + "1,0,0,0,0,0,0\n0.5,0,0,0,0,0,0\n") ==
          "T.csv:3: t: time goes backwards (0.5 s after 1 s)");
    CHECK(error_of(header + "0,0,inf,0,0,0,0\n") == "T.csv:2: y: \"inf\" is not a finite number");
}

TEST_CASE("a circle looks at its centre from every pose", "[trajectory]") {
    const Trajectory t = circle_trajectory("1.5,-2,0.25,3,1,12", 4.0, "--circle");
    REQUIRE(t.size() == 12);
    for (size_t k = 0; k < t.size(); ++k) {
        const Polar p = world_to_sonar_polar(t[k].pose, {1.5, -2, 0.25});
        CHECK(p.range_m == Approx(std::sqrt(10.0)).margin(1e-9));
        CHECK(p.azimuth_deg == Approx(0).margin(1e-9));
        CHECK(p.elevation_deg == Approx(0).margin(1e-9));
        CHECK(t[k].pose.position_m[2] == Approx(1.25));
        CHECK(t[k].t_s == Approx(0.25 * double(k)));
    }
    CHECK(t[3].pose.position_m[0] == Approx(1.5).margin(1e-12)); // a quarter turn: on +y of the centre
    CHECK(t[3].pose.position_m[1] == Approx(1.0));
}

TEST_CASE("a line runs from end to end with a fixed orientation", "[trajectory]") {
    const Trajectory t = line_trajectory("0,0,1,4,2,1,5", {0, 20, 45}, 10.0, "--line");
    REQUIRE(t.size() == 5);
    CHECK(t[0].pose.position_m == Vec3d{0, 0, 1});
    CHECK(t[4].pose.position_m == Vec3d{4, 2, 1});
    CHECK(t[1].pose.position_m[0] == Approx(1.0));
    CHECK(t[2].pose.orientation_deg == Vec3d{0, 20, 45});
    CHECK(t[4].t_s == Approx(0.4));
    CHECK_THROWS_WITH(line_trajectory("0,0,1,4,2,1,0", {}, 10, "--line"),
                      "--line: frames: \"0\" is not an integer in [1, 1000000]");
    CHECK_THROWS_WITH(circle_trajectory("0,0,0,1,1", 10, "--circle"),
                      "--circle: \"0,0,0,1,1\": expected cx,cy,cz,radius_m,height_m,frames");
}

TEST_CASE("a trajectory comes from exactly one of a file or a circle or a line", "[trajectory]") {
    CHECK(make_trajectory("", "0,0,0,1,1,3", "", 10, {}).size() == 3);
    CHECK(make_trajectory("", "", "0,0,1,4,2,1,4", 10, {0, 10, 20})[3].pose.orientation_deg ==
          Vec3d{0, 10, 20});
    CHECK_THROWS_WITH(make_trajectory("", "", "", 10, {}), Catch::Contains("give exactly one of"));
    CHECK_THROWS_WITH(make_trajectory("t.csv", "0,0,0,1,1,3", "", 10, {}),
                      Catch::Contains("give exactly one of"));
    CHECK_THROWS_WITH(make_trajectory("no/such.csv", "", "", 10, {}),
                      "no/such.csv: trajectory file cannot be read");
}
