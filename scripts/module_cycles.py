#!/usr/bin/env python3
"""Finds import cycles between the modules of each crate of the workspace; exits 1 if there is one.

Usage: scripts/module_cycles.py [--graph] [--tests] [CRATE_SRC …]   (default: scene/src renderer/src app/src)
       scripts/module_cycles.py --self-test   (finds a planted cycle, and none in ordinary shapes)

What counts as a cycle: at every level of a crate's module tree, the children of one module are the nodes,
and child A depends on child B when any file in A's subtree names a path into B's subtree (`crate::b::…`,
`super::b::…`, in `use` lines, grouped `use` braces and inline paths alike). Code under `#[cfg(test)]` is
left out, as `cargo modules dependencies` leaves it out without `--cfg-test`: a test may build its input
with any part of the crate. `--tests` counts it too. A cycle among
siblings — a → b → c → a — is an import cycle. A child naming its own ancestors' items (`super::Hit`)
or a parent naming its children is the ordinary shape of a Rust module, not a cycle. A path through a
re-export (`crate::Camera`, made by `pub use camera::Camera`) counts as a path to where the item lives.

`--graph` also prints each level's edges. Standard library only; the parse is of `use` syntax and
`crate::`/`super::`/`self::` paths, with comments and string literals removed first.
"""
import os
import re
import sys

IDENT = r'[A-Za-z_][A-Za-z0-9_]*'


def strip_comments_and_strings(text):
    """The source with comments, string and char literals blanked (line breaks kept)."""
    out, i, n = [], 0, len(text)
    while i < n:
        c = text[i]
        if text.startswith('//', i):
            j = text.find('\n', i)
            i = n if j < 0 else j
        elif text.startswith('/*', i):
            depth, i = 1, i + 2
            while i < n and depth:
                if text.startswith('/*', i):
                    depth, i = depth + 1, i + 2
                elif text.startswith('*/', i):
                    depth, i = depth - 1, i + 2
                else:
                    out.append('\n' if text[i] == '\n' else '')
                    i += 1
        elif c == 'r' and re.match(r'r#*"', text[i:i + 20]) and (i == 0 or not re.match(r'\w', text[i - 1])):
            hashes = re.match(r'r(#*)"', text[i:]).group(1)
            end = text.find('"' + hashes, i + 2 + len(hashes))
            end = n if end < 0 else end + 1 + len(hashes)
            out.append('""' + '\n' * text.count('\n', i, end))
            i = end
        elif c == '"':
            j = i + 1
            while j < n and text[j] != '"':
                j += 2 if text[j] == '\\' else 1
            out.append('""' + '\n' * text.count('\n', i, j))
            i = j + 1
        elif c == "'" and re.match(r"'(\\.|[^\\'])'|'\\u\{[0-9a-fA-F]+\}'|'\\x[0-9a-fA-F]{2}'", text[i:i + 12]):
            m = re.match(r"'(\\.|[^\\'])'|'\\u\{[0-9a-fA-F]+\}'|'\\x[0-9a-fA-F]{2}'", text[i:i + 12])
            out.append("' '")
            i += len(m.group(0))
        else:
            out.append(c)
            i += 1
    return ''.join(out)


def strip_test_items(code):
    """The code without items under `#[cfg(test)]`, and the names of child modules declared so (`mod x;`)."""
    out, test_children, pos = [], set(), 0
    pattern = re.compile(r'#\[cfg\(test\)\]')
    while True:
        m = pattern.search(code, pos)
        if not m:
            out.append(code[pos:])
            return ''.join(out), test_children
        out.append(code[pos:m.start()])
        i = m.end()
        while True:  # further attributes on the same item
            a = re.match(r'\s*#\[', code[i:])
            if not a:
                break
            depth, i = 1, i + a.end()
            while depth:
                depth += {'[': 1, ']': -1}.get(code[i], 0)
                i += 1
        declared = re.match(r'\s*(?:pub(?:\([^)]*\))?\s+)?mod\s+(' + IDENT + r')\s*;', code[i:])
        if declared:
            test_children.add(declared.group(1))
        k = i
        while k < len(code) and code[k] not in ';{':
            k += 1
        if k < len(code) and code[k] == '{':
            depth = 0
            while k < len(code):
                depth += {'{': 1, '}': -1}.get(code[k], 0)
                k += 1
                if depth == 0:
                    break
        else:
            k += 1
        out.append('\n' * code.count('\n', m.start(), k))
        pos = k


def module_files(src):
    """{module path tuple: file} for every .rs file of a crate's src folder (lib.rs/main.rs is ())."""
    modules = {}
    for root, _, files in os.walk(src):
        for name in files:
            if not name.endswith('.rs'):
                continue
            rel = os.path.relpath(os.path.join(root, name), src)
            parts = rel[:-3].split(os.sep)
            if parts[-1] == 'mod' or (len(parts) == 1 and parts[0] in ('lib', 'main')):
                parts = parts[:-1]
            modules[tuple(parts)] = os.path.join(root, name)
    return modules


def expand_use_tree(tree):
    """'a::{b, c::{d, e as f}, self}' -> ['a::b', 'a::c::d', 'a::c::e', 'a']."""
    tree = re.sub(r'\s+', '', tree)

    def expand(prefix, text):
        paths, depth, start = [], 0, 0
        parts = []
        for k, ch in enumerate(text):
            if ch == '{':
                depth += 1
            elif ch == '}':
                depth -= 1
            elif ch == ',' and depth == 0:
                parts.append(text[start:k])
                start = k + 1
        parts.append(text[start:])
        for part in parts:
            if not part:
                continue
            brace = part.find('{')
            if brace >= 0:
                head = part[:brace].rstrip(':')
                inner = part[brace + 1:part.rindex('}')]
                paths += expand(join(prefix, head), inner)
            else:
                part = re.sub(r'as' + IDENT + '$', '', part) if 'as' in part else part
                part = part.split('as')[0] if re.search(r'\bas\b', part) else part
                if part == 'self':
                    paths.append(prefix)
                elif part != '*':
                    paths.append(join(prefix, part))
                else:
                    paths.append(prefix)
        return paths

    def join(prefix, rest):
        return f'{prefix}::{rest}' if prefix and rest else prefix or rest

    return expand('', tree)


def paths_in(code):
    """Every path a file names, as written: from `use` trees and from inline `crate::`/`super::`/`self::`."""
    paths = []
    for m in re.finditer(r'\buse\s+([^;]+);', code):
        tree = re.sub(r'\bas\s+' + IDENT, '', m.group(1))
        paths += expand_use_tree(tree)
    body = re.sub(r'\buse\s+[^;]+;', '', code)
    for m in re.finditer(r'\b(?:crate|super|self)(?:\s*::\s*(?:' + IDENT + r'))+', body):
        paths.append(re.sub(r'\s+', '', m.group(0)))
    return paths


def resolve(path, here, modules, reexports):
    """The module a path leads into, as a tuple, or None for a path outside the crate."""
    segments = path.split('::')
    if segments[0] == 'crate':
        base, segments = (), segments[1:]
    elif segments[0] in ('super', 'self'):
        base = here
        while segments and segments[0] in ('super', 'self'):
            if segments[0] == 'super':
                base = base[:-1]
            segments = segments[1:]
    else:
        return None  # an external crate, std, or a name relative to the file (its own child)
    module = base
    for k, segment in enumerate(segments):
        if module + (segment,) in modules:
            module = module + (segment,)
            continue
        target = reexports.get((module, segment))
        if target is not None:
            return resolve('crate::' + '::'.join(target + tuple(segments[k + 1:])), (), modules, reexports)
        break
    return module


def reexports_of(modules, codes):
    """{(module, name): module path the name is re-exported from} for `pub use` of crate modules."""
    found = {}
    for module, code in codes.items():
        for m in re.finditer(r'\bpub(?:\([^)]*\))?\s+use\s+([^;]+);', code):
            raw = m.group(1)
            for path in expand_use_tree(raw):
                name = re.search(IDENT + r'\s*$', path)
                alias = re.search(r'\b' + re.escape(path.split('::')[-1]) + r'\s+as\s+(' + IDENT + ')', raw)
                segments = path.split('::')
                if segments[0] not in ('crate', 'super', 'self'):
                    if module + (segments[0],) not in modules:
                        continue
                    path = 'self::' + path
                    segments = path.split('::')
                key = alias.group(1) if alias else (name.group(0) if name else None)
                if key is None or segments[-1] == '*':
                    continue
                found[(module, key)] = path
    resolved = {}
    for (module, name), path in found.items():
        segments = path.split('::')
        base = () if segments[0] == 'crate' else module
        rest = segments[1:]
        while rest and rest[0] in ('super', 'self'):
            base = base[:-1] if rest[0] == 'super' else base
            rest = rest[1:]
        target = base
        for segment in rest[:-1]:
            target = target + (segment,)
        resolved[(module, name)] = target
    return resolved


def sibling_edges(modules, reexports, codes):
    """{parent: {child_a: {child_b: [example file, path]}}} — the dependencies among siblings."""
    edges = {}
    for module, code in codes.items():
        for path in paths_in(code):
            target = resolve(path, module, modules, reexports)
            if target is None:
                continue
            k = 0
            while k < len(module) and k < len(target) and module[k] == target[k]:
                k += 1
            if k < len(module) and k < len(target):
                parent = module[:k]
                edges.setdefault(parent, {}).setdefault(module[k], {}).setdefault(target[k], (modules[module], path))
    return edges


def cycles_of(graph):
    """The strongly connected components with more than one node (Tarjan)."""
    index, low, on_stack, stack, components, counter = {}, {}, set(), [], [], [0]

    def visit(v):
        index[v] = low[v] = counter[0]
        counter[0] += 1
        stack.append(v)
        on_stack.add(v)
        for w in graph.get(v, {}):
            if w not in index:
                visit(w)
                low[v] = min(low[v], low[w])
            elif w in on_stack:
                low[v] = min(low[v], index[w])
        if low[v] == index[v]:
            component = []
            while True:
                w = stack.pop()
                on_stack.discard(w)
                component.append(w)
                if w == v:
                    break
            if len(component) > 1:
                components.append(sorted(component))

    for v in sorted(graph):
        if v not in index:
            visit(v)
    return components


def check(src, show_graph, with_tests):
    modules = module_files(src)
    codes = {m: strip_comments_and_strings(open(f, encoding='utf-8').read()) for m, f in modules.items()}
    if not with_tests:
        test_modules = set()
        for module in sorted(codes, key=len):
            if any(module[:k] in test_modules for k in range(len(module) + 1)):
                codes[module] = ''
                continue
            codes[module], children = strip_test_items(codes[module])
            test_modules |= {module + (child,) for child in children}
        for module in list(codes):
            if any(module[:k] in test_modules for k in range(len(module) + 1)):
                codes[module] = ''
    reexports = reexports_of(modules, codes)
    edges = sibling_edges(modules, reexports, codes)
    found = 0
    for parent in sorted(edges):
        graph = edges[parent]
        where = '::'.join(('crate',) + parent)
        if show_graph:
            for a in sorted(graph):
                print(f'{src}: {where}: {a} -> {", ".join(sorted(graph[a]))}')
        for component in cycles_of(graph):
            found += 1
            print(f'{src}: cycle in {where}: {" <-> ".join(component)}')
            members = set(component)
            for a in component:
                for b, (file, path) in sorted(graph[a].items()):
                    if b in members:
                        print(f'    {a} -> {b}: {file} names {path}')
    return found


def self_test():
    """The checker finds a planted cycle and nothing in the ordinary shapes of a module tree."""
    import tempfile
    crate = {
        'lib.rs': 'mod a;\nmod b;\nmod shapes;\npub use a::A;\n',
        # a -> b through a grouped use, b -> a through a root re-export: a cycle.
        'a.rs': 'use crate::{b::{B, other}};\npub struct A;\n',
        'b.rs': 'pub struct B;\npub fn other() -> crate::A { crate::A }\n',
        # a parent naming its children and children naming the parent: no cycle.
        'shapes/mod.rs': 'mod sphere;\nmod plane;\npub struct Hit;\npub use sphere::Sphere;\n',
        # paths in comments and strings are not uses; a test reaching back (sphere -> plane) is a
        # cycle only with --tests.
        'shapes/sphere.rs': 'use super::Hit;\n/// crate::shapes::plane::Plane in a comment\npub struct Sphere;\n'
                            'const S: &str = "crate::shapes::plane";\n'
                            '#[cfg(test)]\nmod tests {\n    use crate::shapes::plane::Plane;\n}\n',
        'shapes/plane.rs': 'use super::sphere::Sphere;\npub struct Plane;\n'
                           '#[cfg(test)]\nfn helper() { let _ = crate::a::A; }\n',
    }
    with tempfile.TemporaryDirectory() as root:
        for name, text in crate.items():
            os.makedirs(os.path.dirname(os.path.join(root, name)), exist_ok=True)
            with open(os.path.join(root, name), 'w') as f:
                f.write(text)
        import contextlib
        import io
        with contextlib.redirect_stdout(io.StringIO()):
            found = check(root, False, False)
            found_with_tests = check(root, False, True)
    assert found == 1, f'expected the one planted cycle, found {found}'
    assert found_with_tests == 2, f'expected the planted cycle and the test-only one, found {found_with_tests}'
    print('self-test passed')


def main():
    args = sys.argv[1:]
    if '--self-test' in args:
        self_test()
        return
    show_graph = '--graph' in args
    with_tests = '--tests' in args
    crates = [a for a in args if not a.startswith('--')] or ['scene/src', 'renderer/src', 'app/src']
    os.chdir(os.path.join(os.path.dirname(os.path.abspath(__file__)), '..'))
    total = sum(check(src, show_graph, with_tests) for src in crates)
    if total:
        print(f'{total} import cycle(s)')
        sys.exit(1)
    print(f'no import cycles in {", ".join(crates)}')


if __name__ == '__main__':
    main()
