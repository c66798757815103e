"""The fusion of one segment into a map line (thesis sections 3.1.4 and 3.2.4, Eqs. 3.20-3.21), with real edges.

:func:`fuse_segment` is the rule :class:`~cga_lessons.mapping2d.builder.MapBuilder` applies when a scan's segment
corresponds to a map line, and when two map lines turn out to be one (duplicates).
"""

from __future__ import annotations

import numpy as np

from .geometry import SegmentSet
from .segment import line_from_sums

__all__ = ["fuse_segment"]


def fuse_segment(lines: SegmentSet, g: int, geometry, ls, le, lsums, ledge, edge_match: float) -> None:
    """Fuse one segment (ends ``ls``, ``le``, point sums ``lsums``, edge counts ``ledge``) into map line ``g`` of
    ``lines``, in place (sections 3.1.4, 3.2.4).

    The ends follow (3.20)-(3.21): the longer segment's ends, pushed out by
    any end of the shorter outside its sphere (2.118).  Ends that are real
    edges take precedence: an edge seen again (within ``edge_match``, m) is
    averaged with the map's (so the map's edge is not the most extreme of its
    noisy sightings), a map edge is not pushed out by an end that is not an
    edge, and an edge seen near a map end that was not one replaces it.  The
    line is refitted from all the points gathered.
    """
    G = lines
    s, e, replaced, g_longer, same = geometry.fuse_ends(G.start[g], G.end[g], ls, le)
    if (e - s) @ (G.end[g] - G.start[g]) < 0:  # back to the global segment's sense
        s, e = e, s
    union = [s, e]
    gends, gcount = [G.start[g], G.end[g]], G.edge[g]
    ledge = np.asarray(ledge)
    lends, lcount = ([ls, le], ledge) if same else ([le, ls], ledge[::-1])
    ends, counts = [None, None], np.zeros(2, int)
    for k in range(2):
        close = geometry.distance(gends[k], lends[k]) < edge_match
        if gcount[k] and lcount[k] and close:
            n = gcount[k] + lcount[k]
            ends[k], counts[k] = (gcount[k] * gends[k] + lcount[k] * lends[k]) / n, n
        elif gcount[k]:
            ends[k], counts[k] = gends[k], gcount[k]
        elif lcount[k] and close:
            ends[k], counts[k] = lends[k], lcount[k]
        else:
            ends[k], counts[k] = union[k], 0
    sums = G.sums[g] + lsums
    c, d = line_from_sums(sums, ends[1] - ends[0])
    G.start[g] = c + d * ((ends[0] - c) @ d)
    G.end[g] = c + d * ((ends[1] - c) @ d)
    G.sums[g] = sums
    G.edge[g] = counts
