#!/usr/bin/env python3
"""The how-to examples of docs/architecture.md are patches in docs/examples/
that a reader applies (issue 25): this checks one of them against the tree.

    check_example.py --source SRC --build BUILD --patch docs/examples/hello.patch \
        --max-production-files 4 [--compile FILE.cpp]...

1. The patch applies to the tree as it is (git apply --check).
2. It touches at most --max-production-files production files (files
   outside tests/ and docs/: its test and its page do not count) and at most
   --max-files files in all when given.
3. docs/architecture.md shows its `git diff --stat` (the fenced block after
   `<!-- stat: docs/examples/NAME.patch -->`) with the patch's own figures.
4. In a copy of the files it touches, with the patch applied, the C++ files
   it touches and those named by --compile (the sources behind the headers it
   changes) compile against the core: the compiler, flags and include paths
   of the build's compile_commands.json, with the copy found first.
   Syntax only (-fsyntax-only): linking the example would mean building the
   core a second time, minutes on two cores; its test ran on the branch the
   patch was made on (docs/examples/README.md).
"""
import argparse
import json
import os
import re
import shlex
import shutil
import subprocess
import sys
import tempfile


def fail(message):
    print('FAIL: ' + message)
    sys.exit(1)


def git_apply(args, cwd, patch):
    env = dict(os.environ, GIT_CEILING_DIRECTORIES=os.path.dirname(os.path.abspath(cwd)))
    return subprocess.run(['git', 'apply', *args, patch], cwd=cwd, env=env, text=True,
                          capture_output=True)


def numstat(source, patch):
    """[(added, deleted, path)] of the patch."""
    run = git_apply(['--numstat'], source, patch)
    if run.returncode != 0:
        fail(f'git apply --numstat {patch}: {run.stderr.strip()}')
    rows = []
    for line in run.stdout.splitlines():
        added, deleted, path = line.split('\t')
        rows.append((int(added), int(deleted), path))
    return rows


def is_production(path):
    return not (path.startswith('tests/') or path.startswith('docs/') or path.endswith('.md'))


def documented_stat(source, patch_rel):
    """The `git diff --stat` block docs/architecture.md shows for the patch:
    ({path: changed lines}, files, insertions, deletions)."""
    doc = os.path.join(source, 'docs', 'architecture.md')
    with open(doc, encoding='utf-8') as f:
        lines = f.read().splitlines()
    marker = f'<!-- stat: {patch_rel} -->'
    if marker not in lines:
        fail(f'docs/architecture.md has no {marker} before the patch\'s git diff --stat')
    k = lines.index(marker) + 1
    if k >= len(lines) or not lines[k].startswith('```'):
        fail(f'docs/architecture.md: no fenced block right after {marker}')
    per_file = {}
    summary = None
    for line in lines[k + 1:]:
        if line.startswith('```'):
            break
        m = re.match(r'^\s*(\S+)\s*\|\s*(\d+)\s*[+-]*\s*$', line)
        if m:
            per_file[m.group(1)] = int(m.group(2))
            continue
        m = re.match(r'^\s*(\d+) files? changed(?:, (\d+) insertions?\(\+\))?'
                     r'(?:, (\d+) deletions?\(-\))?\s*$', line)
        if m:
            summary = tuple(int(g or 0) for g in m.groups())
            continue
        fail(f'docs/architecture.md: a line of the stat block of {patch_rel} is neither a '
             f'file nor the summary: {line!r}')
    if summary is None:
        fail(f'docs/architecture.md: the stat block of {patch_rel} has no summary line')
    return per_file, summary


def compile_command(commands, source, rel):
    """The build's command for `rel`, or for a sibling in its directory (a file
    the patch adds is in no build yet), as an argument list."""
    path = os.path.realpath(os.path.join(source, rel))
    chosen = None
    for entry in commands:
        file = os.path.realpath(os.path.join(entry['directory'], entry['file']))
        if file == path:
            chosen = (entry, file)
            break
        if chosen is None and os.path.dirname(file) == os.path.dirname(path):
            chosen = (entry, file)
    if chosen is None:
        fail(f'compile_commands.json has no file in {os.path.dirname(rel)}/')
    entry, file = chosen
    args = entry['arguments'] if 'arguments' in entry else shlex.split(entry['command'])
    return args, entry['directory'], file


def syntax_only(args, cwd, built_file, copy, overlay, original_dir):
    """The build's command for `built_file` turned into a syntax check of
    `copy`: the overlay's core searched before the tree's, the original's
    directory for its quoted includes, no object or dependency file."""
    out = [args[0], '-I' + os.path.join(overlay, 'core'), '-iquote' + original_dir]
    skip = False
    for a in args[1:]:
        if skip:
            skip = False
            continue
        if a in ('-o', '-MF', '-MT', '-MQ'):
            skip = True
            continue
        if a in ('-c', '-MD', '-MMD') or a.startswith('-o'):
            continue
        if not a.startswith('-') and os.path.realpath(os.path.join(cwd, a)) == built_file:
            continue
        out.append(a)
    return out + ['-fsyntax-only', copy]


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument('--source', required=True)
    parser.add_argument('--build', required=True)
    parser.add_argument('--patch', required=True, help='relative to --source')
    parser.add_argument('--max-production-files', type=int, required=True)
    parser.add_argument('--max-files', type=int, help='all files, tests and pages included')
    parser.add_argument('--compile', action='append', default=[])
    args = parser.parse_args()
    source = os.path.realpath(args.source)
    patch = os.path.join(source, args.patch)
    if not os.path.isfile(patch):
        fail(f'{args.patch} is not in the tree')

    # 1. It applies to the tree.
    run = git_apply(['--check'], source, patch)
    if run.returncode != 0 and git_apply(['--check', '-R'], source, patch).returncode == 0:
        fail(f'{args.patch} is applied to the tree (git apply -R {args.patch} takes it out)')
    if run.returncode != 0:
        fail(f'{args.patch} no longer applies to the tree; make it again on a branch '
             f'(docs/examples/README.md):\n{run.stderr}')
    print(f'{args.patch} applies to the tree')

    # 2. Its production files.
    rows = numstat(source, patch)
    production = [p for _, _, p in rows if is_production(p)]
    print(f'{len(rows)} files, {len(production)} of them production files '
          f'(at most {args.max_production_files}): {", ".join(production)}')
    if len(production) > args.max_production_files:
        fail(f'{args.patch} touches {len(production)} production files, '
             f'more than {args.max_production_files}')
    if args.max_files is not None and len(rows) > args.max_files:
        fail(f'{args.patch} touches {len(rows)} files, more than {args.max_files}')

    # 3. The how-to shows its figures.
    per_file, summary = documented_stat(source, args.patch)
    actual = {p: a + d for a, d, p in rows}
    totals = (len(rows), sum(a for a, _, _ in rows), sum(d for _, d, _ in rows))
    if per_file != actual or summary != totals:
        fail(f'docs/architecture.md\'s git diff --stat of {args.patch} says {per_file} {summary}, '
             f'the patch {actual} {totals}')
    print(f'docs/architecture.md shows its stat: {totals[0]} files, {totals[1]} insertions, '
          f'{totals[2]} deletions')

    # 4. It compiles against the core.
    db = os.path.join(args.build, 'compile_commands.json')
    if not os.path.isfile(db):
        fail(f'{db} is missing (CMAKE_EXPORT_COMPILE_COMMANDS, a Ninja or Makefile build)')
    with open(db, encoding='utf-8') as f:
        commands = json.load(f)
    overlay = tempfile.mkdtemp(prefix='rotord_example_')
    try:
        for _, _, rel in rows:
            if os.path.exists(os.path.join(source, rel)):
                os.makedirs(os.path.dirname(os.path.join(overlay, rel)), exist_ok=True)
                shutil.copy(os.path.join(source, rel), os.path.join(overlay, rel))
        run = git_apply([], overlay, patch)
        if run.returncode != 0:
            fail(f'git apply in a copy: {run.stderr}')
        for rel in args.compile:
            if not os.path.exists(os.path.join(overlay, rel)):
                os.makedirs(os.path.dirname(os.path.join(overlay, rel)), exist_ok=True)
                shutil.copy(os.path.join(source, rel), os.path.join(overlay, rel))
        to_compile = [p for _, _, p in rows if p.endswith('.cpp')] + args.compile
        for rel in to_compile:
            cmd, cwd, built_file = compile_command(commands, source, rel)
            check = syntax_only(cmd, cwd, built_file, os.path.join(overlay, rel), overlay,
                                os.path.dirname(os.path.join(source, rel)))
            run = subprocess.run(check, cwd=cwd, text=True, capture_output=True)
            if run.returncode != 0:
                fail(f'{rel} with {args.patch} applied does not compile:\n'
                     f'{" ".join(check)}\n{run.stdout}{run.stderr}')
            print(f'{rel} with the patch applied compiles')
    finally:
        shutil.rmtree(overlay, ignore_errors=True)
    return 0


if __name__ == '__main__':
    sys.exit(main())
