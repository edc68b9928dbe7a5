"""The base of every typed report: :class:`Report`, a dataclass read like a mapping, with
``to_dict()`` (fields in order, then ``extra``).
"""
from __future__ import annotations

from collections.abc import Mapping
from dataclasses import fields


class Report(Mapping):
    """Mapping view and ``to_dict()`` of a report dataclass (fields first, then ``extra``)."""

    extra: dict

    def _names(self) -> list:
        return [f.name for f in fields(self) if f.name != "extra"]

    def to_dict(self) -> dict:
        """The report as plain JSON keys (fields in order, then the extra facts); a report
        held in a field (a planetary set's wheels, a scene's parts) becomes its own dict."""
        d = {k: _plain(getattr(self, k)) for k in self._names()}
        d.update(self.extra)
        return d

    @classmethod
    def pick(cls, source, missing: bool = False):
        """This report built from the same keys of ``source`` (a mapping: a larger report);
        ``missing``: a key ``source`` lacks is None."""
        get = source.get if missing else source.__getitem__
        return cls(**{f.name: get(f.name) for f in fields(cls) if f.name != "extra" and f.init})

    def __getitem__(self, key):
        if key != "extra" and key in self._names():
            return getattr(self, key)
        return self.extra[key]

    def __setitem__(self, key, value):
        if key != "extra" and key in self._names():
            setattr(self, key, value)
        else:
            self.extra[key] = value

    def update(self, other=(), **kw):
        for k, v in dict(other, **kw).items():
            self[k] = v

    def __iter__(self):
        return iter(self._names() + [k for k in self.extra if k not in self._names()])

    def __len__(self) -> int:
        return len(list(iter(self)))

    def __repr__(self) -> str:
        return f"{type(self).__name__}({self.to_dict()!r})"


def _plain(v):
    """``v`` with every :class:`Report` in it (through dicts and lists) turned into its dict."""
    if isinstance(v, (Report, dict)):
        return v.to_dict() if isinstance(v, Report) else {k: _plain(x) for k, x in v.items()}
    return [_plain(x) for x in v] if isinstance(v, list) else v
