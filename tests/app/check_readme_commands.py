#!/usr/bin/python3
"""Checks that README.md's command list and the programs' --help agree.

    check_readme_commands.py README.md GRADEM BIN_DIR...

README.md's "## Commands" section lists one synopsis a line ("    gradem lab <...> [--out DIR]",
"    gradem-bench [--sizes ...]"). Checked:
  - every gradem command of the README is in `gradem --help` (exit 0) and answers
    `gradem <command> --help` with exit 0 and its usage on stdout;
  - every command `gradem --help` lists is in the README;
  - every --option of a README line is in that command's --help;
  - a <a|b|c> choice (the report kinds) is the same in the README, in `gradem --help` and in
    the command's --help;
  - every bench program of the README (found in one of BIN_DIR, when built) answers --help with
    exit 0, its usage on stdout, and knows the options the README gives it;
  - the README's "Exit status" paragraph and the --help texts give the same codes 0-3.
"""
import os
import re
import subprocess
import sys

failures = []


def fail(message):
    failures.append(message)
    print("FAILED: " + message)


def run(argv):
    r = subprocess.run(argv, capture_output=True, text=True, errors="replace", timeout=120)
    return r.returncode, r.stdout, r.stderr


def readme_commands(text):
    section = text.split("\n## Commands", 1)[1].split("\n## ", 1)[0]
    lines = [l.strip() for l in section.splitlines() if l.startswith("    gradem")]
    return section, lines


def choices(text):
    return [set(g.split("|")) for g in re.findall(r"<([\w-]+(?:\|[\w-]+)+)>", text)]


def exit_codes(text):
    return set(re.findall(r"\b([0-3]) (?:success|bad input|bad usage|[^;\n]*fail)", text))


def main():
    readme_path, gradem, bin_dirs = sys.argv[1], sys.argv[2], sys.argv[3:]
    readme = open(readme_path, encoding="utf-8").read()
    section, lines = readme_commands(readme)
    if not lines:
        fail("no command lines in README.md's ## Commands section")

    code, top, err = run([gradem, "--help"])
    if code != 0:
        fail("gradem --help: exit %d" % code)
    listed = re.findall(r"^  ([a-z][\w-]*)\s{2,}\S", top.split("\ncommands:\n", 1)[-1].split("\n\n", 1)[0], re.MULTILINE)
    if not listed:
        fail("gradem --help lists no command")

    readme_gradem = {}
    benches = {}
    for line in lines:
        words = line.split()
        if words[0] == "gradem":
            readme_gradem.setdefault(words[1], []).append(line)
        else:
            benches.setdefault(words[0], []).append(line)

    for name, name_lines in readme_gradem.items():
        if name not in listed:
            fail("README command '%s' is not in gradem --help" % name)
        code, help_text, err = run([gradem, name, "--help"])
        if code != 0 or not help_text.startswith("usage: gradem " + name):
            fail("gradem %s --help: exit %d, stdout starts %r" % (name, code, help_text[:40]))
            continue
        top_line = next((l for l in top.splitlines() if l.strip().startswith("gradem %s " % name)), "")
        for line in name_lines:
            for option in re.findall(r"(--[a-z][\w-]*)", line):
                if option not in help_text:
                    fail("README gives gradem %s %s; its --help does not list it" % (name, option))
            for group in choices(line):
                usage_line = help_text.splitlines()[0]
                if group not in choices(usage_line):
                    fail("README's <%s> of gradem %s differs from its --help: %s" % ("|".join(sorted(group)), name, usage_line))
                if group not in choices(top_line):
                    fail("README's <%s> of gradem %s differs from gradem --help: %s" % ("|".join(sorted(group)), name, top_line))
    for name in listed:
        if name not in readme_gradem:
            fail("gradem --help lists '%s'; README.md's command list does not" % name)

    for program, program_lines in benches.items():
        path = next((os.path.join(d, program) for d in bin_dirs if os.path.exists(os.path.join(d, program))), None)
        if path is None:
            print("skipped: %s is not built" % program)
            continue
        code, help_text, err = run([path, "--help"])
        if code != 0 or not re.match(r"usage: (mpirun -np N )?" + re.escape(program), help_text):
            fail("%s --help: exit %d, stdout starts %r" % (program, code, help_text[:40]))
            continue
        for line in program_lines:
            for option in re.findall(r"(--[a-z][\w-]*)", line):
                if option not in help_text:
                    fail("README gives %s %s; its --help does not list it" % (program, option))
        if exit_codes(help_text) != {"0", "1", "2", "3"}:
            fail("%s --help does not give the exit status 0-3" % program)

    status = re.search(r"Exit status[^\n]*\n?(.*?)(\n\n|$)", section, re.DOTALL)
    if not status:
        fail("README.md's ## Commands has no 'Exit status' paragraph")
    elif exit_codes(status.group(0)) != {"0", "1", "2", "3"}:
        fail("README.md's Exit status paragraph does not give 0 success, 1 bad input, 2 bad usage, 3 ...")
    if exit_codes(top) != {"0", "1", "2", "3"}:
        fail("gradem --help does not give the exit status 0-3")

    print("README.md's command list and the --help texts agree" if not failures else "%d differences" % len(failures))
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
