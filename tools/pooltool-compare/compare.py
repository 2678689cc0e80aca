"""Compare two result files for the same shots; print a short markdown report.

    python compare.py SHOTS.json A.json B.json [--names ours pooltool] [--title TEXT] [--far]

A and B are in cuesight's result format (one entry per shot, in order):
{"final": [[x, y] | null, ...], "events": [{"time", "kind", "balls"}], "error", "seconds"}.

* Event sequences agree when the lists of (kind, sorted balls) of the "ball",
  "cushion" and "pocket" events are equal ("rest" events and anything else ignored).
* Final positions agree when every ball is within one ball radius of its counterpart,
  or pocketed in both.
* Final distance: the largest distance (in ball radii R) between a ball's two final
  positions (0 for a ball pocketed in both), over the shots whose sequences agree, by
  the number of ball-ball events in the sequence (0, 1, 2, 3+) and by table.
* First difference: where the sequences differ, the kinds of the first events that do
  ("end" where one sequence is a prefix of the other), counted per table.
* --far: those shots whose sequences agree but whose finals are more than R apart, with
  where the event times part (see `parting`).
* Timing: B's seconds over A's, per shot.
"""

from __future__ import annotations

import json
import math
import statistics as st
import sys

RADIUS = {"pool": 0.028575, "carom": 0.03075}
COLLISIONS = ("ball", "cushion", "pocket")
# Event times "part" once they differ by more than this (s): 0.1 ms is 0.1 mm at 1 m/s,
# ~0.004 R. Where the finals agree to 1e-4 R, matching events agree to ~1e-6 s.
PARTED = 1e-4
GROUPS = ("carom", "pool, open", "pool, 9-ball break")


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


def collisions(result: dict) -> list:
    return [e for e in result["events"] if e["kind"] in COLLISIONS]


def ball_events(result: dict) -> int:
    return sum(e["kind"] == "ball" for e in result["events"])


def bucket(n: int) -> str:
    return str(n) if n < 3 else "3+"


def final_distance(shot: dict, a: dict, b: dict) -> tuple[float, int]:
    """Largest final distance between counterparts (R) and its ball; inf if pocketed in one."""
    worst, ball = 0.0, -1
    for i, (p, q) in enumerate(zip(a["final"], b["final"], strict=True)):
        d = (math.inf if (p is None) != (q is None) else 0.0 if p is None
             else math.dist(p, q) / RADIUS[shot["table"]])
        if d > worst:
            worst, ball = d, i
    return worst, ball


def describe(e: dict) -> str:
    return f"{e['kind']} {'-'.join(map(str, e['balls']))}"


def parting(a: dict, b: dict) -> str:
    """Where two agreeing sequences' event times part: the first event whose times differ
    by more than PARTED, and the last ball-ball event before it (a likely source)."""
    ea, eb = collisions(a), collisions(b)
    k = next((k for k, (x, y) in enumerate(zip(ea, eb)) if abs(x["time"] - y["time"]) > PARTED),
             None)
    if k is None:
        return f"event times within {PARTED:g} s throughout"
    dt = ea[k]["time"] - eb[k]["time"]
    text = f"#{k} {describe(ea[k])} at {eb[k]['time']:.3f} s (Δt {dt:+.1e} s)"
    src = next((j for j in range(k - 1, -1, -1) if ea[j]["kind"] == "ball"), None)
    if src is not None:
        dt = ea[src]["time"] - eb[src]["time"]
        text += f", after #{src} {describe(ea[src])} at {eb[src]['time']:.3f} s (Δt {dt:+.1e} s)"
    return text


def first_difference(a: list, b: list) -> str:
    k = next((k for k, (x, y) in enumerate(zip(a, b)) if x != y), min(len(a), len(b)))
    return " → ".join(s[k][0] if k < len(s) else "end" for s in (a, b))


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
    title = None
    far = "--far" in args
    if far:
        args.remove("--far")
    if "--title" in args:
        i = args.index("--title")
        title = args[i + 1]
        del args[i:i + 2]
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

    print(f"## {title or f'{A} vs {B}'}: {len(shots)} shots\n")
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
    same = [i for i in ok if sequence(a_res[i]) == sequence(b_res[i])]
    dist = {i: final_distance(shots[i], a_res[i], b_res[i]) for i in same}

    print("\n### Final distance where the sequences agree (R; n: median / max)\n")
    print("| ball-ball events | " + " | ".join(GROUPS) + " | all |")
    print("|---" * (len(GROUPS) + 2) + "|")
    for n in ("0", "1", "2", "3+", "all"):
        row = []
        for g in GROUPS + ("all",):
            ds = [dist[i][0] for i in same if n in ("all", bucket(ball_events(a_res[i])))
                  and g in ("all", group(shots[i]))]
            row.append(f"{len(ds)}: {st.median(ds):.2g} / {max(ds):.2g}" if ds else "-")
        print(f"| {n} | " + " | ".join(row) + " |")

    firsts = {}
    for i in ok:
        sa, sb = sequence(a_res[i]), sequence(b_res[i])
        if sa != sb:
            key = first_difference(sa, sb)
            firsts.setdefault(key, {g: 0 for g in GROUPS})[group(shots[i])] += 1
    print(f"\n### First difference, where the sequences differ ({A} → {B})\n")
    print("| first differing events | " + " | ".join(GROUPS) + " |")
    print("|---" * (len(GROUPS) + 1) + "|")
    for key, counts in sorted(firsts.items(), key=lambda kv: -sum(kv[1].values())):
        print(f"| {key} | " + " | ".join(str(counts[g]) for g in GROUPS) + " |")

    if far:
        out = [i for i in same if dist[i][0] > 1.0]
        print(f"\n### Sequences agree, finals more than R apart: {len(out)}\n")
        if out:
            print("| shot | table | balls | ball-ball events | max final distance (R), ball "
                  f"| event times part (> {PARTED:g} s) |")
            print("|---|---|---|---|---|---|")
        for i in out:
            d, ball = dist[i]
            print(f"| {i} | {group(shots[i])} | {len(shots[i]['balls'])} "
                  f"| {ball_events(a_res[i])} | {d:.2f}, ball {ball} "
                  f"| {parting(a_res[i], b_res[i])} |")

    ratios = [b_res[i]["seconds"] / a_res[i]["seconds"] for i in ok if a_res[i]["seconds"] > 0]
    print(f"\n### Timing (wall seconds per shot)\n")
    for name, res in ((A, a_res), (B, b_res)):
        per_event = [res[i]["seconds"] / n for i in ok if (n := len(sequence(res[i])))]
        print(f"- {name}: per shot {stats([res[i]['seconds'] for i in ok])}; "
              f"per ball/cushion/pocket event {stats(per_event)}")
    print(f"- {B} / {A}, per shot: {stats(ratios)}")


if __name__ == "__main__":
    main()
