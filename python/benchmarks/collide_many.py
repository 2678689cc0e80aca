"""Throughput of ``cuesight.collide_many`` with ``kim-grip``: collisions per second on
one core over random scenes (not a test; the figure goes in python/README.md).

    python python/benchmarks/collide_many.py [--n 1000000] [--repeat 5] [--model kim-grip]

Scenes (seeded): speed 0.5–5 m/s, cut ±80°, spin each component ±100 rad/s, μ 0.02–0.1
per scene, the other parameters the pool defaults. Prints the best of ``repeat`` runs
(the whole call: argument conversion, prediction, result arrays) and the median.
"""

from __future__ import annotations

import argparse
import os
import platform
import statistics
import time

import numpy as np

import cuesight


def scenes(n: int, seed: int = 18) -> dict:
    rng = np.random.default_rng(seed)
    return {
        "speed": rng.uniform(0.5, 5.0, n),
        "cut_deg": rng.uniform(-80.0, 80.0, n),
        "spin": rng.uniform(-100.0, 100.0, (n, 3)),
        "mu": rng.uniform(0.02, 0.1, n),
    }


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--n", type=int, default=1_000_000)
    parser.add_argument("--repeat", type=int, default=5)
    parser.add_argument("--model", default="kim-grip")
    args = parser.parse_args()
    if hasattr(os, "sched_setaffinity"):
        # One core, whatever the machine has (collide_many is single-threaded anyway).
        os.sched_setaffinity(0, {sorted(os.sched_getaffinity(0))[0]})
    inputs = scenes(args.n)
    cuesight.collide_many(**{k: v[:1000] for k, v in inputs.items()}, model=args.model)
    times = []
    for _ in range(args.repeat):
        start = time.perf_counter()
        out = cuesight.collide_many(**inputs, model=args.model)
        times.append(time.perf_counter() - start)
    assert len(out) == args.n and out.valid.all()
    best, median = min(times), statistics.median(times)
    print(
        f"collide_many, model {args.model}: {args.n:,} scenes, best {best * 1e3:.1f} ms "
        f"({args.n / best / 1e6:.2f} M collisions/s), median {median * 1e3:.1f} ms "
        f"({args.n / median / 1e6:.2f} M/s); one core, {platform.processor() or platform.machine()}, "
        f"Python {platform.python_version()}, cuesight {cuesight.__version__}"
    )


if __name__ == "__main__":
    main()
