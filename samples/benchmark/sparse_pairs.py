"""The sparse-pairs suite: calibrated real pairs with 40 to 150 matches, where a small object or a
wide baseline leaves few correspondences (a user's first side-by-side run on a turntable set).
Made from the dev data of ../shared/data, in two ways:

(1) turntable pairs at wider baselines: templeSR frame i to i + 2, i + 3 and i + 4 (the main suite
  pairs i with the first of i + 1..i + 3 that passes), all their SIFT matches when there are 40 to
  150, an evenly spaced 150 of them when there are more;
(2) the main suite's KITTI and fountain pairs with their matches subsampled evenly (every k-th in
  the matcher's order) to 40, 60, 80, 100, 120 or 150, in turn from pair to pair.

A pair is kept when at least 15 of its matches agree with the true motion (Sampson distance below
2 px), so that a right answer exists. Every method runs once per pair at exactly N and with
the libraries' adaptive termination, as on the main suite; run_benchmark.py --sparse-only writes
the suite's report (sparse_pairs.md)."""
import numpy as np

import pairs
from pairs import Pair

MIN_MATCHES, MAX_MATCHES = 40, 150
SUBSAMPLED_COUNTS = [40, 60, 80, 100, 120, 150]
TURNTABLE_GAPS = (2, 3, 4)
MIN_TRUE = 15  # matches that agree with the true motion, for a right answer to exist


def _evenly(count, keep):
    """Indices of `keep` of `count` items, evenly spaced (all of them when keep >= count)."""
    if keep >= count:
        return np.arange(count)
    return np.round(np.linspace(0, count - 1, keep)).astype(int)


def _pair(dataset, name, p1, p2, K, R, t, note):
    if len(p1) < MIN_MATCHES or np.sum(pairs.agrees_with_truth(p1, p2, K, R, t)) < MIN_TRUE:
        return None
    return Pair(dataset, name, p1, p2, K, R, t, note=note)


def turntable_pairs(sequence, matcher, references):
    """Frame i to i + 2..4 of a turntable sequence for each i of `references`, at most
    MAX_MATCHES matches each."""
    found = []
    for i in references:
        for gap in TURNTABLE_GAPS:
            j = i + gap
            if j >= len(sequence.images):
                continue
            p1, p2, _ = matcher.match(sequence.images[i], sequence.images[j],
                                      sequence.max_side or None)
            keep = _evenly(len(p1), MAX_MATCHES)
            R, t, _ = sequence.relative_motion(i, j)
            pair = _pair("%s i+2..4" % sequence.name, "%s %d-%d" % (sequence.name, i, j),
                         p1[keep], p2[keep], sequence.K, R, t,
                         "%d of %d matches" % (len(keep), len(p1)))
            if pair is not None:
                found.append(pair)
    return found


def subsampled_pairs(dense):
    """The pairs of `dense` with their matches evenly subsampled, the count cycling through
    SUBSAMPLED_COUNTS."""
    found = []
    for k, pair in enumerate(dense):
        keep = _evenly(len(pair.points1), SUBSAMPLED_COUNTS[k % len(SUBSAMPLED_COUNTS)])
        sparse = _pair("%s subsampled" % pair.dataset, pair.name + " sub%d" % len(keep),
                       pair.points1[keep], pair.points2[keep], pair.K, pair.R_gt, pair.t_gt,
                       "%d of %d matches" % (len(keep), len(pair.points1)))
        if sparse is not None:
            found.append(sparse)
    return found


def sparse_pairs(sequences, dense_pairs, matcher, quick=False):
    """The suite: turntable sequences (templeSR) at wider baselines, the other sequences' dense
    pairs (dense_pairs, the main suite's) subsampled. quick: at most 4 pairs per dataset."""
    found = []
    for sequence in sequences:
        if sequence.name == "templeSR":
            found += turntable_pairs(sequence, matcher,
                                     range(2 if quick else len(sequence.images)))
    found += subsampled_pairs([p for p in dense_pairs if p.K is not None
                               and not p.dataset.startswith("templeSR")])
    if quick:
        by_dataset = {}
        for pair in found:
            by_dataset.setdefault(pair.dataset, []).append(pair)
        found = [p for group in by_dataset.values() for p in group[:4]]
    return found
