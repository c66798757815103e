"""List every bad input the fuzz tries and what it did: ``python tests/fuzz/report.py [group or case id ...]``.

With ``--failures`` only the failing rows are printed.  The last lines count the outcomes.
"""

from __future__ import annotations

import sys
from collections import Counter
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))

from fuzz.catalogue import all_cases, uncovered  # noqa: E402
from fuzz.harness import FAILURES, problems_of, run_case  # noqa: E402


def main(argv: list[str]) -> int:
    only_failures = "--failures" in argv
    wanted = [a for a in argv if not a.startswith("--")]
    counts, failing = Counter(), 0
    for group, case in all_cases():
        if wanted and group not in wanted and case.id not in wanted:
            continue
        rows = run_case(case)
        bad = problems_of(rows)
        failing += bool(bad)
        counts.update(r[2] for r in rows[1:])
        if only_failures and not bad:
            continue
        print(f"\n## {group}: {case.id}")
        for arg, value, status, detail in rows:
            if only_failures and status not in FAILURES and arg:
                continue
            print(f"  {arg or '-':14s} {value:34.34s} {status:10s} {detail[:110]}")
    missing = uncovered()
    print(f"\n{sum(counts.values())} bad inputs: " + ", ".join(f"{k} {v}" for k, v in counts.most_common()))
    print(f"{failing} case(s) failing; {len(missing)} public callable(s) without a case or an exemption")
    for m in missing if not wanted else []:
        print("  uncovered:", m)
    return 1 if failing or (missing and not wanted) else 0


if __name__ == "__main__":
    raise SystemExit(main(sys.argv[1:]))
