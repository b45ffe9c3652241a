#!/usr/bin/env python3
"""Rules of docs/ARCHITECTURE.md, checked on the sources.

include-graph: every quoted #include names its file from the repository root
(the build's one include root: "shared/protocol/messages.hpp",
"provider/net/server.hpp", "tests/support/temp_dir.hpp"), and every arrow must
point down:
  - between components: shared/ includes only itself; native/ and tools/
    shared/; provider/, requester/, browser/host/ and web/wasm/ shared/ and
    native/, never each other;
  - within shared/ and within provider/: from a folder to one listed below it
    in LAYERS (or to itself);
  - Qt (<Q...>) only in provider/, OpenCV (<opencv2/...>) only in requester/.
There are no named exceptions: a new arrow up is a failure, which moves a
file or splits one, or changes LAYERS here and in docs/ARCHITECTURE.md.

type-names: no two headers define a type of one name at namespace scope
(one meaning per word: a `Screen` of the protocol and one of the network
would be read for each other).

  python3 tests/architecture/rules.py include-graph|type-names REPOSITORY
"""
import os
import re
import sys

# Each component's folders, lowest first: a folder may include its own and
# those before it.
LAYERS = {
    'shared': ['io', 'cli', 'data', 'field', 'detect', 'protocol', 'overlay', 'aiming', 'requester_core'],
    'provider': ['common', 'trust', 'net', 'board', 'screen', 'desktop', 'content', 'put', 'browser', 'discovery',
                 'field_overlay', 'service', 'tuning', 'commands', '.'],
}
# What each component may include besides itself.
COMPONENTS = {
    'shared': [],
    'native': ['shared'],
    'tools': ['shared'],
    'provider': ['shared', 'native'],
    'requester': ['shared', 'native'],
    'browser': ['shared', 'native'],
    'web': ['shared'],
}
QUOTED = re.compile(r'^\s*#\s*include\s+"([^"]+)"')
ANGLED = re.compile(r'^\s*#\s*include\s+<([^>]+)>')
SOURCE = ('.hpp', '.cpp', '.h')
# Headers made by the build (wayland-scanner's client code), on its own include path.
GENERATED = re.compile(r'^[a-z0-9-]+-client-protocol\.h$')


def resolve(repo, path, target):
    """The repository-relative file an include names: (file, rooted), or
    (None, True) for generated code. Every include names its file from the
    repository root; one that resolves only from its own folder is not rooted."""
    if os.path.isfile(os.path.join(repo, target)) and os.path.normpath(target) == target:
        return target, True
    here = os.path.normpath(os.path.join(os.path.dirname(path), target))
    if os.path.isfile(os.path.join(repo, here)):
        return here, False
    if GENERATED.search(target):
        return None, True
    return target, False


def folder(path):
    """(component, folder within it) of a repository-relative path."""
    parts = path.split('/')
    component = parts[0]
    inner = parts[1] if len(parts) > 2 else '.'
    return component, inner


def check(repo):
    problems = []
    arrows = 0
    for component in list(COMPONENTS) + ['tests']:
        for dirpath, dirnames, files in os.walk(os.path.join(repo, component)):
            dirnames[:] = [d for d in dirnames if d not in ('node_modules', 'extension')]
            for name in files:
                if not name.endswith(SOURCE):
                    continue
                path = os.path.relpath(os.path.join(dirpath, name), repo)
                with open(os.path.join(repo, path), encoding='utf-8', errors='replace') as f:
                    lines = f.readlines()
                for number, line in enumerate(lines, 1):
                    where = f'{path}:{number}'
                    angled = ANGLED.match(line)
                    if angled:
                        header = angled.group(1)
                        # Tests may use Qt and OpenCV to drive and check any component.
                        if component != 'tests' and re.match(r'Q[A-Za-z]+$|Qt[A-Za-z]+/', header) \
                                and component != 'provider':
                            problems.append(f'{where}: Qt (<{header}>) outside provider/')
                        if component != 'tests' and header.startswith('opencv2/') and component != 'requester':
                            problems.append(f'{where}: OpenCV (<{header}>) outside requester/')
                        continue
                    quoted = QUOTED.match(line)
                    if not quoted:
                        continue
                    target, rooted = resolve(repo, path, quoted.group(1))
                    if target is None:
                        continue  # generated: Wayland protocol code
                    if not rooted:
                        problems.append(f'{where}: "{quoted.group(1)}" is not named from the repository root'
                                        + (f': "{target}"' if target != quoted.group(1) else ''))
                        continue
                    if component == 'tests':
                        continue  # tests may include any component
                    arrows += 1
                    problem = arrow_problem(path, target)
                    if problem:
                        problems.append(f'{where}: {path} -> {target}: {problem}')
    return problems, arrows


def arrow_problem(source, target):
    (src_component, src_folder), (dst_component, dst_folder) = folder(source), folder(target)
    if src_component != dst_component:
        if dst_component not in COMPONENTS.get(src_component, []):
            return f'{src_component}/ may not include {dst_component}/'
        return None
    layers = LAYERS.get(src_component)
    if not layers or src_folder == dst_folder:
        return None
    for f in (src_folder, dst_folder):
        if f not in layers:
            return f'{src_component}/{f}/ is in no layer of tests/architecture/rules.py'
    if layers.index(dst_folder) > layers.index(src_folder):
        return f'an arrow up, from {src_component}/{src_folder}/ to {src_component}/{dst_folder}/'
    return None


# A type defined at namespace scope: at the start of its line, not a
# declaration (no ';' on the line), not a nested type defined out of line (A::B).
TYPE = re.compile(r'^(?:struct|class|enum class|enum)\s+([A-Za-z_]\w*)(?!\s*::)\b[^;]*$')


def sources(repo, suffixes):
    for component in COMPONENTS:
        for dirpath, dirnames, files in os.walk(os.path.join(repo, component)):
            dirnames[:] = [d for d in dirnames if d not in ('node_modules', 'extension')]
            for name in sorted(files):
                if name.endswith(suffixes):
                    yield os.path.relpath(os.path.join(dirpath, name), repo)


def check_type_names(repo):
    places = {}
    for path in sources(repo, ('.hpp', '.h')):
        with open(os.path.join(repo, path), encoding='utf-8', errors='replace') as f:
            for number, line in enumerate(f, 1):
                m = TYPE.match(line)
                if m:
                    places.setdefault(m.group(1), []).append(f'{path}:{number}')
    problems = [f'{name} is defined in {len(where)} places: {", ".join(where)}'
                for name, where in sorted(places.items()) if len(where) > 1]
    return problems, len(places)


def main():
    if len(sys.argv) != 3 or sys.argv[1] not in ('include-graph', 'type-names'):
        print(__doc__)
        return 2
    repo = os.path.abspath(sys.argv[2])
    if sys.argv[1] == 'include-graph':
        problems, arrows = check(repo)
        summary = f'include graph: {arrows} arrows, {len(problems)} against the rule'
    else:
        problems, types = check_type_names(repo)
        summary = f'type names: {types} types at namespace scope, {len(problems)} defined twice'
    for p in problems:
        print(p)
    print(summary)
    return 1 if problems else 0


if __name__ == '__main__':
    sys.exit(main())
