#!/usr/bin/env python3
"""Count the tunables in C++ sources: named numeric constants and non-trivial numeric literals.

    apps/vispmorph-count-tunables.py [--rev REV] [--list] [PATH ...]  (default: modules/morph_vs/src and include)

A named numeric constant is a `constexpr` or `const` declaration initialised by a constant expression: numeric
literals, other named constants (kName), M_PI and math functions of them; a local computed from variables is not one
(its literals count as literals). A data member's default (`double m_gain = 0.1;`) and a getter's constant
(`static double getWindow() { return 16; }`) are named constants too. Each non-trivial number counts once, as named
or as a literal. A non-trivial literal is any other numeric literal but 0, 1, 2 and 0.5 (halves and doublings), the
integers 3 to 6 (the sizes of the pose's vectors and matrices: 3 axes, the 4 planar components, 6 degrees of freedom)
and integer subscripts (`C[6][7]`): those are structure, every other number is a choice.
Comments and string literals are ignored. --rev reads the files of a git revision instead of the work tree, so that
before and after can be compared from one checkout; --list prints every counted item with its file and line.
"""
import argparse
import re
import subprocess
import sys
from pathlib import Path

SOURCE_EXT = ('.cpp', '.h', '.hpp')
TRIVIAL = {0.0, 0.5, 1.0, 2.0}
DIMENSIONS = {3.0, 4.0, 5.0, 6.0}
# A C++ numeric literal (decimal, float with optional exponent, hex), with its suffixes; not inside an identifier.
NUMBER = re.compile(r'(?<![\w.])(0[xX][0-9a-fA-F\']+|(?:\d[\d\']*\.?[\d\']*|\.\d[\d\']*)(?:[eE][+-]?\d+)?)[uUlLfF]*(?![\w.])')
MEMBER_DEFAULT = re.compile(r'\b(m_\w+|[a-z]\w*)\s*(?:=|\{)\s*([-+.\d][^;{},()]*)\}?[;,]')
GETTER = re.compile(r'\bget\w*\(\)\s*(?:const\s*)?\{\s*return\s+([^;]*);')
NAMED = re.compile(r'\b(?:static\s+)?(?:inline\s+)?(?:constexpr|const)\s+[\w:<>\s]+?\b(\w+)\s*(?:=|\{)([^;]*);')


def strip(code):
    """The code without comments, string and character literals (same line numbers)."""
    out, i, n = [], 0, len(code)
    while i < n:
        c = code[i]
        if code.startswith('//', i):
            j = code.find('\n', i)
            i = n if j < 0 else j
        elif code.startswith('/*', i):
            j = code.find('*/', i + 2)
            j = n if j < 0 else j + 2
            out.append('\n' * code.count('\n', i, j))
            i = j
        elif c in '"\'' and not (c == "'" and i > 0 and code[i - 1].isalnum()):  # digit separators are not quotes
            j = i + 1
            while j < n and code[j] != c:
                j += 2 if code[j] == '\\' else 1
            out.append(' ')
            i = j + 1
        else:
            out.append(c)
            i += 1
    return ''.join(out)


CONSTANT_NAMES = re.compile(r'\b(?:k\w+|M_PI|std|vpMath|sqrt|log|exp|pow|rad|double|int|unsigned|size_t)\b|::')


def constant(init):
    """Whether an initialiser is a constant expression (nothing left but numbers and operators)."""
    rest = NUMBER.sub(' ', CONSTANT_NAMES.sub(' ', init))
    return re.search(r'[A-Za-z_]', rest) is None


def value(text):
    t = text.replace("'", '')
    try:
        return float(int(t, 16)) if t.lower().startswith('0x') else float(t)
    except ValueError:
        return None


def count(name, code):
    """(named, literals) of one file: lists of (line, text), one item per non-trivial number."""
    code = strip(code)
    spans = [(m.start(2), m.end(2)) for m in NAMED.finditer(code) if constant(m.group(2))]
    spans += [(m.start(2), m.end(2)) for m in MEMBER_DEFAULT.finditer(code) if constant(m.group(2))]
    spans += [(m.start(1), m.end(1)) for m in GETTER.finditer(code)]
    named, literals = [], []
    for m in NUMBER.finditer(code):
        v = value(m.group(1))
        integer = '.' not in m.group(1) and 'e' not in m.group(1).lower()
        subscript = integer and code[:m.start()].rstrip().endswith('[') and code[m.end():].lstrip().startswith(']')
        if v is None or v in TRIVIAL or (integer and v in DIMENSIONS) or subscript:
            continue
        item = (code.count('\n', 0, m.start()) + 1, m.group(0))
        (named if any(a <= m.start() < b for a, b in spans) else literals).append(item)
    return named, literals


def files_of(dirs, rev):
    if rev is None:
        for d in dirs:
            for p in [Path(d)] if Path(d).is_file() else sorted(Path(d).rglob('*')):
                if p.suffix in SOURCE_EXT:
                    yield str(p), p.read_text(errors='replace')
        return
    listed = subprocess.run(['git', 'ls-tree', '-r', '--name-only', rev, '--'] + dirs, check=True,
                            capture_output=True, text=True).stdout.split()
    for path in sorted(listed):
        if path.endswith(SOURCE_EXT):
            yield path, subprocess.run(['git', 'show', f'{rev}:{path}'], check=True, capture_output=True,
                                       text=True).stdout


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument('dirs', nargs='*', default=['modules/morph_vs/src', 'modules/morph_vs/include'])
    ap.add_argument('--rev', help='a git revision to read the files from (default: the work tree)')
    ap.add_argument('--list', action='store_true', help='print every counted item')
    args = ap.parse_args()
    total_named = total_literals = 0
    print(f'{"file":66s} {"named":>6s} {"literals":>8s}')
    for path, code in files_of(args.dirs, args.rev):
        named, literals = count(path, code)
        total_named += len(named)
        total_literals += len(literals)
        if named or literals:
            print(f'{path:66s} {len(named):6d} {len(literals):8d}')
        if args.list:
            for line, text in named:
                print(f'    {path}:{line}: named {text}')
            for line, text in literals:
                print(f'    {path}:{line}: literal {text}')
    print(f'{"total":66s} {total_named:6d} {total_literals:8d}')
    print(f'tunables: {total_named + total_literals}')
    return 0


if __name__ == '__main__':
    sys.exit(main())
