#!/usr/bin/env python3
"""fit_curet.py: load measured BRDF data, fit reflectance models to one
material, print a table and -- when matplotlib is installed -- plot the
measured against the predicted normalised radiance (the paper's Figures
3-6).

    python3 python/examples/fit_curet.py ../shared/data/curet --material 5
    python3 python/examples/fit_curet.py DATA --models VH-E,FC-E,LFTG \\
        --on-params ../shared/reference/oren_nayar_params.tsv --plot fit.png
    python3 python/examples/fit_curet.py \\
        ../shared/data/cornell-pbrt-v2/acryl_blue.brdf --channel 550 \\
        --fit exact --models ON,FC-E,LFTG

DATA is anything brdffit.load reads (a CURET folder, .brdf, .astm, tidy
CSV). Run from the repository with PYTHONPATH=python, or after
`pip install ./python`. With --fit exact the parameters come with their
95% profile intervals and the table shows what the fit says about itself
(flags: reduces_to=LAMBERT, not_identified=rho, ...).
"""

import argparse
import sys

import brdffit


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("data", help="CURET folder or data file")
    ap.add_argument("--material", type=int, default=None,
                    help="material (CURET sample) number; default: the "
                    "first")
    ap.add_argument("--models", default="VH-G,VH-E,FC-G,FC-E,LFTG",
                    help="comma-separated model names (default %(default)s)")
    ap.add_argument("--channel", default="mean",
                    help="channel to fit (default: the mean over them)")
    ap.add_argument("--fit", choices=("paper", "exact"), default="paper",
                    help="the paper's grid, or the exact fit (default "
                    "%(default)s)")
    ap.add_argument("--on-params", default=None,
                    help="Oren-Nayar rho, sigma per sample (to fit ON too)")
    ap.add_argument("--plot", default="fit_curet.png",
                    help="figure file (default %(default)s)")
    ap.add_argument("--no-plot", action="store_true", help="no figure")
    args = ap.parse_args(argv)

    ds = brdffit.load(args.data)
    material = ds.material(args.material) if args.material else ds[0]
    models = args.models.split(",")
    if args.on_params and "ON" not in models:
        models.insert(0, "ON")
    results = [brdffit.fit(ds, m, material=material, channel=args.channel,
                           fit=args.fit, on_params=args.on_params)
               for m in models]

    print("%s: material %d (%s), channel %s, K = %d configurations, fit %s"
          % (args.data, material.number, material.name, args.channel,
             results[0].k, args.fit))
    print("%-8s %-44s %10s %10s %10s %10s  %s"
          % ("model", "parameters", "LSE", "AIC", "BIC", "CV", "flags"))
    for r in results:
        par = " ".join(
            "%s=%.4g%s%s" % (k, v, "*" if r.bound.get(k) else "",
                             "[%.3g,%.3g]" % r.intervals[k]
                             if args.fit == "exact" and k in r.free else "")
            for k, v in r.parameters.items())
        print("%-8s %-44s %10.6g %10.6g %10.6g %10.6g  %s"
              % (r.model.name, par, r.objective, r.aic, r.bic, r.cv,
                 r.flags or "-"))
    print("(* = optimum on a bound of its search range; [a,b] = 95%% profile"
          " interval; LSE = the objective %s)" % results[0].objective_name)

    if args.no_plot:
        return 0
    try:
        import matplotlib
        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
    except ImportError:
        print("matplotlib is not installed: no figure", file=sys.stderr)
        return 0
    fig, axes = plt.subplots(1, len(results), figsize=(3 * len(results), 3.2),
                             squeeze=False)
    for ax, r in zip(axes[0], results):
        ax.plot([0, 1], [0, 1], color="0.6", lw=0.8)
        ax.scatter(r.measured, r.predicted, s=6)
        ax.set(xlim=(0, 1), ylim=(0, 1), aspect="equal",
               xlabel="measured", title="%s  LSE %.3g" % (r.model.name,
                                                          r.objective))
    axes[0][0].set_ylabel("predicted")
    fig.suptitle("%d %s" % (material.number, material.name))
    fig.tight_layout()
    fig.savefig(args.plot, dpi=120)
    print("figure: %s" % args.plot)
    return 0


if __name__ == "__main__":
    sys.exit(main())
