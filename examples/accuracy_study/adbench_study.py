#!/usr/bin/env python3
"""ROC-AUC of hbos' default mode, PyOD's default HBOS and candidate defaults on ADBench and ODDS.

What it does (docs/accuracy_adbench.md has the results and the reasoning):

- reads the 43 ADBench "Classical" sets (``*.npz``, keys ``X`` and ``y``) and the 17 ODDS sets
  (CSV, header row, last column ``label``; 1 = outlier);
- fits every model on all rows and scores the same rows, no scaling, no split (the protocol of
  docs/accuracy.md), and computes the ROC-AUC as the Mann-Whitney statistic with tied scores
  sharing their average rank (= scikit-learn's ``roc_auc_score``, cross-checked on every run);
- models: the PyOD mode with PyOD's defaults (``HBOS(mode="pyod")``: n_bins=10, alpha=0.1,
  tol=0.5; PyOD 3.6.5's HBOS bit for bit), the current default mode (``HBOS()``: 5 equal-width
  bins x 5 shifted origins), and the candidate defaults bins x shifts with bins in
  {5, 8, 10, 15, 20, auto (Birge-Rozenblac), sturges (ceil(log2 n + 1), computed here from n and
  passed as an int)} and shifts in {1, 3, 5, 10}, through ``_hbos.DefaultModel.fit``;
- scale test: every feature multiplied by 2^k, k uniform in {-9, ..., 9}, drawn from mt19937_64
  seeded with 1985 + FNV-1a(set name) exactly as hbos-accuracy-study does (so the ODDS draws are
  the C++ study's); every default-mode and candidate score vector must be bit-identical after it,
  and the PyOD mode's AUC after it is reported for contrast;
- a probe that is not a candidate (it would need a change to the library's score): the default
  mode's per-feature terms saturated as PyOD's alpha saturates them, but relative to the modal
  bin's height so that it stays scale-invariant (SOFTCAP below);
- selection protocol for the candidates: pick the best mean on one collection, report it on the
  other (ODDS -> ADBench and back, and against the 26 ADBench sets that share no source data with
  an ODDS set, which is the only truly disjoint split);
- writes a JSON file and a Markdown report, each atomically (temporary file, then os.replace);
  progress goes to stderr, one line per set.

Run from the repository root, with the Python module built (build/examples/python/hbos) or a
copy of it on PYTHONPATH, and numpy, scipy and scikit-learn installed:

    PYTHONPATH=build/examples/python nice -n 10 /usr/bin/python3 \\
        examples/accuracy_study/adbench_study.py --json adbench_study.json \\
        --markdown adbench_study.md

Optional ``--verify-pyod`` also runs the real PyOD 3.6.5 package (``--pyod-dir``, default
../shared/tools/pyod-3.6.5; it needs numba) on every set and checks that its decision_scores_
equal the PyOD mode's bit for bit. A full run (60 sets, 2 x 30 fits each) takes 67-83 s on two
cores shared with a build, peak memory 0.7 GB.
"""

import argparse
import json
import math
import os
import platform
import sys
import tempfile
import time

import numpy as np
from scipy.stats import rankdata, spearmanr

REPO_ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
SHARED = os.path.join(REPO_ROOT, "..", "shared")
DEFAULT_ADBENCH = os.path.join(SHARED, "data", "odds", "adbench_classical")
DEFAULT_ODDS = os.path.join(SHARED, "data", "odds", "csv")
DEFAULT_PYOD = os.path.join(SHARED, "tools", "pyod-3.6.5")

SEED = 1985  # as hbos-accuracy-study
BINS = ["5", "8", "10", "15", "20", "auto", "sturges"]
SHIFTS = [1, 3, 5, 10]
CURRENT_DEFAULT = ("5", 5)
SOFTCAP = [0.01, 0.1, 0.3]  # the soft-cap probe's pseudo-heights (relative to the modal bin)

# ADBench sets built from the same source data as one of the 17 ODDS sets (ADBench took most of
# its "Classical" sets from ODDS). The relation found by comparing the arrays is recorded per set
# at run time; this table only names the source. Landsat is the Statlog satellite data with a
# different outlier definition; WDBC is the Wisconsin diagnostic data that ODDS' "wbc" samples.
SAME_SOURCE_AS_ODDS = {
    "6_cardio": "cardio", "14_glass": "glass", "18_Ionosphere": "ionosphere",
    "19_landsat": "satellite", "20_letter": "letter", "21_Lymphography": "lympho",
    "24_mnist": "mnist", "25_musk": "musk", "26_optdigits": "optdigits",
    "28_pendigits": "pendigits", "29_Pima": "pima", "30_satellite": "satellite",
    "31_satimage-2": "satimage-2", "32_shuttle": "shuttle", "39_vertebral": "vertebral",
    "40_vowels": "vowels", "43_WDBC": "wbc",
}


def log(msg):
    print(msg, file=sys.stderr, flush=True)


# ----------------------------------------------------------------------------- random factors

class MT19937_64:
    """std::mt19937_64 (its output sequence is fixed by the C++ standard)."""

    _MASK = (1 << 64) - 1

    def __init__(self, seed):
        mt = [seed & self._MASK]
        for i in range(1, 312):
            prev = mt[-1]
            mt.append((6364136223846793005 * (prev ^ (prev >> 62)) + i) & self._MASK)
        self.mt = mt
        self.index = 312

    def _twist(self):
        mt = self.mt
        for i in range(312):
            x = (mt[i] & 0xFFFFFFFF80000000) | (mt[(i + 1) % 312] & 0x7FFFFFFF)
            xa = x >> 1
            if x & 1:
                xa ^= 0xB5026F5AA96619E9
            mt[i] = mt[(i + 156) % 312] ^ xa
        self.index = 0

    def __call__(self):
        if self.index >= 312:
            self._twist()
        x = self.mt[self.index]
        self.index += 1
        x ^= (x >> 29) & 0x5555555555555555
        x ^= (x << 17) & 0x71D67FFFEDA60000
        x ^= (x << 37) & 0xFFF7EEE000000000
        x ^= x >> 43
        return x & self._MASK


def _check_mt19937_64():
    rng = MT19937_64(5489)
    for _ in range(9999):
        rng()
    if rng() != 9981545732273789042:  # the C++ standard's check value
        raise RuntimeError("MT19937_64 does not reproduce std::mt19937_64")


def fnv1a(name):
    h = 14695981039346656037
    for c in name.encode("utf-8"):
        h ^= c
        h = (h * 1099511628211) & ((1 << 64) - 1)
    return h


def power_of_two_exponents(name, d):
    """hbos-accuracy-study's rescale_power_of_two draws: k_j = -9 + rng() % 19 per feature."""
    rng = MT19937_64((SEED + fnv1a(name)) & ((1 << 64) - 1))
    return np.array([-9 + rng() % 19 for _ in range(d)], dtype=np.int64)


# ----------------------------------------------------------------------------- data

def load_adbench(path):
    z = np.load(path, allow_pickle=False)
    return z["X"], z["y"]


def load_odds(path):
    with open(path) as f:
        header = f.readline().strip().split(",")
    if header[-1] != "label":
        raise ValueError(f"{path}: last column is {header[-1]!r}, expected 'label'")
    a = np.loadtxt(path, delimiter=",", skiprows=1, dtype=np.float64, ndmin=2)
    return a[:, :-1], a[:, -1]


def list_sets(adbench_dir, odds_dir):
    sets = []
    ad = [f for f in os.listdir(adbench_dir) if f.endswith(".npz")]
    ad.sort(key=lambda f: (int(f.split("_")[0]) if f.split("_")[0].isdigit() else 10**9, f))
    for f in ad:
        sets.append(("adbench", f[:-4], os.path.join(adbench_dir, f)))
    for f in sorted(f for f in os.listdir(odds_dir) if f.endswith(".csv")):
        sets.append(("odds", f[:-4], os.path.join(odds_dir, f)))
    return sets


def describe(X):
    """Scale-invariant descriptors of the features (used to explain wins and losses)."""
    n, d = X.shape
    finite = bool(np.isfinite(X).all())
    out = {"nonfinite_values": int((~np.isfinite(X)).sum())}
    if not finite:
        return out
    ptp = np.ptp(X, axis=0)
    const = ptp == 0
    out["constant_columns"] = int(const.sum())
    distinct, integral, few, spike, fullest5, pyod_peak = [], 0, 0, 0, [], []
    for j in np.flatnonzero(~const):
        col = X[:, j]
        values, counts = np.unique(col, return_counts=True)
        distinct.append(len(values))
        integral += bool(np.all(col == np.round(col)))
        few += len(values) <= 10
        spike += counts.max() > 0.9 * n
        h, _ = np.histogram(col, bins=5, range=(col.min(), col.max()))
        fullest5.append(h.max() / n)
        # Not scale-invariant on purpose: PyOD's largest density (10 bins, 1/feature-unit),
        # to be compared with its alpha = 0.1.
        pyod_peak.append(float(np.histogram(col, bins=10, density=True)[0].max()))
    k = max(1, int((~const).sum()))
    out.update({
        "median_distinct_values": float(np.median(distinct)) if distinct else 0.0,
        "share_integer_columns": integral / k,
        "share_columns_le10_values": few / k,
        "share_columns_mode_gt90pct": spike / k,
        "median_fullest_of_5_bins": float(np.median(fullest5)) if fullest5 else 1.0,
        "columns_pyod_density_below_alpha": int(sum(p < 0.1 for p in pyod_peak)),
        "median_pyod_peak_density": float(np.median(pyod_peak)) if pyod_peak else 0.0,
    })
    return out


# ----------------------------------------------------------------------------- scoring

def roc_auc(scores, y):
    """Mann-Whitney U / (n1 n0), tied scores sharing their average rank."""
    pos = y == 1
    n1 = int(pos.sum())
    n0 = len(y) - n1
    if n1 == 0 or n0 == 0:
        raise ValueError("the labels hold one class only")
    r = rankdata(scores, method="average")
    return float((r[pos].sum() - n1 * (n1 + 1) / 2.0) / (n1 * n0))


def candidate_key(bins, shifts):
    return f"{bins}x{shifts}"


def bins_arg(bins, n):
    if bins == "sturges":
        return str(int(math.ceil(math.log2(n) + 1.0)))
    return bins


def score_set(hbos, name, X, y, verify_pyod_cls):
    """Everything measured on one set; a mode that raises is recorded, not dropped."""
    from hbos import _hbos

    n, d = X.shape
    res = {"auc": {}, "errors": {}, "seconds": {}, "scale_test": {}}
    k = power_of_two_exponents(name, d)
    Xs = X * np.ldexp(1.0, k)[None, :]  # exact: powers of two
    res["scale_exponents"] = k.tolist()

    def run(key, fn, data):
        t = time.perf_counter()
        try:
            s = np.asarray(fn(data), dtype=np.float64)
        except (hbos.InvalidArgument, ValueError) as e:
            res["errors"][key] = f"{type(e).__name__}: {e}"
            return None
        res["seconds"][key] = time.perf_counter() - t
        if not np.isfinite(s).all():
            res["errors"][key] = "non-finite scores"
            return None
        return s

    pyod_fn = lambda A: hbos.HBOS(mode="pyod").fit(A).decision_scores_
    default_fn = lambda A: hbos.HBOS().fit(A).decision_scores_

    s_pyod = run("pyod", pyod_fn, X)
    if s_pyod is not None:
        res["auc"]["pyod"] = roc_auc(s_pyod, y)
        from sklearn.metrics import roc_auc_score
        res["sklearn_auc_diff"] = abs(res["auc"]["pyod"] - float(roc_auc_score(y, s_pyod)))
    s = run("pyod_rescaled", pyod_fn, Xs)
    if s is not None:
        res["auc"]["pyod_rescaled"] = roc_auc(s, y)

    s_default = run("default", default_fn, X)
    if s_default is not None:
        res["auc"]["default"] = roc_auc(s_default, y)
        s = run("default_rescaled", default_fn, Xs)
        if s is not None:
            res["scale_test"]["default"] = bool(np.array_equal(s, s_default))
            res["auc"]["default_rescaled"] = roc_auc(s, y)

    for bins in BINS:
        b = bins_arg(bins, n)
        for shifts in SHIFTS:
            key = candidate_key(bins, shifts)
            fn = lambda A, b=b, shifts=shifts: _hbos.DefaultModel.fit(A, b, shifts).training_scores
            s = run(key, fn, X)
            if s is None:
                continue
            res["auc"][key] = roc_auc(s, y)
            if (bins, shifts) == CURRENT_DEFAULT and s_default is not None:
                res["candidate_equals_default"] = bool(np.array_equal(s, s_default))
            s2 = run(key + "_rescaled", fn, Xs)
            if s2 is not None:
                res["scale_test"][key] = bool(np.array_equal(s2, s))
    res["sturges_bins"] = int(bins_arg("sturges", n))

    # Probe (not a candidate: it needs a change to the library's score). The default score is a
    # sum of per-feature terms c_j = log(h_max / h); fitting each column alone gives them. The
    # probe saturates each term as PyOD's alpha does, but in units of the modal bin's height
    # (so it stays scale-invariant): c'_j = log((1 + a) / (h / h_max + a)), at most log(1 + 1/a).
    if s_default is not None:
        t = time.perf_counter()
        C = np.empty((n, d))
        for j in range(d):
            C[:, j] = _hbos.DefaultModel.fit(np.ascontiguousarray(X[:, [j]]), "", 5).training_scores
        res["softcap_additivity_error"] = float(
            np.max(np.abs(C.sum(axis=1) - s_default)) / max(1.0, float(np.max(np.abs(s_default)))))
        ratio = np.exp(-C)  # h / h_max per feature and row
        for a in SOFTCAP:
            res["auc"][f"softcap_{a:g}"] = roc_auc(np.log((1.0 + a) / (ratio + a)).sum(axis=1), y)
        res["seconds"]["softcap"] = time.perf_counter() - t

    if verify_pyod_cls is not None and s_pyod is not None:
        t = time.perf_counter()
        ref = verify_pyod_cls().fit(X).decision_scores_
        res["seconds"]["real_pyod"] = time.perf_counter() - t
        res["real_pyod"] = {"bit_identical": bool(np.array_equal(ref, s_pyod)),
                            "max_abs_diff": float(np.max(np.abs(ref - s_pyod)))}
    return res


# ----------------------------------------------------------------------------- summaries

def mean_over(sets, key):
    vals = [s["auc"].get(key) for s in sets]
    if any(v is None for v in vals) or not vals:
        return None
    return float(np.mean(vals))


def paired(sets, key, ref, rng_seed):
    """Candidate minus reference over sets: mean, wins/losses/ties, bootstrap 95% CI of the mean."""
    diff = np.array([s["auc"][key] - s["auc"][ref] for s in sets])
    rng = np.random.default_rng(rng_seed)
    boot = diff[rng.integers(0, len(diff), size=(10000, len(diff)))].mean(axis=1)
    return {"mean_diff": float(diff.mean()), "wins": int((diff > 0).sum()),
            "losses": int((diff < 0).sum()), "ties": int((diff == 0).sum()),
            "ci95": [float(np.quantile(boot, 0.025)), float(np.quantile(boot, 0.975))]}


DESCRIPTORS = [
    ("log n", lambda r: math.log(r["n"])), ("outlier share", lambda r: r["outlier_share"]),
    ("d", lambda r: r["d"]), ("median distinct values", lambda r: r["describe"]["median_distinct_values"]),
    ("integer columns", lambda r: r["describe"]["share_integer_columns"]),
    ("columns <= 10 values", lambda r: r["describe"]["share_columns_le10_values"]),
    ("columns with mode > 90 %", lambda r: r["describe"]["share_columns_mode_gt90pct"]),
    ("fullest of 5 bins", lambda r: r["describe"]["median_fullest_of_5_bins"]),
]
GAINS = [("default - PyOD", "default", "pyod"), ("sturges x5 - default", "sturgesx5", "default"),
         ("auto x1 - default", "autox1", "default")]


def descriptor_correlations(scored):
    """Spearman rank correlation, across the sets of a collection, of an AUC difference with a
    descriptor of the data (which kinds of data favour which binning)."""
    out = {}
    for coll in ["odds", "adbench"]:
        rs = [r for r in scored[coll] if "median_distinct_values" in r["describe"]]
        out[coll] = {}
        for gname, a, b in GAINS:
            g = [r["auc"][a] - r["auc"][b] for r in rs]
            out[coll][gname] = {}
            for dname, f in DESCRIPTORS:
                rho, pval = spearmanr([f(r) for r in rs], g)
                out[coll][gname][dname] = [float(rho) if np.isfinite(rho) else None,
                                           float(pval) if np.isfinite(pval) else None]
    return out


def summarise(records, candidate_keys):
    cols = {
        "odds": [r for r in records if r["collection"] == "odds"],
        "adbench": [r for r in records if r["collection"] == "adbench"],
        "adbench_disjoint": [r for r in records
                             if r["collection"] == "adbench" and r["name"] not in SAME_SOURCE_AS_ODDS],
    }
    scored = {c: [r for r in rs if not r["errors"]] for c, rs in cols.items()}
    scored["all"] = scored["odds"] + scored["adbench"]
    keys = (["pyod", "pyod_rescaled", "default", "default_rescaled"] + candidate_keys
            + [f"softcap_{a:g}" for a in SOFTCAP])
    means = {c: {k: mean_over(rs, k) for k in keys} for c, rs in scored.items()}
    summary = {
        "collections": {c: [r["name"] for r in rs] for c, rs in cols.items()},
        "excluded_from_means": {c: [r["name"] for r in rs if r["errors"]] for c, rs in cols.items()},
        "means": means,
    }
    # Selection: best candidate mean on one collection, reported on the other.
    directions = [("odds", "adbench"), ("adbench", "odds"),
                  ("odds", "adbench_disjoint"), ("adbench_disjoint", "odds")]
    selection = []
    for pick_on, held_out in directions:
        ranked = sorted(candidate_keys, key=lambda k: -means[pick_on][k])
        best = ranked[0]
        selection.append({
            "pick_on": pick_on, "held_out": held_out, "chosen": best,
            "top5_on_pick": [[k, means[pick_on][k], means[held_out][k]] for k in ranked[:5]],
            "chosen_mean_pick": means[pick_on][best], "chosen_mean_held_out": means[held_out][best],
            "pyod_mean_held_out": means[held_out]["pyod"],
            "default_mean_held_out": means[held_out]["default"],
            "held_out_rank_of_chosen": 1 + sorted(candidate_keys,
                                                  key=lambda k: -means[held_out][k]).index(best),
            "vs_pyod_held_out": paired(scored[held_out], best, "pyod", SEED),
            "vs_default_held_out": paired(scored[held_out], best, "default", SEED),
        })
    summary["selection"] = selection
    summary["beat_pyod_on_both"] = {
        pair: [k for k in candidate_keys
               if means[pair[0]][k] >= means[pair[0]]["pyod"] and means[pair[1]][k] >= means[pair[1]]["pyod"]]
        for pair in [("odds", "adbench"), ("odds", "adbench_disjoint")]}
    summary["beat_pyod_on_both"] = {f"{a}+{b}": v for (a, b), v in summary["beat_pyod_on_both"].items()}
    summary["paired_vs_pyod"] = {c: {k: paired(rs, k, "pyod", SEED) for k in ["default"] + candidate_keys}
                                 for c, rs in scored.items()}
    summary["scale_invariant"] = {
        k: all(r["scale_test"].get(k, False) for rs in scored.values() for r in rs)
        for k in ["default"] + candidate_keys}
    summary["descriptor_correlations"] = descriptor_correlations(scored)
    summary["default_losses"] = sorted(
        ([r["collection"], r["name"], r["auc"]["default"] - r["auc"]["pyod"]]
         for r in scored["all"] if r["auc"]["default"] < r["auc"]["pyod"]), key=lambda t: t[2])
    return summary


# ----------------------------------------------------------------------------- output

def atomic_write(path, text):
    d = os.path.dirname(os.path.abspath(path))
    fd, tmp = tempfile.mkstemp(prefix=".tmp_", dir=d)
    umask = os.umask(0)
    os.umask(umask)
    try:
        os.fchmod(fd, 0o666 & ~umask)
        with os.fdopen(fd, "w") as f:
            f.write(text)
        os.replace(tmp, path)
    except BaseException:
        if os.path.exists(tmp):
            os.unlink(tmp)
        raise


def fmt(v, digits=4):
    return "n/a" if v is None else f"{v:.{digits}f}"


def scale_cell(r):
    if "default" not in r["scale_test"]:
        return "n/a"
    return "yes" if r["scale_test"]["default"] else "NO"


def markdown(result):
    recs, summ, cands = result["sets"], result["summary"], result["candidates"]
    means = summ["means"]
    L = []
    L.append("# ROC-AUC on ADBench Classical and ODDS (generated by adbench_study.py)\n")
    L.append(f"Command: `{result['meta']['command']}`  ")
    L.append(f"Wall time: {result['meta']['wall_seconds']:.1f} s on {result['meta']['machine']}\n")
    L.append("Fit on all rows, no scaling, ROC-AUC = Mann-Whitney with average ranks for ties.\n")
    for coll, title in [("adbench", "ADBench Classical"), ("odds", "ODDS")]:
        L.append(f"## {title}: PyOD mode vs default mode\n")
        L.append("| set | n | d | outliers | const. cols | PyOD | default | default − PyOD | "
                 "PyOD rescaled | default rescaled bit-identical | notes |")
        L.append("|---|--:|--:|--:|--:|--:|--:|--:|--:|:-:|---|")
        for r in recs:
            if r["collection"] != coll:
                continue
            a = r["auc"]
            diff = None if "default" not in a or "pyod" not in a else a["default"] - a["pyod"]
            notes = []
            if r["name"] in SAME_SOURCE_AS_ODDS:
                notes.append(f"ODDS {SAME_SOURCE_AS_ODDS[r['name']]}: {r.get('odds_relation', '')}")
            if r["errors"]:
                first = next(iter(r["errors"].values()))
                notes.append(f"not scored by {len(r['errors'])} of the runs, e.g. {first}; "
                             "left out of the means")
            if r["dtype"] != "float64":
                notes.append(f"stored as {r['dtype']}")
            L.append(f"| {r['name']} | {r['n']} | {r['d']} | {r['outlier_share']:.1%} | "
                     f"{r['describe'].get('constant_columns', 'n/a')} | {fmt(a.get('pyod'))} | "
                     f"{fmt(a.get('default'))} | {fmt(diff, 4) if diff is not None else 'n/a'} | "
                     f"{fmt(a.get('pyod_rescaled'))} | "
                     f"{scale_cell(r)} | {'; '.join(notes)} |")
        m = means[coll]
        if summ["excluded_from_means"][coll]:
            L.append(f"| *left out of the means* | {', '.join(summ['excluded_from_means'][coll])} "
                     "| | | | | | | | | |")
        L.append(f"| **mean** | | | | | **{fmt(m['pyod'])}** | **{fmt(m['default'])}** | "
                 f"**{fmt(m['default'] - m['pyod'])}** | **{fmt(m['pyod_rescaled'])}** | | |\n")
    L.append("## Candidate means (bins x shifts)\n")
    L.append("| candidate | ODDS (17) | ADBench (43) | ADBench disjoint from ODDS (26) | all 60 | "
             "scale-invariant |")
    L.append("|---|--:|--:|--:|--:|:-:|")
    for k in ["pyod", "default"] + cands:
        mo, ma, md, allm = (means[c][k] for c in ["odds", "adbench", "adbench_disjoint", "all"])
        inv = "n/a (PyOD)" if k == "pyod" else ("yes" if summ["scale_invariant"][k] else "NO")
        L.append(f"| {k} | {fmt(mo)} | {fmt(ma)} | {fmt(md)} | {fmt(allm)} | {inv} |")
    L.append("")
    L.append("Soft-cap probe (5 x 5 with each feature's term saturated, pseudo-height a relative to "
             "the modal bin; needs a library change, not a candidate):\n")
    L.append("| variant | ODDS | ADBench | ADBench disjoint | all 60 |")
    L.append("|---|--:|--:|--:|--:|")
    for k in ["default"] + [f"softcap_{a:g}" for a in SOFTCAP]:
        L.append(f"| {k} | " + " | ".join(fmt(means[c][k]) for c in
                                          ["odds", "adbench", "adbench_disjoint", "all"]) + " |")
    L.append("")
    L.append("## Selection: pick on one collection, report on the other\n")
    L.append("| picked on | held out | chosen | mean (pick) | mean (held out) | PyOD (held out) | "
             "default (held out) | rank held out | vs PyOD held out: mean diff [95% CI], W/L |")
    L.append("|---|---|---|--:|--:|--:|--:|--:|---|")
    for s in summ["selection"]:
        p = s["vs_pyod_held_out"]
        L.append(f"| {s['pick_on']} | {s['held_out']} | {s['chosen']} | {fmt(s['chosen_mean_pick'], 5)} | "
                 f"{fmt(s['chosen_mean_held_out'], 5)} | {fmt(s['pyod_mean_held_out'], 5)} | "
                 f"{fmt(s['default_mean_held_out'], 5)} | {s['held_out_rank_of_chosen']} of {len(cands)} | "
                 f"{p['mean_diff']:+.4f} [{p['ci95'][0]:+.4f}, {p['ci95'][1]:+.4f}], "
                 f"{p['wins']}/{p['losses']} |")
    L.append("")
    for s in summ["selection"]:
        L.append(f"- Top 5 on {s['pick_on']} (mean there / on {s['held_out']}): " + ", ".join(
            f"{k} {m1:.5f} / {m2:.5f}" for k, m1, m2 in s["top5_on_pick"]))
    L.append("")
    L.append("Default mode below the PyOD mode: " + ", ".join(
        f"{c}/{n} ({d:+.4f})" for c, n, d in summ["default_losses"]) + ".\n")
    for pair, ks in summ["beat_pyod_on_both"].items():
        L.append(f"- Candidates at or above PyOD's mean on both {pair}: "
                 f"{', '.join(ks) if ks else 'none'}.")
    L.append("")
    L.append("## Which data favour which binning (Spearman rho across sets, p in brackets)\n")
    corr = summ["descriptor_correlations"]
    L.append("| collection | AUC difference | " + " | ".join(d for d, _ in DESCRIPTORS) + " |")
    L.append("|---|---|" + "--:|" * len(DESCRIPTORS))
    for coll, by_gain in corr.items():
        for gname, by_desc in by_gain.items():
            L.append(f"| {coll} | {gname} | " + " | ".join(
                "n/a" if by_desc[d][0] is None or by_desc[d][1] is None
                else f"{by_desc[d][0]:+.2f} ({by_desc[d][1]:.2f})" for d, _ in DESCRIPTORS) + " |")
    L.append("")
    L.append("## Every candidate on every set\n")
    for coll in ["adbench", "odds"]:
        L.append(f"### {coll}\n")
        L.append("| set | PyOD | " + " | ".join(cands) + " |")
        L.append("|---|--:|" + "--:|" * len(cands))
        for r in recs:
            if r["collection"] == coll:
                L.append(f"| {r['name']} | {fmt(r['auc'].get('pyod'), 3)} | " +
                         " | ".join(fmt(r["auc"].get(k), 3) for k in cands) + " |")
        L.append("")
    L.append("## Data descriptors\n")
    L.append("All scale-invariant except the last two: PyOD's largest density per column (10 bins, "
             "in 1/feature-unit), compared with its alpha = 0.1.\n")
    L.append("| set | median distinct values | integer cols | cols <= 10 values | cols with mode > 90 % "
             "| median fullest of 5 bins | Sturges bins | cols with PyOD density < alpha "
             "| median PyOD peak density |")
    L.append("|---|--:|--:|--:|--:|--:|--:|--:|--:|")
    for r in recs:
        dsc = r["describe"]
        if "median_distinct_values" not in dsc:
            continue
        L.append(f"| {r['collection']}/{r['name']} | {dsc['median_distinct_values']:.0f} | "
                 f"{dsc['share_integer_columns']:.0%} | {dsc['share_columns_le10_values']:.0%} | "
                 f"{dsc['share_columns_mode_gt90pct']:.0%} | {dsc['median_fullest_of_5_bins']:.0%} | "
                 f"{r.get('sturges_bins', '')} | {dsc['columns_pyod_density_below_alpha']} of "
                 f"{r['d'] - dsc['constant_columns']} | {dsc['median_pyod_peak_density']:.3g} |")
    L.append("")
    return "\n".join(L) + "\n"


# ----------------------------------------------------------------------------- main

def odds_relation(X, y, Xo, yo):
    if Xo is None:
        return "ODDS file not loaded"
    if X.shape == Xo.shape and np.array_equal(X, Xo) and np.array_equal(y, yo):
        return "identical X and y"
    if X.shape[0] == Xo.shape[0] and np.array_equal(y, yo):
        return "same rows and labels, columns transformed or dropped"
    if X.shape[0] == Xo.shape[0]:
        return "same size, different labels or row order"
    return "different rows"


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--adbench-dir", default=DEFAULT_ADBENCH)
    ap.add_argument("--odds-dir", default=DEFAULT_ODDS)
    ap.add_argument("--json", metavar="OUT", required=True)
    ap.add_argument("--markdown", metavar="OUT", required=True)
    ap.add_argument("--verify-pyod", action="store_true",
                    help="also run the real PyOD 3.6.5 and check bit-identical decision_scores_")
    ap.add_argument("--pyod-dir", default=DEFAULT_PYOD)
    args = ap.parse_args(argv)

    start = time.perf_counter()
    _check_mt19937_64()
    import hbos

    verify_cls = None
    if args.verify_pyod:
        sys.path.insert(0, os.path.abspath(args.pyod_dir))
        from pyod.models.hbos import HBOS as PyodHBOS
        verify_cls = PyodHBOS

    candidate_keys = [candidate_key(b, s) for b in BINS for s in SHIFTS]
    records = []
    odds_cache = {}
    sets = list_sets(args.adbench_dir, args.odds_dir)
    for i, (collection, name, path) in enumerate(sets):
        t0 = time.perf_counter()
        if collection == "adbench":
            Xraw, yraw = load_adbench(path)
        else:
            Xraw, yraw = load_odds(path)
        X = np.ascontiguousarray(Xraw, dtype=np.float64)
        y = np.asarray(yraw).astype(np.int64).ravel()
        if not set(np.unique(y)) <= {0, 1}:
            raise ValueError(f"{name}: labels are not 0/1")
        rec = {"collection": collection, "name": name, "n": int(X.shape[0]), "d": int(X.shape[1]),
               "dtype": str(Xraw.dtype), "outliers": int(y.sum()),
               "outlier_share": float(y.mean()), "describe": describe(X)}
        rec.update(score_set(hbos, name, X, y, verify_cls))
        c = rec["describe"].get("constant_columns", 0)
        if c and "default" in rec["auc"]:
            keep = np.ptp(X, axis=0) > 0
            rec["default_auc_without_constant_columns"] = roc_auc(
                hbos.HBOS().fit(X[:, keep]).decision_scores_, y)
            rec["pyod_auc_without_constant_columns"] = roc_auc(
                hbos.HBOS(mode="pyod").fit(X[:, keep]).decision_scores_, y)
            rec["constant_columns_auc_change"] = {
                "default": rec["default_auc_without_constant_columns"] - rec["auc"]["default"],
                "pyod": rec["pyod_auc_without_constant_columns"] - rec["auc"].get("pyod", float("nan"))}
        if collection == "adbench" and name in SAME_SOURCE_AS_ODDS:
            oname = SAME_SOURCE_AS_ODDS[name]
            if oname not in odds_cache:
                opath = os.path.join(args.odds_dir, oname + ".csv")
                odds_cache[oname] = load_odds(opath) if os.path.exists(opath) else (None, None)
            Xo, yo = odds_cache[oname]
            rec["odds_relation"] = odds_relation(X, y, Xo, None if yo is None else yo.astype(np.int64))
        records.append(rec)
        a = rec["auc"]
        log(f"[{i + 1:2d}/{len(sets)}] {collection:7s} {name:20s} {rec['n']:7d} x {rec['d']:<5d} "
            f"pyod {fmt(a.get('pyod'))} default {fmt(a.get('default'))} "
            f"scale-ok {all(rec['scale_test'].values()) if rec['scale_test'] else 'n/a'} "
            f"{'ERRORS ' + str(rec['errors']) if rec['errors'] else ''}"
            f"({time.perf_counter() - t0:.1f} s)")

    summary = summarise(records, candidate_keys)
    wall = time.perf_counter() - start
    import scipy
    import sklearn
    result = {
        "meta": {
            "command": " ".join([os.path.basename(sys.executable)] + sys.argv),
            "wall_seconds": wall,
            "machine": f"{platform.machine()}, {os.cpu_count()} CPUs, Python {platform.python_version()}",
            "numpy": np.__version__, "scipy": scipy.__version__, "sklearn": sklearn.__version__,
            "hbos_module": os.path.dirname(hbos.__file__),
            "pythonpath": os.environ.get("PYTHONPATH", ""),
            "verify_pyod": bool(args.verify_pyod),
            "seed": SEED,
            "protocol": "fit on all rows, score the same rows, no scaling; ROC-AUC Mann-Whitney "
                        "with average ranks; scale test: per-feature 2^k, k in -9..9 from "
                        "mt19937_64(1985 + FNV-1a(name)), scores must be bit-identical",
            "max_abs_diff_vs_sklearn_auc": max(r.get("sklearn_auc_diff", 0.0) for r in records),
        },
        "candidates": candidate_keys,
        "sets": records,
        "summary": summary,
    }
    atomic_write(args.json, json.dumps(result, indent=1) + "\n")
    atomic_write(args.markdown, markdown(result))
    means = summary["means"]
    for c in ["odds", "adbench", "adbench_disjoint"]:
        log(f"mean {c:17s} pyod {fmt(means[c]['pyod'])} default {fmt(means[c]['default'])}")
    log(f"done in {wall:.1f} s")


if __name__ == "__main__":
    main()
