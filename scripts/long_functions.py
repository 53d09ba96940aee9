#!/usr/bin/env python3
"""Lists the functions and source files of chutelab's library code that are too long (issue 52's
"no function over 150 lines, no library source file over 800 lines").

Usage: scripts/long_functions.py [--functions N] [--files N] [--check] [DIR|FILE ...]
  --functions N  report function bodies longer than N lines (default 150)
  --files N      report .cpp/.h files longer than N lines (default 800)
  --check        exit 1 when anything is reported (a check for CI or a test)
  DIR            folders or files to scan (default: the library folders; tests/ and bench/ are not)

A function's length is counted from the line of its opening brace to the line of its closing brace,
as an editor shows it. The scan is lexical, not a C++ parser: comments, strings and character
literals are blanked, then every brace block opened outside a function whose header looks like a
function (a parameter list, not class/struct/enum/namespace or an initialiser) is one function;
lambdas and local classes count in the function around them.
"""
import argparse
import pathlib
import re
import sys

ROOT = pathlib.Path(__file__).resolve().parent.parent
LIBRARY = ["analytical", "api", "app", "core", "dem", "effects", "logs", "python", "reports", "studies",
           "validation"]
SOURCE = {".cpp", ".h", ".hpp", ".cc"}
NOT_FUNCTION = re.compile(r"^\s*(template\s*<.*>\s*)?(class|struct|union|enum|namespace|extern)\b",
                          re.S)


def blank(text):
    """The text with comments, string and character literals replaced by spaces (newlines kept)."""
    out = []
    i, n = 0, len(text)
    while i < n:
        c = text[i]
        if text.startswith("//", i):
            j = text.find("\n", i)
            j = n if j < 0 else j
            out.append(" " * (j - i))
            i = j
        elif text.startswith("/*", i):
            j = text.find("*/", i + 2)
            j = n if j < 0 else j + 2
            out.append(re.sub(r"[^\n]", " ", text[i:j]))
            i = j
        elif c == 'R' and text.startswith('R"', i) and (i == 0 or not (text[i - 1].isalnum() or text[i - 1] == '_')):
            k = text.find("(", i + 2)
            delim = ")" + text[i + 2:k] + '"'
            j = text.find(delim, k)
            j = n if j < 0 else j + len(delim)
            out.append(re.sub(r"[^\n]", " ", text[i:j]))
            i = j
        elif c in "\"'":
            if c == "'" and i > 0 and text[i - 1].isalnum():  # digit separator 1'000
                out.append(" ")
                i += 1
                continue
            j = i + 1
            while j < n and text[j] != c and text[j] != "\n":
                j += 2 if text[j] == "\\" else 1
            j = min(j + 1, n)
            out.append(re.sub(r"[^\n]", " ", text[i:j]))
            i = j
        else:
            out.append(c)
            i += 1
    return "".join(out)


def looks_like_function(header):
    header = re.sub(r"^\s*#.*$", "", header, flags=re.M).strip()
    if "(" not in header or NOT_FUNCTION.match(header):
        return False
    before_paren = header[:header.index("(")]
    if "=" in before_paren and "operator" not in before_paren:
        return False  # an initialiser: auto x = f(...) { ... } is not a definition
    return True


def functions(path):
    """(name, first line, length in lines) of each function defined in the file."""
    text = blank(path.read_text(encoding="utf-8", errors="replace"))
    found = []
    stack = []  # per open brace: True when it opened a function body
    header_start = 0
    in_function = 0
    for i, c in enumerate(text):
        if c == "{":
            is_function = not in_function and looks_like_function(text[header_start:i])
            if is_function:
                name_text = text[header_start:i]
                name = re.findall(r"([~\w:]+(?:operator\s*\S+?)?)\s*\(", name_text)
                line = text.count("\n", 0, i) + 1
                stack.append((True, name[0] if name else "?", line))
                in_function += 1
            else:
                stack.append((False, None, 0))
            header_start = i + 1
        elif c == "}":
            if stack:
                is_function, name, line = stack.pop()
                if is_function:
                    in_function -= 1
                    found.append((name, line, text.count("\n", 0, i) + 1 - line + 1))
            header_start = i + 1
        elif c == ";" and not in_function:
            header_start = i + 1
        elif c == ":" and not in_function and re.search(r"\b(public|private|protected)\s*$",
                                                        text[header_start:i]):
            header_start = i + 1
    return found


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--functions", type=int, default=150)
    parser.add_argument("--files", type=int, default=800)
    parser.add_argument("--check", action="store_true")
    parser.add_argument("dirs", nargs="*", default=LIBRARY)
    args = parser.parse_args()
    long_functions, long_files = [], []
    for d in args.dirs:
        top = ROOT / d
        for path in [top] if top.is_file() else sorted(top.rglob("*")):
            if path.suffix not in SOURCE or not path.is_file():
                continue
            rel = path.relative_to(ROOT)
            lines = path.read_text(encoding="utf-8", errors="replace").count("\n")
            if lines > args.files:
                long_files.append((lines, rel))
            for name, line, length in functions(path):
                if length > args.functions:
                    long_functions.append((length, f"{rel}:{line}", name))
    for length, where, name in sorted(long_functions, reverse=True):
        print(f"function {length:5d} lines  {where}  {name}")
    for lines, rel in sorted(long_files, reverse=True):
        print(f"file     {lines:5d} lines  {rel}")
    if args.check and (long_functions or long_files):
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main())
