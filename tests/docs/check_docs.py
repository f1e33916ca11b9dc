#!/usr/bin/env python3
"""Checks that the docs are current and that their links resolve.

  check_docs.py SONARSIM REPO parameters [--update]   docs/parameters.md == header + `sonarsim params`
  check_docs.py SONARSIM REPO devices                 docs/devices.md holds `sonarsim devices --markdown`
  check_docs.py SONARSIM REPO materials               docs/model.md holds `sonarsim materials --markdown`
  check_docs.py SONARSIM REPO links                   every relative link and image in README.md, docs/*.md,
                                                      core/ARCHITECTURE.md, core/*/README.md and the other READMEs names an
                                                      existing file; none points at ../shared/reference
Exit status 0 when current, 1 with a message (and the command that fixes it) otherwise.
"""
import difflib
import pathlib
import re
import subprocess
import sys

HEADER = """# Parameters

Generated from the one parameter table (`core/scene/rows/*.cpp`) by `sonarsim params`; do not edit by hand.
Every key works in a scene file (nested: `{"sonar": {"beams": 64}}`), with `--set sonar.beams=64` and in
Python (`sim.set("sonar.beams", 64)`). `material.*` keys belong to a material: the seafloor's
(`seafloor.material.nu_db`), the water surface's (`water.surface_material.q`) or an object's
(`objects.0.material.mu`). The objects (`box` or `mesh`, `position`, `orientation_deg`, `scale`) and the
seafloor (`height_m`) are described in [scenes.md](scenes.md). Regenerate after changing the table:

    python3 tests/docs/check_docs.py build/sonarsim . parameters --update

(`ctest -R docs.parameters_current` fails while this file is stale.)

"""

UPDATE_CMD = "python3 tests/docs/check_docs.py build/sonarsim . parameters --update"


def run(sonarsim, *args):
    return subprocess.run([sonarsim, *args], check=True, capture_output=True, text=True).stdout


def show_diff(expected, actual, name):
    diff = list(difflib.unified_diff(actual.splitlines(), expected.splitlines(), name, "expected", lineterm=""))
    print("\n".join(diff[:40]) + ("\n..." if len(diff) > 40 else ""))


def check_parameters(sonarsim, repo, update):
    path = repo / "docs" / "parameters.md"
    expected = HEADER + run(sonarsim, "params")
    if update:
        path.write_text(expected, encoding="utf-8")
        print(f"wrote {path}")
        return 0
    actual = path.read_text(encoding="utf-8") if path.exists() else ""
    if actual == expected:
        print("docs/parameters.md is current")
        return 0
    show_diff(expected, actual, "docs/parameters.md")
    print(f"docs/parameters.md is stale: it differs from `sonarsim params`. Regenerate it (from the repository root):\n"
          f"  {UPDATE_CMD}")
    return 1


def check_generated_table(sonarsim, repo, command, doc, first, last, what):
    """Whether docs/`doc` holds the current output of `sonarsim COMMAND --markdown` (its table runs from the
    line starting `first` to the line holding `last`); prints how to mend it when not."""
    table = run(sonarsim, command, "--markdown").strip()
    text = (repo / "docs" / doc).read_text(encoding="utf-8")
    if table in text:
        print(f"docs/{doc} holds the current `sonarsim {command} --markdown` table")
        return 0
    start = text.find(first)
    end = text.find("\n", text.find(last, start)) if start >= 0 else -1
    show_diff(table, text[start:end] if start >= 0 else "", f"docs/{doc}")
    print(f"docs/{doc} is stale: replace its {what} (from `{first}` to the `{last}` line) with the output of\n"
          f"  build/sonarsim {command} --markdown")
    return 1


def check_devices(sonarsim, repo):
    return check_generated_table(sonarsim, repo, "devices", "devices.md", "| name |", "? = unsure", "table")


def check_materials(sonarsim, repo):
    return check_generated_table(sonarsim, repo, "materials", "model.md", "| preset |", "`-`: not set",
                                 "presets table")


def anchors(md):
    """GitHub's anchors of a Markdown file's headings: lower case, punctuation dropped, spaces to hyphens."""
    text = re.sub(r"```.*?```", "", md.read_text(encoding="utf-8"), flags=re.S)
    return {re.sub(r"[^\w\- ]", "", h.strip().lower()).replace(" ", "-")
            for h in re.findall(r"^#+ (.*)$", text, flags=re.M)}


LINK = re.compile(r"!?\[[^\]]*\]\(([^)\s]+)\)")


def check_links(repo):
    files = [repo / "README.md", *sorted((repo / "docs").glob("*.md")), *sorted((repo / "core").glob("*/README.md")),
             *[repo / p for p in ("core/ARCHITECTURE.md", "bench/README.md", "bench/NOTEBOOK.md", "tests/fuzz/README.md",
                                  "assets/meshes/SOURCES.md") if (repo / p).exists()]]
    bad = []
    for f in files:
        text = f.read_text(encoding="utf-8")
        # Fenced code is not prose: links there are examples.
        text = re.sub(r"```.*?```", lambda m: "\n" * m.group(0).count("\n"), text, flags=re.S)
        for n, line in enumerate(text.splitlines(), 1):
            if "shared/reference" in line:
                bad.append(f"{f.relative_to(repo)}:{n}: points at ../shared/reference, which a clone does not have")
            for target in LINK.findall(line):
                if re.match(r"[a-z]+:", target):
                    continue
                if target.startswith("#"):
                    target = f.name + target
                path, _, anchor = target.partition("#")
                p = (f.parent / path).resolve()
                if not p.exists():
                    bad.append(f"{f.relative_to(repo)}:{n}: link to {target}: no such file")
                elif anchor and p.suffix == ".md" and anchor not in anchors(p):
                    bad.append(f"{f.relative_to(repo)}:{n}: link to {target}: no heading with that anchor")
                elif repo.resolve() not in p.parents and p != repo.resolve():
                    bad.append(f"{f.relative_to(repo)}:{n}: link to {target} leaves the repository")
    for b in bad:
        print(b)
    print(f"{len(files)} files checked, {len(bad)} bad links")
    return 1 if bad else 0


def main():
    if len(sys.argv) < 4:
        print(__doc__)
        return 2
    sonarsim, repo, what = sys.argv[1], pathlib.Path(sys.argv[2]), sys.argv[3]
    if what == "parameters":
        return check_parameters(sonarsim, repo, "--update" in sys.argv[4:])
    if what == "devices":
        return check_devices(sonarsim, repo)
    if what == "materials":
        return check_materials(sonarsim, repo)
    if what == "links":
        return check_links(repo)
    print(__doc__)
    return 2


if __name__ == "__main__":
    sys.exit(main())
