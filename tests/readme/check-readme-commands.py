#!/usr/bin/python3
"""Checks the commands README.md shows for the tools and tutorials against readme-commands.txt (see its header).

Usage: check-readme-commands.py README LIST BUILD_DIR SOURCE_DIR DATASETS_DIR CTEST WORK_DIR
Prints what it checks; exit status 0 when every command is listed, its options exist and its workload passes.
"""
import os
import re
import shlex
import shutil
import subprocess
import sys

# A README line is a tool or tutorial command when its program is one of the build's or a script run by Debian's
# python; set-up commands (./vispmorph, cmake, ctest) are not.
PROGRAM = re.compile(r"^(build/\S+|/usr/bin/python3 apps/\S+)")


def readme_commands(text):
    """The tool and tutorial commands of README's fenced shell blocks and of its tables' code spans."""
    commands = []
    in_block, shell, variables = False, False, {}
    for line in text.splitlines():
        if line.startswith("```"):
            in_block = not in_block
            shell = in_block and line[3:].strip() in ("sh", "bash", "")
            variables = {}
            continue
        if in_block and shell:
            line = re.sub(r"\s+#.*$", "", line).strip()
            m = re.match(r"^([A-Z_][A-Z0-9_]*)=(\S+)$", line)
            if m:
                variables[m.group(1)] = m.group(2)
                continue
            for name, value in variables.items():
                line = line.replace('"$' + name + '"', value).replace("$" + name, value)
            if PROGRAM.match(line):
                commands.append(" ".join(line.split()))
        elif not in_block:
            for span in re.findall(r"`([^`]+)`", line):
                if PROGRAM.match(span) and " " in span:
                    commands.append(" ".join(span.split()))
    return commands


def read_list(path):
    entries, current = [], None
    with open(path) as f:
        for raw in f:
            line = raw.rstrip("\n")
            if not line.strip() or line.startswith("#"):
                continue
            key, _, value = line.partition(": ")
            if key == "readme":
                current = {"readme": " ".join(value.split()), "run": None, "ctest": None, "datasets": False}
                entries.append(current)
            elif current is not None and key in ("run", "ctest"):
                current[key] = value.strip()
            elif current is not None and key == "needs" and value.strip() == "datasets":
                current["datasets"] = True
            else:
                raise SystemExit("%s: cannot read line %r" % (path, line))
    return entries


def program_of(command, build):
    words = shlex.split(command)
    if words[0] == "/usr/bin/python3":
        return words[:2], words[2:]
    return [os.path.join(build, words[0][len("build/"):])], words[1:]


def main():
    readme, listing, build, source, datasets, ctest, work = sys.argv[1:8]
    with open(readme) as f:
        shown = readme_commands(f.read())
    entries = read_list(listing)
    listed = {e["readme"]: e for e in entries}
    errors = []
    for c in shown:
        if c not in listed:
            errors.append("README command not in %s: %s" % (os.path.basename(listing), c))
    for e in entries:
        if e["readme"] not in shown:
            errors.append("listed command no longer in the README: %s" % e["readme"])
    os.makedirs(work, exist_ok=True)
    for c in dict.fromkeys(shown):
        e = listed.get(c)
        if e is None:
            continue
        program, args = program_of(c, build)
        if program[0] != "/usr/bin/python3" and not os.access(program[0], os.X_OK):
            errors.append("%s: no such program in the build" % c)
            continue
        usage = subprocess.run(program + ["--help"], cwd=source, capture_output=True, text=True, timeout=60)
        text = usage.stdout + usage.stderr
        for a in args:
            option = a.split("=", 1)[0]
            if option.startswith("-") and not re.search(r"(^|[\s\[|,(])" + re.escape(option) + r"\b", text):
                errors.append("%s: option %s not in its --help" % (c, option))
        if e["ctest"]:
            listing_out = subprocess.run([ctest, "--test-dir", build, "-N", "-V", "-R", "^" + re.escape(e["ctest"]) + "$"],
                                         capture_output=True, text=True).stdout
            if "Total Tests: 1" not in listing_out:
                errors.append("%s: no ctest named '%s'" % (c, e["ctest"]))
            elif os.path.basename(program[-1]) not in listing_out:
                errors.append("%s: ctest '%s' does not run %s" % (c, e["ctest"], os.path.basename(program[-1])))
            else:
                print("ok (ctest '%s'): %s" % (e["ctest"], c))
        elif e["run"]:
            if e["datasets"] and not os.path.isdir(datasets):
                print("skipped (no shape datasets in %s): %s" % (datasets, c))
                continue
            scratch = os.path.join(work, "run")
            shutil.rmtree(scratch, ignore_errors=True)
            os.makedirs(scratch)
            os.symlink(os.path.abspath(build), os.path.join(scratch, "build"))
            os.symlink(os.path.join(source, "data"), os.path.join(scratch, "data"))
            os.symlink(os.path.join(source, "apps"), os.path.join(scratch, "apps"))
            shell = e["run"].replace("same", c, 1) if e["run"].startswith("same") else e["run"]
            r = subprocess.run(["sh", "-c", shell], cwd=scratch, capture_output=True, text=True, timeout=300)
            if r.returncode != 0:
                errors.append("%s: its workload failed (exit %d): %s\n%s%s" % (c, r.returncode, shell, r.stdout[-2000:],
                                                                           r.stderr[-2000:]))
            else:
                print("ok (ran '%s'): %s" % (shell, c))
        else:
            errors.append("%s: the entry has neither run: nor ctest:" % c)
    for err in errors:
        print("ERROR: " + err)
    print("%d README commands checked, %d errors" % (len(set(shown)), len(errors)))
    return 1 if errors else 0


if __name__ == "__main__":
    sys.exit(main())
