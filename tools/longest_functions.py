#!/usr/bin/env python3
"""The longest functions of C++ sources, for STYLE.md's "functions short enough to see whole".

A brace counter, not a parser: it skips comments, string and character literals and
preprocessor lines, and takes a '{' outside any function as a function's body when its
statement has a parameter list and is not a control statement, class, namespace or
initialiser (lambdas and local blocks count within their function). A function's length runs
from its signature's first line to its closing brace.

    python3 tools/longest_functions.py 10 render ui
"""
import re, sys, pathlib

def strip(src):
    out, i, n = [], 0, len(src)
    while i < n:
        c = src[i]
        if src.startswith('//', i):
            j = src.find('\n', i); j = n if j < 0 else j
            out.append(' ' * (j - i)); i = j
        elif src.startswith('/*', i):
            j = src.find('*/', i + 2); j = n if j < 0 else j + 2
            out.append(re.sub(r'[^\n]', ' ', src[i:j])); i = j
        elif c == 'R' and src.startswith('R"', i):
            m = re.match(r'R"([^(]*)\(', src[i:])
            end = src.find(')' + m.group(1) + '"', i) + len(m.group(1)) + 2
            out.append(re.sub(r'[^\n]', ' ', src[i:end])); i = end
        elif c == '#' and (i == 0 or src[i - 1] == '\n'):
            j = i
            while True:  # a directive, with its continued lines
                j = src.find('\n', j); j = n if j < 0 else j
                if j == n or src[j - 1] != '\\':
                    break
                j += 1
            out.append(re.sub(r'[^\n]', ' ', src[i:j])); i = j
        elif c in '"\'':
            j = i + 1
            while j < n and src[j] != c:
                j += 2 if src[j] == '\\' else 1
            out.append(' ' * (j + 1 - i)); i = j + 1
        else:
            out.append(c); i += 1
    return ''.join(out)

KEYWORDS = re.compile(r'^\s*(if|for|while|switch|catch|else|do|namespace|class|struct|enum|union|extern)\b')
def functions(path):
    src = strip(path.read_text(errors='replace'))
    stack, stmt_start, res = [], 0, []
    for i, c in enumerate(src):
        if c in ';':
            stmt_start = i + 1
        elif c == '{':
            stmt = src[stmt_start:i]
            # A macro statement with no semicolon (Q_LOGGING_CATEGORY(...)) ends at its line.
            macros = list(re.finditer(r'^[ \t]*[A-Z_][A-Z0-9_]*\(.*\)[ \t]*\n', stmt, re.M))
            if macros:
                stmt_start += macros[-1].end()
            stmt = src[stmt_start:i]
            in_fn = any(kind == 'fn' for kind, _ in stack)
            is_fn = (not in_fn and '(' in stmt and ')' in stmt and not KEYWORDS.match(stmt)
                     and not re.search(r'=\s*$', stmt) and not stmt.strip().startswith('['))
            stack.append(('fn' if is_fn else 'block', stmt_start if is_fn else i))
            stmt_start = i + 1
        elif c == '}':
            if stack:
                kind, start = stack.pop()
                if kind == 'fn':
                    s = src[start:i]
                    first = start + len(s) - len(s.lstrip())
                    l0 = src.count('\n', 0, first) + 1
                    l1 = src.count('\n', 0, i) + 1
                    head = ' '.join(src[first:src.index('{', first)].split())
                    res.append((l1 - l0 + 1, f'{path}:{l0}', head[:90]))
            stmt_start = i + 1
    return res

if len(sys.argv) < 3:
    sys.exit('usage: longest_functions.py COUNT DIR...')
n = int(sys.argv[1])
rows = []
for d in sys.argv[2:]:
    for p in sorted(pathlib.Path(d).rglob('*')):
        if p.suffix in ('.cpp', '.h'):
            rows += functions(p)
for lines, where, head in sorted(rows, reverse=True)[:n]:
    print(f'{lines:5d}  {where}  {head}')
