#!/usr/bin/env python3
"""The documentation's links and the files the sources name, checked against the repository.

1. Every relative link of every Markdown file ([text](path#anchor)) names a file that exists and,
   with an anchor, a heading of that file (GitHub's anchor rule).
2. Every repository path named in a source comment (``validation/gci.h``, ``bench/log/STATION.md``,
   ``docs/DESIGN.md §2``) is a file or folder of the repository, found from the repository root or
   from the commenting file's folder. A bare "DESIGN.md" is a path too: the design document is
   docs/DESIGN.md.

3. bench/README.md, the index of the measurements, links every page of bench/ and bench/log/.

bench/'s pages and its sources are checked like the rest; the outputs its runs recorded in its
sub-folders (bench/sensitivity/, bench/liggghts-engine/, ...) quote other trees and are not.

Usage: check_links.py REPO_ROOT. Prints one line per problem and exits 1 when there is any.
       check_links.py --self-test FIXTURE: exits 0 only when the checker finds exactly the four
       problems planted in the fixture (tests/docs/broken), so that the check is known to fail.
"""
import os
import re
import subprocess
import sys

SELF_TEST = len(sys.argv) > 2 and sys.argv[1] == "--self-test"
ROOT = os.path.abspath(sys.argv[-1] if len(sys.argv) > 1 else ".")
SKIP_DIRS = {".git", "build", "out", "node_modules", "__pycache__"}
# Recorded outputs and third-party snapshots quote other trees' paths; they are records, not docs.
SKIP_PREFIXES = ("bench/", "tests/fuzz/corpus/", "tests/peer/dem-cache/", "datasets/", "tests/docs/broken/")
SOURCE_EXT = (".h", ".hpp", ".cpp", ".py", ".sh", ".cmake", ".toml")


def repository_files():
    try:
        out = subprocess.run(["git", "-C", ROOT, "ls-files", "--cached", "--others", "--exclude-standard"],
                             check=True, capture_output=True, text=True).stdout
        files = [f for f in out.splitlines() if f]
    except (OSError, subprocess.CalledProcessError):
        files = []
        for d, dirs, names in os.walk(ROOT):
            dirs[:] = [x for x in dirs if x not in SKIP_DIRS]
            files += [os.path.relpath(os.path.join(d, n), ROOT) for n in names]
    return sorted(f for f in files if os.path.exists(os.path.join(ROOT, f)))


def slug(heading):
    s = heading.strip().lower()
    s = re.sub(r"[`*_~]|\[|\]|\(.*?\)(?=\s|$)", lambda m: "" if m.group(0) in "`*_~[]" else m.group(0), s)
    s = re.sub(r"[^\w\- ]", "", s, flags=re.UNICODE)
    return s.replace(" ", "-")


def anchors(path, cache={}):
    if path not in cache:
        found, seen, fence = set(), {}, False
        with open(path, encoding="utf-8") as f:
            for line in f:
                if line.lstrip().startswith("```"):
                    fence = not fence
                    continue
                m = None if fence else re.match(r"^(#{1,6})\s+(.*?)\s*#*\s*$", line)
                if m:
                    base = slug(re.sub(r"\[([^\]]*)\]\([^)]*\)", r"\1", m.group(2)))
                    n = seen.get(base, 0)
                    seen[base] = n + 1
                    found.add(base if n == 0 else f"{base}-{n}")
        cache[path] = found
    return cache[path]


def check_markdown(rel, problems):
    path = os.path.join(ROOT, rel)
    text = open(path, encoding="utf-8").read()
    text = re.sub(r"(?ms)^\s*```.*?^\s*```", "", text)   # code blocks hold commands, not links
    text = re.sub(r"`[^`\n]*`", "", text)                # and so does inline code
    for m in re.finditer(r"\[[^\]\n]*\]\(([^)\s]+)\)", text):
        target = m.group(1)
        if re.match(r"^[a-z][a-z0-9+.-]*:", target):     # http:, https:, mailto:, file:
            continue
        where, _, anchor = target.partition("#")
        dest = os.path.normpath(os.path.join(os.path.dirname(path), where)) if where else path
        line = text.count("\n", 0, m.start()) + 1
        if not os.path.exists(dest):
            problems.append(f"{rel}:{line}: dead link {target} (no {os.path.relpath(dest, ROOT)})")
        elif anchor and dest.endswith(".md") and anchor not in anchors(dest):
            problems.append(f"{rel}:{line}: dead link {target} (no heading '#{anchor}' in "
                            f"{os.path.relpath(dest, ROOT)})")


def comments(rel, text):
    """(line, comment text) of a source file: // and /* */ in C++, # elsewhere."""
    out = []
    if rel.endswith((".h", ".hpp", ".cpp")):
        # Strings first, so that "http://..." or "a // b" inside a literal is not a comment.
        pattern = re.compile(r'"(?:\\.|[^"\\\n])*"|//[^\n]*|/\*.*?\*/', re.S)
        for m in pattern.finditer(text):
            if m.group(0).startswith(("//", "/*")):
                out.append((text.count("\n", 0, m.start()) + 1, m.group(0)))
    else:
        for i, line in enumerate(text.splitlines(), 1):
            at = line.find("#")
            if at >= 0 and not line.startswith("#!"):
                out.append((i, line[at:]))
    return out


PATH = re.compile(r"(?<![\w./~$-])((?:[A-Za-z0-9_.-]+/)+[A-Za-z0-9_.-]*[A-Za-z0-9_])")
KNOWN_TOP = None


def check_comments(rel, files, problems):
    global KNOWN_TOP
    if KNOWN_TOP is None:
        KNOWN_TOP = {f.split("/", 1)[0] for f in files if "/" in f}
    text = open(os.path.join(ROOT, rel), encoding="utf-8", errors="replace").read()
    here = os.path.dirname(rel)
    for line, c in comments(rel, text):
        if re.search(r"(?<![\w/.-])DESIGN\.md", c) and not os.path.exists(os.path.join(ROOT, "docs", "DESIGN.md")):
            problems.append(f"{rel}:{line}: names DESIGN.md, but docs/DESIGN.md is not in the repository")
        for m in PATH.finditer(c):
            p = m.group(1).rstrip(".")
            parts = p.split("/")
            # A repository path starts at one of the repository's top folders, or next to the file
            # (or, with "..", above it). Placeholders (OUT/, DIR/, TARGET) and build products are not.
            if parts[0] == "..":
                # Above the file: a reference names a file with its extension; "../../ds" is data.
                if "." not in parts[-1]:
                    continue
            elif parts[0] not in KNOWN_TOP and not os.path.exists(os.path.join(ROOT, here, parts[0])):
                continue
            if parts[0] in ("build", "out") or any(x.isupper() and len(x) > 1 for x in parts):
                continue
            candidates = [os.path.join(ROOT, p), os.path.join(ROOT, here, p)]
            # "validation/gci" names the module, "bench/core_latency" the program built from it.
            candidates += [c + ext for c in candidates[:2] for ext in (".h", ".cpp", ".sh", ".py")]
            inside = [c for c in candidates if os.path.normpath(c).startswith(ROOT + os.sep)]
            if not any(os.path.exists(c) for c in inside):
                problems.append(f"{rel}:{line}: names {p}, which is not in the repository")


BENCH_PAGE = re.compile(r"^bench/(log/)?[^/]+\.md$")


def checked(f):
    """Whether f is documentation or source to check: bench/'s pages and code are, the outputs its
    runs recorded in its sub-folders are not."""
    if not f.startswith("bench/"):
        return not f.startswith(SKIP_PREFIXES)
    rest = f[len("bench/"):]
    if BENCH_PAGE.match(f):
        return True
    if "/" not in rest:
        return True
    return rest.endswith((".h", ".hpp", ".cpp", ".py", ".sh", ".js")) or os.path.basename(f) == "CMakeLists.txt"


def check_bench_index(files, problems):
    """bench/README.md links every page of bench/ and bench/log/: a page it does not name is lost."""
    pages = [f for f in files if BENCH_PAGE.match(f) and f != "bench/README.md"]
    if not pages:
        return
    if "bench/README.md" not in files:
        problems.append("bench/README.md: missing; it is the index of bench/'s pages")
        return
    text = open(os.path.join(ROOT, "bench", "README.md"), encoding="utf-8").read()
    linked = set()
    for m in re.finditer(r"\[[^\]\n]*\]\(([^)\s#]+)(?:#[^)\s]*)?\)", text):
        linked.add(os.path.normpath(os.path.join("bench", m.group(1))))
    for p in pages:
        if p not in linked:
            problems.append(f"bench/README.md: does not link {p}")


def main():
    files = repository_files()
    problems = []
    for f in files:
        if not checked(f):
            continue
        if f.endswith(".md"):
            check_markdown(f, problems)
        elif f.endswith(SOURCE_EXT) or os.path.basename(f) == "CMakeLists.txt":
            check_comments(f, files, problems)
    check_bench_index(files, problems)
    for p in problems:
        print(p)
    print(f"checked {len(files)} files: {len(problems)} problems")
    if SELF_TEST:
        planted = ["README.md:3: dead link guide.md#no-such-section", "README.md:4: dead link missing.md",
                   "src/a.cpp:1: names src/missing.h", "bench/README.md: does not link bench/log/LOST.md"]
        ok = len(problems) == len(planted) and all(any(p.startswith(x) for p in problems) for x in planted)
        print("self-test:", "the planted problems were found" if ok else "FAILED: expected " + "; ".join(planted))
        return 0 if ok else 1
    return 1 if problems else 0


if __name__ == "__main__":
    sys.exit(main())
