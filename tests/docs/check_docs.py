#!/usr/bin/python3
"""Checks the documentation against the tree and the built program.

  check_docs.py links    --root SRC
  check_docs.py commands --root SRC --rcbench BUILD/rcbench [--no-run]

links: every relative link and image in README.md, docs/*.md and the folder
READMEs resolves to a file or folder, and every #anchor to a heading of the
target page (GitHub's heading ids). A link into ../shared (outside the
repository) is checked when ../shared is there and skipped, with a message,
when it is not. Links inside code are not links.

commands: every command in a ```sh block of the same files (and
every `$ build/rcbench ...` line of a ```text block, which shows a real
run) that calls build/rcbench uses only subcommands and --options that the
subcommand's --help lists; a command of a study script
(scripts/NAME.py) uses only options its --help lists, and the options after
`--`, which those scripts pass to `rcbench delibot`, must be delibot's.
Then the ```sh commands that need no external data are run in document
order (README.md first), in one temporary folder (so `out/...` lands there
and a later page may read what an earlier command wrote); a command that
appears twice runs once. Each must exit 0. A command needs external data when it names ../shared or
/usr/share, contains a placeholder (FILE, robotdataN, ...), or its
subcommand reads ../shared/data by default (its --help says so).

Every problem is printed as "FILE:LINE: what is wrong"; the exit status is
1 if there was any.
"""
import argparse
import glob
import os
import re
import shlex
import subprocess
import sys
import tempfile

SKIP_DIRS = {".git", "build", "out", "node_modules"}
FENCE = re.compile(r"^(\s*)(```+|~~~+)\s*([\w+-]*)")
LINK = re.compile(r"(!?)\[((?:[^\[\]]|\[[^\]]*\])*)\]\(\s*<?([^)\s>]+)>?(?:\s+\"[^\"]*\")?\s*\)")
PLACEHOLDER = re.compile(r"(^|[^A-Za-z])(FILE|FILES|DIR|TIMELINE|OUT|N|S|K|NAME)([^A-Za-z]|$)|robotdataN|<[^>]+>")
RUN_TIMEOUT_S = 300
# The study scripts run with Debian's interpreter, which has their packages.
PYTHON = "/usr/bin/python3" if os.path.exists("/usr/bin/python3") else sys.executable


def markdown_files(root):
    """README.md, docs/*.md and every folder README.md (build and output folders excluded)."""
    files = [os.path.join(root, "README.md")] + sorted(glob.glob(os.path.join(root, "docs", "*.md")))
    for folder, dirs, names in os.walk(root):
        dirs[:] = sorted(d for d in dirs if d not in SKIP_DIRS and not d.startswith("build"))
        if folder != root and "README.md" in names:
            files.append(os.path.join(folder, "README.md"))
    return files


def split_blocks(text):
    """(prose lines with their numbers, [(language, [(line number, line)])]) of a Markdown text."""
    prose, blocks, block = [], [], None
    fence = None
    for number, line in enumerate(text.split("\n"), 1):
        m = FENCE.match(line)
        if block is None and m:
            fence, block = m.group(2), (m.group(3).lower(), [])
            continue
        if block is not None:
            if line.strip().startswith(fence) and line.strip().strip(fence[0]) == "":
                blocks.append(block)
                block = None
            else:
                block[1].append((number, line))
            continue
        prose.append((number, line))
    return prose, blocks


def heading_ids(path, cache={}):
    """GitHub's ids of a Markdown file's headings: lower case, punctuation
    dropped, spaces to hyphens, repeats numbered -1, -2, ..."""
    if path not in cache:
        with open(path, encoding="utf-8") as f:
            prose, _ = split_blocks(f.read())
        ids, seen = set(), {}
        for _, line in prose:
            m = re.match(r"^#{1,6}\s+(.*?)\s*#*\s*$", line)
            if not m:
                continue
            text = re.sub(r"\[([^\]]*)\]\([^)]*\)", r"\1", m.group(1))  # a link's text only
            slug = re.sub(r"[^\w\- ]", "", text.lower()).replace(" ", "-")
            n = seen.get(slug, 0)
            seen[slug] = n + 1
            ids.add(slug if n == 0 else f"{slug}-{n}")
        cache[path] = ids
    return cache[path]


def check_links(root):
    problems, checked, skipped = [], 0, 0
    repo = os.path.realpath(root)
    shared = os.path.normpath(os.path.join(repo, "..", "shared"))
    for md in markdown_files(root):
        rel_md = os.path.relpath(md, root)
        with open(md, encoding="utf-8") as f:
            prose, _ = split_blocks(f.read())
        for number, line in prose:
            line = re.sub(r"`[^`]*`", "``", line)  # inline code is not a link
            for m in LINK.finditer(line):
                target = m.group(3)
                if re.match(r"^[a-z][a-z0-9+.-]*:", target):  # http:, https:, mailto:
                    continue
                path, _, anchor = target.partition("#")
                resolved = os.path.normpath(os.path.join(os.path.dirname(md), path)) if path else md
                where = f"{rel_md}:{number}"
                if not resolved.startswith(repo + os.sep) and resolved != repo:
                    if resolved.startswith(shared + os.sep) and not os.path.isdir(shared):
                        skipped += 1
                        print(f"{where}: skipped {target} (../shared is not here)")
                        continue
                checked += 1
                if not os.path.exists(resolved):
                    problems.append(f"{where}: {'image' if m.group(1) else 'link'} {target}: no such file")
                    continue
                if anchor:
                    if not resolved.endswith(".md"):
                        problems.append(f"{where}: link {target}: an anchor into a file that is not Markdown")
                    elif anchor not in heading_ids(resolved):
                        problems.append(f"{where}: link {target}: no heading '{anchor}' in "
                                        f"{os.path.relpath(resolved, root)}")
    print(f"links: {checked} checked, {skipped} skipped, {len(problems)} broken")
    return problems


# ------------------------------------------------------------- commands ---

def logical_lines(lines):
    """Joins backslash continuations: [(first line number, text)]."""
    out, pending, start = [], "", None
    for number, line in lines:
        if start is None:
            start = number
        if line.rstrip().endswith("\\"):
            pending += line.rstrip()[:-1] + " "
            continue
        out.append((start, pending + line))
        pending, start = "", None
    if pending:
        out.append((start, pending))
    return out


def shown_commands(lines):
    """The `$ build/rcbench ...` lines of a transcript (with their continuations), without the `$ `."""
    out, k = [], 0
    while k < len(lines):
        number, line = lines[k]
        if line.startswith("$ build/rcbench"):
            out.append((number, line[2:]))
            while line.rstrip().endswith("\\") and k + 1 < len(lines):
                k += 1
                number, line = lines[k]
                out.append((number, line))
        k += 1
    return out


def commands_of(text):
    """Simple commands of a shell line: lists of words, split at && || ; |, comments dropped."""
    lexer = shlex.shlex(text, posix=True, punctuation_chars=True)
    lexer.whitespace_split = True
    commands, words = [], []
    for token in lexer:
        if token in ("&&", "||", ";", "|", "&"):
            if words:
                commands.append(words)
            words = []
        else:
            words.append(token)
    if words:
        commands.append(words)
    return commands


def listed_options(help_text):
    """The --options a CLI11 or argparse --help lists in its option column."""
    options = set()
    for line in help_text.split("\n"):
        if not re.match(r"^\s+-", line):
            continue
        column = re.split(r"\s{2,}", line.strip(), maxsplit=1)[0]
        options.update(re.findall(r"--[\w][\w-]*", column))
    return options


class Helps:
    """--help texts, each fetched once."""

    def __init__(self, root, rcbench):
        self.root, self.rcbench, self.cache = root, rcbench, {}

    def get(self, argv):
        key = tuple(argv)
        if key not in self.cache:
            p = subprocess.run(argv + ["--help"], cwd=self.root, capture_output=True, text=True, timeout=60)
            self.cache[key] = (p.returncode, p.stdout + p.stderr)
        return self.cache[key]

    def subcommand(self, name):
        return self.get([self.rcbench, name])

    def script(self, path):
        return self.get([PYTHON, os.path.join(self.root, path)])


def options_used(words):
    return [w.split("=", 1)[0] for w in words if w.startswith("--") and len(w) > 2]


def check_command(words, helps, where):
    """(option problems of one simple command, "rcbench" | "script" | None: what it runs)."""
    problems = []
    if words and words[0] in ("python3", "/usr/bin/python3", PYTHON):
        words = words[1:]
    if not words:
        return problems, None
    program = words[0]
    if program == "build/rcbench":
        if len(words) < 2 or words[1].startswith("-"):
            code, text = helps.get([helps.rcbench])
            for option in options_used(words[1:]):
                if option not in listed_options(text):
                    problems.append(f"{where}: rcbench has no option {option}")
            return problems, "rcbench"
        code, text = helps.subcommand(words[1])
        if code != 0:
            return [f"{where}: 'rcbench {words[1]} --help' failed (exit {code}): is '{words[1]}' a subcommand?"], "rcbench"
        listed = listed_options(text)
        for option in options_used(words[2:]):
            if option not in listed:
                problems.append(f"{where}: rcbench {words[1]} has no option {option} (not in its --help)")
        return problems, "rcbench"
    m = re.match(r"^(?:\./)?(scripts/[\w-]+\.py)$", program)
    if m:
        if not os.path.exists(os.path.join(helps.root, m.group(1))):
            return [f"{where}: {m.group(1)}: no such script"], "script"
        own, extra = (words[1:], []) if "--" not in words else (words[1:words.index("--")], words[words.index("--") + 1:])
        if not options_used(own) and not options_used(extra):
            return problems, "script"  # nothing to check against a --help it may not have
        code, text = helps.script(m.group(1))
        if code != 0:
            return [f"{where}: '{m.group(1)} --help' failed (exit {code})"], "script"
        listed = listed_options(text)
        for option in options_used(own):
            if option not in listed:
                problems.append(f"{where}: {m.group(1)} has no option {option} (not in its --help)")
        if extra:
            _, delibot = helps.subcommand("delibot")
            for option in options_used(extra):
                if option not in listed_options(delibot):
                    problems.append(f"{where}: {m.group(1)} passes {option} to rcbench delibot, which has no such option")
        return problems, "script"
    return problems, None


def needs_external_data(words, helps):
    for w in words:
        if "../shared" in w or w.startswith("/usr/share") or PLACEHOLDER.search(w):
            return True
    if len(words) > 1 and not words[1].startswith("-"):
        _, text = helps.subcommand(words[1])
        if "../shared" in text and "--help" not in words:
            return True
    return False


def check_commands(root, rcbench, run):
    helps = Helps(root, os.path.abspath(rcbench))
    problems, checked, ran, skipped = [], 0, 0, 0
    pages = markdown_files(root)
    # One folder for every page, so a page may use what an earlier command
    # wrote (out/demo/); a command already run is not run again.
    work = tempfile.TemporaryDirectory(prefix="rc-docs-")
    os.makedirs(os.path.join(work.name, "build"))
    os.symlink(os.path.abspath(rcbench), os.path.join(work.name, "build", "rcbench"))
    done = set()
    for md in pages:
        rel_md = os.path.relpath(md, root)
        with open(md, encoding="utf-8") as f:
            _, blocks = split_blocks(f.read())
        to_run = []
        for language, lines in blocks:
            if language in ("sh", "bash", "shell"):
                source = lines
            elif language in ("text", ""):
                source = shown_commands(lines)
            else:
                continue
            for number, text in logical_lines(source):
                if not text.strip() or text.strip().startswith("#"):
                    continue
                try:
                    commands = commands_of(text)
                except ValueError as e:
                    problems.append(f"{rel_md}:{number}: cannot parse the command: {e}")
                    continue
                for words in commands:
                    found, kind = check_command(words, helps, f"{rel_md}:{number}")
                    problems += found
                    if kind:
                        checked += 1
                    if kind == "rcbench" and language in ("sh", "bash", "shell"):
                        if needs_external_data(words, helps):
                            skipped += 1
                        else:
                            to_run.append((number, words))
        for number, words in (to_run if run else []):
            if tuple(words) in done:
                continue
            done.add(tuple(words))
            try:
                p = subprocess.run(words, cwd=work.name, capture_output=True, text=True, timeout=RUN_TIMEOUT_S)
                code, output = p.returncode, p.stdout + p.stderr
            except subprocess.TimeoutExpired:
                code, output = "timeout", f"ran over {RUN_TIMEOUT_S} s"
            ran += 1
            print(f"ran {rel_md}:{number}: {' '.join(words)} -> exit {code}")
            if code != 0:
                tail = "\n    ".join(output.strip().split("\n")[-5:])
                problems.append(f"{rel_md}:{number}: '{' '.join(words)}' exited {code}:\n    {tail}")
    work.cleanup()
    print(f"commands: {checked} option-checked, {ran} run, {skipped} not run (they need ../shared/data, "
          f"/usr/share or a placeholder file), {len(problems)} problems")
    return problems


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("check", choices=["links", "commands"])
    ap.add_argument("--root", required=True, help="the source tree")
    ap.add_argument("--rcbench", help="the built rcbench (commands)")
    ap.add_argument("--no-run", action="store_true", help="check options only")
    args = ap.parse_args()
    if args.check == "links":
        problems = check_links(args.root)
    else:
        if not args.rcbench:
            ap.error("commands needs --rcbench")
        problems = check_commands(args.root, args.rcbench, not args.no_run)
    for p in problems:
        print(p)
    sys.exit(1 if problems else 0)


if __name__ == "__main__":
    main()
