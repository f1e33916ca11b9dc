// Checks the JSON the viewer exports in scripted GL tests (--state, --layout, script `state` / `layout`).
//   ui_json_check eq FILE_A PTR_A FILE_B PTR_B [TOL] : the values at the two JSON pointers are equal (numbers
//       and arrays of numbers within TOL, default 1e-9)
//   ui_json_check ne FILE_A PTR_A FILE_B PTR_B [TOL] : they differ by more than TOL somewhere
//   ui_json_check is FILE PTR JSON                    : the value at PTR equals the JSON literal
//   ui_json_check ge FILE PTR NUMBER                  : the number at PTR is at least NUMBER
//   ui_json_check ratio A PA A0 PA0 B PB B0 PB0 R TOL : (A - A0) / (B - B0) is R within TOL
//   ui_json_check layout FILE                         : no overlapping, cut-off or outside text ("problems")
//   ui_json_check runs FILE WINDOW MIN               : a --layout file has at least MIN text runs drawn by
//   WINDOW ui_json_check files DIR SUFFIX N                  : DIR holds exactly N files whose names end in
//   SUFFIX
#include <nlohmann/json.hpp>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <string>

using json = nlohmann::json;

namespace {

json load(const std::string& path) {
    std::ifstream f(path);
    if (!f) throw std::runtime_error("cannot read " + path);
    return json::parse(f);
}

bool close(const json& a, const json& b, double tol) {
    if (a.is_number() && b.is_number()) return std::abs(a.get<double>() - b.get<double>()) <= tol;
    if (a.is_array() && b.is_array()) {
        if (a.size() != b.size()) return false;
        for (size_t i = 0; i < a.size(); ++i)
            if (!close(a[i], b[i], tol)) return false;
        return true;
    }
    if (a.is_object() && b.is_object()) {
        if (a.size() != b.size()) return false;
        for (auto it = a.begin(); it != a.end(); ++it)
            if (!b.contains(it.key()) || !close(it.value(), b[it.key()], tol)) return false;
        return true;
    }
    return a == b;
}

int run(int argc, char** argv) {
    const std::string cmd = argc > 1 ? argv[1] : "";
    if ((cmd == "eq" || cmd == "ne") && (argc == 6 || argc == 7)) {
        const json a = load(argv[2]).at(json::json_pointer(argv[3]));
        const json b = load(argv[4]).at(json::json_pointer(argv[5]));
        const double tol = argc == 7 ? std::stod(argv[6]) : 1e-9;
        const bool same = close(a, b, tol);
        std::cout << argv[3] << ": " << a.dump() << "\n" << argv[5] << ": " << b.dump() << "\n";
        if (same != (cmd == "eq")) {
            std::cerr << "FAIL: expected the values to " << (cmd == "eq" ? "agree" : "differ") << "\n";
            return 1;
        }
        return 0;
    }
    if (cmd == "is" && argc == 5) {
        const json a = load(argv[2]).at(json::json_pointer(argv[3])), b = json::parse(argv[4]);
        std::cout << argv[3] << ": " << a.dump() << "\n";
        if (!close(a, b, 1e-9)) {
            std::cerr << "FAIL: expected " << b.dump() << "\n";
            return 1;
        }
        return 0;
    }
    if (cmd == "ge" && argc == 5) {
        const double a = load(argv[2]).at(json::json_pointer(argv[3])).get<double>(), b = std::stod(argv[4]);
        std::cout << argv[3] << ": " << a << "\n";
        if (!(a >= b)) {
            std::cerr << "FAIL: expected at least " << b << "\n";
            return 1;
        }
        return 0;
    }
    if (cmd == "ratio" && argc == 12) {
        auto num = [&](int i) { return load(argv[i]).at(json::json_pointer(argv[i + 1])).get<double>(); };
        const double a = num(2), a0 = num(4), b = num(6), b0 = num(8), r = std::stod(argv[10]),
                     tol = std::stod(argv[11]);
        const double got = (a - a0) / (b - b0);
        std::cout << "(" << a << " - " << a0 << ") / (" << b << " - " << b0 << ") = " << got << "\n";
        if (!(std::abs(got - r) <= tol)) {
            std::cerr << "FAIL: expected " << r << " +- " << tol << "\n";
            return 1;
        }
        return 0;
    }
    if (cmd == "layout" && argc == 3) {
        const json j = load(argv[2]);
        const size_t runs = j.at("runs").size();
        std::cout << runs << " text runs in " << j.at("width") << " x " << j.at("height") << "\n";
        if (runs < 20) {
            std::cerr << "FAIL: too little text on screen\n";
            return 1;
        }
        const std::string p = j.at("problems").get<std::string>();
        if (!p.empty()) {
            std::cerr << "FAIL:\n" << p;
            return 1;
        }
        return 0;
    }
    if (cmd == "runs" && argc == 5) {
        int n = 0;
        const json layout = load(argv[2]); // kept alive for the loop
        for (const json& r : layout.at("runs")) n += r.at("window").get<std::string>() == argv[3];
        std::cout << n << " text runs in " << argv[3] << "\n";
        if (n < std::stoi(argv[4])) {
            std::cerr << "FAIL: expected at least " << argv[4] << "\n";
            return 1;
        }
        return 0;
    }
    if (cmd == "files" && argc == 5) {
        const std::string suffix = argv[3];
        int n = 0;
        for (auto& e : std::filesystem::directory_iterator(argv[2])) {
            const std::string name = e.path().filename().string();
            if (name.size() >= suffix.size() &&
                name.compare(name.size() - suffix.size(), suffix.size(), suffix) == 0)
                ++n;
        }
        std::cout << n << " files *" << suffix << "\n";
        if (n != std::stoi(argv[4])) {
            std::cerr << "FAIL: expected " << argv[4] << "\n";
            return 1;
        }
        return 0;
    }
    std::cerr << "usage: see the top of tests/ui/json_check.cpp\n";
    return 2;
}

} // namespace

int main(int argc, char** argv) {
    try {
        return run(argc, argv);
    } catch (const std::exception& e) {
        std::cerr << "FAIL: " << e.what() << "\n";
        return 1;
    }
}
