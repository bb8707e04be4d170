/* calibration.c: the check of a study's intervals on simulated
 * measurements (calibration.h, doc/methods.md §3): the run, calibrate.csv
 * and the table that `brdffit calibrate` prints and report.html shows. */
#include <math.h>
#include <string.h>

#include "calibration.h"
#include "ranking.h"

int bf_rep_calibrate_check(const char *hint, const bf_report_options *o)
{
    if (o->calibrate > 0 && o->calibrate < BF_CALIBRATE_MIN_SIM) {
        return bf_rep_usage_fail(BF_REPORT_BADVALUE, hint,
                                 "--calibrate: %zu simulations: at least %d "
                                 "are needed (0: no calibration)",
                                 o->calibrate, BF_CALIBRATE_MIN_SIM);
    }
    if (o->calibrate > 0 && o->channel != NULL &&
        strcmp(o->channel, "joint") == 0) {
        return bf_rep_usage_fail(BF_REPORT_CONFLICT, hint,
                                 "--calibrate: a --channel joint fit (SPEC "
                                 "§9.4) is not simulated; calibrate one "
                                 "channel");
    }
    return BF_REPORT_OK;
}

/* The calibration's progress (a bf_progress_fn) as the options'. */
static void calibration_tick(void *ctx, size_t done, size_t total)
{
    const bf_rep_study *st = ctx;
    st->opts.progress(st->opts.progress_ctx,
                      "calibrating: simulated measurements refitted", done,
                      total);
}

int bf_rep_study_calibrate(bf_rep_study *st)
{
    bf_analysis_opts ao;
    bf_error err;
    int rc;
    if (st->opts.calibrate == 0) {
        return BF_REPORT_OK;
    }
    if (st->stats == NULL) {
        bf_rep_err("internal error: calibration without the analysis");
        return BF_REPORT_SOFTWARE;
    }
    ao = st->analysis;
    ao.progress = st->opts.progress != NULL ? calibration_tick : NULL;
    ao.progress_ctx = st;
    rc = bf_study_calibrate_all(&st->spec, &ao, st->rows, st->stats,
                                st->opts.calibrate, st->opts.seed, &st->cal,
                                &err);
    if (st->opts.progress != NULL) {
        st->opts.progress(st->opts.progress_ctx, NULL, 0, 0);
    }
    return rc == BF_OK ? BF_REPORT_OK : bf_rep_study_error(&err);
}

/* The columns of the table. */
enum {
    C_SAMPLE,
    C_MODEL,
    C_PARAM,
    C_VALUE,
    C_ML,
    C_INTERVAL,
    C_N,
    C_COVERED,
    C_BAND,
    C_CHECK,
    C_BIAS,
    C_WIDTH,
    C_NOTID,
    C_NCOLS
};

/* One row per fitted parameter of pair i of st->cal. */
static void pair_rows(bf_tt *t, const bf_rep_study *st, size_t i)
{
    static const char *const verdict[3] = {"low", "ok", "high"};
    const bf_calibration *c = &st->cal.cal[i];
    const bf_study_row *r = &st->rows[st->cal.pair[i]];
    const bf_fit_stats *f = &st->stats[st->cal.pair[i]];
    size_t j;
    for (j = 0; j < r->type->p; j++) {
        bf_calibration_summary s;
        if (!((f->free_mask >> j) & 1u)) {
            continue;
        }
        bf_tt_add_row(t);
        bf_tt_set(t, C_SAMPLE, "%d", r->sample);
        bf_tt_set(t, C_MODEL, "%s", r->type->name);
        bf_tt_set(t, C_PARAM, "%s", r->type->param[j].name);
        bf_tt_set(t, C_VALUE, "%.4g", c->truth[j]);
        if (isfinite(f->ml_param[j])) {
            bf_tt_set(t, C_ML, "%.4g", f->ml_param[j]);
        } else {
            bf_tt_set(t, C_ML, "\xe2\x80\x93");
        }
        if (isfinite(f->ci_low[j]) && isfinite(f->ci_high[j])) {
            char iv[96];
            bf_rep_interval_text(iv, sizeof iv, f, j);
            bf_tt_set(t, C_INTERVAL, "%s", iv);
        } else {
            bf_tt_set(t, C_INTERVAL, "\xe2\x80\x93");
        }
        bf_tt_set(t, C_N, "%zu", c->n_sim);
        if (bf_calibration_summarise(c, j, st->analysis.level, &s) !=
            BF_OK) {
            bf_tt_set(t, C_COVERED, "\xe2\x80\x93");
            continue;
        }
        bf_tt_set(t, C_COVERED, "%.3f \xc2\xb1 %.3f", s.coverage,
                  s.coverage_sd);
        bf_tt_set(t, C_BAND, "[%.3f, %.3f]", s.band_low, s.band_high);
        bf_tt_set(t, C_CHECK, "%s", verdict[s.verdict + 1]);
        if (isfinite(s.bias_sd)) { /* NaN: the estimates did not spread */
            bf_tt_set(t, C_BIAS, "%+.2f", s.bias_sd);
            bf_tt_set(t, C_WIDTH, "%.2f", s.width_spread);
        } else {
            bf_tt_set(t, C_BIAS, "\xe2\x80\x93");
            bf_tt_set(t, C_WIDTH, "\xe2\x80\x93");
        }
        bf_tt_set(t, C_NOTID, "%.2f", s.not_identified);
    }
}

bf_tt *bf_rep_calibration_table(const bf_rep_study *st)
{
    static const char *const head[C_NCOLS] = {
        "sample",  "model",   "parameter", "value", "ML estimate",
        "95% interval", "n",  "covered",   "band",  "check",
        "bias/sd", "width/spread", "not identified"};
    bf_tt *t = bf_tt_alloc(C_NCOLS);
    size_t i;
    if (t == NULL) {
        return NULL;
    }
    for (i = 0; i < C_NCOLS; i++) {
        bf_tt_header(t, i, head[i]);
        if (i >= C_VALUE && i != C_CHECK) {
            bf_tt_right(t, i);
        }
    }
    for (i = 0; i < st->cal.n; i++) {
        pair_rows(t, st, i);
    }
    if (bf_tt_failed(t)) {
        bf_tt_free(t);
        return NULL;
    }
    return t;
}

/* What the columns mean, one sentence each (the text and the page). */
static void legend(const bf_rep_study *st, char *buf, size_t len)
{
    double level = 100.0 * st->analysis.level;
    snprintf(buf, len,
             "value: the fitted value (the objective's optimum), simulated "
             "as the truth; ML estimate: the noise model's "
             "maximum-likelihood estimate on the data, which the interval "
             "is about (where the value lies far outside the interval, the "
             "objective's fit and the likelihood's disagree, as where the "
             "model does not fit the data); %.0f%% interval: the fit's on "
             "the data; n: simulations fitted; "
             "covered: share of the simulations' %.0f%% intervals holding "
             "the value simulated, \xc2\xb1 the binomial sd of a calibrated "
             "interval's coverage over n simulations; band: the coverages "
             "calibrated intervals give %.0f%% of the time (exact binomial); "
             "check: low (the intervals cover less than they say), ok, "
             "high; bias/sd: the mean of the maximum-likelihood estimates "
             "(those the intervals are about) minus the value, in their "
             "sds; width/spread: the median interval width over 2 z sd of "
             "those estimates (z the standard normal quantile of (1 + "
             "level)/2, 1.96 at 95%%; 1 is calibrated); not identified: "
             "share of the simulations whose interval reached a bound of "
             "the search range or spans two separate regions.",
             level, level, 100.0 * BF_CALIBRATION_BAND);
}

/* The pairs whose noise power, estimated (--noise auto), sits on the bound
 * BF_NOISE_PMAX of its range, as a sentence into buf ("" when none): the
 * data would take a variance growing faster than the squared mean, which
 * measurement noise does not, and the check simulates from the bound
 * (doc/methods.md §3: on the two Cornell paints whose gloss lobe rises
 * above the noise floor at 4 configurations, LAMBERT+GGX's check was low
 * there). At most NOTE_PAIRS pairs named. */
#define NOTE_PAIRS 8
static void bound_note(const bf_rep_study *st, char *buf, size_t len)
{
    size_t i;
    size_t n = 0;
    size_t at = 0;
    buf[0] = '\0';
    for (i = 0; st->analysis.noise == BF_NOISE_AUTO && i < st->cal.n; i++) {
        const bf_study_row *r = &st->rows[st->cal.pair[i]];
        const bf_fit_stats *f = &st->stats[st->cal.pair[i]];
        if (!(f->noise_power >= BF_NOISE_PMAX)) {
            continue;
        }
        if (n < NOTE_PAIRS && at < len) {
            at += (size_t)snprintf(buf + at, len - at, "%s sample %d %s",
                                   n == 0 ? "" : ",", r->sample,
                                   r->type->name);
        }
        n++;
    }
    if (n == 0) {
        return;
    }
    if (n > NOTE_PAIRS && at < len) {
        at += (size_t)snprintf(buf + at, len - at, " and %zu more",
                               n - NOTE_PAIRS);
    }
    if (at < len) {
        snprintf(buf + at, len - at,
                 ": the fitted noise power is at the bound %.0f of its "
                 "range (relative noise): these data would take a variance "
                 "growing faster than the squared mean, which measurement "
                 "noise does not (a lack of fit where the signal is high); "
                 "the intervals hold p at the bound, and such checks were "
                 "low on the Cornell paints whose gloss lobe rises above "
                 "the noise floor at a few configurations (doc/methods.md "
                 "\xc2\xa7" "3).",
                 BF_NOISE_PMAX);
    }
}

/* "200 simulations of each fit under its fitted noise model (--noise
 * auto), objective max, seed 1" into buf. */
static void what(const bf_rep_study *st, char *buf, size_t len)
{
    snprintf(buf, len,
             "%zu simulated measurements of each fit at its sample's "
             "configurations, from the fitted parameters under the fitted "
             "noise model (--noise %s), each refitted under the objective "
             "%s and given its %.0f%% interval (seed %lu)",
             st->opts.calibrate, bf_noise_name(st->analysis.noise),
             bf_objective_name(st->analysis.objective),
             100.0 * st->analysis.level, st->opts.seed);
}

int bf_rep_calibration_print(const bf_rep_study *st, FILE *fp)
{
    char text[2048];
    bf_tt *t = bf_rep_calibration_table(st);
    if (t == NULL) {
        bf_rep_err("out of memory");
        return BF_REPORT_SOFTWARE;
    }
    what(st, text, sizeof text);
    fprintf(fp, "\nCalibration: %s\n\n", text);
    bf_tt_print(t, fp);
    legend(st, text, sizeof text);
    fprintf(fp, "\n%s\n", text);
    bound_note(st, text, sizeof text);
    if (text[0] != '\0') {
        fprintf(fp, "\nNoise power at its bound:%s\n", text);
    }
    bf_tt_free(t);
    return BF_REPORT_OK;
}

int bf_rep_calibration_write(const bf_rep_study *st)
{
    bf_out csv;
    int rc;
    if (st->opts.calibrate == 0) {
        return BF_REPORT_OK;
    }
    rc = bf_rep_make_outdir(st->out_dir);
    if (rc == BF_REPORT_OK) {
        rc = bf_out_open(&csv, st->out_dir, "calibrate.csv");
    }
    if (rc != BF_REPORT_OK) {
        return rc;
    }
    rc = bf_calibration_csv_write(csv.fp, &st->spec, st->rows, st->stats,
                                  &st->analysis, st->cal.pair, st->cal.n,
                                  st->cal.cal);
    if (rc != BF_OK) {
        bf_out_abort(&csv);
        return bf_rep_write_error("calibrate.csv", rc);
    }
    return bf_out_commit(&csv);
}

int bf_report_calibration(FILE *fp, const bf_rep_study *st)
{
    char text[2048];
    bf_tt *t = bf_rep_calibration_table(st);
    what(st, text, sizeof text);
    fputs("<p>Can the intervals be trusted on these data? ", fp);
    bf_tt_html_text(fp, text);
    fputs(" (doc/methods.md §3; the same in <a href=\"calibrate.csv\">"
          "calibrate.csv</a>). When they mean what they say, the coverage "
          "lies in the band, bias/sd is near 0 and width/spread near 1.</p>"
          "\n<p>",
          fp);
    legend(st, text, sizeof text);
    bf_tt_html_text(fp, text);
    fputs("</p>\n", fp);
    bound_note(st, text, sizeof text);
    if (text[0] != '\0') {
        fputs("<p>Noise power at its bound:", fp);
        bf_tt_html_text(fp, text);
        fputs("</p>\n", fp);
    }
    if (t == NULL) {
        return -2;
    }
    bf_tt_print_html(t, "calibration", fp);
    bf_tt_free(t);
    return 0;
}
