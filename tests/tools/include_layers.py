#!/usr/bin/env python3
"""The engine's include graph, checked against its layers (issue 48).

engine/src is in folders by stage; each may include the engine's public headers
(engine/include/tumble) and the folders before it in LAYERS, never one after it; the
public headers include no private one; no stage includes the World (tumble/world.h), which
calls them; and the engine's users (ui/, app/, engine/io/) include only the public headers.
Prints the graph's size and depth and every include that breaks a rule; exit status 1 when
there is one. ctest runs it (lint/include_layers).

  tests/tools/include_layers.py [ENGINE_DIR] [--map MOVES]   (default: engine/ beside tests/)

--map FILE (for measuring a tree from before the folders): lines "old/path new/path"; a file
is placed in the folder its new path names.
"""
import os
import re
import sys

# Lowest first. docs/architecture.md "Engine source layout" says what each owns.
LAYERS = ["common", "mesh", "collision", "model", "dynamics", "islands", "solver", "impacts",
          "guard", "world"]

INCLUDE = re.compile(r'^\s*#\s*include\s*([<"])([^>"]+)[>"]')


def files_of(engine):
    out = []
    for root in ("src", "include"):
        for d, _, names in os.walk(os.path.join(engine, root)):
            for n in names:
                if n.endswith((".h", ".cpp")):
                    out.append(os.path.relpath(os.path.join(d, n), engine))
    return sorted(out)


def main(argv):
    engine = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "engine")
    moves = {}
    args = list(argv)
    if "--map" in args:
        i = args.index("--map")
        for line in open(args[i + 1]):
            if line.strip():
                old, new = line.split()
                moves[old] = new
        del args[i:i + 2]
    if args:
        engine = args[0]
    files = files_of(engine)
    known = set(files)

    def place(f):  # the layer a file is in; None for the public headers
        f = moves.get(f, f)
        if f.startswith("include/"):
            return None
        parts = f.split("/")
        return parts[1] if len(parts) > 2 else "(top)"

    def target(f, quote, name):
        if quote == "<":
            cand = "include/" + name
            return cand if cand in known else None
        for cand in ("src/" + name, os.path.join(os.path.dirname(f), name)):
            cand = os.path.normpath(cand)
            if cand in known:
                return cand
        return None

    edges = {f: [] for f in files}
    for f in files:
        for line in open(os.path.join(engine, f), encoding="utf-8"):
            m = INCLUDE.match(line)
            if m:
                t = target(f, m.group(1), m.group(2))
                if t and t != f:
                    edges[f].append(t)

    level = {}

    def depth(f, stack=()):
        if f in level:
            return level[f]
        if f in stack:
            raise SystemExit("include cycle: " + " -> ".join(stack + (f,)))
        level[f] = 1 + max((depth(t, stack + (f,)) for t in edges[f]), default=-1)
        return level[f]

    for f in files:
        depth(f)
    wrong = []
    for f in files:
        a = place(f)
        for t in edges[f]:
            b = place(t)
            if b is None:
                continue  # the public headers are below everything
            if a is None:
                wrong.append(f"{f} -> {t}: a public header includes a private one")
            elif a == "(top)" or b == "(top)":
                continue  # a flat tree: no layers to break
            elif a not in LAYERS or b not in LAYERS:
                wrong.append(f"{f} -> {t}: {a if a not in LAYERS else b}/ is not in LAYERS")
            elif LAYERS.index(b) > LAYERS.index(a):
                wrong.append(f"{f} -> {t}: {a}/ includes {b}/, which is above it")
    # Stages that include the World (the orchestrator) for anything.
    world = [f"{f} -> include/tumble/world.h" for f in files
             if "include/tumble/world.h" in edges[f] and place(f) not in ("world", None)]
    # The engine's users: nothing of engine/src, by any path.
    private = {os.path.basename(f) for f in files if f.startswith("src/")}
    root = os.path.normpath(os.path.join(engine, ".."))
    for user in ("ui", "app", os.path.join("engine", "io")):
        for d, _, names in os.walk(os.path.join(root, user)):
            for n in names:
                if not n.endswith((".h", ".cpp")):
                    continue
                p = os.path.join(d, n)
                for line in open(p, encoding="utf-8"):
                    m = INCLUDE.match(line)
                    if m and m.group(1) == '"' and ("engine/src" in m.group(2) or
                            (os.path.basename(m.group(2)) in private and not os.path.exists(
                                os.path.join(d, m.group(2))) and "/" in m.group(2) and
                             m.group(2).split("/")[0] in LAYERS)):
                        wrong.append(f"{os.path.relpath(p, root)} -> {m.group(2)}: the engine's users "
                                     "include its public headers only")
    print(f"files: {len(files)}, includes among them: {sum(len(e) for e in edges.values())}, "
          f"levels: {max(level.values()) + 1}")
    print(f"includes pointing up a layer: {len(wrong)}; stage files including the World: {len(world)}")
    for w in wrong + world:
        print("  " + w)
    return 1 if wrong or world else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
