#!/usr/bin/env python3
"""Runs the tours of README.md and checks what they print (ctest: `readme_tour.NAME`).

A tour is an HTML comment `<!-- tour: NAME -->`, then a ```sh block (the commands), then a
```text block (what they print). The sh block runs with bash (`set -euo pipefail`) in a fresh
temporary folder where `scenes` and `models` are symlinks to ROOT's and `build/app/stitchsim`
is a symlink to BINARY, so the README's literal commands run unchanged; the folder is removed
afterwards. The commands must exit 0, and the text block must match stdout and stderr
combined:
- expected lines are found in the output in order; consecutive expected lines must match
  consecutive output lines, and a line that is only `...` skips any number of lines (before
  the first and after the last expected line any lines may come);
- inside a line, `...` matches any text (times, rates, paths) and a run of spaces any run of
  spaces; the rest must match the whole output line exactly;
- every file under `out/` that the text or the commands name must exist afterwards.

Usage: python3 scripts/readme_tours.py ROOT --stitchsim BINARY [--tour NAME] [--timeout S]
       python3 scripts/readme_tours.py --self-test   (the matcher's own checks)
Exits 0 when every tour matches, 1 on a failed or timed-out command or a mismatch (the
expected line not found and the actual output are printed), 2 on bad usage (unknown tour,
no binary, a README whose tour lacks a block).
"""
import argparse
import os
import re
import signal
import subprocess
import sys
import tempfile

MARKER = re.compile(r"^<!--\s*tour:\s*([\w-]+)\s*-->\s*$")
# The repository folders a tour reads; outputs go to out/ in the temporary folder.
LINKED = ("scenes", "models")
OUT_PATH = re.compile(r"(?<![\w./-])out/[^\s'\"`(),;:]*")
GLOB = re.compile(r"[*?\[{$]|\.\.\.")  # a pattern, a variable or an elision: not one file
SKIP = "..."


def fenced_blocks(lines, start):
    """(language, body lines) of each fenced block from line index `start` on."""
    i = start
    while i < len(lines):
        fence = lines[i].strip()
        if fence.startswith("```"):
            lang, body, i = fence[3:].strip(), [], i + 1
            while i < len(lines) and lines[i].strip() != "```":
                body.append(lines[i])
                i += 1
            yield lang, body
        i += 1


def read_tours(readme):
    """{name: (sh lines, text lines)}: the first ```sh block after each marker and the first
    ```text block after that, both before the next marker."""
    lines = open(readme, encoding="utf-8").read().split("\n")
    marks = [(i, m.group(1)) for i, line in enumerate(lines) if (m := MARKER.match(line))]
    tours = {}
    for k, (at, name) in enumerate(marks):
        end = marks[k + 1][0] if k + 1 < len(marks) else len(lines)
        sh = text = None
        for lang, body in fenced_blocks(lines[:end], at + 1):
            if sh is None and lang == "sh":
                sh = body
            elif sh is not None and lang == "text":
                text = body
                break
        if name in tours or sh is None or text is None:
            raise ValueError(f"{readme}:{at + 1}: tour '{name}' needs one ```sh block then one "
                             "```text block before the next tour")
        tours[name] = (sh, text)
    return tours


def line_pattern(expected):
    """The expected line as a regex: `...` matches any text, a run of spaces any run (a
    table's columns widen with its widest value), the rest literally."""
    pieces = re.split(r"(\.\.\.|\s+)", expected.strip())
    regex = "".join(".*" if p == SKIP else r"\s+" if p.isspace() else re.escape(p)
                    for p in pieces if p)
    return re.compile(r"\s*" + regex + r"\s*")


def out_files(lines):
    """The files and folders under out/ that `lines` name (not patterns or elided paths)."""
    paths = (p.rstrip(".") for p in OUT_PATH.findall("\n".join(lines)))
    return sorted({p for p in paths if not GLOB.search(p)})


def match(expected, actual):
    """None when `expected` (lines) matches `actual` (lines), else the expected line that was
    not found (the first line of the run of consecutive lines that could not be placed)."""
    runs, run = [], []
    for line in expected:
        if line.strip() == SKIP:
            runs.append(run)
            run = []
        else:
            run.append(line)
    runs.append(run)
    pos = 0
    for run in filter(None, runs):
        patterns = [line_pattern(line) for line in run]
        found = next((s for s in range(pos, len(actual) - len(run) + 1)
                      if all(p.fullmatch(actual[s + j]) for j, p in enumerate(patterns))), None)
        if found is None:
            # Name the line that breaks the run: the longest prefix that still fits anywhere.
            for n in range(len(run), 0, -1):
                if any(all(p.fullmatch(actual[s + j]) for j, p in enumerate(patterns[:n]))
                       for s in range(pos, len(actual) - n + 1)):
                    return run[n] if n < len(run) else run[0]
            return run[0]
        pos = found + len(run)
    return None


def run_tour(root, binary, name, sh, text, timeout):
    """True when the tour's commands succeed and print what its text block says."""
    with tempfile.TemporaryDirectory(prefix=f"readme_tour.{name}.") as work:
        for folder in LINKED:
            os.symlink(os.path.join(root, folder), os.path.join(work, folder))
        os.makedirs(os.path.join(work, "build", "app"))
        os.symlink(binary, os.path.join(work, "build", "app", "stitchsim"))
        script = "set -euo pipefail\n" + "\n".join(sh) + "\n"
        # Own session, so stitchsim goes down with bash on a timeout or an interrupt.
        proc = subprocess.Popen(["bash", "-c", script], cwd=work, stdin=subprocess.DEVNULL,
                                stdout=subprocess.PIPE, stderr=subprocess.STDOUT,
                                start_new_session=True)
        timed_out = False
        try:
            raw = proc.communicate(timeout=timeout)[0]
        except subprocess.TimeoutExpired:
            os.killpg(proc.pid, signal.SIGKILL)
            raw, timed_out = proc.communicate()[0], True
        except BaseException:
            os.killpg(proc.pid, signal.SIGKILL)
            proc.wait()
            raise
        output = raw.decode("utf-8", "replace")
        output += "" if output.endswith("\n") or not output else "\n"
        actual = output.split("\n")
        # The text's files (the spec), and the commands' own (an --html page prints no path).
        missing = [p for p in out_files(text + sh) if not os.path.exists(os.path.join(work, p))]
    problem = None
    if timed_out:
        problem = f"the commands ran past --timeout {timeout:g} s"
    elif proc.returncode != 0:
        problem = f"the commands exited {proc.returncode}"
    elif (line := match(text, actual)) is not None:
        problem = f"expected line not found (in order):\n  {line.strip()}"
    elif missing:
        problem = "not written: " + ", ".join(missing)
    if problem is None:
        print(f"tour {name}: ok")
        return True
    print(f"tour {name}: FAILED: {problem}\n--- actual output ---\n{output}--- end ---")
    return False


def self_test():
    """The matcher's own checks (ctest: `readme_tour.matcher`)."""
    out = ["plan: 3 stitches", "  rate 1200 lines/s", "verdict: PASS", "(a+b)*2", "done"]
    cases = [  # (expected, should match, what it shows)
        (["plan: 3 stitches", "verdict: PASS"], False, "consecutive lines must be adjacent"),
        (["plan: 3 stitches", "...", "verdict: PASS"], True, "a `...` line skips a line"),
        (["plan: 3 stitches", "...", "(a+b)*2"], True, "a `...` line skips several lines"),
        (["verdict: PASS", "...", "(a+b)*2"], True, "a `...` line may skip none"),
        (["plan: 3 stitches", "rate ... lines/s", "verdict: PASS"], True, "`...` in a line"),
        (["verdict: PASS"], True, "any lines before the first expected line"),
        (["verdict: FAIL"], False, "a wrong expected line fails"),
        (["plan: 4 stitches", "...", "done"], False, "a wrong number fails"),
        (["verdict: PASS", "...", "plan: 3 stitches"], False, "order matters"),
        (["verdict:"], False, "an expected line matches a whole line"),
        (["(a+b)*2"], True, "regex characters are literal"),
        (["rate   1200 lines/s"], True, "a run of spaces matches any run"),
        (["rate 1200lines/s"], False, "but spaces are not optional"),
        (["(a+b)...2", "...", "nothing"], False, "every expected line must appear"),
        (["...", "...plan...", "...", "do..."], True, "several `...` forms together"),
    ]
    failed = 0
    for expected, ok, what in cases:
        if (match(expected, out) is None) != ok:
            failed += 1
            print(f"self-test FAILED: {what}: {expected} should {'' if ok else 'not '}match")
    readme = ["<!-- tour: t -->", "```sh", "echo hi", "```", "```text", "hi", "```"]
    with tempfile.TemporaryDirectory() as work:
        path = os.path.join(work, "README.md")
        with open(path, "w", encoding="utf-8") as f:
            f.write("\n".join(readme) + "\n")
        if read_tours(path) != {"t": (["echo hi"], ["hi"])}:
            failed += 1
            print("self-test FAILED: the tour's blocks are not read back")
    print(f"self-test: {len(cases) + 1 - failed} of {len(cases) + 1} checks passed")
    return 1 if failed else 0


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])  # exits 2 on misuse
    parser.add_argument("root", nargs="?", help="the repository root (holds README.md)")
    parser.add_argument("--stitchsim", help="the stitchsim binary the tours run")
    parser.add_argument("--tour", action="append", help="run only this tour (repeatable)")
    # Below ctest's TIMEOUT (120 s), which kills with SIGKILL: time to remove the folder.
    parser.add_argument("--timeout", type=float, default=110, help="seconds per tour")
    parser.add_argument("--self-test", action="store_true", help="check the matcher only")
    args = parser.parse_args()
    if args.self_test:
        return self_test()
    if not args.root or not args.stitchsim:
        parser.error("ROOT and --stitchsim BINARY are required")
    root, binary = os.path.abspath(args.root), os.path.abspath(args.stitchsim)
    if not os.access(binary, os.X_OK):
        parser.error(f"{binary}: not an executable")
    try:
        tours = read_tours(os.path.join(root, "README.md"))
    except (OSError, ValueError) as e:
        print(f"error: {e}", file=sys.stderr)
        return 2
    unknown = [t for t in args.tour or [] if t not in tours]
    if unknown or not tours:
        parser.error(f"no tour {', '.join(unknown)} in README.md; it has: {', '.join(tours)}")
    # A SIGTERM (kill, a CI runner stopping) unwinds too, so the folder is removed.
    signal.signal(signal.SIGTERM, lambda *_: sys.exit(1))
    results = [run_tour(root, binary, name, *tours[name], args.timeout)
               for name in args.tour or tours]
    return 0 if all(results) else 1


if __name__ == "__main__":
    sys.exit(main())
