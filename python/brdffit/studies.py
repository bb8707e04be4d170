"""studies: the CLI's studies (`brdffit compare`, `brdffit rank`) from
Python, returning the rows of fits.csv and ranking.csv as records.

The study is the CLI's: the same library functions set it up
(bf_study_models, bf_study_variants, bf_study_rows_check). The records
are the library's structs, the lines its writers print: compare()'s
bf_fits_lines (bf_fits_csv_write), rank()'s bf_ranking_lines
(bf_ranking_csv_write). .text is the CLI's file, byte for byte.
"""

import warnings

from ._errors import InvalidArgumentError
from ._study import CRITERIA, Study

def _model_set(which):
    """The library's default model list (bf_model_set_names) as a tuple;
    which is the name of a bf_model_set value."""
    from ._lib import lib, text
    return tuple(text(lib.bf_model_set_names(getattr(lib, which)))
                 .split(","))


#: The models `brdffit compare` fits by default (the paper's six), from
#: the library (bf_model_set_names).
COMPARE_MODELS = _model_set("BF_MODELS_PAPER")
#: The models `brdffit rank` fits by default (with the Lambert baseline
#: and the two Wolff-Nayar-Oren models).
RANK_MODELS = _model_set("BF_MODELS_RANKING")


def _samples(dataset, samples, default):
    """samples, with None resolved as the CLI does: the paper's 24 samples
    on CURET data (default "paper"), every material otherwise."""
    if samples is None:
        curet = len(dataset) > 0 and all(m.format == "curet"
                                         for m in dataset)
        return default if curet else "all"
    return samples


def _run(kw, default_models, default_samples, context):
    """The Study of compare's or rank's arguments kw (their locals()),
    with the command's default models and samples; warns, as the CLI's
    note does, about models left out for lack of inputs."""
    kw = dict(kw)
    dataset = kw.pop("dataset")
    samples = _samples(dataset, kw.pop("samples"), default_samples)
    study = Study(dataset, samples, kw.pop("models"),
                  defaults=default_models, context=context, **kw)
    note = study.missing_note()
    if note:
        warnings.warn(note, UserWarning, stacklevel=3)
    return study


def compare(dataset, models=None, samples=None, channel="mean", fit="paper",
            objective="max", stats=False, bootstrap=0, folds=None,
            seed=None, level=None, n=None, n_file=None, on_params=None,
            exclude=(), max_theta=None, cone=None, ranges=None, threads=1,
            progress=None, fresnel=None, smith=None, intervals=True,
            neyman="auto"):
    """Fits every model to every sample, as `brdffit compare` does, and
    returns the rows of its fits.csv.

    Args:
        dataset: a Dataset.
        models: model names or Models, a comma-separated string, or "all"
            (every registry model); default the paper's six (VH-G, VH-E,
            FC-G, FC-E, ON, LFTG), as the CLI's.
        samples: "paper" (the study's 24 CURET samples), "all", or
            material numbers, names or Materials; default: "paper" on
            CURET data, "all" otherwise (the CLI's --samples).
        channel: "mean" (default), a channel name, "each" (one target
            per channel of each material) or "joint" (one shape for all
            channels, the scales per channel, SPEC §9.4: fit="exact",
            objective="ngan"; fits.csv's shape rows on channel "joint").
        fit, objective, stats, bootstrap, folds, seed, level, n, n_file,
        on_params, exclude, max_theta, cone, ranges, threads, progress,
        fresnel, smith, intervals, neyman: as in brdffit.fit (the CLI's
            --fit, --objective, --stats, --bootstrap, --folds, --seed, --n,
            --n-file, --on-params, --exclude, --max-theta and
            --exclude-specular in radians, --range, --threads, --fresnel,
            --smith, --intervals, --neyman; the records'
            ndf, masking and fresnel name the variant fitted). The analysis (the columns after k) runs
            with fit="exact", stats=True, bootstrap or neyman=N; otherwise
            those columns are empty.
    Returns:
        Records: one dict per fits.csv row (sample, name, channel, model,
        parameter, unit, value, lse, bound_hit, k, objective, fit, ...;
        README "Output files") from the library's structs
        (bf_fits_lines: numbers at full precision, an empty field None),
        .columns, .text (the CSV as the library wrote it, %.10g),
        .to_dataframe() and .dispersion: the rows of dispersion.csv
        (Records; n against wavelength with its interval for fits with
        fresnel="dielectric" on spectral channels, bf_dispersion_points;
        empty otherwise). A model that lacks its inputs for a
        sample (ON without on_params) has no rows there, and a
        UserWarning says so, as the CLI's note does.
    Raises the errors of brdffit.fit (InvalidArgumentError, NotFoundError,
    DomainError, the loaders' errors).
    """
    study = _run(locals(), "BF_MODELS_PAPER", "paper", "compare")
    out = study.fits_records()
    out.dispersion = study.dispersion_records()
    return out


def rank(dataset, models=None, samples="all", channel="mean", fit="exact",
         objective="max", bootstrap=0, folds=None, seed=None, level=None,
         n=None, n_file=None, on_params=None, exclude=(), max_theta=None,
         cone=None, ranges=None, threads=1, progress=None, fresnel=None,
         smith=None, intervals=True, neyman="auto"):
    """Ranks models per sample by AIC, BIC and cross-validated error, as
    `brdffit rank` does, and returns the rows of its ranking.csv.

    Args: as brdffit.compare, with rank's defaults: every material
        (samples="all"), fit="exact", models VH-G, VH-E, FC-G, FC-E, ON,
        LFTG, LAMBERT, WNO, WNO-R. The analysis always runs.
    Returns:
        Records: one dict per (sample, model) with the columns of
        ranking.csv (sample, name, channel, model, objective, fit, k, n,
        objective_value, aic, bic, cv, rank_aic, rank_bic, rank_cv,
        best_aic, best_bic, best_cv, counts_as, flags, then pJ, pJ_value,
        pJ_ci_low, pJ_ci_high, pJ_ci_gap_low, pJ_ci_gap_high, pJ_boot_low,
        pJ_boot_high, pJ_ml per
        fitted parameter; README) from the library's structs (bf_ranking_lines:
        numbers at full precision, an empty field None), .columns, .text
        (the CSV as the library wrote it, %.10g), .to_dataframe(), and .wins:
        {criterion: [(model, wins), ...]} over the samples, most wins
        first (bf_study_wins; a fit that reduces to a smaller model wins
        for that model), for "AIC", "BIC" and "CV" (CV empty with
        folds=0).
    """
    study = _run(dict(locals(), stats=True), "BF_MODELS_RANKING", "all",
                 "rank")
    out = study.ranking_records()
    out.wins = {c: study.spec.wins(study.stats, c) for c in CRITERIA}
    return out
