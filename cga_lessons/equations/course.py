"""The course's chapters and how they depend on each other: one table for the README and notebook 00.

>>> [c.notebook for c in CHAPTERS if "07" in c.needs]
['08_fused_3d_map', '11_future_work']
>>> ("06", "09") in arrows()
True
"""

from __future__ import annotations

from dataclasses import dataclass

__all__ = ["Chapter", "CHAPTERS", "arrows", "dependency_table", "dependency_sentence"]


@dataclass(frozen=True)
class Chapter:
    """One chapter notebook: its file name (no suffix), the thesis's sections, the chapters it uses, a summary."""

    notebook: str
    thesis: str
    needs: tuple[str, ...]
    summary: str

    @property
    def number(self) -> str:
        """The two-digit prefix, e.g. ``"05"``."""
        return self.notebook[:2]


CHAPTERS = (
    Chapter("01_geometric_algebra", "2.1–2.2", (),
            "the Clifford product, $\\mathcal{G}_{p,q,r}$ from its axioms, inner and outer products, reverse, dual, "
            "exp"),
    Chapter("02_conformal_model", "2.3.1–2.3.3", ("01",),
            "stereographic projection, the Minkowski plane, conformal points and the entities of table 2.1"),
    Chapter("03_conformal_transformations", "2.3.4–2.3.5", ("02",),
            "reflections, inversions, rotors, translators, motors, screws (table 2.2); logarithms and registration"),
    Chapter("04_entity_properties", "2.4", ("03",),
            "reading centre, radius, direction, moment... back from every entity; rotors and motors taken apart"),
    Chapter("05_laser_line_maps", "3.1", ("04",),
            "segments from scans, Hough-space matching, odometry correction, the map of an office and of a real log"),
    Chapter("06_conformal_line_maps", "3.2", ("05",), "the same map with point pairs, spheres and motors"),
    Chapter("07_stereo_reconstruction", "app. A, 4.1", ("04",),
            "cameras, the 8-point algorithm, triangulation, conformal entities from two views"),
    Chapter("08_fused_3d_map", "4.2", ("06", "07"), "the robot's motor chains and one 3D map from laser and stereo"),
    Chapter("09_relocalization", "5", ("05", "06"),
            "where am I in a known map: the thesis's votes, why they fail, what works"),
    Chapter("10_exploration", "2nd document", ("04",), "seen, unseen and occupied nodes; a path around an obstacle"),
    Chapter("11_future_work", "6", ("07", "08", "09"),
            "the future work built: Monte Carlo localization with chapter 5 as its proposal, motors for n joints "
            "(forward and inverse kinematics), conformal entities registered automatically"),
)  # fmt: skip


def arrows() -> list[tuple[str, str]]:
    """``(a, b)`` for every chapter ``b`` that uses chapter ``a`` directly (the arrows of notebook 00's diagram)."""
    return [(a, c.number) for c in CHAPTERS for a in c.needs]


def dependency_table() -> str:
    """The Markdown table of notebook 00: notebook, thesis sections, the chapters it needs, what you do there."""
    rows = ["| notebook | thesis | needs | what you do there |", "|---|---|---|---|"]
    rows += [f"| `{c.notebook}` | {c.thesis} | {', '.join(c.needs) or '–'} | {c.summary} |" for c in CHAPTERS]
    return "\n".join(rows)


def dependency_sentence() -> str:
    """One sentence for the README: which chapter needs which (beyond chapter 2, which every chapter builds on)."""
    base = {"01", "02", "03", "04"}
    parts = []
    for c in CHAPTERS:
        if c.number in base:
            continue
        beyond = [n for n in c.needs if n not in base]
        parts.append(f"`{c.number}` needs " + (" and ".join(f"`{n}`" for n in beyond) if beyond else "nothing else"))
    return "Every chapter builds on chapter 2 (`01`-`04`); " + "; ".join(parts) + "."
