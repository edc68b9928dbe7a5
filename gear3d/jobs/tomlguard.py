"""Bounds on a template's TOML text, checked in one linear pass *before* it is parsed.

``tomllib`` parses nested arrays and inline tables recursively (a few thousand levels give a
``RecursionError``) and builds a table per part of a dotted key (a 20,000-part key took
2.3 GB before its refusal). :func:`check_text` scans the text once, tracking strings,
comments and brackets, and refuses (``GearError`` naming the file and line) a file larger
than :data:`MAX_BYTES`, more than :data:`MAX_TABLES` ``[[table]]`` headers, brackets nested
deeper than :data:`MAX_DEPTH`, a key of more than :data:`MAX_KEY_PARTS` dotted parts or
:data:`MAX_KEY_CHARS` characters. No template needs
more: the deepest key of the schema is ``library.sweep.body.width`` (4 parts), the deepest
value an array of inline tables (2 levels).
"""
from __future__ import annotations

import re

from ..errors import GearError

_SPECIAL = re.compile(r"[\n#\"'\[\]{}=,.]")

#: a template's largest size (bytes): a 20,000-part scene is about 1 MB
MAX_BYTES = 4 * 1024 ** 2
#: deepest nesting of [ and { (table headers count one or two)
MAX_DEPTH = 32
#: most [[table]] headers (a scene's parts, pairs and assemblies): a scene lists its parts
#: one by one; sweeps of many parts are libraries (gear3d batch), which need one table
MAX_TABLES = 20_000
#: most parts of a dotted key (a.b.c is 3) and longest key (characters)
MAX_KEY_PARTS = 16
MAX_KEY_CHARS = 256


def _fail(file, line: int, what: str, value, allowed: str):
    raise GearError(f"{file}: line {line}", value, allowed, what)


def check_text(text: str, file="template") -> None:
    """Refuse ``text`` over the bounds of the module doc (one pass, no recursion)."""
    if len(text) > MAX_BYTES:
        _fail(file, 1, "the template is too large", f"{len(text):,} characters", f"at most {MAX_BYTES:,}")
    tables = text.count("[[") - text.count("[[[")
    if tables > MAX_TABLES:
        _fail(file, 1, "too many [[tables]] (a scene lists its parts one by one; sweep many parts in a "
              "library: gear3d batch)", f"{tables:,} tables", f"at most {MAX_TABLES:,}")
    stack = []                  # open brackets: "[" array / header, "{" inline table
    key_ctx = True              # reading a key (line start, after "{" or "," in an inline table)
    parts, klen, line = 1, 0, 1
    i, n = 0, len(text)
    while i < n:
        c = text[i]
        if c == "\n":
            line += 1
            if not stack or stack[-1] == "{":
                key_ctx, parts, klen = not stack, 1, 0
            i += 1
            continue
        if c == "#":
            j = text.find("\n", i)
            i = n if j < 0 else j
            continue
        if c in "\"'":
            quote = text[i:i + 3] if text[i:i + 3] in ('"""', "'''") else c
            j = i + len(quote)
            while True:
                k = text.find(quote, j)
                if k < 0:
                    return          # an unterminated string: tomllib says where
                if quote[0] == '"' and _escaped(text, k):
                    j = k + 1
                    continue
                break
            line += text.count("\n", i, k)
            if key_ctx:
                klen += k - i
                if klen > MAX_KEY_CHARS:
                    _fail(file, line, "a key too long", f"{klen} characters", f"at most {MAX_KEY_CHARS}")
            i = k + len(quote)
            continue
        if c in "[{":
            header = c == "[" and key_ctx and not stack
            stack.append(c)
            if len(stack) > MAX_DEPTH:
                _fail(file, line, "brackets nested too deep", f"{len(stack)} levels", f"at most {MAX_DEPTH}")
            key_ctx = header or c == "{"
            if key_ctx:
                parts, klen = 1, 0
        elif c in "]}":
            if stack:
                stack.pop()
            if not stack or stack[-1] == "{":
                key_ctx = False
        elif c == "=" and key_ctx:
            key_ctx = False
        elif c == "," and stack and stack[-1] == "{":
            key_ctx, parts, klen = True, 1, 0
        elif c == "." and key_ctx:
            parts, klen = parts + 1, klen + 1
            if parts > MAX_KEY_PARTS:
                _fail(file, line, "a dotted key too deep", f"{parts} parts", f"at most {MAX_KEY_PARTS}")
        elif c not in ".,=":            # plain text up to the next special character
            m = _SPECIAL.search(text, i)
            j = n if m is None else m.start()
            if key_ctx:
                klen += j - i - sum(text.count(w, i, j) for w in " \t\r")
                if klen > MAX_KEY_CHARS:
                    _fail(file, line, "a key too long", f"{klen} characters", f"at most {MAX_KEY_CHARS}")
            i = j
            continue
        i += 1


def _escaped(text: str, k: int) -> bool:
    """True when the quote at ``k`` is escaped (an odd run of backslashes before it)."""
    b = 0
    while k - 1 - b >= 0 and text[k - 1 - b] == "\\":
        b += 1
    return b % 2 == 1


def check_key(key: str, file="--set") -> None:
    """A ``--set`` key's parts and length within the same bounds."""
    if len(key) > MAX_KEY_CHARS or key.count(".") + 1 > MAX_KEY_PARTS:
        raise GearError(f"{file}", key[:40] + ("..." if len(key) > 40 else ""),
                        f"a dotted key of at most {MAX_KEY_PARTS} parts and {MAX_KEY_CHARS} characters")
