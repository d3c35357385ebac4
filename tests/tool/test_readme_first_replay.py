#!/usr/bin/python3
"""The README's first replay, as written, in a fresh clone with no ../shared beside it.

Clones the checkout into an empty temporary folder, puts the built tool where the README's
commands expect it (build/tool/mote), runs the last step of the Makefile's `run` recipe (what
`make run` runs once the tool is built), then the README's first `mote replay` command block as
it is written, from the clone's root. Fails unless it exits 0 and prints the summary rows the
README shows, in the same order, with the same scans / updates and `localized` verdict.

Exits 77 (ctest's SKIP_RETURN_CODE) when the source is not a git checkout or git is missing.
"""
import argparse
import os
import re
import shutil
import subprocess
import sys
import tempfile

SKIP = 77


def fail(message):
    print("FAIL: " + message)
    sys.exit(1)


def make_run_step(makefile):
    """The Makefile's `run:` recipe line that runs the tool, with $(BUILD) as its default."""
    text = open(makefile).read()
    recipe = re.search(r"^run:.*\n((?:\t.*\n)+)", text, re.M)
    if not recipe:
        fail("no run: recipe in " + makefile)
    lines = [line.strip() for line in recipe.group(1).splitlines() if "/tool/mote run" in line]
    if not lines:
        fail("the run: recipe does not run the tool")
    return lines[-1].replace("$(BUILD)", "build")


def first_replay(readme):
    """The first ```sh block of the README that runs `mote replay`, and the ``` block after it."""
    text = open(readme).read()
    blocks = re.findall(r"^```(\w*)\n(.*?)^```", text, re.M | re.S)
    for k, (lang, body) in enumerate(blocks):
        if lang == "sh" and "mote replay" in body:
            if k + 1 >= len(blocks) or blocks[k + 1][0] != "":
                fail("the first replay command is not followed by its output")
            return body, blocks[k + 1][1]
    fail("no `mote replay` command block in " + readme)


def rows(summary):
    """(name, value) of the summary's rows: two spaces, the name, two or more spaces, the value."""
    return [(m.group(1), m.group(2)) for m in
            re.finditer(r"^  (\S.*?)  +(\S.*)$", summary, re.M)]


def run(cmd, cwd):
    print("$ " + cmd)
    done = subprocess.run(cmd, shell=True, cwd=cwd, capture_output=True, text=True)
    print(done.stdout + done.stderr)
    return done


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--mote", required=True, help="the built mote executable")
    ap.add_argument("--source", required=True, help="the checkout to clone")
    args = ap.parse_args()
    if shutil.which("git") is None:
        print("SKIP: git not found")
        sys.exit(SKIP)
    if subprocess.run(["git", "-C", args.source, "rev-parse", "--git-dir"],
                      capture_output=True).returncode != 0:
        print("SKIP: " + args.source + " is not a git checkout")
        sys.exit(SKIP)
    with tempfile.TemporaryDirectory() as tmp:
        clone = os.path.join(tmp, "mote")
        subprocess.run(["git", "clone", "-q", args.source, clone], check=True)
        if os.path.exists(os.path.join(tmp, "shared")):
            fail("the temporary folder has a shared/ beside the clone")
        os.makedirs(os.path.join(clone, "build", "tool"))
        os.symlink(os.path.abspath(args.mote), os.path.join(clone, "build", "tool", "mote"))
        demo = run(make_run_step(os.path.join(clone, "Makefile")), clone)
        if demo.returncode != 0:
            fail("make run's demo exited %d" % demo.returncode)
        command, shown = first_replay(os.path.join(clone, "README.md"))
        done = run(command.replace("\\\n", " "), clone)
        if done.returncode != 0:
            fail("the README's first replay exited %d" % done.returncode)
        got, want = rows(done.stdout), rows(shown)
        if len(want) < 10:
            fail("the README's output block after the command has %d summary rows" % len(want))
        if [n for n, _ in got] != [n for n, _ in want]:
            fail("rows %s, the README shows %s" % ([n for n, _ in got], [n for n, _ in want]))
        for name in ("scans / updates", "localized"):
            if dict(got)[name] != dict(want)[name]:
                fail("%s: %r, the README shows %r" % (name, dict(got)[name], dict(want)[name]))
    print("ok: the README's first replay runs in a fresh clone as written")


if __name__ == "__main__":
    main()
