#!/usr/bin/env python3
"""How far can any predictor of the IK-target depth get from what walking-in-place sees?

Issue 13's depth goal (r >= 0.9, RMS <= 8 cm, cross-validated by subject) is scored on
the 57 shared walks. This script asks whether a different model of the same inputs
could reach it: predictors far more flexible than the learned table, several of them
given the *future* as well (not possible live), each scored twice:

- leave one **subject** out (the goal's protocol: never learned and scored on the same
  subject), and
- leave one **trial** out (the held-out subject's other walks may be learned from).

Inputs per foot and frame (30 Hz, wip::Info from `depth_dump`): both ankles' heights
over a window (own foot first), divided by the leg length, and the head's turning
rate (`turn`, rad/s, clamped to pi). Target: the foot's true depth / leg length.
Scored like `wip eval`: frames after 0.5 s, both feet pooled, metres back.

    build/scripts/wip-depth-analysis/depth_dump ../shared/data/cmu/bvh/walking > /tmp/wipdepth-dump.csv
    build/scripts/wip-depth-analysis/depth_lab /tmp/wipdepth-dump.csv > /dev/null   # the shipped table's predictions
    python3 scripts/wip-depth-analysis/depth_bound.py /tmp/wipdepth-dump.csv --shipped /tmp/wipdepth-pred.csv --json /tmp/depth-bound.json

numpy only. About a minute on this 2-core machine, `--mlp` included.
"""
import argparse
import csv
import json
import sys
import time

import numpy as np

p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
p.add_argument("dump", help="per-frame CSV written by depth_dump")
p.add_argument("--shipped", help="depth_lab's cross-validated predictions (/tmp/wipdepth-pred.csv): adds the shipped table's row and its average with the causal kNN")
p.add_argument("--json", help="write the table here")
p.add_argument("--mlp", action="store_true", help="also a 64x64 ReLU network (numpy, Adam, 15 epochs), leave one subject out")
a = p.parse_args()

need = ["trial", "subject", "leg", "t", "hL", "hR", "zL", "zR", "turn"]
try:
    rows = list(csv.DictReader(open(a.dump)))
except OSError as e:
    sys.exit(f"depth_bound: cannot read {a.dump}: {e.strerror}")
if not rows or any(k not in rows[0] for k in need):
    sys.exit(f"depth_bound: {a.dump}: not a depth_dump CSV (needs the columns {', '.join(need)})")


def finite(text):
    """The number a CSV field holds, or NaN when it holds none (or an empty field)."""
    try:
        return float(text)
    except (TypeError, ValueError):
        return float("nan")


def number(i, k):
    """Field k of the dump's data row i (line i + 2 of the file), or a message naming both."""
    x = finite(rows[i][k])
    if not np.isfinite(x):
        sys.exit(f"depth_bound: {a.dump} line {i + 2}: field '{k}' is '{rows[i][k]}', not a finite number")
    return x


rows_by_trial = {}  # trial -> the dump's row numbers (depth_lab's lines), in the dump's order
for i, r in enumerate(rows):
    rows_by_trial.setdefault(r["trial"], []).append(i)
trials = sorted(rows_by_trial)
D = {}
for tr in trials:
    rows_of = rows_by_trial[tr]
    col = lambda k: np.array([number(i, k) for i in rows_of])
    D[tr] = dict(subject=rows[rows_of[0]]["subject"], leg=number(rows_of[0], "leg"), t=col("t"),
                 h=np.stack([col("hL"), col("hR")]), z=np.stack([col("zL"), col("zR")]), turn=col("turn"), rows=rows_of)
subjects = sorted(set(d["subject"] for d in D.values()))
if len(subjects) < 2:
    sys.exit(f"depth_bound: {a.dump} holds walks of {len(subjects)} subject; leaving one subject out needs at least 2")
if any(d["leg"] <= 0 for d in D.values()):
    sys.exit(f"depth_bound: {a.dump}: a leg length is not positive (field 'leg')")

HALF, STEP, TURN_WEIGHT = 15, 3, 0.1  # +-0.5 s every 0.1 s; the turn rate weighted like a 10 % leg-length height


def features(d, causal):
    offsets = np.arange(-HALF, 1 if causal else HALF + 1, STEP)
    h = d["h"] / d["leg"]
    n = h.shape[1]
    idx = np.clip(np.arange(n)[:, None] + offsets[None, :], 0, n - 1)
    turn = np.minimum(np.abs(d["turn"]), np.pi)[:, None] * TURN_WEIGHT
    X = np.vstack([np.hstack([h[f][idx], h[1 - f][idx], turn]) for f in (0, 1)])
    Y = np.concatenate([d["z"][f] / d["leg"] for f in (0, 1)])
    keep = np.concatenate([d["t"] >= 0.5, d["t"] >= 0.5])
    return X, Y, keep


def folds(protocol):
    for tr in trials:
        if protocol == "subject":
            yield tr, [u for u in trials if D[u]["subject"] != D[tr]["subject"]]
        else:
            yield tr, [u for u in trials if u != tr]


def knn(F, protocol, k=20):
    out = {}
    for tr, train in folds(protocol):
        Xtr = np.vstack([F[u][0] for u in train])
        if len(Xtr) <= k:
            sys.exit(f"depth_bound: holding out {tr} leaves {len(Xtr)} samples to learn from; the kNN needs more than {k}")
        Ytr = np.concatenate([F[u][1] for u in train])
        Xte = F[tr][0]
        d2 = (Xte ** 2).sum(1)[:, None] - 2 * Xte @ Xtr.T + (Xtr ** 2).sum(1)[None, :]
        out[tr] = Ytr[np.argpartition(d2, k, axis=1)[:, :k]].mean(1)
    return out


def ridge(F, protocol, lam=1e-3):
    quad = lambda X: np.hstack([X, X ** 2, np.ones((len(X), 1))])
    out = {}
    for tr, train in folds(protocol):
        A = quad(np.vstack([F[u][0] for u in train]))
        y = np.concatenate([F[u][1] for u in train])
        w = np.linalg.solve(A.T @ A + lam * len(A) * np.eye(A.shape[1]), A.T @ y)
        out[tr] = quad(F[tr][0]) @ w
    return out


def mlp(F, hidden=64, epochs=15, lr=1e-3):
    out = {}
    for s in subjects:
        test = [t for t in trials if D[t]["subject"] == s]
        train = [t for t in trials if D[t]["subject"] != s]
        X = np.vstack([F[u][0] for u in train])
        Y = np.concatenate([F[u][1] for u in train])
        rng = np.random.default_rng(0)
        mu, sd = X.mean(0), X.std(0) + 1e-6
        X = (X - mu) / sd
        P = [rng.normal(0, 1 / np.sqrt(X.shape[1]), (X.shape[1], hidden)), np.zeros(hidden),
             rng.normal(0, 1 / np.sqrt(hidden), (hidden, hidden)), np.zeros(hidden),
             rng.normal(0, 1 / np.sqrt(hidden), hidden), np.zeros(())]
        M = [np.zeros_like(q) for q in P]
        V = [np.zeros_like(q) for q in P]
        step = 0
        for _ in range(epochs):
            order = rng.permutation(len(X))
            for i in range(0, len(X), 256):
                b = order[i:i + 256]
                x, y = X[b], Y[b]
                a1 = np.maximum(x @ P[0] + P[1], 0)
                a2 = np.maximum(a1 @ P[2] + P[3], 0)
                g = 2 * (a2 @ P[4] + P[5] - y) / len(b)
                d2 = np.outer(g, P[4]) * (a2 > 0)
                d1 = (d2 @ P[2].T) * (a1 > 0)
                grads = [x.T @ d1, d1.sum(0), a1.T @ d2, d2.sum(0), a2.T @ g, np.array(g.sum())]
                step += 1
                for j, gr in enumerate(grads):
                    M[j] = 0.9 * M[j] + 0.1 * gr
                    V[j] = 0.999 * V[j] + 0.001 * gr * gr
                    P[j] = P[j] - lr * (M[j] / (1 - 0.9 ** step)) / (np.sqrt(V[j] / (1 - 0.999 ** step)) + 1e-8)
        for t in test:
            Z = (F[t][0] - mu) / sd
            a2 = np.maximum(np.maximum(Z @ P[0] + P[1], 0) @ P[2] + P[3], 0)
            out[t] = a2 @ P[4] + P[5]
    return out


def score(pred, F, subject=None):
    """pred: trial -> normalised depth over both feet (len 2n). Pooled r and RMS (cm) over t >= 0.5 s."""
    P, T = [], []
    for tr in trials:
        if subject is not None and D[tr]["subject"] != subject:
            continue
        _, Y, keep = F[tr]
        P.append(pred[tr][keep] * D[tr]["leg"])
        T.append(Y[keep] * D[tr]["leg"])
    P, T = np.concatenate(P), np.concatenate(T)
    return float(np.corrcoef(P, T)[0, 1]), float(np.sqrt(np.mean((P - T) ** 2)) * 100), len(P)


F = {False: {tr: features(D[tr], False) for tr in trials}, True: {tr: features(D[tr], True) for tr in trials}}
results = []


def add(name, live, protocol, pred, feats):
    r, rms, n = score(pred, feats)
    per = {s: dict(zip(("r", "rms_cm", "samples"), score(pred, feats, s))) for s in subjects}
    results.append(dict(predictor=name, live=live, protocol=protocol, r=r, rms_cm=rms, samples=n, per_subject=per))
    print(f"{name:58s} {'yes' if live else 'no ':3s}  {protocol:7s}  r {r:.3f}  RMS {rms:5.2f} cm   " +
          " ".join(f"{s}:{per[s]['r']:.2f}/{per[s]['rms_cm']:.1f}" for s in subjects), flush=True)


if a.shipped:
    try:
        lines = open(a.shipped).read().splitlines()
    except OSError as e:
        sys.exit(f"depth_bound: cannot read {a.shipped}: {e.strerror}")
    if len(lines) != len(rows):
        sys.exit(f"depth_bound: {a.shipped}: {len(lines)} lines, the dump has {len(rows)} frames (depth_lab writes one line of 2 feet a frame)")
    shipped_rows = np.zeros((len(rows), 2))
    for i, line in enumerate(lines):
        fields = line.split(",")
        shipped_rows[i] = [finite(x) for x in fields] if len(fields) == 2 else np.nan
        if not np.isfinite(shipped_rows[i]).all():
            sys.exit(f"depth_bound: {a.shipped} line {i + 1}: '{line[:60]}' is not two finite numbers (depth_lab's left,right depths)")
    shipped = {tr: np.concatenate([shipped_rows[d["rows"], f] / d["leg"] for f in (0, 1)]) for tr, d in D.items()}
print(f"{len(trials)} trials, {len(subjects)} subjects; columns: predictor, realisable live, held out, pooled, per subject r/RMS cm")
t0 = time.time()
if a.shipped:
    add("shipped learned table + turning gain (depth_lab)", True, "subject", shipped, F[True])
for protocol in ("subject", "trial"):
    causal = knn(F[True], protocol)
    add("kNN k=20, both ankles' past 0.5 s + turn rate", True, protocol, causal, F[True])
    if a.shipped and protocol == "subject":
        add("mean of the shipped table and that kNN", True, protocol, {t: (shipped[t] + causal[t]) / 2 for t in trials}, F[True])
    add("kNN k=20, both ankles +-0.5 s (the future too) + turn rate", False, protocol, knn(F[False], protocol), F[False])
    add("quadratic ridge, both ankles +-0.5 s + turn rate", False, protocol, ridge(F[False], protocol), F[False])
    print(f"  ({time.time() - t0:.0f} s)", file=sys.stderr, flush=True)
if a.mlp:
    add("64x64 ReLU network, both ankles +-0.5 s + turn rate", False, "subject", mlp(F[False]), F[False])
if a.json:
    with open(a.json, "w") as f:
        json.dump(dict(goal=dict(r=0.9, rms_cm=8.0), window_s=HALF / 30, results=results), f, indent=1)
