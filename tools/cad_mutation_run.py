#!/usr/bin/env python3
"""Mutation run of IGES/STEP/BREP files through `knotwork convert` (not in CI).

Each case is a seed file (IGES, STEP or BREP) with one to four random mutations (bytes
flipped, inserted or deleted, chunks repeated or cut, the file truncated, numbers or entity
references replaced, section counts inflated, lines repeated or swapped), converted to .knot
by `knotwork convert` (which reads these formats in its child process). Outcomes:

  ok       exit 0 and the written .knot reopens with `knotwork info` (exit 0), or
           exit 1 with one line on stderr naming the file (a clear refusal)
  crash    any other exit status, a signal, or exit 0 with a .knot that does not reopen
  hang     convert still running after --hang-seconds (it is killed)

Crashing and hanging inputs are copied to OUT/crash and OUT/hang; OUT/summary.json holds the
counts. docs/RELIABILITY.md records the runs.

  python3 tools/cad_mutation_run.py --cases 5000 --jobs 2 --out /tmp/kw-mutation
"""
import argparse
import json
import os
import random
import re
import shutil
import subprocess
import sys
import tempfile
import time
from concurrent.futures import ThreadPoolExecutor

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
DEFAULT_SEEDS = [
    "tests/data/teapot.igs",
    "tests/data/hammer.iges",
    "tests/data/screw.step",
    "tests/data/Pump_Nut.brep",
]


def mutate(data: bytes, rng: random.Random, ext: str) -> bytes:
    b = bytearray(data)
    for _ in range(rng.randint(1, 4)):
        if not b:
            break
        kind = rng.randrange(10)
        i = rng.randrange(len(b))
        if kind == 0:  # flip bytes
            for _ in range(rng.randint(1, 8)):
                j = rng.randrange(len(b))
                b[j] = rng.randrange(256)
        elif kind == 1:  # insert random bytes
            b[i:i] = bytes(rng.randrange(256) for _ in range(rng.randint(1, 16)))
        elif kind == 2:  # delete a chunk
            del b[i:i + rng.randint(1, 4096)]
        elif kind == 3:  # repeat a chunk
            n = rng.randint(1, 4096)
            b[i:i] = b[i:i + n] * rng.randint(1, 4)
        elif kind == 4:  # truncate
            del b[i:]
        elif kind == 5:  # replace a number with an extreme one
            ms = list(re.finditer(rb"-?\d+(\.\d*)?(E[-+]?\d+)?", bytes(b[i:i + 2000])))
            if ms:
                m = rng.choice(ms)
                new = rng.choice([b"0", b"-1", b"1E308", b"-1E308", b"999999999", b"1E-320",
                                  b"2147483648", b"65536", b"3.5", b"NaN"])
                b[i + m.start():i + m.end()] = new
        elif kind == 6 and ext in ("step", "stp"):  # point an entity reference elsewhere
            ms = list(re.finditer(rb"#(\d+)", bytes(b[i:i + 2000])))
            if ms:
                m = rng.choice(ms)
                target = rng.choice([m.group(1), b"0", b"1", str(rng.randint(1, 2000)).encode()])
                if rng.random() < 0.3:  # a reference to the entity itself (a cycle)
                    line_start = b.rfind(b"\n", 0, i + m.start()) + 1
                    own = re.match(rb"#(\d+)", bytes(b[line_start:line_start + 20]))
                    target = own.group(1) if own else target
                b[i + m.start():i + m.end()] = b"#" + target
        elif kind == 7 and ext in ("brep", "brp"):  # inflate a section count
            ms = list(re.finditer(rb"\n([A-Za-z0-9]+) (\d+)\n", bytes(b)))
            if ms:
                m = rng.choice(ms)
                b[m.start(2):m.end(2)] = str(int(m.group(2)) * rng.choice([2, 10, 1000]) + 1).encode()
        elif kind == 8:  # repeat or swap lines
            lines = bytes(b).split(b"\n")
            if len(lines) > 2:
                a, c = rng.randrange(len(lines)), rng.randrange(len(lines))
                if rng.random() < 0.5:
                    lines[a], lines[c] = lines[c], lines[a]
                else:
                    lines.insert(a, lines[c])
                b = bytearray(b"\n".join(lines))
        else:  # overwrite a chunk with one from elsewhere
            n = rng.randint(1, 512)
            j = rng.randrange(len(b))
            b[i:i + n] = b[j:j + n]
    return bytes(b)


def run_case(args, index, seed_path, work):
    rng = random.Random(args.seed * 1_000_003 + index)
    ext = seed_path.rsplit(".", 1)[-1].lower()
    with open(seed_path, "rb") as f:
        data = mutate(f.read(), rng, ext)
    case = os.path.join(work, f"case{index:06d}.{ext}")
    out = os.path.join(work, f"case{index:06d}.knot")
    with open(case, "wb") as f:
        f.write(data)
    env = dict(os.environ, KNOTWORK_CAD_TIME_LIMIT=str(args.child_seconds))
    start = time.monotonic()
    try:
        p = subprocess.run([args.knotwork, "convert", case, out], capture_output=True,
                           timeout=args.hang_seconds, env=env)
        code, err = p.returncode, p.stderr.decode("utf-8", "replace").strip()
    except subprocess.TimeoutExpired:
        code, err = None, "timeout"
    seconds = time.monotonic() - start
    outcome = "ok"
    if code is None:
        outcome = "hang"
    elif code == 0:
        r = subprocess.run([args.knotwork, "info", out], capture_output=True, timeout=120)
        if r.returncode != 0:
            outcome = "crash"
            err = "written .knot does not reopen: " + r.stderr.decode("utf-8", "replace")
    elif code != 1 or not err or "\n" in err.strip():
        outcome = "crash"
    detail = {"case": index, "seed": os.path.basename(seed_path), "exit": code,
              "seconds": round(seconds, 3), "stderr": err[-400:]}
    if outcome != "ok":
        dest = os.path.join(args.out, outcome)
        os.makedirs(dest, exist_ok=True)
        shutil.copy(case, dest)
    for p in (case, out):
        if os.path.exists(p):
            os.remove(p)
    return outcome, code, detail


def main():
    ap = argparse.ArgumentParser(description=__doc__,
                                 formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--knotwork", default=os.path.join(ROOT, "build/bin/knotwork"))
    ap.add_argument("--cases", type=int, default=5000)
    ap.add_argument("--jobs", type=int, default=2)
    ap.add_argument("--seed", type=int, default=1)
    ap.add_argument("--child-seconds", type=float, default=30,
                    help="KNOTWORK_CAD_TIME_LIMIT for each case (the child's time limit)")
    ap.add_argument("--hang-seconds", type=float, default=90,
                    help="a convert still running after this is a hang")
    ap.add_argument("--out", default=os.path.join(tempfile.gettempdir(), "kw-mutation"))
    ap.add_argument("seeds", nargs="*", help="seed files (default: the CAD files in tests/data)")
    args = ap.parse_args()
    seeds = [os.path.join(ROOT, s) for s in DEFAULT_SEEDS] if not args.seeds else args.seeds
    os.makedirs(args.out, exist_ok=True)
    work = tempfile.mkdtemp(prefix="cases-", dir=args.out)
    counts = {"ok": 0, "crash": 0, "hang": 0}
    exits = {}
    per_seed = {}
    bad = []
    start = time.monotonic()
    with ThreadPoolExecutor(max_workers=args.jobs) as pool:
        futures = [pool.submit(run_case, args, i, seeds[i % len(seeds)], work)
                   for i in range(args.cases)]
        for n, fut in enumerate(futures, 1):
            outcome, code, detail = fut.result()
            counts[outcome] += 1
            exits[str(code)] = exits.get(str(code), 0) + 1
            s = per_seed.setdefault(detail["seed"], {"ok": 0, "crash": 0, "hang": 0})
            s[outcome] += 1
            if outcome != "ok":
                bad.append(detail)
                print(f"{outcome}: case {detail['case']} ({detail['seed']}): {detail['stderr']}",
                      file=sys.stderr)
            if n % 250 == 0:
                print(f"{n}/{args.cases} cases, {counts}, {time.monotonic() - start:.0f} s",
                      file=sys.stderr)
    shutil.rmtree(work, ignore_errors=True)
    summary = {"cases": args.cases, "seed": args.seed, "counts": counts, "exit_codes": exits,
               "per_seed": per_seed, "seconds": round(time.monotonic() - start, 1),
               "child_seconds": args.child_seconds, "hang_seconds": args.hang_seconds,
               "failures": bad}
    with open(os.path.join(args.out, "summary.json"), "w") as f:
        json.dump(summary, f, indent=1)
    print(json.dumps({k: summary[k] for k in ("cases", "counts", "exit_codes", "per_seed",
                                               "seconds")}, indent=1))
    return 0 if counts["crash"] == 0 and counts["hang"] == 0 else 1


if __name__ == "__main__":
    sys.exit(main())
