#!/usr/bin/python3
"""The best multiple-scattering table any Psi(r, mu_s) could be, for the
report's sky-view comparison (docs/decisions/converged-psi-ms.md). Research script, not part of the build or the
tests.

Run (from the repository, after building the target psi_oracle_dump):

    build/bench/psi_oracle_dump presets/mars.json /tmp/mars_32x32.json 32x32 16384 2
    /usr/bin/python3 bench/psi_oracle.py /tmp/mars_32x32.json
    # a finer table, the references taken from the first dump (same seeds):
    build/bench/psi_oracle_dump presets/mars.json /tmp/mars_64x64.json 64x64 16384 0
    /usr/bin/python3 bench/psi_oracle.py /tmp/mars_64x64.json --refs /tmp/mars_32x32.json
    # fitted tables judged on views they were not fitted to:
    build/bench/psi_oracle_dump presets/mars.json /tmp/mars_heldout.json 32x32 16384 1 heldout
    /usr/bin/python3 bench/psi_oracle.py /tmp/mars_32x32.json --heldout /tmp/mars_heldout.json
    # fitted to more views (--also, stacked into every fit), judged on others:
    build/bench/psi_oracle_dump presets/mars.json /tmp/mars_heldout2.json 32x32 16384 1 heldout2
    /usr/bin/python3 bench/psi_oracle.py /tmp/mars_32x32.json --also /tmp/mars_heldout.json \
        --heldout /tmp/mars_heldout2.json

Needs numpy and scipy (Debian: apt-get install python3-scipy). The report's
views render as L = s + A x per channel (report/psi_weights.hpp: s the single
scattering, A the views x texels weights, x the table), so per channel, with
b the path tracer's radiance and x held in a box [lo, hi]:

- least squares: min over the box of the report's relative RMSE
  sqrt(mean(((A x + s - b) / b)^2)) (bounded linear least squares); the
  report's own metric, so its optimum bounds every table in the box;
- minimax: min e subject to |A x + s - b| <= e b (an LP, HiGHS);
- the reference's noise: each fit is made against seed set 0 and judged
  against set 1 too (the fit cannot follow set 1's noise); the report's
  denoising sqrt(rmse^2 - noise^2) is applied to both;
- with --heldout, every fitted table is also judged on other views
  (elevations 10, 35, 50 degrees, azimuths between the report's): a table
  that only fits the report's 72 numbers fails there.

Boxes: x >= 0 (any table); the range of the true source over directions at
each texel, [min_v j, max_v j] (any estimator that is a mean of the source
with weights >= 0); the converged relative table times [1/k, k].

A dump of the form by view (psi_oracle_dump's 7th argument `view`;
docs/reference.md "Psi_ms by view") holds the weights of every texel of
the volume a(nu) + b(mu_v); its boxes are the converged table by view times
[1/k, k] (each texel between v / k and v k, whatever its sign), and no box
at all (a fit of the 72 numbers, judged by the held-out views). Its
isotropic row is the relative table read the by-view way (a its value, b 0).

    build/bench/psi_oracle_dump presets/mars.json /tmp/mars_view.json 16x16 16384 2 - view
    build/bench/psi_oracle_dump presets/mars.json /tmp/mars_view_h.json 16x16 16384 1 heldout view
    /usr/bin/python3 bench/psi_oracle.py /tmp/mars_view.json --heldout /tmp/mars_view_h.json
    # (dumps made with 0 seed sets take their references from another dump of
    # the same views: --refs for the report's views, --heldout-refs for the
    # held-out ones)
"""
import json
import sys

import numpy as np
from scipy.optimize import linprog, lsq_linear


def load(path, refs_path=None):
    d = json.load(open(path))
    A = np.transpose(np.array(d["weights"]), (1, 0, 2))  # [channel][view][texel]
    s = np.array(d["single"])  # [channel][view]
    r = json.load(open(refs_path)) if refs_path else d
    refs = [(np.array(x["mean"]), np.array(x["ci95"]) / 1.96) for x in r["references"]]
    return d, A, s, refs


def stats(L, b, se):
    """The report's statistics of one channel (report/sky_radiance.cpp)."""
    rel = (L - b) / b
    rmse = np.sqrt(np.mean(rel ** 2))
    noise = np.sqrt(np.mean((se / b) ** 2))
    return np.sqrt(max(rmse ** 2 - noise ** 2, 0.0)), np.mean(rel), np.max(np.abs(rel))


def least_squares(A, s, b, lo, hi):
    D = 1.0 / b
    fixed = hi <= lo  # a degenerate box: the value is given
    x = lo.copy()
    free = ~fixed
    rhs = (b - s - A[:, fixed] @ lo[fixed]) * D
    res = lsq_linear(A[:, free] * D[:, None], rhs, bounds=(lo[free], hi[free]),
                     method="bvls", tol=1e-12, max_iter=20000)
    assert res.status > 0, res.message
    x[free] = res.x
    return x


def minimax(A, s, b, lo, hi):
    """min e s.t. |A x + s - b| <= e b, lo <= x <= hi."""
    n, k = A.shape
    c = np.zeros(k + 1)
    c[-1] = 1.0
    A_ub = np.block([[A, -b[:, None]], [-A, -b[:, None]]])
    b_ub = np.concatenate([b - s, s - b])
    bounds = [(l, max(h, l)) for l, h in zip(lo, hi)] + [(0, None)]
    res = linprog(c, A_ub=A_ub, b_ub=b_ub, bounds=bounds, method="highs")
    assert res.success, res.message
    return res.x[:k]


HELDOUT = None  # (A, s, refs) of the held-out views, when given
ALSO = []  # (A, s, refs) of more views every fit is made to (their set 0)


def stacked(A, s, b, c):
    """The fit's rows: the views of channel c and those of ALSO."""
    return (np.vstack([A] + [a[c] for a, _, _ in ALSO]),
            np.concatenate([s] + [x[c] for _, x, _ in ALSO]),
            np.concatenate([b] + [r[0][0][c] for _, _, r in ALSO]))


def line(name, L, refs, c, x=None):
    """One table's statistics; x (its values) also judges it on the held-out views."""
    cells, out = [], []
    sets = [(L, b, se) for b, se in refs]
    if HELDOUT is not None and x is not None:
        A_h, s_h, refs_h = HELDOUT
        sets.append((s_h[c] + A_h[c] @ x, refs_h[0][0], refs_h[0][1]))
    for LL, b, se in sets:
        den, bias, mx = stats(LL, b[c], se[c])
        cells.append(f"{100*den:6.2f} {100*bias:+6.1f} {100*mx:6.1f}")
        out.append(den)
    print(f"  {name:34s} " + " | ".join(cells))
    return out


def where(d, x, conv, A, c):
    """The oracle against the converged table by altitude and sun cosine,
    weighted by each texel's share of the views' multiple part."""
    alt = np.array(d["texel_altitude_m"]) / 1e3
    mu = np.array(d["texel_mu_s"])
    used = (A[c] * conv[None, :]).sum(axis=0)
    used = used / used.sum()
    mus = [(-1, -0.1), (-0.1, 0.05), (0.05, 0.2), (0.2, 0.5), (0.5, 0.8), (0.8, 1.01)]
    print("    oracle / converged (share of the views' multiple part); mu_s "
          + " ".join(f"[{a:g},{b:g})" for a, b in mus))
    for a0, a1 in [(0, 2), (2, 5), (5, 10), (10, 20), (20, 40), (40, 1e9)]:
        row = []
        for m0, m1 in mus:
            sel = (alt >= a0) & (alt < a1) & (mu >= m0) & (mu < m1) & (used > 1e-4)
            if sel.any():
                w = used[sel]
                ratio = np.sum(w * x[sel]) / np.sum(w * conv[sel])
                row.append(f"{ratio:6.2f}({100*w.sum():3.0f}%)")
            else:
                row.append(f"{'-':>12s}")
        print(f"    alt {a0:>3g}-{a1 if a1 < 1e8 else 'top':<4} km " + " ".join(row))


def main(path, refs_path=None):
    d, A, s, refs = load(path, refs_path)
    w, h = d["table"]
    print(f"{path}: table {w}x{h}, {A.shape[1]} views x {A.shape[2]} texels, "
          f"{len(refs)} reference sets")
    for name, t in d["tables"].items():
        L = s + np.einsum("cvk,ck->cv", A, np.array(t["values"]))
        err = np.max(np.abs(L - np.array(t["rendered"])) / np.array(t["rendered"]))
        print(f"  weights x {name} vs the report's rendering of it: max rel diff {err:.1e}")
    if d.get("form") == "view":
        return main_view(d, A, s, refs)
    conv = np.array(d["tables"]["converged_relative"]["values"])
    jmin, jmax = np.array(d["texel_source_min"]), np.array(d["texel_source_max"])
    inside = np.mean((conv >= jmin * (1 - 1e-6)) & (conv <= jmax * (1 + 1e-6)))
    print(f"  converged relative table inside [min_v j, max_v j]: {100*inside:.1f} % of texels")
    worst = {}
    for c, ch in enumerate("RGB"):
        print(f"channel {ch}: denoised rel RMSE, bias, max rel (%) against set 0 | set 1"
              + (" | held-out views" if HELDOUT else "") + "; fits against set 0")
        for name in ["hillaire", "converged_mean", "converged_relative"]:
            worst.setdefault(name, []).append(
                line(name, np.array(d["tables"][name]["rendered"])[c], refs, c,
                     np.array(d["tables"][name]["values"])[c]))
        b0 = refs[0][0][c]
        boxes = [("x >= 0", np.zeros_like(conv[c]), np.full_like(conv[c], np.inf)),
                 ("[min_v j, max_v j]", jmin[c], jmax[c])]
        boxes += [(f"converged x [1/{k:g}, {k:g}]", conv[c] / k, conv[c] * k)
                  for k in (1.25, 1.5, 2, 3, 5, 10)]
        for bname, lo, hi in boxes:
            x = least_squares(*stacked(A[c], s[c], b0, c), lo, hi)
            worst.setdefault("LS " + bname, []).append(line("LS " + bname, s[c] + A[c] @ x, refs, c, x))
            if bname == "x >= 0":
                x_any = x
            if bname == "[min_v j, max_v j]":
                x_env = x
            if np.all(np.isfinite(hi)) or bname == "x >= 0":
                xm = minimax(*stacked(A[c], s[c], b0, c), lo, np.where(np.isfinite(hi), hi, 1e30))
                worst.setdefault("minimax " + bname, []).append(
                    line("minimax " + bname, s[c] + A[c] @ xm, refs, c, xm))
        print("  LS x >= 0:")
        where(d, x_any[:], conv[c], A, c)
        print("  LS [min_v j, max_v j]:")
        where(d, x_env, conv[c], A, c)
    print("worst channel, denoised rel RMSE (%) against set 0 / set 1"
          + (" / held-out views" if HELDOUT else "") + ":")
    for name, v in worst.items():
        v = np.array(v)
        print(f"  {name:34s} " + " / ".join(f"{100*v[:, i].max():6.2f}" for i in range(v.shape[1])))


def main_view(d, A, s, refs):
    """The oracle for the form by view: boxes around the converged table by view."""
    view = np.array(d["tables"]["converged_view"]["values"])
    worst = {}
    for c, ch in enumerate("RGB"):
        print(f"channel {ch}: denoised rel RMSE, bias, max rel (%) against set 0 | set 1"
              + (" | held-out views" if HELDOUT else "") + "; fits against set 0")
        for name in ["converged_relative", "converged_view"]:
            worst.setdefault(name, []).append(
                line(name, np.array(d["tables"][name]["rendered"])[c], refs, c,
                     np.array(d["tables"][name]["values"])[c]))
        b0 = refs[0][0][c]
        v = view[c]
        boxes = [(f"view x [1/{k:g}, {k:g}]", np.minimum(v / k, v * k), np.maximum(v / k, v * k))
                 for k in (1.25, 1.5, 2, 3)]
        boxes.append(("no box", np.full_like(v, -np.inf), np.full_like(v, np.inf)))
        for bname, lo, hi in boxes:
            if bname == "no box":  # more texels than views: the least-norm fit
                A_f, s_f, b_f = stacked(A[c], s[c], b0, c)
                x = np.linalg.lstsq(A_f / b_f[:, None], (b_f - s_f) / b_f, rcond=None)[0]
            else:
                x = least_squares(*stacked(A[c], s[c], b0, c), lo, hi)
            worst.setdefault("LS " + bname, []).append(line("LS " + bname, s[c] + A[c] @ x, refs, c, x))
    print("worst channel, denoised rel RMSE (%) against set 0 / set 1"
          + (" / held-out views" if HELDOUT else "") + ":")
    for name, v in worst.items():
        v = np.array(v)
        print(f"  {name:34s} " + " / ".join(f"{100*v[:, i].max():6.2f}" for i in range(v.shape[1])))


if __name__ == "__main__":
    args = sys.argv[1:]
    refs_path = heldout = None
    if "--refs" in args:
        i = args.index("--refs")
        refs_path = args.pop(i + 1)
        args.pop(i)
    while "--also" in args:
        i = args.index("--also")
        _, A_a, s_a, refs_a = load(args.pop(i + 1))
        args.pop(i)
        ALSO.append((A_a, s_a, refs_a))
    heldout_refs = None  # the held-out views' references from another dump of them
    if "--heldout-refs" in args:
        i = args.index("--heldout-refs")
        heldout_refs = args.pop(i + 1)
        args.pop(i)
    if "--heldout" in args:
        i = args.index("--heldout")
        heldout = args.pop(i + 1)
        args.pop(i)
    if heldout:
        _, A_h, s_h, refs_h = load(heldout, heldout_refs)
        HELDOUT = (A_h, s_h, refs_h)
    main(args[0], refs_path)
