"""Compare two result files for the same shots; print a short markdown report.

    python compare.py SHOTS.json A.json B.json [--names ours pooltool]

A and B are in cuesight's result format (one entry per shot, in order):
{"final": [[x, y] | null, ...], "events": [{"time", "kind", "balls"}], "error", "seconds"}.

* Event sequences agree when the lists of (kind, sorted balls) of the "ball",
  "cushion" and "pocket" events are equal ("rest" events and anything else ignored).
* Final positions agree when every ball is within one ball radius of its counterpart,
  or pocketed in both.
* Timing: B's seconds over A's, per shot.
"""

from __future__ import annotations

import json
import math
import statistics as st
import sys

RADIUS = {"pool": 0.028575, "carom": 0.03075}
COLLISIONS = ("ball", "cushion", "pocket")


def group(shot: dict) -> str:
    if shot["table"] == "carom":
        return "carom"
    return "pool, 9-ball break" if len(shot["balls"]) == 10 else "pool, open"


def sequence(result: dict) -> list:
    return [(e["kind"], tuple(sorted(e["balls"]))) for e in result["events"]
            if e["kind"] in COLLISIONS]


def prefix_share(a: list, b: list) -> float:
    """How much of the longer sequence the two share from the start (1 if both empty)."""
    n = 0
    while n < min(len(a), len(b)) and a[n] == b[n]:
        n += 1
    return n / max(len(a), len(b)) if a or b else 1.0


def finals_agree(shot: dict, a: dict, b: dict) -> bool:
    R = RADIUS[shot["table"]]
    for p, q in zip(a["final"], b["final"], strict=True):
        if (p is None) != (q is None):
            return False
        if p is not None and math.dist(p, q) > R:
            return False
    return True


def pct(n: int, d: int) -> str:
    return f"{n}/{d} ({100 * n / d:.0f} %)" if d else "0/0"


def stats(xs: list) -> str:
    if not xs:
        return "-"
    geo = math.exp(st.mean(math.log(x) for x in xs)) if min(xs) > 0 else float("nan")
    return (f"median {st.median(xs):.3g}, mean {st.mean(xs):.3g}, geometric mean {geo:.3g}, "
            f"min {min(xs):.3g}, max {max(xs):.3g}")


def main() -> None:
    args = sys.argv[1:]
    names = ["ours", "pooltool"]
    if "--names" in args:
        i = args.index("--names")
        names = args[i + 1:i + 3]
        del args[i:i + 3]
    if len(args) != 3:
        sys.exit(__doc__)
    shots, a_res, b_res = (json.load(open(p)) for p in args)
    if not len(shots) == len(a_res) == len(b_res):
        sys.exit(f"lengths differ: {len(shots)} shots, {len(a_res)} and {len(b_res)} results")
    A, B = names

    print(f"## {A} vs {B}: {len(shots)} shots\n")
    for name, res in ((A, a_res), (B, b_res)):
        errs = [(i, r["error"]) for i, r in enumerate(res) if r["error"] is not None]
        print(f"- {name}: {len(errs)} errors" + "".join(f"\n  - shot {i}: {e}" for i, e in errs[:5]))
    print()
    print("| shots | both ran | event sequences agree | of those, finals within R "
          "| mean agreeing prefix |")
    print("|---|---|---|---|---|")
    groups = sorted({group(s) for s in shots}) + ["all"]
    for g in groups:
        idx = [i for i, s in enumerate(shots) if g in ("all", group(s))]
        ok = [i for i in idx if a_res[i]["error"] is None and b_res[i]["error"] is None]
        same = [i for i in ok if sequence(a_res[i]) == sequence(b_res[i])]
        close = [i for i in same if finals_agree(shots[i], a_res[i], b_res[i])]
        shares = [prefix_share(sequence(a_res[i]), sequence(b_res[i])) for i in ok]
        print(f"| {g} | {len(ok)}/{len(idx)} | {pct(len(same), len(ok))} "
              f"| {pct(len(close), len(same))} | {100 * st.mean(shares) if shares else 0:.0f} % |")

    ok = [i for i in range(len(shots)) if a_res[i]["error"] is None and b_res[i]["error"] is None]
    ratios = [b_res[i]["seconds"] / a_res[i]["seconds"] for i in ok if a_res[i]["seconds"] > 0]
    print(f"\n### Timing (wall seconds per shot)\n")
    for name, res in ((A, a_res), (B, b_res)):
        per_event = [res[i]["seconds"] / n for i in ok if (n := len(sequence(res[i])))]
        print(f"- {name}: per shot {stats([res[i]['seconds'] for i in ok])}; "
              f"per ball/cushion/pocket event {stats(per_event)}")
    print(f"- {B} / {A}, per shot: {stats(ratios)}")


if __name__ == "__main__":
    main()
