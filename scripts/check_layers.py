#!/usr/bin/env python3
"""The floors of core: every `#include "core/..."` in core/**/*.{h,cpp} must
be one that the module table of docs/ARCHITECTURE.md (section "## Modules",
column "may include") allows, and nothing in core includes Emscripten.

The table: one row a module, `core/<name>` in the first column; the last
column lists, separated by commas, the other core modules (their folder
names under core/) that the module's files may include, or says `nothing`.
A module may always include its own files. Rows of folders outside core/
(cli/, wasm/, web/, docs/) are not checked here. The table itself must be
true to the tree (a row for every folder of core/, only core modules
listed) and have no cycle; the floors printed are its longest paths from
the bottom (floor 0: includes nothing).

Exit 0 with a one-line summary; 1 with one line a violation
(`file:line: core/A includes core/B, which the module table does not
allow`); 2 when the table cannot be read.

Usage:
  scripts/check_layers.py [--root REPO]
  scripts/check_layers.py --self-test
"""
import argparse
import pathlib
import re
import shutil
import subprocess
import sys
import tempfile

ROOT = pathlib.Path(__file__).resolve().parent.parent
DOC = pathlib.Path("docs/ARCHITECTURE.md")
INCLUDE = re.compile(r'^\s*#\s*include\s*([<"])([^>"]+)[>"]')
SOURCE_SUFFIXES = (".h", ".hpp", ".cpp", ".cc")


class TableError(Exception):
    pass


def read_table(doc: pathlib.Path) -> dict[str, set[str]]:
    """{module: modules it may include} from the "## Modules" table."""
    name = DOC.as_posix()
    try:
        text = doc.read_text(encoding="utf-8")
    except OSError as e:
        raise TableError(f"{name}: cannot read it ({e.strerror})")
    lines = text.splitlines()
    try:
        start = next(i for i, l in enumerate(lines) if l.strip() == "## Modules")
    except StopIteration:
        raise TableError(f"{name}: no \"## Modules\" section")
    section = []
    for l in lines[start + 1:]:
        if l.startswith("## "):
            break
        section.append(l)
    rows = [l for l in section if l.lstrip().startswith("|")]
    if len(rows) < 3:
        raise TableError(f"{name}: the \"## Modules\" section has no table")
    header = [c.strip().lower() for c in rows[0].strip().strip("|").split("|")]
    if header[0] != "folder" or header[-1] != "may include":
        raise TableError(f"{name}: the module table's columns must start with \"folder\" "
                         f"and end with \"may include\" (found: {' | '.join(header)})")
    table: dict[str, set[str]] = {}
    for row in rows[2:]:
        cells = [c.strip() for c in row.strip().strip("|").split("|")]
        folder = cells[0].strip("`").rstrip("/")
        if not folder.startswith("core/"):
            continue
        module = folder[len("core/"):]
        if "/" in module or not module:
            raise TableError(f"{name}: row {folder}: a core module is a folder right under core/")
        if module in table:
            raise TableError(f"{name}: two rows for core/{module}")
        allowed = cells[-1].replace("`", "").strip()
        if allowed == "nothing":
            table[module] = set()
            continue
        names = [n.strip() for n in allowed.split(",")]
        for n in names:
            if not re.fullmatch(r"[a-z0-9_]+", n):
                raise TableError(f"{name}: row core/{module}: \"{n}\" in \"may include\" is not "
                                 "a module name (the column is a comma list of module names, "
                                 "or \"nothing\")")
        table[module] = set(names) - {module}
    for module, allowed in sorted(table.items()):
        unknown = sorted(allowed - table.keys())
        if unknown:
            raise TableError(f"{name}: row core/{module} allows \"{unknown[0]}\", which has no row")
    return table


def floors(table: dict[str, set[str]]) -> dict[str, int]:
    """Longest path down from each module; TableError on a cycle."""
    floor: dict[str, int] = {}
    visiting: list[str] = []

    def visit(m: str) -> int:
        if m in floor:
            return floor[m]
        if m in visiting:
            cycle = visiting[visiting.index(m):] + [m]
            raise TableError("the module table has a cycle: " + " -> ".join(cycle))
        visiting.append(m)
        f = 1 + max((visit(n) for n in sorted(table[m])), default=-1)
        visiting.pop()
        floor[m] = f
        return f

    for m in sorted(table):
        visit(m)
    return floor


def check(root: pathlib.Path) -> tuple[list[str], str]:
    """(violations, summary) for the tree at root."""
    table = read_table(root / DOC)
    floor = floors(table)
    core = root / "core"
    problems = []
    for d in sorted(p for p in core.iterdir() if p.is_dir()):
        if d.name not in table:
            problems.append(f"core/{d.name}/: no row in the module table of {DOC.as_posix()}")
    for m in sorted(table.keys() - {p.name for p in core.iterdir() if p.is_dir()}):
        problems.append(f"{DOC.as_posix()}: row core/{m}: no such folder")
    checked = 0
    files = sorted(p for p in core.rglob("*") if p.is_file() and p.suffix in SOURCE_SUFFIXES)
    for f in files:
        rel = f.relative_to(root).as_posix()
        parts = f.relative_to(core).parts
        module = parts[0] if len(parts) > 1 else None
        for n, line in enumerate(f.read_text(encoding="utf-8", errors="replace").splitlines(), 1):
            m = INCLUDE.match(line)
            if not m:
                continue
            target = m.group(2)
            if "emscripten" in target.lower():
                problems.append(f"{rel}:{n}: core/{module} includes {target}: core never "
                                "includes Emscripten (wasm/ does)")
                continue
            if not target.startswith("core/"):
                continue
            checked += 1
            other = target.split("/")[1] if target.count("/") >= 2 else None
            if module is None:
                problems.append(f"{rel}:{n}: a file right in core/ belongs to no module")
            elif other is None or other not in table:
                problems.append(f"{rel}:{n}: core/{module} includes {target}, "
                                "which is in no module of the table")
            elif module in table and other != module and other not in table[module]:
                problems.append(f"{rel}:{n}: core/{module} includes core/{other}, "
                                "which the module table does not allow")
    by_floor: dict[int, list[str]] = {}
    for m, f in floor.items():
        by_floor.setdefault(f, []).append(m)
    order = " < ".join(", ".join(sorted(by_floor[f])) for f in sorted(by_floor))
    summary = (f"check_layers: {checked} includes in {len(files)} files of core follow "
               f"{DOC.as_posix()}'s module table; floors: {order}")
    return problems, summary


def self_test() -> int:
    """A copy of the real table over a fake core/: a downward include passes,
    an include up a floor, one into no module and an Emscripten include are
    each reported; a cycle in the table is refused."""
    try:
        failures = self_test_failures()
    except TableError as e:
        failures = [f"the module table of {DOC.as_posix()} cannot be read: {e}"]
    if failures:
        print("check_layers self-test FAILED:\n" + "\n".join(failures))
        return 1
    print("check_layers self-test: an include up a floor, one into no module, an Emscripten "
          "include and a cyclic table are each caught")
    return 0


def self_test_failures() -> list[str]:
    failures = []
    with tempfile.TemporaryDirectory() as tmp:
        root = pathlib.Path(tmp)
        (root / "docs").mkdir()
        shutil.copy(ROOT / DOC, root / DOC)
        table = read_table(root / DOC)
        for m in table:
            (root / "core" / m).mkdir(parents=True)

        def write(path: str, *includes: str) -> None:
            body = "".join(f"#include {i}\n" for i in includes)
            (root / path).write_text("// self-test\n" + body)

        write("core/util/a.h", "<vector>")
        write("core/mesh/m.h", '"core/util/a.h"', '"core/geom/g.h"', '"core/mesh/n.h"')
        problems, _ = check(root)
        if problems:
            failures.append(f"a tree that follows the table was refused: {problems}")

        write("core/util/up.cpp", '"core/util/a.h"', '"core/pipeline/mesh_job.h"')
        write("core/geom/side.h", '"core/quality/q.h"')
        write("core/mesh/wasm.cpp", "<emscripten/bind.h>")
        write("core/mesh/ghost.h", '"core/nosuch/x.h"')
        want = [
            "core/geom/side.h:2: core/geom includes core/quality, which the module table does not allow",
            "core/mesh/ghost.h:2: core/mesh includes core/nosuch/x.h, which is in no module of the table",
            "core/mesh/wasm.cpp:2: core/mesh includes emscripten/bind.h: core never includes Emscripten (wasm/ does)",
            "core/util/up.cpp:3: core/util includes core/pipeline, which the module table does not allow",
        ]
        # As a user runs it: exit 1, one line a violation, then the count.
        r = subprocess.run([sys.executable, __file__, "--root", str(root)],
                           capture_output=True, text=True)
        got = r.stdout.splitlines()
        if r.returncode != 1 or got[:-1] != want:
            failures.append(f"violations (exit {r.returncode}, want 1):\n  got  " +
                            "\n       ".join(got) + "\n  want " + "\n       ".join(want))

        doc = (root / DOC).read_text()
        (root / DOC).write_text(re.sub(r"(\| `core/util` \|.*\|) nothing \|", r"\1 pipeline |", doc))
        try:
            check(root)
            failures.append("a table with a cycle (util may include pipeline) was accepted")
        except TableError as e:
            if "cycle" not in str(e):
                failures.append(f"a table with a cycle gave another error: {e}")
    return failures


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__,
                                 formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--root", default=str(ROOT), help="the repository (default: this script's)")
    ap.add_argument("--self-test", action="store_true",
                    help="prove on a fake tree that violations are caught")
    args = ap.parse_args()
    if args.self_test:
        return self_test()
    try:
        problems, summary = check(pathlib.Path(args.root))
    except TableError as e:
        print(f"check_layers: {e}", file=sys.stderr)
        return 2
    if problems:
        print("\n".join(problems))
        print(f"check_layers: {len(problems)} include(s) against the module table of "
              f"{DOC.as_posix()}: move the code down a floor, or (an include down a floor the "
              "table omits) add it to the row")
        return 1
    print(summary)
    return 0


if __name__ == "__main__":
    sys.exit(main())
