"""Text tables for notebook 11: the stored results of the chapter's three benchmarks, as a student reads them.

Each function takes the JSON record a benchmark script wrote (``benchmarks/bench_mcl.py``,
``benchmarks/bench_kinematics.py``, ``benchmarks/bench_stereo_detect.py``, each with ``--out``) and returns
a table as one string, every number formatted from the record (nothing typed in).  :func:`read_record` reads
such a file, or returns None when it has not been written yet.
"""

from __future__ import annotations

import json
from pathlib import Path

import numpy as np

from cga_lessons.checks import fail, integer

__all__ = ["read_record", "mcl_table", "kinematics_table", "stereo_table"]


def read_record(path):
    """The JSON record at ``path`` (a dict), or None when there is no such file (nothing at ``path``)."""
    func = "read_record"
    if not isinstance(path, (str, Path)) or (isinstance(path, str) and not path):
        raise fail(func, "path", f"expected a path, got {path!r}")
    p = Path(path)
    if not p.exists():
        return None
    if not p.is_file():
        raise fail(func, "path", f"is not a file: {p}")
    try:
        record = json.loads(p.read_text(encoding="utf-8"))
    except (json.JSONDecodeError, UnicodeDecodeError) as exc:
        raise fail(func, "path", f"{p}: not JSON ({exc})") from None
    if not isinstance(record, dict):
        raise fail(func, "path", f"{p}: expected a JSON object, got {type(record).__name__}")
    return record


def _need(record, keys, func):
    if not isinstance(record, dict):
        raise fail(func, "record", f"expected a dict (a benchmark's JSON), got {type(record).__name__}")
    missing = [k for k in keys if k not in record]
    if missing:
        raise fail(func, "record", f"missing {missing}; was it written by the right benchmark?")


def _malformed(func: str, where: str, exc: Exception):
    return fail(func, where, f"missing or malformed field ({type(exc).__name__}: {exc})")


def _at(d: dict, k: int):
    """``d[k]`` for a dict whose int keys went through JSON (they come back as strings)."""
    return d[str(k)] if str(k) in d else d[k]


def mcl_table(record) -> str:
    """Monte Carlo localization against chapter 5, per log (``benchmarks/bench_mcl.py --out``).

    Columns: sequences; located (converged and within the tolerance) after 1, 3 and 10 scans; sequences
    confidently wrong at some scan (all / beyond twice the tolerance); chapter 5 on the k-th scan alone and on
    the first three as one run; median particles at the end; ms per update after the first.
    """
    func = "mcl_table"
    _need(record, ("logs",), func)
    rows = [f"{'log':<13} {'seqs':>5} | {'MCL@1':>6} {'@3':>6} {'@10':>6} {'wrong':>7} {'parts':>6} {'ms':>5} | "
            f"{'ch5@1':>6} {'@3':>6} {'@10':>6} {'seq3':>6}"]  # fmt: skip
    rows.append("-" * len(rows[0]))
    if not isinstance(record["logs"], dict):
        raise fail(func, "record['logs']", "expected a dict log name -> results")
    for name, s in record["logs"].items():
        try:
            loc, single = s["located"], s["single"]
            rows.append(
                f"{name:<13} {s['n']:5d} | {100 * _at(loc, 1):5.1f}% {100 * _at(loc, 3):5.1f}% "
                f"{100 * _at(loc, 10):5.1f}% {str(s['wrong']) + '/' + str(s['gross']):>7} {s['particles']:6.0f} "
                f"{s['later_ms']:5.1f} | {100 * _at(single, 1):5.1f}% {100 * _at(single, 3):5.1f}% "
                f"{100 * _at(single, 10):5.1f}% {100 * s['seq3']:5.1f}%"
            )
        except (KeyError, TypeError, ValueError, AttributeError) as exc:
            raise _malformed(func, f"record['logs'][{name!r}]", exc) from None
    return "\n".join(rows)


def kinematics_table(record) -> str:
    """Forward kinematics timings of one arm, motors against 4x4 matrices (``benchmarks/bench_kinematics.py``)."""
    func = "kinematics_table"
    _need(record, ("cases", "floor", "configurations", "max_deviation"), func)
    try:
        return _kinematics_rows(record)
    except (KeyError, TypeError, ValueError, AttributeError) as exc:
        raise _malformed(func, "record", exc) from None


def _kinematics_rows(record) -> str:
    width = max(len(k) for k in record["cases"])
    rows = [f"{record.get('arm', 'arm')}, {record['configurations']:,} configurations at once; "
            f"'x floor' = time / time of '{record['floor']}' (median over rounds)", "",
            f"{'case':<{width}} {'median ms':>10} {'x floor':>8} {'max |dH|':>9}"]  # fmt: skip
    for name, c in record["cases"].items():
        dev = record["max_deviation"].get(name)
        rows.append(f"{name:<{width}} {c['median_ms']:10.2f} {c['x_floor']:8.2f} "
                    + (f"{dev:9.1e}" if dev is not None else f"{'':>9}"))  # fmt: skip
    if "multivector_product_ms" in record:
        rows.append(f"{'general Multivector product (one run)':<{width}} {record['multivector_product_ms']:10.2f} "
                    f"{record['multivector_x_floor']:8.2f}")  # fmt: skip
    return "\n".join(rows)


def stereo_table(record, section: int) -> str:
    """Precision / recall per kind of one section (1-based) of ``benchmarks/bench_stereo_detect.py --out``."""
    func = "stereo_table"
    _need(record, ("sections", "kinds"), func)
    if not isinstance(record["sections"], list) or not isinstance(record["kinds"], list):
        raise fail(func, "record", "expected lists under 'sections' and 'kinds'")
    if not isinstance(section, (int, np.integer)) or not record["sections"]:
        raise fail(func, "section", f"expected a whole number 1..{len(record['sections'])}, got {section!r}")
    section = integer(section, func, "section", low=1, high=len(record["sections"]))
    try:
        return _stereo_rows(record, section)
    except (KeyError, TypeError, ValueError, AttributeError, IndexError) as exc:
        raise _malformed(func, f"record['sections'][{section - 1}]", exc) from None


def _stereo_rows(record, section: int) -> str:
    sec = record["sections"][section - 1]
    kinds = record["kinds"]
    rows = [sec["title"], f"{'':<27}" + " ".join(f"{k:^13}" for k in kinds) + f" {'points':>7} {'s/cloud':>8}",
            f"{'':<27}" + " ".join(f"{'prec':>6} {'rec':>6}" for _ in kinds)]  # fmt: skip
    for r in sec["rows"]:
        cells = []
        for k in kinds:
            c = r["kinds"][k]
            cells.append(f"{c['tp'] / max(c['detected'], 1):6.2f} {c['tp'] / max(c['truth'], 1):6.2f}")
        rows.append(f"{r['label']:<27}" + " ".join(cells) + f" {r['points']:7.0f} {r['seconds']:8.2f}")
    return "\n".join(rows)
