// The scene's nested parts (core/scene/scene_parts.hpp): each part's key prefix, the routing of a key to its
// part, and a value set through a prefix landing in that part's material and nowhere else.
#include "core/base/errors.hpp"
#include "core/scene/params.hpp"
#include "core/scene/scene_io.hpp"
#include "core/scene/scene_parts.hpp"

#include <catch2/catch.hpp>

using namespace sonarsim;

TEST_CASE("the scene's parts: prefixes, routing and values land in their own material", "[params][parts]") {
    SceneDesc s = default_scene();
    s.water.surface_height_m = 3.0;
    REQUIRE(s.seafloor);
    REQUIRE(s.objects.size() >= 1);
    CHECK(material_prefix(kSurfacePart) == "water.surface_material.");
    CHECK(material_prefix(kSeafloorPart) == "seafloor.material.");
    CHECK(material_prefix(0) == "objects.0.material.");
    CHECK(part_prefix(kSeafloorPart) == "seafloor.");
    CHECK(part_prefix(0) == "objects.0.");
    const std::vector<int> parts = material_parts(s);
    CHECK(parts.size() == 2 + s.objects.size());

    const auto k = part_key(s, "objects.0.material.q", "t");
    REQUIRE(k);
    CHECK((k->part == 0 && k->material && k->field == "q"));
    const auto o = part_key(s, "objects.0.position", "t");
    REQUIRE(o);
    CHECK((o->part == 0 && !o->material && o->field == "position"));
    CHECK_FALSE(part_key(s, "sonar.beams", "t"));
    CHECK_THROWS_AS(part_key(s, "objects.7.material.q", "t"), InputError);
    CHECK_THROWS_AS(part_key(s, "objects.x.position", "t"), InputError);

    // A value set through each part's prefix changes that part's material alone, and only re-shades.
    double q = 3.25;
    for (int part : parts) {
        INFO(part);
        SceneDesc before = s;
        const Stage st = apply_setting(s, material_prefix(part) + "q", q, "t");
        CHECK(material_of(s, part)->q == q);
        for (int other : parts)
            if (other != part) CHECK(material_of(s, other)->q == material_of(before, other)->q);
        CHECK(st >= Stage::Place);
        CHECK(st <= Stage::Shade);
        q += 0.5;
    }
    SceneDesc bare = s;
    bare.seafloor.reset();
    CHECK(material_of(bare, kSeafloorPart) == nullptr);
    CHECK_THROWS_AS(apply_setting(bare, "seafloor.material.q", 2.0, "t"), InputError);
}
