#!/usr/bin/env python3
"""Moves the lab layer (lab/) from namespace cdem::dem into cdem::lab, mechanically.

Run from the repository root: python3 scripts/lab_namespace.py. Idempotent: running it again,
say after merging a branch that adds lab/ code still in cdem::dem, moves only what is left.

1. In lab/*.hpp and lab/*.cpp, `namespace cdem::dem` becomes `namespace cdem::lab` (openings and
   closing comments, cdem::dem::summary_field included), and each file that sees the engine (it
   includes a dem/ header, or a lab/ header that sees it) says once, after its first opening,
   `using namespace cdem::dem;`: the lab layer drives the engine and names its types (World,
   Discs, ContactClass, ...) unqualified, as it did inside cdem::dem.
2. Forward declarations in lab headers of engine types (a `class X;` or `struct X;` that dem/
   defines) stay in cdem::dem: they move into a `namespace cdem::dem { ... }` block before the
   first lab opening.
3. Everywhere else (apps/, python/, calibrate/, campaign/, mesogen/, tests/, bench/), a name that
   lab/ headers declare and that is qualified `dem::NAME` or `cdem::dem::NAME` becomes
   `lab::NAME` / `cdem::lab::NAME`, a block forward-declaring lab types moves to cdem::lab; a
   file that includes a lab/ header and says
   `using namespace cdem::dem;` (or `dem;`) also says `using namespace cdem::lab;` after it, and
   one with the alias `namespace dem = cdem::dem;` gets `namespace lab = cdem::lab;` beside it
   (when the file sees no engine header, its `using namespace cdem::dem;` becomes the lab one); a
   file that includes a lab/ header and opens `namespace cdem::dem {` gets `using namespace
   cdem::lab;` after the opening.
"""
import pathlib
import re
import sys

ROOT = pathlib.Path(__file__).resolve().parent.parent
OUTSIDE = ["apps", "python", "calibrate", "campaign", "mesogen", "tests", "bench", "doe", "io"]
USING_ENGINE = "using namespace cdem::dem;  // the engine the lab layer drives"


def sources(folder):
    base = ROOT / folder
    return sorted(p for p in base.rglob("*") if p.suffix in (".hpp", ".cpp") and p.is_file())


def defined_names(files):
    """Types, aliases, constants and functions declared at namespace scope (column 0)."""
    names = set()
    for p in files:
        text = p.read_text()
        names.update(re.findall(r"^(?:struct|class|enum class|enum) (\w+)[^;{]*\{", text, re.M))
        names.update(re.findall(r"^using (\w+) =", text, re.M))
        names.update(re.findall(r"^(?:inline )?constexpr [^=;(]*?\b(\w+)(?:\[\])? =", text, re.M))
        names.update(re.findall(r"^(?:inline )?constexpr [^=;(]*?\b(\w+)\(", text, re.M))
        for m in re.finditer(r"^(?!//|#|namespace|}|using|template|struct|class|enum|inline constexpr|constexpr|\s)"
                             r"[\w:<>,*& ]*?[\s*&](\w+)\(", text, re.M):
            names.add(m.group(1))
        names.update(re.findall(r"^namespace cdem::(?:dem|lab)::(\w+) \{", text, re.M))
    return names


def engine_types():
    names = set()
    for p in sources("dem") + sources("core"):
        names.update(re.findall(r"^(?:struct|class) (\w+)\b[^;]*\{", p.read_text(), re.M))
    return names


def sees_engine(lab_files, engine):
    """The lab files that include a dem/ header, directly or through other lab/ headers, or
    declare an engine type ahead."""
    includes = {p.name: re.findall(r'^#include "(dem|lab)/([\w.]+)"', p.read_text(), re.M)
                for p in lab_files}
    seeing = {p.name for p in lab_files
              if set(re.findall(r"^(?:class|struct) (\w+);", p.read_text(), re.M)) & engine}
    changed = True
    while changed:
        changed = False
        for p in lab_files:
            if p.name in seeing:
                continue
            if any(folder == "dem" or (folder == "lab" and name in seeing)
                   for folder, name in includes[p.name]):
                seeing.add(p.name)
                changed = True
    return seeing


# A block that only forward-declares engine types (written by this script): stays in cdem::dem.
ENGINE_FORWARD = re.compile(r"^namespace cdem::dem \{\n(?:(?:class|struct) \w+;\n)+"
                            r"\}  // namespace cdem::dem\n", re.M)


def rename_namespace(text):
    """cdem::dem openings and closing comments become cdem::lab, but for engine forward blocks."""
    out, last = [], 0
    for m in ENGINE_FORWARD.finditer(text):
        out.append(text[last:m.start()])
        out.append(m.group(0))
        last = m.end()
    out.append(text[last:])
    for i in range(0, len(out), 2):
        out[i] = re.sub(r"^namespace cdem::dem\b", "namespace cdem::lab", out[i], flags=re.M)
        out[i] = re.sub(r"^\}  // namespace cdem::dem\b", "}  // namespace cdem::lab", out[i],
                        flags=re.M)
    return "".join(out)


def move_lab_file(p, engine, seeing):
    text = p.read_text()
    old = text
    text = rename_namespace(text)
    opening = re.search(r"^namespace cdem::lab \{\n", text, re.M)
    if not opening:
        return old != text and p.write_text(text)
    # Engine forward declarations stay in the engine's namespace.
    if p.suffix == ".hpp":
        forward = [m for m in re.finditer(r"^(class|struct) (\w+);\n", text, re.M)
                   if m.group(2) in engine and m.start() > opening.start()]
        if forward:
            decls = "".join(m.group(0) for m in forward)
            for m in reversed(forward):
                text = text[:m.start()] + text[m.end():]
            opening = re.search(r"^namespace cdem::lab \{\n", text, re.M)
            block = "namespace cdem::dem {\n" + decls + "}  // namespace cdem::dem\n\n"
            text = text[:opening.start()] + block + text[opening.start():]
            opening = re.search(r"^namespace cdem::lab \{\n", text, re.M)
    if USING_ENGINE not in text and p.name in seeing:
        text = text[:opening.end()] + "\n" + USING_ENGINE + "\n" + text[opening.end():]
    if text != old:
        p.write_text(text)


def move_outside_file(p, lab_names, lab_headers, seeing):
    text = p.read_text()
    old = text
    alternation = "|".join(sorted(lab_names, key=len, reverse=True))
    text = re.sub(r"\b(cdem::)?dem::(" + alternation + r")\b", r"\1lab::\2", text)

    # A block of forward declarations of lab types, `namespace cdem::dem { struct X; }`.
    def forward_block(m):
        declared = re.findall(r"(?:struct|class) (\w+);", m.group(1))
        return ("namespace cdem::lab {" + m.group(1) + "}  // namespace cdem::lab"
                if declared and set(declared) <= lab_names else m.group(0))

    text = re.sub(r"namespace cdem::dem \{(\n(?:(?:struct|class) \w+;\n)+)\}(?:  // namespace cdem::dem)?",
                  forward_block, text)
    if re.search(r"\blab::", text) and "namespace lab = cdem::lab;" not in text:
        text = re.sub(r"^(\s*)namespace dem = cdem::dem;\n",
                      lambda m: m.group(0) + m.group(1) + "namespace lab = cdem::lab;\n", text,
                      count=1, flags=re.M)
    includes_lab = any(f'"lab/{h}"' in text for h in lab_headers)
    # Whether cdem::dem is declared for the file: a dem/ header, a lab/ header that sees the
    # engine, or a header of its own folder (test fixtures) included.
    included = re.findall(r'^#include "(?:(\w+)/)?([\w.]+)"', text, re.M)
    sees = any(folder in ("dem", "") or (folder == "lab" and name in seeing)
               for folder, name in included)
    engine_directive = r"^(\s*)using namespace (cdem::)?dem;\n"
    if includes_lab and not sees:
        if "using namespace cdem::lab;" in text:
            text = re.sub(engine_directive, "", text, flags=re.M)
        else:
            text = re.sub(engine_directive, r"\1using namespace cdem::lab;\n", text, count=1,
                          flags=re.M)
    elif includes_lab and "using namespace cdem::lab;" not in text:
        text = re.sub(engine_directive,
                      lambda m: m.group(0) + m.group(1) + "using namespace cdem::lab;\n", text,
                      count=1, flags=re.M)
    # Code written inside cdem::dem (a test of lab code kept there) sees lab's names too.
    if includes_lab and "using namespace cdem::lab;" not in text:
        text = re.sub(r"^namespace cdem::dem \{\n",
                      "namespace cdem::dem {\n\nusing namespace cdem::lab;\n", text, count=1,
                      flags=re.M)
    if text != old:
        p.write_text(text)


def main():
    lab_files = sources("lab")
    if not lab_files:
        sys.exit("run from a cdem checkout: no lab/ sources under " + str(ROOT))
    engine = engine_types()
    lab_names = defined_names([p for p in lab_files if p.suffix == ".hpp"]) - engine
    lab_headers = [p.name for p in lab_files if p.suffix == ".hpp"]
    seeing = sees_engine(lab_files, engine)
    for p in lab_files:
        move_lab_file(p, engine, seeing)
    for folder in OUTSIDE:
        for p in sources(folder):
            move_outside_file(p, lab_names, lab_headers, seeing)
    print(f"lab names moved: {len(lab_names)}")


if __name__ == "__main__":
    main()
