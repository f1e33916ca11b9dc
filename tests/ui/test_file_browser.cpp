// The Open dialog's logic: a single click selects (files and folders alike), a double click or Enter opens
// (enters a folder, chooses a file); a double click on a folder never opens a file of the folder it enters.
#include "support.hpp"

#include "ui/model/file_browser.hpp"
#include "ui/model/input_events.hpp"

#include <catch2/catch.hpp>
#include <filesystem>
#include <fstream>
#include <functional>

using namespace sonarsim::ui;
namespace fs = std::filesystem;

namespace {

/// A tree of its own per test case: ctest runs the cases as parallel processes.
std::string case_dir() {
    const std::string name = Catch::getResultCapture().getCurrentTestName();
    return "file_browser/" + std::to_string(std::hash<std::string>{}(name));
}

struct Tree {
    fs::path root = fs::path(sonarsim::test::ui_out_path(case_dir()));
    Tree() {
        fs::remove_all(root);
        fs::create_directories(root / "scenes");
        fs::create_directories(root / "meshes");
        for (const char* f : {"a.json", "notes.txt", "scenes/fig9.json", "scenes/tank.json"})
            std::ofstream(root / f) << "{}";
    }
    size_t index_of(const FileBrowser& b, const std::string& name) const {
        for (size_t i = 0; i < b.entries().size(); ++i)
            if (b.entries()[i].name == name) return i;
        FAIL("no entry " << name);
        return 0;
    }
};

} // namespace

TEST_CASE("the listing: parent, folders, then the files that pass the filter", "[ui][file_dialog]") {
    Tree t;
    FileBrowser b;
    b.open(t.root.string(), {".json"});
    std::vector<std::string> names;
    for (const auto& e : b.entries()) names.push_back(e.name);
    CHECK(names == std::vector<std::string>{"../", "meshes/", "scenes/", "a.json"});
    CHECK(b.selected() == -1);
}

TEST_CASE("a single click selects a folder without entering it, a double click enters it",
          "[ui][file_dialog]") {
    Tree t;
    FileBrowser b;
    b.open(t.root.string(), {".json"});
    const size_t scenes = t.index_of(b, "scenes/");
    b.click(scenes);
    CHECK(fs::path(b.dir()) == t.root);
    CHECK(b.selected() == int(scenes));
    CHECK(b.name.empty()); // a folder does not fill the name field
    // The double click: its first click selected, its second opens. The folder is entered and nothing is
    // chosen, whatever lands under the pointer in the new listing.
    CHECK_FALSE(b.activate(scenes).has_value());
    CHECK(fs::path(b.dir()) == t.root / "scenes");
    CHECK(b.selected() == -1);
}

TEST_CASE("a single click selects a file, a double click or Enter opens it", "[ui][file_dialog]") {
    Tree t;
    FileBrowser b;
    b.open((t.root / "scenes").string(), {".json"});
    const size_t tank = t.index_of(b, "tank.json");
    b.click(tank);
    CHECK(b.name == "tank.json");
    const auto enter = b.confirm();
    REQUIRE(enter.has_value());
    CHECK(fs::path(*enter) == t.root / "scenes" / "tank.json");
    const auto dbl = b.activate(t.index_of(b, "fig9.json"));
    REQUIRE(dbl.has_value());
    CHECK(fs::path(*dbl) == t.root / "scenes" / "fig9.json");
}

TEST_CASE("Enter on a selected folder enters it; arrows move the selection; ../ goes up",
          "[ui][file_dialog]") {
    Tree t;
    FileBrowser b;
    b.open(t.root.string(), {".json"});
    b.move_selection(1); // ../
    b.move_selection(1); // meshes/
    b.move_selection(1); // scenes/
    CHECK(b.entries()[size_t(b.selected())].name == "scenes/");
    CHECK_FALSE(b.confirm().has_value());
    CHECK(fs::path(b.dir()) == t.root / "scenes");
    b.click(t.index_of(b, "../"));
    CHECK(fs::path(b.dir()) == t.root / "scenes"); // a click on ../ only selects it
    CHECK_FALSE(b.confirm().has_value());
    CHECK(fs::path(b.dir()) == t.root);
    // Nothing selected and nothing typed: Enter does nothing.
    CHECK_FALSE(b.confirm().has_value());
    b.name = "new.json";
    REQUIRE(b.typed().has_value());
    CHECK(fs::path(*b.typed()) == t.root / "new.json");
}

TEST_CASE("two left presses close in time and place are a double click, a third starts anew",
          "[ui][file_dialog]") {
    MouseState m;
    auto press = [&](double t, glm::dvec2 p, int b = button::Left) {
        InputEvent e;
        e.type = InputEvent::Type::Press, e.button = b, e.pos = p, e.time_s = t;
        m.apply(e);
        e.type = InputEvent::Type::Release;
        m.apply(e);
        const bool d = m.double_clicked_since_frame;
        m.next_frame();
        return d;
    };
    CHECK_FALSE(press(10.0, {100, 100}));
    CHECK(press(10.2, {102, 101})); // both clicks may fall into one frame or two: the times decide
    CHECK_FALSE(press(10.3, {102, 101}));
    CHECK_FALSE(press(11.0, {102, 101}));
    CHECK_FALSE(press(11.0 + kDoubleClickS + 0.05, {102, 101})); // too slow
    CHECK_FALSE(press(20.0, {100, 100}));
    CHECK_FALSE(press(20.1, {140, 100})); // too far
    CHECK_FALSE(press(30.0, {100, 100}));
    CHECK_FALSE(press(30.1, {100, 100}, button::Right));
}
