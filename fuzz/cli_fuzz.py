#!/usr/bin/env python3
"""Fuzz whole command lines of the `shisen` binary, with every input file kind.

Each case is a command line built from the real commands and options, with
values drawn from what breaks programs (huge, negative, NaN, empty, paths
that are folders, devices, missing, read-only, or the command's own input),
and input files made by mutating the shipped ones (scenes, studies, gains,
muscle databases, landmarks, bindings, emotion scripts, results tables,
JUnit reports, traces): numbers swapped for extremes, fields renamed,
brackets dropped, bytes cut.

A case fails if the process
  - exits with a code other than 0, 1, 2 or 130,
  - prints a Rust panic,
  - is still running after --timeout seconds, and then does not stop
    within 1.5 s of Ctrl-C (SIGINT) with exit 130,
  - exits 2 on a file input without naming `file:line:col` (when the
    message is about a file's contents).

Usage (release build first):
  python3 fuzz/cli_fuzz.py --bin target/release/shisen --minutes 10 --out fuzz-out
Failing cases are written to OUT/failures/N.json (command, files, output).
"""

import argparse
import json
import os
import random
import re
import shutil
import signal
import subprocess
import sys
import tempfile
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent

EXTREMES = [
    "0", "-0", "-1", "1e300", "-1e300", "1e-300", "NaN", "inf", "-inf",
    "1e999", "18446744073709551616", "4294967296", "9999999999", "0.5",
    "48.5", "", " ", "abc", "1/0", "0/0", "7/3", "3/3", "-1/4", "0x10",
    "1_000", "٣", "\u202e1",
]

SIZES = ["64x64", "8192x8192", "0x0", "63x64", "1x99999", "100", "axb", "-64x64", "64x"]


def shipped(kind):
    """Seed files of each input kind."""
    scenes = sorted((ROOT / "scenes").glob("*.ron"))
    return {
        "scene": scenes,
        "study": sorted((ROOT / "scenes/studies").glob("*.ron")),
        "gains": sorted((ROOT / "scenes/gains").glob("*.ron")),
        "muscles": [ROOT / "scenes/face/muscles.ron"],
        "script": sorted((ROOT / "scenes/face").glob("*.txt")),
        "csv": [ROOT / "scenes/face/thesis_appendix_a.csv"],
    }.get(kind, [])


NUMBER = re.compile(r"(?<![A-Za-z_])-?\d+(\.\d+)?(e-?\d+)?")
IDENT = re.compile(r"\b([a-z_][a-z0-9_]*)\s*:")


def mutate(text, rng):
    """A few random damaging edits of a text file."""
    for _ in range(rng.randint(1, 4)):
        op = rng.randrange(8)
        if op == 0:  # a number to an extreme
            ms = list(NUMBER.finditer(text))
            if ms:
                m = rng.choice(ms)
                text = text[: m.start()] + rng.choice(EXTREMES[:16]) + text[m.end():]
        elif op == 1:  # a field renamed (a typo)
            ms = list(IDENT.finditer(text))
            if ms:
                m = rng.choice(ms)
                name = m.group(1)
                typo = name[:-1] if len(name) > 2 and rng.random() < 0.5 else name + "x"
                text = text[: m.start(1)] + typo + text[m.end(1):]
        elif op == 2:  # an unknown field added inside a parenthesis
            i = text.find("(", rng.randrange(max(1, len(text))))
            if i >= 0:
                text = text[: i + 1] + "bogus_field: 1.0, " + text[i + 1:]
        elif op == 3:  # a bracket dropped
            ps = [i for i, c in enumerate(text) if c in "()[]{}"]
            if ps:
                i = rng.choice(ps)
                text = text[:i] + text[i + 1:]
        elif op == 4:  # cut short
            text = text[: rng.randrange(max(1, len(text)))]
        elif op == 5:  # a line duplicated
            lines = text.split("\n")
            k = rng.randrange(len(lines))
            lines.insert(k, lines[k])
            text = "\n".join(lines)
        elif op == 6:  # random bytes
            i = rng.randrange(max(1, len(text)))
            text = text[:i] + "".join(chr(rng.randrange(1, 0x3000)) for _ in range(rng.randint(1, 8))) + text[i:]
        else:  # a number made fractional or huge
            ms = list(NUMBER.finditer(text))
            if ms:
                m = rng.choice(ms)
                text = text[: m.start()] + m.group(0) + rng.choice([".5", "e300", "000000000"]) + text[m.end():]
    return text


class Case:
    def __init__(self, work, rng):
        self.work = work
        self.rng = rng
        self.files = {}

    def file(self, kind):
        """A path to an input of `kind`: often a mutation of a shipped file,
        sometimes a special path."""
        r = self.rng.random()
        if r < 0.06:
            return "/dev/zero"
        if r < 0.10:
            return str(self.work / "missing" / "x.ron")
        if r < 0.13:
            return str(self.work)
        seeds = shipped(kind)
        name = f"in{len(self.files)}_{kind}.ron"
        if kind == "script":
            name = name.replace(".ron", ".txt")
        if kind == "csv":
            name = name.replace(".ron", ".csv")
        path = self.work / name
        if seeds:
            src = self.rng.choice(seeds)
            text = src.read_text(encoding="utf-8")
            # Relative references resolve against the copy's folder.
            text = text.replace('"../', f'"{src.parent.parent}/').replace(
                'gains_file: "', f'gains_file: "{src.parent}/'
            )
            if kind == "study":
                text = text.replace('scene: "', f'scene: "{src.parent}/')
        else:
            text = "()"
        if self.rng.random() < 0.8:
            text = mutate(text, self.rng)
        path.write_text(text, encoding="utf-8", errors="surrogatepass")
        self.files[str(path)] = text
        return str(path)

    def out(self, ext):
        """An output path: usually fresh, sometimes a trap."""
        r = self.rng.random()
        if r < 0.05:
            return str(self.work / "no" / "such" / f"o{ext}")
        if r < 0.08:
            return str(self.work)
        if r < 0.11 and self.files:
            return self.rng.choice(list(self.files))
        if r < 0.13:
            return str(self.work / "ro" / f"o{ext}")
        return str(self.work / f"out{self.rng.randrange(3)}{ext}")

    def num(self, typical):
        return self.rng.choice(EXTREMES) if self.rng.random() < 0.5 else str(typical)

    def build(self):
        rng = self.rng
        c = rng.randrange(14)
        scene = lambda: self.file("scene") if rng.random() < 0.9 else "default"
        if c == 0:
            a = ["run", scene()]
            if rng.random() < 0.5:
                a += ["--trace", rng.choice(["-", self.out(".csv")])]
            if rng.random() < 0.3:
                a += ["--trace-every", self.num(10)]
            if rng.random() < 0.3:
                a += ["--seed", self.num(7)]
            if rng.random() < 0.3:
                a += ["--duration", self.num(2)]
            if rng.random() < 0.2:
                a += ["--plot", self.out(".png")]
            return a
        if c == 1:
            a = ["test"] + [self.file("scene") for _ in range(rng.randint(1, 3))]
            if rng.random() < 0.4:
                a += ["--jobs", self.num(2)]
            if rng.random() < 0.3:
                a += ["--junit", self.out(".xml")]
            if rng.random() < 0.3:
                a += ["--out", self.out("")]
            if rng.random() < 0.3:
                a += ["--shard", self.num("0/2")]
            return a
        if c == 2:
            a = ["study", self.file("study"), "--out", self.out(".csv")]
            if rng.random() < 0.3:
                a += ["--shard", self.num("1/3")]
            if rng.random() < 0.3:
                a += ["--jobs", self.num(2)]
            return a
        if c == 3:
            ins = []
            for _ in range(rng.randint(1, 4)):
                p = self.work / f"shard{rng.randrange(4)}.csv"
                n = rng.randint(1, 4)
                i = rng.randrange(n)
                rows = "\n".join(f"{k},{k}" for k in range(i, 8, n))
                text = f"# shisen study: runs=8 shard={i}/{n}\nrun,x\n{rows}\n"
                if rng.random() < 0.5:
                    text = mutate(text, rng)
                p.write_text(text)
                ins.append(str(p))
            return ["merge", "--out", self.out(rng.choice([".csv", ".xml"]))] + ins
        if c == 4:
            a = ["tune", "--group", rng.choice(["eye", "neck", "eye,neck", "bogus", ""])]
            a += ["--out", self.out("")]
            if rng.random() < 0.5:
                a += ["--dt", self.num(0.001)]
            if rng.random() < 0.3:
                a += ["--gains", self.file("gains")]
            if rng.random() < 0.3:
                a += ["--write-gains", self.out(".ron")]
            return a
        if c == 5:
            a = ["sweep", "--group", "eye", "--runs", self.num(12), "--out", self.out("")]
            if rng.random() < 0.5:
                a += ["--grid"]
            return a
        if c == 6:
            return ["soak", "--minutes", self.num(0.05), "--seed", self.num(1)]
        if c == 7:
            a = ["render", scene(), "--out", self.out(".png"), "--at", self.num(0.5)]
            if rng.random() < 0.5:
                a += ["--size", rng.choice(SIZES)]
            if rng.random() < 0.3:
                a += ["--view", rng.choice(["first", "orbit", "face", "orbit:1,2,3", "orbit:nan,0,1", "x"])]
            if rng.random() < 0.3:
                a += ["--until", self.num(0.6), "--fps", self.num(5), "--slow", self.num(1)]
            return a
        if c == 8:
            sub = rng.choice(["export", "sheet", "calibrate"])
            if sub == "export":
                return ["face", "export", "--out", self.out(".glb"), "--rows", self.num(32)]
            if sub == "sheet":
                return ["face", "sheet", "--out", self.out(".png"), "--rows", self.num(24), "--cell", rng.choice(SIZES)]
            return ["face", "calibrate", self.file("csv"), "--out", self.out(".ron")]
        if c == 9:
            return ["plot", self.out(".csv") if rng.random() < 0.5 else self.file("scene"), "--out", self.out(".png")]
        if c == 10:
            a = ["fidelity"]
            if rng.random() < 0.5:
                a += ["--scene", self.file("scene")]
            if rng.random() < 0.3:
                a += ["--out", self.out("")]
            return a
        if c == 11:
            return ["schema"] + rng.choice([[], ["scene"], ["--markdown"], ["bogus"], ["gains", "--markdown"]])
        if c == 12:
            return ["export-mjcf", "--out", self.out(".xml")]
        # The window's options before a subcommand, and bad flags.
        return rng.choice([["--scene", self.file("scene"), "run", "default"], ["--bogus"], ["run"], [], ["--print-bindings", "x"]])


def judge(args, proc_out, code, timed_out, stopped_code):
    stdout, stderr = proc_out
    problems = []
    if timed_out:
        if stopped_code != 130:
            problems.append(f"did not stop with 130 after Ctrl-C (got {stopped_code})")
    elif code not in (0, 1, 2, 130):
        problems.append(f"exit code {code}")
    if "panicked" in stderr or "RUST_BACKTRACE" in stderr:
        problems.append("panic")
    return problems


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--bin", default=str(ROOT / "target/release/shisen"))
    ap.add_argument("--minutes", type=float, default=10.0)
    ap.add_argument("--timeout", type=float, default=8.0)
    ap.add_argument("--seed", type=int, default=1)
    ap.add_argument("--out", default="fuzz-out")
    a = ap.parse_args()
    # Cases run in scratch folders: the binary by its absolute path.
    a.bin = str(Path(a.bin).resolve())
    if not os.access(a.bin, os.X_OK):
        ap.error(f"--bin: {a.bin}: not an executable (build it first)")
    out = Path(a.out)
    (out / "failures").mkdir(parents=True, exist_ok=True)
    rng = random.Random(a.seed)
    end = time.time() + a.minutes * 60
    n = fails = 0
    codes = {}
    env = dict(os.environ, RUST_BACKTRACE="0", NODEVICE_SELECT="1")
    while time.time() < end:
        work = Path(tempfile.mkdtemp(prefix="shisen-fuzz-"))
        ro = work / "ro"
        ro.mkdir()
        ro.chmod(0o555)
        case = Case(work, rng)
        args = case.build()
        t0 = time.time()
        p = subprocess.Popen([a.bin] + args, cwd=work, env=env, stdout=subprocess.PIPE,
                             stderr=subprocess.PIPE, text=True, errors="replace",
                             stdin=subprocess.DEVNULL)
        timed_out, stopped = False, None
        try:
            so, se = p.communicate(timeout=a.timeout)
        except subprocess.TimeoutExpired:
            timed_out = True
            p.send_signal(signal.SIGINT)
            try:
                so, se = p.communicate(timeout=1.5)
                stopped = p.returncode
            except subprocess.TimeoutExpired:
                p.kill()
                so, se = p.communicate()
                stopped = "still running"
        code = p.returncode
        codes[code] = codes.get(code, 0) + 1
        problems = judge(args, (so, se), code, timed_out, stopped)
        n += 1
        if problems:
            fails += 1
            rec = {"args": args, "problems": problems, "code": code, "seconds": time.time() - t0,
                   "files": case.files, "stdout": so[-2000:], "stderr": se[-4000:]}
            (out / "failures" / f"{fails}.json").write_text(json.dumps(rec, indent=1))
            print(f"FAIL {fails}: {problems}: shisen {' '.join(args)}", file=sys.stderr)
        ro.chmod(0o755)
        shutil.rmtree(work, ignore_errors=True)
    summary = {"cases": n, "failures": fails, "minutes": a.minutes, "exit_codes": {str(k): v for k, v in codes.items()}}
    (out / "summary.json").write_text(json.dumps(summary, indent=1))
    print(json.dumps(summary))
    return 1 if fails else 0


if __name__ == "__main__":
    sys.exit(main())
