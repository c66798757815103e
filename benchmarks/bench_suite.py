"""Wall time of the whole test suite (unit tests, doctests, notebooks) and where it goes.

Run by hand from the repository root (it takes a few minutes)::

    python benchmarks/bench_suite.py              # the whole suite, as CI runs it
    python benchmarks/bench_suite.py tests/       # or any pytest arguments

Runs ``python -m pytest -q -p no:randomly --durations=0`` once in a subprocess
(the checkout first on PYTHONPATH, so that notebook kernels import it), times
the wall clock, and prints the total against the 3-minute budget, the slowest
files (a notebook's cells summed) and the slowest single items.  Nothing is
asserted; failures are reported in pytest's summary line.
"""

from __future__ import annotations

import os
import pathlib
import re
import subprocess
import sys
import time
from collections import defaultdict

ROOT = pathlib.Path(__file__).resolve().parents[1]
BUDGET_S = 180.0
DURATION = re.compile(r"^\s*([0-9.]+)s\s+(setup|call|teardown)\s+(\S.*?)\s*$")


def parse_durations(text: str):
    """``{item: seconds}`` (setup + call + teardown) from pytest's ``--durations`` report."""
    items: dict = defaultdict(float)
    in_report = False
    for line in text.splitlines():
        if "slowest" in line and "durations" in line:
            in_report = True
            continue
        if in_report:
            m = DURATION.match(line)
            if m:
                items[m.group(3)] += float(m.group(1))
            elif line.startswith("=") or (line.strip() and not line.startswith("(")):
                if items:
                    in_report = False
    return dict(items)


def main(args: list[str]) -> int:
    cmd = [sys.executable, "-m", "pytest", "-q", "-p", "no:randomly", "--durations=0", *args]
    env = dict(os.environ)
    env["PYTHONPATH"] = os.pathsep.join([str(ROOT), *filter(None, [env.get("PYTHONPATH")])])
    print("+", " ".join(cmd[1:]), f"(in {ROOT}, {os.cpu_count()} cores)", flush=True)
    t0 = time.perf_counter()
    proc = subprocess.run(cmd, cwd=ROOT, env=env, capture_output=True, text=True)
    wall = time.perf_counter() - t0
    out = proc.stdout + proc.stderr
    summary = [ln for ln in out.splitlines() if re.search(r"\d+ (passed|failed|errors?)\b.* in [0-9.]+s", ln)]
    items = parse_durations(out)
    files: dict = defaultdict(float)
    for item, sec in items.items():
        files[item.split("::")[0]] += sec
    counted = sum(items.values())
    print(
        f"\nwhole suite: {wall:.1f} s wall ({wall / BUDGET_S:.2f} of the {BUDGET_S:.0f} s budget); "
        f"items sum to {counted:.1f} s (the rest is start-up, collection and kernels)"
    )
    print("pytest:", summary[-1].strip("= ") if summary else f"exit code {proc.returncode}")
    failed = [ln.split(" - ")[0] for ln in out.splitlines() if ln.startswith(("FAILED ", "ERROR "))]
    for ln in failed[:25]:
        print("  ", ln)
    if len(failed) > 25:
        print(f"   ... and {len(failed) - 25} more")
    print(f"\n{'slowest files (items summed)':70s} {'[s]':>7s} {'share':>6s}")
    for name, sec in sorted(files.items(), key=lambda kv: -kv[1])[:15]:
        print(f"{name:70s} {sec:7.2f} {sec / wall:6.1%}")
    print(f"\n{'slowest items':70s} {'[s]':>7s}")
    for name, sec in sorted(items.items(), key=lambda kv: -kv[1])[:15]:
        label = name if len(name) <= 70 else name[:33] + "..." + name[-34:]
        print(f"{label:70s} {sec:7.2f}")
    return 0


if __name__ == "__main__":
    raise SystemExit(main(sys.argv[1:]))
