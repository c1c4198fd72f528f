#!/usr/bin/env python3
"""Fails when Kiln's source folders include each other in a cycle.

The nodes are the layers (core, materials, lights, media, scenes) and the renderer's concept folders (renderer/world,
renderer/integrators, ...); an edge A -> B is a `#include "B/..."` in a file of A. Dependencies must point one way
(README, "Layout"), so every strongly connected component of more than one folder is an error: each is printed with
the includes that close it, and the exit status is 1.

    tools/folder_cycles.py [REPO]          # REPO: the checkout (default: this script's)
    tools/folder_cycles.py --graph [REPO]  # also print every folder's dependencies
"""
import os
import re
import sys

LAYERS = ("core", "materials", "lights", "media", "scenes", "renderer")
SOURCE = re.compile(r"\.(h|hpp|cpp|cc)$")
INCLUDE = re.compile(r'^\s*#\s*include\s+"([^"]+)"', re.M)


def folder_of(path):
    """The node a repository-relative path belongs to (None outside the layers)."""
    parts = path.split("/")
    if parts[0] not in LAYERS or len(parts) < 2:
        return None
    if parts[0] == "renderer":
        return "renderer/" + parts[1] if len(parts) > 2 else "renderer"
    return parts[0]


def include_graph(repo):
    """{folder: {included folder: [(file, line), ...]}}"""
    graph = {}
    for layer in LAYERS:
        for root, _, files in os.walk(os.path.join(repo, layer)):
            for name in files:
                if not SOURCE.search(name):
                    continue
                path = os.path.join(root, name)
                rel = os.path.relpath(path, repo).replace(os.sep, "/")
                src = folder_of(rel)
                graph.setdefault(src, {})
                with open(path, encoding="utf-8", errors="replace") as f:
                    text = f.read()
                for m in INCLUDE.finditer(text):
                    inc = m.group(1)
                    # Includes are written from the repository root; a bare name is the including file's neighbour.
                    target = inc if "/" in inc else os.path.relpath(os.path.join(os.path.dirname(path), inc), repo)
                    dst = folder_of(target.replace(os.sep, "/"))
                    if dst and dst != src:
                        line = text.count("\n", 0, m.start()) + 1
                        graph[src].setdefault(dst, []).append((rel, line))
    return graph


def strongly_connected(graph):
    """Tarjan's algorithm: the components of the graph, each a sorted list of nodes."""
    index, low, on_stack, stack, out = {}, {}, set(), [], []

    def visit(v):
        index[v] = low[v] = len(index)
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
            out.append(sorted(component))

    for v in sorted(graph):
        if v not in index:
            visit(v)
    return out


def main(argv):
    show = "--graph" in argv
    args = [a for a in argv if a != "--graph"]
    repo = os.path.abspath(args[0] if args else os.path.join(os.path.dirname(__file__), ".."))
    graph = include_graph(repo)
    if show:
        for src in sorted(graph):
            print(f"{src} -> {', '.join(sorted(graph[src])) or '(nothing)'}")
    cycles = [c for c in strongly_connected(graph) if len(c) > 1]
    for c in cycles:
        print("folder cycle: " + " <-> ".join(c))
        for src in c:
            for dst in sorted(graph[src]):
                if dst in c:
                    file, line = graph[src][dst][0]
                    more = len(graph[src][dst]) - 1
                    print(f"  {src} -> {dst}: {file}:{line}" + (f" (+{more} more)" if more else ""))
    if cycles:
        return 1
    print(f"no folder cycles among {len(graph)} folders")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
