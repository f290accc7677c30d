#!/usr/bin/env python3
"""Import circles between the files of each crate (issue 29: one direction in every crate).

Usage: scripts/import-circles.py [SRC_DIR ...]   (default: every crate of the workspace)

Reads each `src/` tree as text: an edge a -> b for every `crate::b` path in module a (and in
`use crate::{b, ...}`), with lib.rs's re-exports and type aliases (`Ctx`, `Value`) resolved to
the modules they stand for; submodules count as their top-level module; `#[cfg(test)]` modules
are left out (test-only imports are not the crate's graph). Prints each crate's strongly
connected components and exits 1 if any has more than one module.
"""
import re, sys, os, glob
def modules_of(src_dir):
    mods = {}
    for f in glob.glob(src_dir + '/**/*.rs', recursive=True):
        rel = os.path.relpath(f, src_dir)
        if rel.endswith('mod.rs'):
            name = os.path.dirname(rel)
        else:
            name = rel[:-3]
        if name in ('lib', 'main'): continue
        mods[name.replace('/', '::')] = f
    return mods
def strip_tests(s):
    """Drops `#[cfg(test)] mod name { ... }` blocks: test-only imports are not the crate's graph."""
    out, i = [], 0
    for m in re.finditer(r'#\[cfg\(test\)\]\s*mod \w+ \{', s):
        if m.start() < i:
            continue
        out.append(s[i:m.start()])
        depth, j = 0, m.end() - 1
        while j < len(s):
            if s[j] == '{': depth += 1
            elif s[j] == '}':
                depth -= 1
                if depth == 0: break
            j += 1
        i = j + 1
    out.append(s[i:])
    return ''.join(out)
def strip_comments(s):
    s = re.sub(r'//[^\n]*', '', s)
    return strip_tests(s)
def lib_aliases(src):
    """Names lib.rs re-exports or aliases -> the modules they stand for."""
    lib = os.path.join(src, 'lib.rs')
    if not os.path.exists(lib):
        return {}
    text = strip_comments(open(lib).read())
    al = {}
    for m in re.finditer(r'pub use ([a-z_]+)::\{?([^;]*?)\}?;', text):
        for name in re.split(r'[,\s]+', m.group(2)):
            if name: al[name] = {m.group(1)}
    for m in re.finditer(r'pub type (\w+)(<[^=]*>)? = ([^;]*);', text):
        deps = set()
        for w in re.findall(r'\b[A-Za-z_]+\b', m.group(3)):
            deps |= al.get(w, set())
        al[m.group(1)] = deps
    return al
ALIASES = {}
def refs(text, mods):
    out = set()
    text = strip_comments(text)
    for m in re.finditer(r'crate::\{([^;]*?)\};', text, re.S):
        for part in re.split(r'[,\s]+', m.group(1)):
            out |= ALIASES.get(part.strip('{} '), set())
    for m in re.finditer(r'crate::([A-Z]\w*)', text):
        out |= ALIASES.get(m.group(1), set())
    # expand use crate::{...}
    for m in re.finditer(r'crate::\{([^;]*?)\};', text, re.S):
        for part in re.split(r'[,\s]+', m.group(1)):
            part = part.strip('{} ')
            if part: out.add(part.split('::')[0])
    for m in re.finditer(r'crate::([a-z_][a-z0-9_]*)(::([a-z_][a-z0-9_]*))?', text):
        out.add(m.group(1))
        if m.group(3) and f'{m.group(1)}::{m.group(3)}' in mods:
            out.add(f'{m.group(1)}::{m.group(3)}')
    return out
def top(name):
    return name.split('::')[0]
here = os.path.dirname(os.path.abspath(__file__))
root = os.path.dirname(here)
dirs = sys.argv[1:] or sorted(
    [os.path.join(root, 'crates', c, 'src') for c in os.listdir(os.path.join(root, 'crates'))]
    + [os.path.join(root, d, 'src') for d in ('.', 'editor', 'python')]
)
found = False
for src in dirs:
    if not os.path.isdir(src):
        continue
    mods = modules_of(src)
    ALIASES.clear(); ALIASES.update(lib_aliases(src))
    tops = {top(m) for m in mods}
    edges = {}
    for name, f in mods.items():
        t = top(name)
        for r in refs(open(f).read(), mods):
            r = top(r)
            if r in tops and r != t:
                edges.setdefault(t, set()).add(r)
    # Tarjan
    index = {}; low = {}; stack = []; on = set(); sccs = []; i = [0]
    sys.setrecursionlimit(10000)
    def strong(v):
        index[v] = low[v] = i[0]; i[0] += 1; stack.append(v); on.add(v)
        for w in edges.get(v, ()):
            if w not in index:
                strong(w); low[v] = min(low[v], low[w])
            elif w in on:
                low[v] = min(low[v], index[w])
        if low[v] == index[v]:
            comp = []
            while True:
                w = stack.pop(); on.discard(w); comp.append(w)
                if w == v: break
            if len(comp) > 1: sccs.append(sorted(comp))
    for v in sorted(tops):
        if v not in index: strong(v)
    found |= bool(sccs)
    print(f'{os.path.relpath(src, root)}: {len(tops)} modules, {sum(len(e) for e in edges.values())} edges, cycles: {sccs if sccs else "none"}')
    for c in sccs:
        for a in c:
            print('   ', a, '->', sorted(x for x in edges.get(a, ()) if x in c))
sys.exit(1 if found else 0)
