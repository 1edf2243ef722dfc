#!/usr/bin/env python3
"""Checks the examples of docs/ci.md (ctest: `ci_doc`).

- every ```yaml block loads with yaml.safe_load (GitLab CI, GitHub Actions);
- every ```bash block passes `bash -n` (the Slurm scripts);
- lists every `stitchsim <command>` flag the page uses; with `--stitchsim BINARY` it also checks
  that each appears in `BINARY <command> --help` (run that once the CLI has every flag).

Usage: python3 scripts/ci_doc_check.py [ROOT] [--stitchsim BINARY]. Exits 1 on a problem, 77
(ctest: skipped) when PyYAML is missing (Debian: python3-yaml).
"""
import re
import subprocess
import sys

COMMAND = re.compile(r"\bstitchsim((?:[ \t]+[a-z][a-z-]*(?=[\s`\]]|$))+)")
FLAG = re.compile(r"(?<![\w-])--[a-z][a-z-]*")


def code_blocks(text):
    """(language, first line number, body) of each fenced block."""
    blocks, lang, start, body = [], None, 0, []
    for number, line in enumerate(text.split("\n"), 1):
        fence = line.strip()
        if lang is None and fence.startswith("```"):
            lang, start, body = fence[3:].strip(), number + 1, []
        elif lang is not None and fence == "```":
            blocks.append((lang, start, "\n".join(body)))
            lang = None
        elif lang is not None:
            body.append(line)
    return blocks


def indent(line):
    return len(line) - len(line.lstrip())


def command_texts(text):
    """The text of each `stitchsim ...` command: inline code spans, and code lines with their
    continuations (a trailing backslash, or the lines of a YAML folded `>` scalar)."""
    commands = [span for span in re.findall(r"`([^`\n]+)`", text) if COMMAND.search(span)]
    for _, _, body in code_blocks(text):
        lines = body.split("\n")
        for i, line in enumerate(lines):
            if not COMMAND.search(line):
                continue
            folded = i > 0 and lines[i - 1].rstrip().endswith(">")
            command, j = line, i
            while j + 1 < len(lines) and (
                    lines[j].rstrip().endswith("\\")
                    or (folded and lines[j + 1].strip() and indent(lines[j + 1]) == indent(line))):
                j += 1
                command += " " + lines[j].strip()
            commands.append(command)
    return commands


def flags_by_command(text):
    """{"verify": {"--scene", ...}, "report merge": {...}}"""
    found = {}
    for command in command_texts(text):
        for match in COMMAND.finditer(command):
            name = " ".join(match.group(1).split())
            rest = command[match.end():]
            found.setdefault(name, set()).update(FLAG.findall(rest.split("stitchsim ")[0]))
    return found


def pipeline_problems(doc):
    """What a GitLab (`stages`) or GitHub (`jobs`) example must have, as docs/ci.md says."""
    problems = []
    if "stages" in doc:
        if doc.get("verify", {}).get("parallel") != 8:
            problems.append("GitLab: verify has no `parallel: 8`")
        if "verify" not in doc.get("merge", {}).get("needs", []):
            problems.append("GitLab: merge does not need verify")
        if "junit" not in doc.get("merge", {}).get("artifacts", {}).get("reports", {}):
            problems.append("GitLab: merge publishes no `reports: junit:`")
    elif "jobs" in doc:
        jobs = doc["jobs"]
        if jobs.get("verify", {}).get("strategy", {}).get("matrix", {}).get("shard") != list(
                range(1, 9)):
            problems.append("GitHub: verify's matrix is not `shard: [1, ..., 8]`")
        if jobs.get("merge", {}).get("needs") != "verify":
            problems.append("GitHub: merge does not need verify")
        steps = jobs.get("merge", {}).get("steps", [])
        if not any(s.get("with", {}).get("merge-multiple") is True for s in steps):
            problems.append("GitHub: merge downloads no artifacts with merge-multiple")
    else:
        problems.append("neither a GitLab (`stages`) nor a GitHub (`jobs`) pipeline")
    return problems


def main(argv):
    root, binary = ".", None
    args = iter(argv[1:])
    for arg in args:
        if arg == "--stitchsim":
            binary = next(args)
        else:
            root = arg
    try:
        import yaml
    except ImportError:
        print("ci_doc_check: PyYAML missing (Debian: python3-yaml); skipped")
        return 77
    path = root + "/docs/ci.md"
    with open(path, encoding="utf-8") as f:
        text = f.read()
    problems, counts = [], {"yaml": 0, "bash": 0}
    for lang, line, body in code_blocks(text):
        if lang == "yaml":
            counts["yaml"] += 1
            try:
                doc = yaml.safe_load(body)
                if not isinstance(doc, dict):
                    problems.append(f"{path}:{line}: a YAML block that is not a mapping")
                else:
                    problems += [f"{path}:{line}: {p}" for p in pipeline_problems(doc)]
            except yaml.YAMLError as e:
                problems.append(f"{path}:{line}: YAML: {e}")
        elif lang == "bash":
            counts["bash"] += 1
            r = subprocess.run(["bash", "-n"], input=body, text=True, capture_output=True)
            if r.returncode != 0:
                problems.append(f"{path}:{line}: bash -n: {r.stderr.strip()}")
    flags = flags_by_command(text)
    for name in sorted(flags):
        print(f"stitchsim {name}: {' '.join(sorted(flags[name])) or '(no flags)'}")
        if binary is None:
            continue
        r = subprocess.run([binary] + name.split() + ["--help"], text=True, capture_output=True)
        helped = set(FLAG.findall(r.stdout + r.stderr))
        for flag in sorted(flags[name] - helped):
            problems.append(f"{path}: `stitchsim {name}` has no {flag} in its --help")
    if counts["yaml"] < 2 or counts["bash"] < 3:
        problems.append(f"{path}: expected the GitLab and GitHub YAML and three Slurm bash "
                        f"blocks, found {counts}")
    for p in problems:
        print(p)
    print(f"ci_doc_check: {counts['yaml']} YAML and {counts['bash']} bash blocks, "
          f"{len(problems)} problems")
    return 1 if problems else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
