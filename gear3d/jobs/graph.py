"""The stage graph of a job: profile@T -> body@T -> each output, only what is needed.

A stage is (kind, inputs, deps). Its key is the kind plus a hash of the canonical JSON of
its inputs and its dependencies' keys, so two identical stages (the same profile used by
a part and by a pair check, the same tooth in a library) collapse into one node and are
computed once. :meth:`Graph.run` walks back from the requested targets and runs only the
stages they need: a DXF-only scene has no ``body`` stage at all. Compute stages run
before any file is written (so a bad value found while building writes no file), then
the writes, then the reports (phases 0, 1, 2).

``Graph.counts`` counts the stages actually run, by kind (the tests count through it).
A process-wide cache (:data:`CACHE`) keeps small stage results (profiles, by key) so a
batch worker reuses a tooth across the library parts it builds.
"""
from __future__ import annotations

import hashlib
import json
from collections import Counter, OrderedDict
from dataclasses import dataclass, field

#: stage kinds whose results are small and kept across graphs in one process
CACHED_KINDS = ("profile",)
#: process-wide LRU of cached stage results
CACHE: "OrderedDict[str, object]" = OrderedDict()
CACHE_SIZE = 256


def canonical(x) -> str:
    """Canonical JSON (sorted keys, no spaces, floats by repr) of a stage's inputs."""
    def norm(v):
        if isinstance(v, dict):
            return {str(k): norm(v[k]) for k in sorted(v)}
        if isinstance(v, (list, tuple)):
            return [norm(u) for u in v]
        if isinstance(v, float) and v == int(v) and abs(v) < 2 ** 53:
            return int(v)            # 1.0 and 1 are the same input
        return v
    return json.dumps(norm(x), sort_keys=True, separators=(",", ":"), allow_nan=False)


@dataclass
class Stage:
    key: str
    kind: str
    label: str
    inputs: dict
    deps: tuple
    fn: object = field(repr=False, default=None)
    phase: int = 0          # 0 compute, 1 write a file, 2 report
    ctx: dict = field(default_factory=dict)   # not part of the key: names for error messages


class Graph:
    """Stages by key, in insertion order (a stage's deps are always added before it)."""

    def __init__(self, cache: bool = True):
        self.stages: "OrderedDict[str, Stage]" = OrderedDict()
        self.results: dict = {}
        self.counts: Counter = Counter()
        self.cache_hits: Counter = Counter()
        self.use_cache = cache
        self.order: list = []

    def add(self, kind: str, inputs: dict, deps=(), fn=None, label: str = "", phase: int = 0, **ctx) -> str:
        """Add a stage (or find the identical one); return its key."""
        deps = tuple(deps)
        for d in deps:
            if d not in self.stages:
                raise KeyError(f"unknown dependency {d}")
        h = hashlib.sha256(canonical({"kind": kind, "inputs": inputs, "deps": deps}).encode()).hexdigest()[:16]
        key = f"{kind}:{h}"
        if key not in self.stages:
            self.stages[key] = Stage(key, kind, label or kind, inputs, deps, fn, phase, dict(ctx))
        return key

    def needed(self, targets) -> list:
        """Keys of the stages the targets need, in run order (phase, then insertion)."""
        need = set()
        stack = list(targets)
        while stack:
            k = stack.pop()
            if k in need:
                continue
            need.add(k)
            stack.extend(self.stages[k].deps)
        pos = {k: i for i, k in enumerate(self.stages)}
        return sorted(need, key=lambda k: (self.stages[k].phase, pos[k]))

    def plan(self, targets) -> list:
        """One line per stage that :meth:`run` would run (``--dry-run``)."""
        lines = []
        for k in self.needed(targets):
            s = self.stages[k]
            deps = ", ".join(self.stages[d].label for d in s.deps)
            lines.append(f"{s.kind:<9} {s.label}" + (f"   <- {deps}" if deps else ""))
        return lines

    def run(self, targets, on_stage=None) -> dict:
        """Run the needed stages; return {key: result} for ``targets``."""
        for k in self.needed(targets):
            if k in self.results:
                continue
            s = self.stages[k]
            if self.use_cache and s.kind in CACHED_KINDS and k in CACHE:
                CACHE.move_to_end(k)
                self.results[k] = CACHE[k]
                self.cache_hits[s.kind] += 1
                continue
            res = s.fn(s, *[self.results[d] for d in s.deps])
            self.results[k] = res
            self.counts[s.kind] += 1
            self.order.append(k)
            if self.use_cache and s.kind in CACHED_KINDS:
                CACHE[k] = res
                while len(CACHE) > CACHE_SIZE:
                    CACHE.popitem(last=False)
            if on_stage is not None:
                on_stage(s)
        return {k: self.results[k] for k in targets}


def first_upstream(g, key, kind):
    """The result of the stage of ``kind`` nearest upstream of stage ``key`` (breadth first
    through its dependencies; ``key`` itself counts), or None when there is none."""
    stack = [key]
    while stack:
        k = stack.pop(0)
        if g.stages[k].kind == kind:
            return g.results.get(k)
        stack.extend(g.stages[k].deps)
    return None
