#!/usr/bin/env python3
"""Size bounds of our own C++ (docs/architecture.md, "Size bounds").

No source file over 600 lines and no function body over 100 lines, in the library folders,
app/, tests/ and bench/. Run from anywhere: `python3 scripts/size_bounds.py [ROOT]`; prints
every violation as `file:line: ...` and exits 1 if there is one (ctest: `size_bounds`).

Function bodies are found by brace matching on the text with comments, strings and character
literals blanked out: a `{` opens a function body when the statement before it ends in a
parameter list `)` (possibly followed by const, noexcept, override, a trailing return type or
a constructor's initialiser list) and is not a control statement, a lambda or a brace
initialiser. A lambda counts towards the function it is written in.
"""
import os
import re
import sys

MAX_FILE_LINES = 600
MAX_FUNCTION_LINES = 100
FOLDERS = ["common", "geom", "scene", "program", "process", "planner", "trace", "sim",
           "render", "verify", "app", "tests", "bench"]
EXTENSIONS = (".h", ".cpp", ".cc", ".hpp")

CONTROL = re.compile(r"\b(if|for|while|switch|catch|do|else|try)\s*$")
CONTROL_PAREN = re.compile(r"\b(if|for|while|switch|catch)\s*\(")


def blank_literals(text):
    """Comments, string and char literals replaced by spaces (newlines kept)."""
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
            out.append("".join(ch if ch == "\n" else " " for ch in text[i:j]))
            i = j
        elif c == "R" and text.startswith('R"', i) and (i == 0 or not text[i - 1].isalnum()):
            m = re.match(r'R"([^(\s]*)\(', text[i:])
            if not m:
                out.append(c)
                i += 1
                continue
            end = ")" + m.group(1) + '"'
            j = text.find(end, i + m.end())
            j = n if j < 0 else j + len(end)
            out.append("".join(ch if ch == "\n" else " " for ch in text[i:j]))
            i = j
        elif c in "\"'":
            if c == "'" and i > 0 and text[i - 1].isalnum() and i + 1 < n and text[i + 1].isalnum():
                out.append(" ")  # digit separator 1'000
                i += 1
                continue
            j = i + 1
            while j < n and text[j] != c and text[j] != "\n":
                j += 2 if text[j] == "\\" else 1
            j = min(j + 1, n)
            out.append(" " * (j - i))
            i = j
        else:
            out.append(c)
            i += 1
    return "".join(out)


def opens_function(head):
    """`head`: the code between the previous ; { } and this {, whitespace-folded."""
    h = " ".join(head.split())
    if not h or h.endswith("]") or h.endswith("=") or h.endswith(","):
        return False
    if h.startswith("#"):
        h = h.split("\n")[-1]
    if CONTROL.search(h):
        return False
    # Strip a constructor initialiser list: `X(...) : a_(1), b_{2}` -> `X(...)`.
    depth = 0
    cut = None
    for k, ch in enumerate(h):
        if ch in "([<":
            depth += 1
        elif ch in ")]>":
            depth -= 1
        elif ch == ":" and depth == 0:
            prev = h[k - 1] if k > 0 else ""
            nxt = h[k + 1] if k + 1 < len(h) else ""
            if prev != ":" and nxt != ":":
                cut = k
                break
    if cut is not None and h[:cut].rstrip().endswith(")"):
        return not CONTROL_PAREN.match(h.lstrip()) and not re.search(r"\]\s*\(", h[:cut])
    h = re.sub(r"\s*->\s*[\w:<>,\s&*]+$", "", h)
    h = re.sub(r"(\s+(const|noexcept|override|final|mutable|volatile|&|&&))+$", "", h)
    if not h.endswith(")"):
        return False
    if re.search(r"\]\s*(\([^()]*\))?\s*(mutable\s*)?$", h) or re.search(r"\]\s*\(", h):
        return False  # a lambda
    first = h.lstrip()
    if CONTROL_PAREN.match(first) or first.startswith("return") or "=" in first.split("(")[0]:
        return False
    return True


def functions(text):
    """(start_line, end_line) of every function body (outermost only)."""
    code = blank_literals(text)
    # Preprocessor lines do not separate statements but must not join them either.
    code = "\n".join(" " * len(l) if l.lstrip().startswith("#") else l for l in code.split("\n"))
    result = []
    stack = []  # (is_function, line)
    head_start = 0
    line = 1
    in_function = 0
    for k, ch in enumerate(code):
        if ch == "\n":
            line += 1
        elif ch == "{":
            is_fn = in_function == 0 and opens_function(code[head_start:k])
            stack.append((is_fn, line))
            if is_fn:
                in_function += 1
            elif in_function:
                stack[-1] = (False, line)
            head_start = k + 1
        elif ch == "}":
            if stack:
                is_fn, start = stack.pop()
                if is_fn:
                    in_function -= 1
                    result.append((start, line))
            head_start = k + 1
        elif ch == ";":
            head_start = k + 1
    return result


def main():
    root = os.path.abspath(sys.argv[1] if len(sys.argv) > 1 else
                           os.path.join(os.path.dirname(__file__), ".."))
    problems = []
    for folder in FOLDERS:
        for dirpath, _, files in os.walk(os.path.join(root, folder)):
            for name in sorted(files):
                if not name.endswith(EXTENSIONS):
                    continue
                path = os.path.join(dirpath, name)
                rel = os.path.relpath(path, root)
                with open(path, encoding="utf-8", errors="replace") as f:
                    text = f.read()
                n = text.count("\n")
                if n > MAX_FILE_LINES:
                    problems.append(f"{rel}:1: {n} lines, over the {MAX_FILE_LINES}-line bound")
                for start, end in functions(text):
                    length = end - start + 1
                    if length > MAX_FUNCTION_LINES:
                        problems.append(f"{rel}:{start}: function body of {length} lines, over "
                                        f"the {MAX_FUNCTION_LINES}-line bound")
    for p in sorted(problems):
        print(p)
    if problems:
        print(f"size_bounds: {len(problems)} over the bounds")
        return 1
    print("size_bounds: every file and function within the bounds")
    return 0


if __name__ == "__main__":
    sys.exit(main())
