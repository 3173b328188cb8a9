"""The isolator section of a cyclic report: the models of isolator.py fitted per load with their
errors and the recommended one, the designer's properties of design.py per amplitude, and the
property modification factors; for a stack, a friction slider in series with the bags' model.

Runs of the same load (F_v within 1 %) are fills of it (realizations): the first is the nominal
one, the others give the 'fills' factors. A half-speed run of a load (`slow`) gives the 'rate'
factors. Writes isolator.md, isolator_models.csv, design_properties.csv.
"""
from pathlib import Path

import numpy as np

from tbagspost import design, history, isolator, style

MODEL_KEYS = ("R-O, Masing", "R-O, Phillips-Hashash", "bilinear", "Bouc-Wen")


def same_load(a, b):
    """The same load (F_v within 1 %) on the same fabric."""
    return abs(a.fv_N - b.fv_N) <= 0.01 * max(abs(a.fv_N), 1e-9) and a.fabric == b.fabric


def match(pool, run):
    """pool[(fabric, F_v)] for the run's fabric and load (F_v within 1 %), or None."""
    for (fabric, fv), value in pool.items():
        if fabric == run.fabric and abs(fv - run.fv_N) <= 0.01 * max(abs(run.fv_N), 1e-9):
            return value
    return None


def title(run, several_fabrics):
    return "%s%s (%s)" % (run.label.replace("$", ""), ", fabric %s" % run.fabric if several_fabrics
                          else "", run.name)


def group_loads(runs):
    """[(nominal run, [other fills])] in the order of the runs."""
    groups = []
    for r in runs:
        for g in groups:
            if same_load(g[0], r):
                g[1].append(r)
                break
        else:
            groups.append((r, []))
    return groups


def fmt_params(fit):
    out = []
    for k, v in fit.model.params().items():
        sd = fit.sd.get(k)
        out.append("%s %.4g" % (k, v) + (" +- %.2g" % sd if sd is not None and np.isfinite(sd) else ""))
    return ", ".join(out)


def film_strength(run):
    """The film's sliding force (N) of a stack run: the largest |force on film 1 from the bag
    above| over the last cycle of its largest amplitude (the plateau while it slips)."""
    amp = max(a for a, _, _ in run.cycles())
    last = [rows for a, _, rows in run.cycles() if a == amp][-1]
    t = run.stack["t"]
    sel = np.isin(np.round(t, 9), np.round(last["time_s"], 9))
    return float(np.max(np.abs(run.stack["film1_Fabove"][sel])))


def film_stiffness(run, mu_N):
    """The film interface's stiffness before it slips (N/mm): from each amplitude's last cycle,
    the film's slip amplitude a and its loop's h_eq give D_y = a (1 - pi h / 2) (exact for an
    elastic-perfectly-plastic loop); mu_N over the median D_y of the loops that slip (h > 0.3)."""
    last = {}
    for t in run.split:
        last[t["amp"]] = t
    d = [t["film1_mm"] * (1 - np.pi * t["film1_h_eq"] / 2) for t in last.values() if t["film1_h_eq"] > 0.3]
    return mu_N / float(np.median(d)) if d and np.median(d) > 0 else float("inf")


def models_section(name, fits, best, why):
    lines = ["", "### %s" % name, "",
             "| model | parameters (+- 1 sd; mm, N) | rms of S along the loops (of S_a) | worst K_eq error |"
             " worst h_eq error |", "|---|---|---|---|---|"]
    for f in fits:
        lines.append("| %s%s | %s | %.1f %% | %.1f %% | %.3f |" % (
            f.name, " (recommended)" if f is best else "", fmt_params(f), 100 * f.rms_S,
            100 * f.worst_K, f.worst_h))
    lines += ["", "Recommended: " + why + ".", "",
              "| u_a (mm) | K_eq DEM (N/mm) | " + " | ".join("K_eq %s" % f.name for f in fits) +
              " | h_eq DEM | " + " | ".join("h_eq %s" % f.name for f in fits) + " |",
              "|---" * (3 + 2 * len(fits)) + "|"]
    for k in range(len(fits[0].K_eq)):
        lines.append("| %.3g | %.1f | %s | %.3f | %s |" % (
            fits[0].u_a[k], fits[0].K_eq[k][0], " | ".join("%.1f" % f.K_eq[k][1] for f in fits),
            fits[0].h_eq[k][0], " | ".join("%.3f" % f.h_eq[k][1] for f in fits)))
    return lines


def write(runs, out, slow=None, histories=None, formats=("png",), dpi=None):
    """The section for cyclic.CyclicRun / stack.StackRun runs; slow: {F_v-matching run} runs at
    half speed; histories: history.HistoryRun runs, compared with the models of their load.
    Returns (written paths, Markdown text)."""
    from tbagspost import stack as stackmod

    out = Path(out)
    slow = list(slow or [])
    singles = [r for r in runs if not isinstance(r, stackmod.StackRun)]
    stacks = [r for r in runs if isinstance(r, stackmod.StackRun)]
    several = len({r.fabric for r in runs}) > 1
    text = ["", "## Isolator models and design properties", "",
            "Models (tbagspost/isolator.py): R-O with Masing's rules (the fit above); R-O with "
            "Phillips and Hashash's (2009) damping reduction F(u_m) = p1 - p2 (1 - K_sec/K_0)^p3 "
            "(backbone through the tips, F fitted to h_eq); a bilinear isolator (K_u, Q_d, K_d; "
            "D_y = Q_d/(K_u - K_d)) and Bouc-Wen (K, a, D_y, n, b), both by least squares on S. "
            "Each is run through the same displacement history as the DEM (per amplitude the cycle "
            "before the last, then the last, which is compared). Recommended: within 10 % on K_eq "
            "and 0.03 on h_eq at every amplitude with the smallest rms error of S, else the smallest "
            "rms error."]
    model_rows, prop_rows, bag_models, fits_of, stack_models, tables = [], [], {}, {}, {}, {}
    for run, fills in group_loads(singles):
        lanes = isolator.lanes_of(run.cycles())
        fits = isolator.fit_all(lanes)
        best, why = isolator.recommend(fits)
        bag_models[(run.fabric, run.fv_N)] = best.model
        fits_of[(run.fabric, run.fv_N)] = fits
        text += models_section(title(run, several), fits, best, why)
        if len(lanes.u) < 3:
            text += ["", "R-O, Phillips-Hashash: not fitted (its 3 backbone and 3 reduction "
                     "parameters need 3 amplitudes or more; this run has %d)." % len(lanes.u)]
        for f in fits:
            row = dict(run=run.name, Fv_N=run.fv_N, fabric=run.fabric, model=f.name,
                       recommended=f is best,
                       rms_S=f.rms_S, worst_K_rel=f.worst_K, worst_h_abs=f.worst_h)
            row.update({k: float(v) for k, v in f.model.params().items()})
            row.update({"%s_sd" % k: float(v) for k, v in f.sd.items()})
            model_rows.append(row)
        table = design.run_table(run)
        s = next((r for r in slow if same_load(r, run)), None)
        lam = design.lambdas(table, design.run_table(s) if s else None,
                             [design.run_table(f) for f in fills])
        prop_rows += design.property_rows(run.name, run.fv_N, table, lam, run.fabric)
        text += properties_section(run, table, lam, s, fills)
        tables[(run.fabric, run.fv_N)] = table
    text += fabric_section(tables)
    for run in stacks:
        bag = match(bag_models, run)
        if bag is None:
            text += ["", "### %s" % title(run, several), "",
                     "No single bag at this load among the runs: the slider + bags model needs one "
                     "(give a single bag's cyclic run at this load beside the stack: ./tbags plot "
                     "BAG_RUN STACK_RUN)."]
            continue
        mu_N = film_strength(run)
        k_slip = film_stiffness(run, mu_N)
        lanes = isolator.lanes_of(run.cycles())
        stiff = isolator.Slider(bag=bag, mu_N=mu_N, bags=run.bags, k_slip=k_slip)
        candidates = [
            isolator.evaluate(stiff, lanes, label="elastic slider + bags"),
            isolator.evaluate(isolator.Slider(bag=bag, mu_N=mu_N, bags=run.bags), lanes,
                              label="rigid slider + bags"),
            isolator.evaluate(isolator.Slider(bag=bag, mu_N=np.inf, bags=run.bags), lanes,
                              label="%d bags, no slip" % run.bags)]
        text += ["", "### %s" % title(run, several), "",
                 "A friction slider of strength mu N = %.1f N (the film's largest force in the last "
                 "cycle at the largest amplitude) and elastic stiffness k_slip = %.0f N/mm before it "
                 "slips (from the film interface's own loops: an elastic-perfectly-plastic loop of "
                 "slip amplitude a has h = (2/pi)(1 - D_y/a), D_y = mu N / k_slip; the median D_y over "
                 "the amplitudes, %.3f mm), in series with %d bags of the single bag's recommended "
                 "model (%s) at the same load; nothing fitted to the stack's S." % (
                     mu_N, k_slip, mu_N / k_slip, run.bags, bag.name)]
        stack_models[(run.fabric, run.fv_N)] = [(f.name, f.model) for f in candidates]
        best, why = isolator.recommend(candidates)
        text += [""] + models_section("stack model", candidates, best, why)[3:]
        for f in candidates:
            model_rows.append(dict(run=run.name, Fv_N=run.fv_N, fabric=run.fabric,
                                   model="%s (%s)" % (f.name, bag.name), recommended=f is best,
                                   rms_S=f.rms_S, worst_K_rel=f.worst_K, worst_h_abs=f.worst_h,
                                   mu_N=f.model.mu_N, k_slip=f.model.k_slip))
        table = design.run_table(run)
        lam = design.lambdas(table)
        prop_rows += design.property_rows(run.name, run.fv_N, table, lam, run.fabric)
        text += properties_section(run, table, lam, None, [])
    written, check_rows = [], []
    histories = list(histories or [])
    fig_names = history.figure_names([h.path for h in histories])
    for h, fig_name in zip(histories, fig_names):
        pool = stack_models if h.stack else {key: [(f.name, f.model) for f in fits]
                                              for key, fits in fits_of.items()}
        models = match(pool, h)
        what = ("a stack" if h.stack else "one bag") + (", fabric %s" % h.fabric if several else "")
        if models is None:
            text += ["", "### History %s (F_v = %.0f N, fabric %s)" % (h.name, h.fv_N, h.fabric), "",
                     "No %s cyclic run of this fabric at this load among the runs: its models are "
                     "fitted there "
                     "(give one beside the history: ./tbags plot CYCLIC_RUN ... --history %s)." % (
                         "stack and single-bag" if h.stack else "single-bag", h.path)]
            continue
        rows = history.compare(h, models)
        check_rows += rows
        text += history.section(h, rows, what)
        written += style.save(history.figure(h, rows), out / ("history-%s" % fig_name), formats, dpi)
    if check_rows:
        history.write_csv(out / "history_check.csv", check_rows)
        written.append(out / "history_check.csv")
    if model_rows:
        design.write_csv(out / "isolator_models.csv", model_rows)
        written.append(out / "isolator_models.csv")
    if prop_rows:
        design.write_csv(out / "design_properties.csv", prop_rows)
        written.append(out / "design_properties.csv")
    md = "\n".join(text) + "\n"
    (out / "isolator.md").write_text("# Isolator models and design properties\n" + md.split("\n", 3)[3])
    written.append(out / "isolator.md")
    return written, md


def properties_section(run, table, lam, slow, fills):
    lines = ["", "Design properties of %s (last cycle of each amplitude; ASCE 7-22 ch. 17 and AASHTO "
             "definitions in tbagspost/design.py):" % run.label.replace("$", ""), "",
             "| D (mm) | k_eff (N/mm) | beta_eff | Q_d (N) | K_d (N/mm) | D_y (mm) | K_u (N/mm) | "
             "k_eff/K_eq - 1 | beta_eff - h_eq |", "|---|---|---|---|---|---|---|---|---|"]
    for amp in sorted(lam):
        p = table[(amp, max(c for a, c in table if a == amp))]
        lines.append("| %.3g | %.1f | %.3f | %.1f | %.1f | %.3f | %.1f | %+.1e | %+.1e |" % (
            p.D, p.k_eff, p.beta_eff, p.Q_d, p.K_d, p.D_y, p.K_u, p.k_eff / p.K_eq - 1,
            p.beta_eff - p.h_eq))
    env = design.envelope(lam)
    sources = [s for s in ("cycles", "rate", "fills", "combined") if any(s in v for v in env.values())]
    missing = [s for s, have in (("rate", slow is not None), ("fills", bool(fills))) if not have]
    lines += ["", "Property modification factors (lambda_min - lambda_max over all amplitudes):", "",
              "| property | " + " | ".join(sources) + " |", "|---" * (1 + len(sources)) + "|"]
    for p in design.PROPS:
        if p in env:
            lines.append("| %s | %s |" % (p, " | ".join(
                "%.2f - %.2f" % env[p][s] if s in env[p] else "-" for s in sources)))
    if missing:
        lines += ["", "Not measured for this load: %s (%s)." % (", ".join(missing), "; ".join(
            {"rate": "a run at half the speed: tbagspost --slow RUN_DIR",
             "fills": "other fills of the same load among the runs"}[m] for m in missing))]
    return lines


def fabric_section(tables):
    """The fabric's effect beside the lambda factors: per load run on the solid bond and another
    fabric, each property of the other fabric over the solid bond's at the same amplitude (last
    cycles), min - max over the amplitudes."""
    lines = []
    for (fabric, fv), table in tables.items():
        base = next((t for (f, v), t in tables.items() if f == "solid" and abs(v - fv) <= 0.01 * fv), None)
        if fabric == "solid" or base is None:
            continue
        last = lambda t, a: t[(a, max(c for b, c in t if b == a))]  # noqa: E731
        amps = sorted({a for a, _ in table} & {a for a, _ in base})
        if not amps:
            continue
        lines += ["", "### The fabric's effect at F_v = %.0f N: %s over solid" % (fv, fabric), "",
                  "Each property of the %s fabric's last cycle over the solid bond's at the same "
                  "amplitude (min - max over the amplitudes): the model's uncertainty about the bag "
                  "(the fabric a real bag has lies between them or beyond), beside the lambda "
                  "factors above." % fabric, "", "| property | %s / solid |" % fabric, "|---|---|"]
        for p in design.PROPS:
            r = [getattr(last(table, a), p) / getattr(last(base, a), p) for a in amps]
            lines.append("| %s | %.2f - %.2f |" % (p, min(r), max(r)))
    return lines
