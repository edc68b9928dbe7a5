"""``--figure FILE``: the annotated figure next to a command's main output (profile, rack)."""
from __future__ import annotations

import sys

from ..filesafe import check_path


def check_figure_arg(args):
    """``--figure FILE`` checked before any work (extension, folder)."""
    if getattr(args, "figure", None) is not None:
        from ..figures import FIGURE_EXTS
        check_path(args.figure, "figure", exts=tuple("." + e for e in FIGURE_EXTS))


def write_figure_arg(args, obj):
    """Write ``--figure FILE`` (when given) and say so on stdout."""
    if getattr(args, "figure", None) is not None:
        from ..figures import figure
        figure(obj, args.figure)
        sys.stdout.write(f"wrote {args.figure}: figure\n")
