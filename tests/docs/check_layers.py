#!/usr/bin/env python3
"""docs/DESIGN.md §7's dependency table against the code's #include lines.

Each row of the table's first column names a room: its library (`chutelab_dem_station`) and its
folder (`dem/station/`). A file belongs to the room of the longest folder that holds it
(dem/station/scene.cpp to dem_station, dem/contact/hertz.h to dem). The "depends on" column lists,
by name, every other room whose headers the room includes: first the arrows the layering intends,
then, after "against the layering:", those it does not. Names of outside libraries (fmt, Eigen, ...)
are not rooms and are skipped.

A room that includes a room its row does not list, or a row listing a room that is never included,
is a problem: the table says what the code does, not what it once did. So is an arrow to a room
listed below the including room's row: the table is in the order of the layers, and no arrow runs
back up. And so is a top folder of sources without a row (tests/, bench/, scripts/, datasets/ and
docs/ are no rooms), whose arrows would otherwise go unseen.

Usage: check_layers.py REPO_ROOT. Prints one line per problem and exits 1 when there is any.
       check_layers.py --self-test REPO_ROOT: plants an arrow missing from the table and one the
       code lacks, and exits 0 only when exactly those two are found.
"""
import os
import re
import subprocess
import sys

EXTERNAL = {"fmt", "Eigen", "OpenMP", "GSL", "CLI11", "pybind11", "Boost", "MPI", "toml++", "TBB"}
SOURCE_EXT = (".h", ".hpp", ".cpp", ".inc")
# Top folders whose sources are no part of the library's layers: they may include any room.
NOT_ROOMS = {"tests", "bench", "scripts", "datasets", "docs"}


def section7(design):
    m = re.search(r"^## 7\..*?(?=^## 8\.)", design, re.M | re.S)
    if not m:
        raise SystemExit("docs/DESIGN.md has no section 7")
    return m.group(0)


def table_rows(section):
    """(room name, folder, intended arrows, against arrows, unknown names) of the first table."""
    rows = []
    for line in section.splitlines():
        if not line.startswith("| `"):
            continue
        cells = [c.strip() for c in line.strip().strip("|").split("|")]
        if len(cells) < 3:
            continue
        lib = re.search(r"`chutelab_(\w+)`", cells[0])
        folder = re.search(r"`([a-z_]+(?:/[a-z_]+)*)/`", cells[0])
        if not folder:
            continue
        name = lib.group(1) if lib else folder.group(1).replace("/", "_")
        intended, _, against = cells[-1].partition("against the layering:")
        split = lambda text: [w.strip(" .`*") for w in re.split(r"[,;]", text) if w.strip(" .`*")]
        rows.append((name, folder.group(1), split(intended), split(against)))
    return rows


def repository_sources(root):
    out = subprocess.run(["git", "-C", root, "ls-files"], check=True, capture_output=True, text=True).stdout
    return [f for f in out.splitlines() if f.endswith(SOURCE_EXT)]


def code_arrows(root, rooms):
    """{(from room, to room): first 'file:line' that makes it} over the repository's sources."""
    folders = sorted(((folder, name) for name, folder in rooms.items()), key=lambda x: -len(x[0]))

    def room_of(path):
        for folder, name in folders:
            if path.startswith(folder + "/"):
                return name
        return None

    arrows = {}
    for f in repository_sources(root):
        here = room_of(f)
        if here is None:
            continue
        with open(os.path.join(root, f), encoding="utf-8", errors="replace") as src:
            for n, line in enumerate(src, 1):
                m = re.match(r'\s*#\s*include\s+"([^"]+)"', line)
                there = room_of(m.group(1)) if m else None
                if there and there != here:
                    arrows.setdefault((here, there), f"{f}:{n}")
    return arrows


def problems(root, section):
    rows = table_rows(section)
    rooms = {name: folder for name, folder, _, _ in rows}
    out = []
    listed = set()
    for name, folder, intended, against in rows:
        for word in intended + against:
            if word in EXTERNAL:
                continue
            if word not in rooms:
                out.append(f"§7, row {name}: '{word}' is neither a room of the table nor a known outside library")
            else:
                listed.add((name, word))
    # A folder of sources without a row would go unchecked: every top folder of code is a room.
    tops = {f.split("/", 1)[0] for f in repository_sources(root) if "/" in f}
    for top in sorted(tops - NOT_ROOMS - {folder.split("/")[0] for folder in rooms.values()}):
        out.append(f"{top}/ holds sources, but §7's table has no row for it")
    found = code_arrows(root, rooms)
    order = {name: i for i, (name, _, _, _) in enumerate(rows)}
    for (a, b), where in sorted(found.items()):
        if order[b] > order[a]:
            out.append(f"{rooms[a]}/ includes {rooms[b]}/ ({where}), a room §7 lists below it: an arrow back up")
    for (a, b), where in sorted(found.items()):
        if (a, b) not in listed:
            out.append(f"{rooms[a]}/ includes {rooms[b]}/ ({where}), but §7's row {a} does not list {b}: "
                       f"add it to 'depends on' (after 'against the layering:' if the layering does not intend it)")
    for a, b in sorted(listed - set(found)):
        out.append(f"§7's row {a} lists {b}, but no file of {rooms[a]}/ includes a header of {rooms[b]}/")
    return out


def main():
    self_test = len(sys.argv) > 2 and sys.argv[1] == "--self-test"
    root = os.path.abspath(sys.argv[-1] if len(sys.argv) > 1 else ".")
    with open(os.path.join(root, "docs", "DESIGN.md"), encoding="utf-8") as f:
        section = section7(f.read())
    if not self_test:
        found = problems(root, section)
        for p in found:
            print(p)
        print(f"§7: {len(table_rows(section))} rooms checked against the includes: {len(found)} problems")
        return 1 if found else 0
    # Plant two problems in a copy of the section: effects no longer lists analytical (an arrow of the
    # code the table misses), and core lists logs (an arrow the code does not have).
    rows = {r[0]: r for r in table_rows(section)}
    lines = section.splitlines()
    for i, line in enumerate(lines):
        if "`chutelab_effects`" in line:
            cells = line.split("|")
            cells[-2] = " " + ", ".join(w for w in rows["effects"][2] if w != "analytical") + " "
            lines[i] = "|".join(cells)
        elif "`chutelab_core`" in line:
            cells = line.split("|")
            cells[-2] = cells[-2].rstrip() + ", logs "
            lines[i] = "|".join(cells)
    planted = set(problems(root, "\n".join(lines))) - set(problems(root, section))
    expected = ["effects/ includes analytical/", "§7's row core lists logs"]
    ok = len(planted) == 2 and all(any(p.startswith(e) for p in planted) for e in expected)
    for p in sorted(planted):
        print(p)
    print("self-test:", "the planted problems were found" if ok else "FAILED: expected " + "; ".join(expected))
    return 0 if ok else 1


if __name__ == "__main__":
    sys.exit(main())
