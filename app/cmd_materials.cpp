// `sonarsim materials`: the material presets (assets/materials/*.json, `material.preset`) with the values
// they set, as a text table or as Markdown (--markdown, the table in docs/model.md); `sonarsim materials
// NAME` prints one preset's values with their derivations, its sources and its notes.
#include "commands.hpp"

#include "core/base/errors.hpp"
#include "core/scene/materials.hpp"
#include "core/scene/params.hpp"

#include <cstdio>
#include <iostream>
#include <memory>
#include <sstream>
#include <vector>

namespace sonarsim::app {

namespace {

/// The material keys any preset sets, in the table's order: the table's columns.
std::vector<const MaterialSpec*> columns() {
    std::vector<const MaterialSpec*> out;
    for (auto& spec : material_params())
        for (auto& p : material_presets())
            for (auto& v : p.values)
                if (v.key == spec.key && (out.empty() || out.back() != &spec)) out.push_back(&spec);
    return out;
}

/// The preset's value of `key` as text, "-" when it sets none.
std::string show(const MaterialPreset& p, const std::string& key) {
    for (auto& v : p.values)
        if (v.key == key) {
            if (!v.value.is_number()) return v.value.dump();
            char buf[32];
            std::snprintf(buf, sizeof buf, "%.4g", v.value.get<double>());
            return buf;
        }
    return "-";
}

/// "[JR07]" of "[JR07] D. R. Jackson ...", or the whole citation when it has no tag.
std::string tag_of(const std::string& citation) {
    const size_t end = citation.find(']');
    return citation.rfind('[', 0) == 0 && end != std::string::npos ? citation.substr(0, end + 1) : citation;
}

void print_table(bool markdown) {
    const auto cols = columns();
    std::ostringstream out;
    out << (markdown ? "| preset | what |" : "preset\twhat\t");
    for (auto* c : cols)
        out << (markdown ? " " : "") << c->key << (c->unit.empty() ? "" : " [" + c->unit + "]")
            << (markdown ? " |" : "\t");
    out << (markdown ? " sources |\n|---|---|" : "sources\n");
    if (markdown)
        for (size_t i = 0; i <= cols.size(); ++i) out << "---|";
    out << (markdown ? "\n" : "");
    std::vector<std::pair<std::string, std::string>> cited; // tag, full citation: each tag once, first seen
    for (auto& p : material_presets()) {
        out << (markdown ? "| `" + p.name + "` | " + p.title + " |" : p.name + "\t" + p.title + "\t");
        for (auto* c : cols) out << (markdown ? " " : "") << show(p, c->key) << (markdown ? " |" : "\t");
        std::string tags;
        for (auto& s : p.sources) {
            const std::string tag = tag_of(s.citation);
            tags += (tags.empty() ? "" : " ") + tag;
            bool seen = false;
            for (auto& c : cited) seen = seen || c.first == tag;
            if (!seen) cited.push_back({tag, s.citation});
        }
        out << (markdown ? " " + tags + " |\n" : tags + "\n");
    }
    out << "\n";
    for (auto& c : cited) out << (markdown ? "- " : "") << c.second << "\n";
    out << "\n`-`: not set, the surface keeps its own value. Each value's derivation and what a preset "
           "leaves "
           "unset: `sonarsim materials NAME` (assets/materials/NAME.json).\n";
    std::cout << out.str();
}

void print_preset(const MaterialPreset& p) {
    std::ostringstream out;
    out << p.name << ": " << p.title << " (" << p.file << ")\n\nvalues:\n";
    for (auto& v : p.values)
        out << "  " << v.key << " = " << v.value.dump() << "\n      " << v.source << "\n";
    out << "\nsources:\n";
    for (auto& s : p.sources) out << "  " << s.citation << "\n      used for: " << s.used_for << "\n";
    out << "\nnotes: " << p.notes << "\n";
    std::cout << out.str();
}

} // namespace

void register_materials(CLI::App& app, std::function<int()>& run) {
    CLI::App* cmd = app.add_subcommand(
        "materials",
        "List the material presets (material.preset) with their values; NAME: one preset's sources");
    auto markdown = std::make_shared<bool>(false);
    auto name = std::make_shared<std::string>();
    cmd->add_flag("--markdown", *markdown, "Print a Markdown table (as in docs/model.md)");
    cmd->add_option("name", *name, "A preset: print each of its values with its derivation and sources");
    cmd->callback([&run, markdown, name] {
        run = [markdown, name] {
            if (name->empty()) {
                print_table(*markdown);
                return 0;
            }
            const MaterialPreset* p = find_material_preset(*name);
            if (!p) {
                std::string known;
                for (auto& q : material_presets()) known += (known.empty() ? "" : ", ") + q.name;
                throw InputError("materials", "",
                                 "no material preset '" + *name + "' (known: " + known + ")");
            }
            print_preset(*p);
            return 0;
        };
    });
}

} // namespace sonarsim::app
