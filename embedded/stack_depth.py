#!/usr/bin/env python3
"""stack_depth.py -- worst stack depth of the library's entry points from
GCC's call-graph files (-fstack-usage -fcallgraph-info=su: one .ci file per
object, VCG format).

Method: every node carries its function's own frame in bytes (the same
figure as the .su file: locals, spills, saved registers, outgoing
arguments); every edge is a call site. The depth of a function is its frame
plus the deepest of its callees, computed by a depth-first walk of the call
graph (a cycle, i.e. recursion, would make the bound undefined and is an
error -- the library has none). Calls leaving the library (the C library's
expf/logf/memcpy/...) have no frame figure here; they are listed, and their
real share is covered by the firmware's measured stack high-water mark.
A function flagged dynamic (alloca/VLA) would also make the bound undefined
and is reported as an error.

usage: stack_depth.py FILE.ci... ; prints the worst chain per public entry point.
"""
import re
import sys

ENTRY = ("rtb_step", "rtb_evaluate", "rtb_state_init", "rtb_commit")


def parse(paths):
    frames, labels, calls = {}, {}, {}
    node = re.compile(r'node: \{ title: "([^"]+)" label: "([^"]*)"')
    edge = re.compile(r'edge: \{ sourcename: "([^"]+)" targetname: "([^"]+)"')
    for path in paths:
        with open(path) as f:
            for line in f:
                m = node.search(line)
                if m:
                    title, label = m.groups()
                    labels[title] = label.split("\\n")[0]
                    s = re.search(r"(\d+) bytes \((\w+)", label)
                    if s:
                        if s.group(2) != "static":
                            sys.exit("stack_depth: %s has a %s frame" % (labels[title], s.group(2)))
                        frames[title] = int(s.group(1))
                    continue
                m = edge.search(line)
                if m:
                    calls.setdefault(m.group(1), set()).add(m.group(2))
    return frames, labels, calls


def deepest(fn, frames, calls, memo, path):
    if fn in memo:
        return memo[fn]
    if fn in path:
        sys.exit("stack_depth: recursion through " + fn)
    path.add(fn)
    best, chain = 0, []
    for callee in calls.get(fn, ()):
        d, c = deepest(callee, frames, calls, memo, path)
        if d > best or (d == best and not chain):
            best, chain = d, c
    path.discard(fn)
    memo[fn] = (frames.get(fn, 0) + best, [fn] + chain)
    return memo[fn]


def short_name(fn, labels):
    """Function name from its label, or from the node title for GCC clones
    (rtb_step_detailed.part.0, whose label lacks the name)."""
    name = labels.get(fn, fn).split("(")[0].split(" ")[-1]
    return fn.split(":")[-1] if not name or name.isdigit() else name


def main():
    frames, labels, calls = parse(sys.argv[1:])
    memo = {}
    external = sorted({c for cs in calls.values() for c in cs if c not in frames})
    worst = 0
    for e in ENTRY:
        if e not in frames:
            continue
        depth, chain = deepest(e, frames, calls, memo, set())
        worst = max(worst, depth)
        print("%-15s %5d bytes: %s" % (e, depth, " -> ".join(
            "%s (%s)" % (short_name(f, labels), frames.get(f, "ext")) for f in chain)))
    print("worst library stack depth: %d bytes (+ the C library's leaf calls: %s)"
          % (worst, ", ".join(external)))


if __name__ == "__main__":
    main()
