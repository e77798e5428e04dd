#!/usr/bin/env python3
"""Mutation fuzzer for the revdist case readers and commands (issue 10 item 15).

Takes the bundled cases, mutates them (bytes, numbers pushed to extremes, duplicate keys,
deep nesting, hostile names, scaled models, dropped or repeated members) and runs
`revdist distance|circles|fit` on each mutant. A finding is: death by a signal, exit
status other than 0 or 2, an error that is not exactly one line, exit 0 without a finite
bracket (lower <= upper, both finite) in --json output, or a run over the time limit.

  scripts/fuzz_cases.py --binary build/cli/revdist --seed 1 --count 300 [--timeout 20] [--save DIR]

Exit status 1 when there are findings (each saved to --save DIR with the command line).
Deterministic for a seed: the same mutants in the same order.
"""
import argparse
import json
import math
import os
import random
import subprocess
import sys
import tempfile
import time

EXTREMES = [0.0, -0.0, 1e300, -1e300, 1e-300, -1e-300, 1e100, 1e-100, 1e8, -1e8, 1e-20, 5e-324,
            1.7976931348623157e308, 2**53 + 1, -1.0, 0.5, 3.0, 1e16, 123456789012345678901234567890]


def corpus(root):
    files = []
    for sub in ["cases/distance", "cases/models", "cases/regressions", "cases/bad", "cases/circles"]:
        d = os.path.join(root, sub)
        for name in sorted(os.listdir(d)):
            if name.endswith(".json"):
                files.append(os.path.join(d, name))
    return files


def walk(node, path=()):
    """All (container, key) slots of a JSON value."""
    if isinstance(node, dict):
        for k in list(node):
            yield node, k
            yield from walk(node[k])
    elif isinstance(node, list):
        for i in range(len(node)):
            yield node, i
            yield from walk(node[i])


def mutate_json(doc, rng):
    slots = list(walk(doc))
    kind = rng.randrange(11)
    if not slots:
        return json.dumps(doc)
    parent, key = rng.choice(slots)
    value = parent[key]
    if kind == 0:  # a number to an extreme
        nums = [(p, k) for p, k in slots if isinstance(p[k], (int, float)) and not isinstance(p[k], bool)]
        if nums:
            p, k = rng.choice(nums)
            p[k] = rng.choice(EXTREMES)
    elif kind == 1:  # scale every number of the model
        s = rng.choice([1e-300, 1e-100, 1e-20, 1e-8, 1e8, 1e20, 1e100, 1e300])
        for p, k in slots:
            if isinstance(p[k], (int, float)) and not isinstance(p[k], bool) and k not in ("degree", "time"):
                if not (isinstance(p, dict) and k in ("weights", "knots", "rotation")):
                    p[k] = p[k] * s
    elif kind == 2:  # drop a member or element
        del parent[key]
    elif kind == 3:  # repeat an element (a repeated control point, a duplicate instance)
        if isinstance(parent, list):
            parent.insert(key, json.loads(json.dumps(value)))
        else:
            parent[key + "_"] = value
    elif kind == 4:  # hostile names
        strs = [(p, k) for p, k in slots if isinstance(p[k], str)]
        if strs:
            p, k = rng.choice(strs)
            p[k] = rng.choice(["", "a\nb", "x" * 5000, "\u0000", "a.b", "a_b", "a b", "\u00e9\u4e2d", "\"", "\\"])
    elif kind == 5:  # wrong type
        parent[key] = rng.choice([None, True, "1", [], {}, [[1, 2]], 1])
    elif kind == 6:  # duplicate key in the raw text
        text = json.dumps(doc)
        i = text.find('": ', rng.randrange(max(1, len(text))))
        if i > 0:
            j = text.rfind('"', 0, i)
            k = text.rfind('"', 0, j)
            name = text[k:i + 3]
            brace = text.find(", ", i)
            if brace > 0:
                return text[:brace] + ", " + name + "1" + text[brace:]
        return text
    elif kind == 7:  # deep nesting
        depth = rng.choice([63, 64, 65, 1000, 100000, 300000])
        return json.dumps(doc).replace(json.dumps(value), "[" * depth + json.dumps(value) + "]" * depth, 1)
    elif kind == 8:  # blend time / rotation oddities
        parent[key] = rng.choice([[0, 0, 0, 0], [1e-300, 0, 0, 0], [1e300, 1e300, 0, 0], 0.999999999, 1e-17])
    elif kind == 9:  # nan / inf tokens
        text = json.dumps(doc)
        tok = rng.choice(["NaN", "Infinity", "-Infinity", "1e999", "-1e999", "1e-999"])
        nums = [m for m in range(len(text)) if text[m].isdigit() and text[m - 1] in " [,-"]
        if nums:
            m = rng.choice(nums)
            return text[:m] + tok + text[m:]
        return text
    else:  # swap two values
        p2, k2 = rng.choice(slots)
        try:
            parent[key], p2[k2] = p2[k2], parent[key]
        except Exception:
            pass
    return json.dumps(doc)


def mutate_bytes(text, rng):
    b = bytearray(text.encode())
    for _ in range(rng.randrange(1, 4)):
        if not b:
            break
        op = rng.randrange(4)
        i = rng.randrange(len(b))
        if op == 0:
            b[i] = rng.randrange(256)
        elif op == 1:
            del b[i:i + rng.randrange(1, 16)]
        elif op == 2:
            b[i:i] = bytes(rng.choice([b"[", b"{", b"\"", b",", b"0", b"e9", b"\n", b"\\u0000"]))
        else:
            j = rng.randrange(len(b))
            b[i:i] = b[j:j + rng.randrange(1, 64)]
    return bytes(b)


def check(binary, path, command, timeout):
    """Runs one command on a mutant; returns a finding string or None."""
    args = [binary, command, path]
    if command != "fit":
        args.append("--json")
    else:
        args += ["--eps", "1e-3"]
    t0 = time.monotonic()
    try:
        r = subprocess.run(args, capture_output=True, timeout=timeout)
    except subprocess.TimeoutExpired:
        return "timeout after %g s" % timeout, args
    if r.returncode < 0:
        return "killed by signal %d" % -r.returncode, args
    if r.returncode not in (0, 2):
        return "exit %d: %s" % (r.returncode, r.stderr.decode(errors="replace")[:300]), args
    if r.returncode == 2:
        err = r.stderr.decode(errors="replace")
        if err.count("\n") != 1 or not err.endswith("\n"):
            return "error not one line: %r" % err[:300], args
        if r.stdout:
            return "exit 2 with output on stdout", args
        return None, args
    if command == "distance":
        try:
            doc = json.loads(r.stdout)
        except ValueError as e:
            return "exit 0 with invalid JSON: %s" % e, args
        for res in doc.get("results", []):
            lo, hi = res.get("lower"), res.get("upper")
            if not isinstance(lo, (int, float)) or not isinstance(hi, (int, float)) or \
                    not math.isfinite(lo) or not math.isfinite(hi) or lo > hi:
                return "exit 0 without a finite bracket: %s" % json.dumps(res)[:300], args
    return None, args


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--binary", required=True)
    ap.add_argument("--root", default=os.path.join(os.path.dirname(os.path.abspath(__file__)), ".."))
    ap.add_argument("--seed", type=int, default=int(os.environ.get("REVDIST_SEED", "1")))
    ap.add_argument("--count", type=int, default=300)
    ap.add_argument("--timeout", type=float, default=20.0)
    ap.add_argument("--save", default="")
    a = ap.parse_args()
    rng = random.Random(a.seed)
    files = corpus(a.root)
    print("fuzz_cases: seed %d, %d mutants from %d files" % (a.seed, a.count, len(files)), flush=True)
    findings = 0
    counts = {0: 0, 2: 0}
    slowest = (0.0, "")
    with tempfile.TemporaryDirectory(prefix="revdist_fuzz_") as tmp:
        for n in range(a.count):
            src = rng.choice(files)
            text = open(src, encoding="utf-8").read()
            if rng.random() < 0.25:
                data = mutate_bytes(text, rng)
            else:
                try:
                    doc = json.loads(text)
                    data = mutate_json(doc, rng).encode()
                except Exception:
                    data = mutate_bytes(text, rng)
            path = os.path.join(tmp, "m%05d.json" % n)
            with open(path, "wb") as f:
                f.write(data)
            command = "circles" if "/circles/" in src else rng.choice(["distance", "distance", "fit"])
            t0 = time.monotonic()
            problem, args = check(a.binary, path, command, a.timeout)
            dt = time.monotonic() - t0
            if dt > slowest[0]:
                slowest = (dt, "%s (mutant %d of %s)" % (command, n, os.path.basename(src)))
            if problem:
                findings += 1
                print("FINDING mutant %d (%s of %s): %s" % (n, command, os.path.basename(src), problem), flush=True)
                if a.save:
                    os.makedirs(a.save, exist_ok=True)
                    keep = os.path.join(a.save, "seed%d_m%05d.json" % (a.seed, n))
                    with open(keep, "wb") as f:
                        f.write(data)
                    with open(keep + ".cmd", "w") as f:
                        f.write(" ".join(args[:2] + [keep] + args[3:]) + "\n# " + problem + "\n")
    print("fuzz_cases: %d mutants, %d findings; slowest %.2f s: %s" % (a.count, findings, slowest[0], slowest[1]))
    return 1 if findings else 0


if __name__ == "__main__":
    sys.exit(main())
