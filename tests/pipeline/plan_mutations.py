#!/usr/bin/env python3
"""plan.json from anywhere, through the real binary: mutated golden plans through every command that reads
plan.json (export in every format, render one tiny frame, optimize --quality draft, view, info), each
under a time limit. Every run must exit 0, 2 (bad input) or 3 (fails validation), never 1 (a runtime
failure) or by a signal or the time limit; a run that exits non-zero must leave no output; and no Ceres
(glog) line may reach stderr.

render (its start-up costs about 1.7 s a run here, most of the test's time) runs on every plan `view`
accepted and on every eighth of the others: a refused plan is refused by the one reader every command
shares (core/plan_file.h), which the other commands already ran on it.

  plan_mutations.py CINEPATH SOURCE_DIR WORK_DIR [--plans N] [--seed S] [--jobs J] [--timeout-s T]

The mutations (fixed seed, so a failure reproduces): a number replaced by +-1e308, +-1e300, 1e7 + 1, a
negative, 0, 1e-300 or a huge integer, or tweaked (negated, doubled, a third, +0.001, times 1000, +-1e7,
0.1, 1e-6); a number made a NaN-like token (NaN, Infinity, -Infinity, 1e400, which the JSON reader
refuses) or a string ("NaN", "12"); a key deleted; a value swapped for another
type (null, true, [], {}, a string); an array emptied or cut to its first element. Each plan gets one to
three of them; every other plan gets only tweaks, so that more plans reach past the reader. A failing
case is left in WORK_DIR/failures/ with its command line.
"""
import argparse
import collections
import concurrent.futures
import copy
import glob
import json
import os
import random
import re
import shutil
import subprocess
import sys
import time

RAW = "__raw_token__:"  # a string that becomes a bare JSON token (NaN, Infinity, 1e400) when written
NUMBERS = [1e308, -1e308, 1e300, -1e300, 1e7 + 1, -1e7 - 1, -1.0, -90.5, 0, 0.0, 1e-300, -1e-300, 10**20, 2**63,
           400.0, 1e-7, 3.0]
RAW_TOKENS = ["NaN", "Infinity", "-Infinity", "1e400", "-1e400"]
OTHER_TYPES = [None, True, [], {}, "NaN", "12", "", [1, 2, 3], {"a": 1}]
GLOG_LINE = re.compile(r"^[IWEF]\d{4} |trust_region_minimizer|residual_block|Terminating:", re.M)


def leaves(node, path=()):
    """Every (path, value) below node, containers included (depth first, in document order)."""
    yield path, node
    if isinstance(node, dict):
        for k, v in node.items():
            yield from leaves(v, path + (k,))
    elif isinstance(node, list):
        for i, v in enumerate(node):
            yield from leaves(v, path + (i,))


def get(doc, path):
    for p in path:
        doc = doc[p]
    return doc


def set_at(doc, path, value):
    get(doc, path[:-1])[path[-1]] = value


def mutate(doc, rng, tweak_only=False):
    """One mutation of doc in place; returns what it did, for the failure report."""
    nodes = list(leaves(doc))
    numbers = [(p, v) for p, v in nodes if p and isinstance(v, (int, float)) and not isinstance(v, bool)]
    keyed = [(p, v) for p, v in nodes if p and isinstance(p[-1], str)]
    arrays = [(p, v) for p, v in nodes if p and isinstance(v, list) and v]
    kinds = ["number", "number", "tweak", "raw", "delete", "delete", "type", "array"]
    kind = "tweak" if tweak_only else rng.choice(kinds)
    if kind == "tweak" and numbers:  # a value still in its domain, or just outside: deeper into the stages
        path, value = rng.choice(numbers)
        value = rng.choice([-value, 2 * value, value / 3, value + 0.001, value * 1e3, 1e7, -1e7, 0.1, 1e-6])
        set_at(doc, path, value)
        return f"{'/'.join(map(str, path))} = {value}"
    if kind in ("number", "raw") and numbers:
        path, _ = rng.choice(numbers)
        value = rng.choice(NUMBERS) if kind == "number" else RAW + rng.choice(RAW_TOKENS)
        set_at(doc, path, value)
        return f"{'/'.join(map(str, path))} = {value}"
    if kind == "delete" and keyed:
        path, _ = rng.choice(keyed)
        del get(doc, path[:-1])[path[-1]]
        return f"delete {'/'.join(map(str, path))}"
    if kind == "array" and arrays:
        path, value = rng.choice(arrays)
        cut = rng.choice([0, 1])
        set_at(doc, path, value[:cut])
        return f"{'/'.join(map(str, path))} cut to {cut} elements"
    path, _ = rng.choice([n for n in nodes if n[0]])
    value = copy.deepcopy(rng.choice(OTHER_TYPES))
    set_at(doc, path, value)
    return f"{'/'.join(map(str, path))} = {json.dumps(value)}"


def dump(doc):
    text = json.dumps(doc, indent=1)
    return re.sub('"' + re.escape(RAW) + r'([^"]*)"', r"\1", text)


def commands(plan, out, scene):
    """(name, argv, outputs that must not exist after a non-zero exit)."""
    formats = ["qgc-plan", "qgc-wpl", "mavlink-bin", "dji-wpml", "dji-msdk-json", "litchi-csv"]
    export_args = [a for f in formats for a in ("--format", f)]
    return [
        ("export", ["export", plan, *export_args, "-o", f"{out}/export"], [f"{out}/export"]),
        ("export-amsl", ["export", plan, "--format", "qgc-plan", "--format", "dji-wpml", "--firmware", "ardupilot",
                         "--altitude-ref", "amsl", "--scene", scene, "--force", "-o", f"{out}/export-amsl"],
         [f"{out}/export-amsl"]),
        ("view", ["view", plan, "-o", f"{out}/previs.html"], [f"{out}/previs.html"]),
        ("render", ["render", plan, "--scene", scene, "--frames", "0", "--width-px", "16", "--quality", "draft",
                    "-o", f"{out}/frames"], [f"{out}/frames"]),
        ("optimize", ["optimize", plan, "--quality", "draft", "--report", f"{out}/report.json", "-o",
                      f"{out}/optimized.json"], [f"{out}/optimized.json", f"{out}/report.json"]),
        ("info", ["info", plan, "--json"], []),
    ]


def left_behind(path):
    """Files a refused run left at path (a file, or any file under a folder)."""
    if os.path.isfile(path):
        return [path]
    found = []
    for root, _, files in os.walk(path):
        found += [os.path.join(root, f) for f in files]
    return found


def run_case(args, index, source, text, what):
    case = os.path.join(args.work, f"case_{index:04d}")
    shutil.rmtree(case, ignore_errors=True)
    os.makedirs(case)
    plan = os.path.join(case, "plan.json")
    with open(plan, "w") as f:
        f.write(text)
    results = []
    accepted = None  # by view, which runs before render
    for name, argv, outputs in commands(plan, case, args.scene):
        if name == "render" and accepted is False and index % 8 != 0:
            continue
        start = time.monotonic()
        try:
            p = subprocess.run([args.cinepath, *argv], capture_output=True, text=True, timeout=args.timeout_s,
                               errors="replace")
            code, stderr = p.returncode, p.stderr
        except subprocess.TimeoutExpired:
            code, stderr = "timeout", ""
        problems = []
        if code not in (0, 2, 3):
            problems.append(f"exit {code}")
        if code != 0:
            for o in outputs:
                problems += [f"left {f}" for f in left_behind(o)]
        if GLOG_LINE.search(stderr):
            problems.append("a Ceres/glog line on stderr")
        if name == "view":
            accepted = code == 0
        results.append((name, code, time.monotonic() - start, problems, argv, stderr))
    failed = any(r[3] for r in results)
    if failed:
        keep = os.path.join(args.work, "failures", f"case_{index:04d}")
        shutil.rmtree(keep, ignore_errors=True)
        shutil.copytree(case, keep)
    shutil.rmtree(case, ignore_errors=True)
    return index, source, what, results


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("cinepath")
    ap.add_argument("source_dir")
    ap.add_argument("work")
    ap.add_argument("--plans", type=int, default=120)
    ap.add_argument("--seed", type=int, default=33)
    ap.add_argument("--jobs", type=int, default=2)
    ap.add_argument("--timeout-s", type=float, default=60)
    args = ap.parse_args()
    args.work = os.path.abspath(args.work)
    args.scene = os.path.join(args.source_dir, "tests/extremes/data/one_triangle.json")
    shutil.rmtree(args.work, ignore_errors=True)
    os.makedirs(args.work)

    # The golden plans small enough to run many times (the export cases' plans are up to 230 kB).
    goldens = sorted(glob.glob(os.path.join(args.source_dir, "tests/golden/plan/*/expected/plan.json")))
    goldens.append(os.path.join(args.source_dir, "tests/golden/export/fast_flyby_overspeed/plan.json"))
    docs = [(os.path.relpath(g, args.source_dir), json.load(open(g))) for g in goldens]
    rng = random.Random(args.seed)
    cases = []
    for i in range(args.plans):
        source, doc = docs[i % len(docs)]
        doc = copy.deepcopy(doc)
        # Every other plan only tweaked, so that more reach past the reader into the stages.
        what = [mutate(doc, rng, tweak_only=i % 2 == 1) for _ in range(rng.choice([1, 1, 2, 3]))]
        cases.append((i, source, dump(doc), what))

    start = time.monotonic()
    histogram = collections.defaultdict(collections.Counter)
    seconds = collections.Counter()
    failures = []
    with concurrent.futures.ThreadPoolExecutor(max_workers=args.jobs) as pool:
        for index, source, what, results in pool.map(lambda c: run_case(args, *c), cases):
            for name, code, elapsed, problems, argv, stderr in results:
                histogram[name][code] += 1
                seconds[name] += elapsed
                if problems:
                    failures.append((index, source, what, name, problems, argv, stderr))
    total = time.monotonic() - start

    print(f"{args.plans} mutated plans (seed {args.seed}) from {len(docs)} golden plans, "
          f"{sum(sum(c.values()) for c in histogram.values())} runs in {total:.1f} s")
    for name in histogram:
        codes = ", ".join(f"exit {k}: {v}" for k, v in sorted(histogram[name].items(), key=lambda kv: str(kv[0])))
        print(f"  {name:12s} {codes}  ({seconds[name]:.1f} s)")
    for index, source, what, name, problems, argv, stderr in failures:
        print(f"FAIL case {index} ({source}; {'; '.join(what)}): {name}: {', '.join(problems)}")
        print("  cinepath " + " ".join(argv))
        for line in stderr.strip().splitlines()[:5]:
            print("  | " + line)
    if failures:
        print(f"{len(failures)} failing runs; their plans are in {args.work}/failures/")
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main())
