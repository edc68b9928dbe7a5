"""The tooth period a plan's probe sampled, kept for the build that follows (issue 28).

:func:`gear3d.plan.probe_profile` runs a profile's builder up to its first sampled tooth
period (stage 1 of :func:`gear3d.buildsteps.generate`) and stops there; the build that
follows, with the same family and parameters, sampled that period again (about 3.5 ms of
the reference helical STL command's 38 ms). This module keeps what the probe sampled for
that build:

- :func:`build_key` names a build by its family and parameters; only plain values count
  (numbers, strings, booleans, None and tuples or lists of them): a build with any other
  parameter value (an array, a callable) gets no key and is never kept;
- :func:`building` makes a key the current build of this thread (nested builds, a mate's
  generating profile, have their own); the first sampling of each build is its one slot;
- :func:`first_sampling` names the current build's first sampling (None for the others);
- :func:`keep` stores a first sampling made while :func:`probing`, under the arguments it
  was made from; :func:`take` returns it once, to the first sampling of a build with the
  same key and arguments (and forgets it); None otherwise. One entry is kept: the last
  probe's.

The user of a kept sampling still checks it against its own exact pieces
(:func:`gear3d.buildsteps.sample_pieces`), so a stale entry can only cost time, never
change a result.

Example::

    >>> from gear3d import probecache
    >>> k = probecache.build_key("involute", {"teeth": 20, "tolerance": 0.001})
    >>> with probecache.probing(), probecache.building(k):
    ...     probecache.keep(probecache.first_sampling(), (20, 0.001), lambda: "sampled")
    True
    >>> with probecache.building(k):
    ...     s = probecache.first_sampling()
    ...     probecache.take(s, (20, 0.001)), probecache.take(s, (20, 0.001))
    ('sampled', None)
"""
from __future__ import annotations

import contextlib
import threading

__all__ = ["build_key", "building", "first_sampling", "keep", "probing", "take"]

_PLAIN = (bool, int, float, str, type(None))
_LOCAL = threading.local()
#: the last kept sampling: (build key, arguments, the value)
_KEPT: list = []


def _plain(value) -> bool:
    if isinstance(value, (tuple, list)):
        return all(_plain(v) for v in value)
    return type(value) in _PLAIN


def build_key(family: str, params: dict):
    """A hashable name of the build of ``family`` with ``params`` (the builder's keyword
    arguments), or None when a parameter is not a plain value (see the module doc).

    >>> build_key("sine", {"teeth": 12, "rack": [1.0, 2.0]})
    ('sine', (('rack', (1.0, 2.0)), ('teeth', 12)))
    >>> build_key("sine", {"points": object()}) is None
    True
    """
    if not isinstance(family, str) or not all(isinstance(k, str) and _plain(v) for k, v in params.items()):
        return None
    return family, tuple(sorted((k, tuple(v) if isinstance(v, list) else v) for k, v in params.items()))


@contextlib.contextmanager
def building(key):
    """Make ``key`` (:func:`build_key`, None: not kept) the current build of this thread
    while the block runs; its first sampling is the one :func:`first_sampling` names."""
    saved = getattr(_LOCAL, "current", None)
    _LOCAL.current = [key, 0]
    try:
        yield
    finally:
        _LOCAL.current = saved


@contextlib.contextmanager
def probing():
    """While the block runs, :func:`keep` keeps (a plan's probe, :func:`gear3d.plan.probe_call`);
    outside it nothing is kept, so a build's own working samples are never shared."""
    saved = getattr(_LOCAL, "probing", False)
    _LOCAL.probing = True
    try:
        yield
    finally:
        _LOCAL.probing = saved


def first_sampling():
    """The current build's key when this is its first sampling, else None (each call
    counts one sampling of the current build)."""
    cur = getattr(_LOCAL, "current", None)
    if cur is None:
        return None
    cur[1] += 1
    return cur[0] if cur[1] == 1 else None


def keep(key, args, make) -> bool:
    """Keep ``make()`` (called only when it is kept: a copy of the sampling), made from
    ``args`` (hashable) by the first sampling of build ``key`` (:func:`first_sampling`),
    when probing; returns whether it was kept."""
    if key is None or not getattr(_LOCAL, "probing", False):
        return False
    _KEPT[:] = [(key, args, make())]
    return True


def take(key, args):
    """What :func:`keep` kept for build ``key``'s first sampling from ``args``, once (it is
    forgotten); None when there is none."""
    if key is None or not _KEPT or getattr(_LOCAL, "probing", False):
        return None
    k, a, value = _KEPT[0]
    if k != key or a != args:
        return None
    _KEPT.clear()
    return value
