#!/usr/bin/env python3
"""Regression guard: two builds of shisen, the same scene, alternated in
one run, and the ratio of their step costs.

This machine's speed drifts 15-30 % from one run to the next, so a
before-and-after figure means something only when both builds run side by
side: this script runs them in pairs, swapping which goes first in every
other pair (so a drift in the machine's speed falls on both alike), and
reports each run's simulation wall time (shisen's own figure, `N ticks, X s
wall`: the step alone, without the process's start-up or the scene's
loading), the medians, and the ratio after/before with the spread of the
pairs' ratios.

A build is named by the path of a `shisen` binary or by a git revision. A
revision is built once into `target/ab/<commit>` from a worktree of this
repository (with a target directory of its own, `target/ab/target`, shared
by the revisions, so the working tree's build is not touched and a second
revision rebuilds only what changed), and reused by later runs.

Usage:
    python3 benches/ab.py --before HEAD~1                  # against the working tree's release build
    python3 benches/ab.py --before v1 --after v2 --pairs 9
    python3 benches/ab.py --before old/shisen --after target/release/shisen \\
        --scene scenes/default.ron --duration 60 --max-ratio 1.05

Exit status: 0, or 1 when `--max-ratio` is given and the median ratio
after/before exceeds it (a regression), 2 on bad arguments or a run that
failed.
"""

import argparse
import json
import os
import re
import statistics
import subprocess
import sys

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
DEFAULT_AFTER = os.path.join(ROOT, "target", "release", "shisen")
TIMING = re.compile(r"in (\d+) ticks, ([0-9.]+) s wall")


def fail(msg):
    print(f"ab.py: {msg}", file=sys.stderr)
    sys.exit(2)


def resolve(build):
    """The binary for `build`: a path as given, or a git revision built
    into target/ab/<commit>."""
    if os.path.isfile(build):
        return os.path.abspath(build)
    rev = subprocess.run(
        ["git", "rev-parse", "--verify", "--quiet", build + "^{commit}"],
        cwd=ROOT, capture_output=True, text=True,
    )
    if rev.returncode != 0:
        fail(f"{build!r} is neither a shisen binary nor a git revision")
    commit = rev.stdout.strip()
    home = os.path.join(ROOT, "target", "ab", commit[:12])
    binary = os.path.join(home, "shisen")
    if os.path.isfile(binary):
        return binary
    tree = os.path.join(home, "tree")
    if not os.path.isdir(tree):
        subprocess.run(["git", "worktree", "add", "--detach", tree, commit],
                       cwd=ROOT, check=True, capture_output=True)
    print(f"building {build} ({commit[:12]}) into {home} ...", file=sys.stderr)
    # One target directory for every revision: a second revision rebuilds
    # only what changed, not every dependency.
    shared = os.path.join(ROOT, "target", "ab", "target")
    env = dict(os.environ, CARGO_TARGET_DIR=shared)
    subprocess.run(["cargo", "build", "--release", "--quiet", "--bin", "shisen"],
                   cwd=tree, env=env, check=True)
    os.replace(os.path.join(shared, "release", "shisen"), binary)
    subprocess.run(["git", "worktree", "remove", "--force", tree], cwd=ROOT, check=False,
                   capture_output=True)
    return binary


def run_once(binary, scene, duration, seed):
    """One headless run; returns (ticks, seconds of simulation wall time)."""
    cmd = [binary, "run", scene, "--headless", "--duration", str(duration), "--seed", str(seed)]
    out = subprocess.run(cmd, cwd=ROOT, capture_output=True, text=True)
    m = TIMING.search(out.stdout)
    if not m:
        fail(f"could not read the timing of `{' '.join(cmd)}` (exit {out.returncode}):\n"
             + out.stdout[-2000:] + out.stderr[-2000:])
    return int(m.group(1)), float(m.group(2))


def number(lo, hi):
    def parse(text):
        try:
            v = float(text)
        except ValueError:
            raise argparse.ArgumentTypeError(f"{text!r} is not a number")
        if not lo <= v <= hi:
            raise argparse.ArgumentTypeError(f"{v} is outside {lo}-{hi}")
        return v
    return parse


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0],
                                 formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--before", required=True, help="binary path or git revision")
    ap.add_argument("--after", default=DEFAULT_AFTER,
                    help="binary path or git revision (default: target/release/shisen)")
    ap.add_argument("--scene", default="default", help="scene file or embedded name (default: default)")
    ap.add_argument("--duration", type=number(0.1, 86400), default=30.0,
                    help="simulated seconds per run, 0.1-86400 (default 30)")
    ap.add_argument("--pairs", type=number(1, 100), default=7,
                    help="alternated pairs of runs, 1-100 (default 7)")
    ap.add_argument("--seed", type=int, default=1, help="the scene's seed for every run (default 1)")
    ap.add_argument("--max-ratio", type=number(0.01, 100), default=None,
                    help="exit 1 if the median ratio after/before exceeds this")
    ap.add_argument("--json", action="store_true", help="print the result as JSON")
    args = ap.parse_args()

    bins = {"before": resolve(args.before), "after": resolve(args.after)}
    rows = []
    for i in range(int(args.pairs)):
        order = ["before", "after"] if i % 2 == 0 else ["after", "before"]
        row = {}
        for name in order:
            ticks, wall = run_once(bins[name], args.scene, args.duration, args.seed)
            row[name] = wall
            row["ticks"] = ticks
        row["ratio"] = row["after"] / row["before"]
        rows.append(row)
        if not args.json:
            print(f"pair {i + 1}: before {row['before']:.3f} s, after {row['after']:.3f} s, "
                  f"after/before {row['ratio']:.3f}", file=sys.stderr)

    med = {k: statistics.median(r[k] for r in rows) for k in ("before", "after", "ratio")}
    ratios = sorted(r["ratio"] for r in rows)
    ticks = rows[0]["ticks"]
    result = {
        "scene": args.scene, "duration": args.duration, "seed": args.seed,
        "before": bins["before"], "after": bins["after"], "pairs": rows,
        "median_before_s": med["before"], "median_after_s": med["after"],
        "median_ratio": med["ratio"], "ratio_range": [ratios[0], ratios[-1]],
        "realtime_before": args.duration / med["before"],
        "realtime_after": args.duration / med["after"],
        "ticks": ticks,
    }
    regressed = args.max_ratio is not None and med["ratio"] > args.max_ratio
    result["regressed"] = regressed
    if args.json:
        print(json.dumps(result, indent=2))
    else:
        print(f"{args.scene}, {args.duration:g} s simulated ({ticks} ticks), seed {args.seed}, "
              f"{len(rows)} alternated pairs")
        print(f"  before: median {med['before']:.3f} s ({result['realtime_before']:.1f}x real time)  "
              f"{bins['before']}")
        print(f"  after:  median {med['after']:.3f} s ({result['realtime_after']:.1f}x real time)  "
              f"{bins['after']}")
        print(f"  after/before: median of the pairs' ratios {med['ratio']:.3f} "
              f"(pairs {ratios[0]:.3f}-{ratios[-1]:.3f}), ratio of the medians "
              f"{med['after'] / med['before']:.3f}"
              + (f"; above {args.max_ratio:g}: a regression" if regressed else ""))
    sys.exit(1 if regressed else 0)


if __name__ == "__main__":
    main()
