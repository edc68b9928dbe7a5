"""Sum a budget survey's log (``GEAR3D_FUZZ_LOG``, written by :func:`budgetrun.record`).

``python -m tests.fuzz.fuzzlog FILE`` prints, per command: inputs, accepted, refused by the
budget, rejected by a range, failed (broke the promise), the worst CPU / estimate of an
accepted run of at least :data:`MIN_CPU` s (shorter runs are mostly start-up, which the
estimates leave out), the worst use of the promise (CPU / (2 x estimate + start-up): at
most 1 keeps it) and the largest peak RSS; then the failures' lines.

Example: ``summary(["worm\\taccepted\\t0\\t1.2\\t2.0\\t0.6\\t90\\t150\\t-\\tworm ...\\t"])["worm"]["accepted"] == 1``.
"""
from __future__ import annotations

import sys
from collections import defaultdict

STATUSES = ("accepted", "refused", "rejected", "failed")
#: CPU seconds below which a run's ratio is not counted (start-up dominates)
MIN_CPU = 1.0
#: the start-up the promise allows (budgetrun.STARTUP_CPU)
STARTUP = 0.6


def summary(lines) -> dict:
    """{command: {status: count, "worst": (ratio, cpu s, line), "use": promise used, "rss": MiB}}."""
    out = defaultdict(lambda: {**{s: 0 for s in STATUSES}, "worst": (0.0, 0.0, ""), "use": 0.0, "rss": 0.0})
    for line in lines:
        f = line.rstrip("\n").split("\t")
        if len(f) < 10:
            continue
        c = out[f[0]]
        c[f[1]] += 1
        c["rss"] = max(c["rss"], float(f[6]))
        cpu, est = float(f[3]), float(f[4])
        if f[1] == "accepted":
            c["use"] = max(c["use"], cpu / (2 * est + STARTUP))
            if cpu >= MIN_CPU and float(f[5]) > c["worst"][0]:
                c["worst"] = (float(f[5]), cpu, f[9])
    return dict(out)


def table(s: dict) -> str:
    rows = ["| command | inputs | accepted | refused (budget) | rejected (range) | failed | worst CPU/estimate "
            "(its CPU s) | promise used | peak RSS MiB |", "|---|---:|---:|---:|---:|---:|---:|---:|---:|"]
    tot = defaultdict(float)
    for cmd in sorted(s):
        c = s[cmd]
        n = sum(c[k] for k in STATUSES)
        for k in STATUSES:
            tot[k] += c[k]
        tot["rss"] = max(tot["rss"], c["rss"])
        tot["worst"] = max(tot["worst"], c["worst"][0])
        tot["use"] = max(tot["use"], c["use"])
        rows.append(f"| {cmd} | {n} | {c['accepted']} | {c['refused']} | {c['rejected']} | {c['failed']} | "
                    f"{c['worst'][0]:.2f} ({c['worst'][1]:.1f}) | {c['use']:.2f} | {c['rss']:.0f} |")
    n = sum(tot[k] for k in STATUSES)
    rows.append(f"| all | {n:.0f} | {tot['accepted']:.0f} | {tot['refused']:.0f} | {tot['rejected']:.0f} | "
                f"{tot['failed']:.0f} | {tot['worst']:.2f} | {tot['use']:.2f} | {tot['rss']:.0f} |")
    return "\n".join(rows)


def main(argv) -> int:
    with open(argv[0], encoding="utf-8") as fh:
        lines = fh.readlines()
    print(table(summary(lines)))
    for line in lines:
        f = line.rstrip("\n").split("\t")
        if len(f) >= 10 and f[1] == "failed":
            print(f"- {f[0]}: {f[8]} | {f[9]}")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
