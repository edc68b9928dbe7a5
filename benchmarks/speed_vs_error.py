"""Speed against error for every family (issue #9): a thin script around :mod:`gear3d.bench`.

Run: ``python benchmarks/speed_vs_error.py [--quick] [--json OUT] [--publish]``
(same as ``gear3d bench``). Writes ``out/bench/speed_vs_error.{md,png,json}``;
``--publish`` also copies the table to ``BENCHMARKS.md`` and the plot to
``benchmarks/speed_vs_error.png`` (the committed copies).
"""
from __future__ import annotations

import argparse
import os
import shutil
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]


def run(quick=False, json_path=None, out_dir="out/bench") -> list:
    """Run the benchmark; returns the rows (see :func:`gear3d.bench.run`)."""
    from gear3d.bench import run as bench_run
    return bench_run(quick=quick, json_path=json_path, out_dir=out_dir)


#: the BENCHMARKS.md section that comes first (gear3d against its peers), kept above the rest
HEADLINE = "headline"


def publish(out_dir="out/bench"):
    """Copy the latest table and plot to BENCHMARKS.md and benchmarks/speed_vs_error.png.

    The page keeps its order: the title, the peers headline (the ``headline`` marker
    section, kept as it is), then speed against error (this table, its headings one level
    down), then everything from the first other marked section on, as it was (the other
    benchmarks' sections and the headings between them)."""
    out = Path(out_dir)
    md = (out / "speed_vs_error.md").read_text().replace("](speed_vs_error.png)",
                                                         "](benchmarks/speed_vs_error.png)")
    md = "\n".join("#" + line if line.startswith("## ") else line for line in md.splitlines()) + "\n"
    md = md.replace("# Speed against error", "## Speed against error", 1)
    md += ("\nRegenerate with `python benchmarks/speed_vs_error.py --publish` "
           "(or `gear3d bench`, which writes `out/bench/` only).\n")
    # sections other benchmarks own (between <!-- NAME:begin --> and <!-- NAME:end -->) are kept
    import re
    old = (ROOT / "BENCHMARKS.md").read_text() if (ROOT / "BENCHMARKS.md").exists() else ""
    head, tail = "", ""
    for m in re.finditer(r"(?ms)^<!-- ([\w-]+):begin -->$.*?^<!-- \1:end -->$", old):
        if m.group(1) == HEADLINE:
            head = m.group(0) + "\n\n"
        elif not tail:
            tail = old[m.start():]
    md = "# Benchmarks\n\n" + head + md + ("\n" + tail if tail else "")
    tmp = ROOT / "BENCHMARKS.md.tmp"
    tmp.write_text(md)
    os.replace(tmp, ROOT / "BENCHMARKS.md")
    tmp = ROOT / "benchmarks" / "speed_vs_error.tmp.png"
    shutil.copyfile(out / "speed_vs_error.png", tmp)
    os.replace(tmp, ROOT / "benchmarks" / "speed_vs_error.png")


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--quick", action="store_true")
    ap.add_argument("--json", default=None)
    ap.add_argument("--out-dir", default=str(ROOT / "out" / "bench"))
    ap.add_argument("--publish", action="store_true", help="update BENCHMARKS.md and the committed PNG")
    a = ap.parse_args(argv)
    rows = run(a.quick, a.json, a.out_dir)
    from gear3d.bench import headline
    print("\n".join(headline(rows)))
    if a.publish:
        publish(a.out_dir)
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
