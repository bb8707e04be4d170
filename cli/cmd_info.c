/* cmd_info.c: `brdffit info` -- what a dataset holds: its format,
 * materials, channels, configurations, angle ranges, how many
 * configurations lie near the mirror direction (SPEC §1.4, §1.6), and its
 * negative, zero and invalid values (SPEC §2). */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "cli.h"
#include "texttable.h"

#define DEG (M_PI / 180.0)

static void usage(FILE *fp)
{
    fputs(
"Usage: brdffit info [OPTIONS] FILE|DIR...\n"
"\n"
"Describes measured BRDF data in any format brdffit reads (a CURET folder,\n"
"pbrt-v2/Cornell .brdf, ASTM E1392 .astm, MERL .binary, tidy CSV): format,\n"
"materials, channels, configurations, angle ranges (measurement frame,\n"
"SPEC §1.5), how many configurations lie within 1, 5, 10, 15 and 25 deg of\n"
"the mirror direction (the specular cone of --exclude-specular, SPEC §1.6),\n"
"and the negative, zero and invalid values.\n"
"\n"
"Options:\n",
          fp);
    bf_cli_file_args_usage(fp);
    bf_cli_exit_usage(fp);
}

/* Prints "theta_i 0.0-80.0 deg" style ranges. */
static void range(const char *what, double lo, double hi)
{
    printf("%s %.2f to %.2f deg", what, lo / DEG, hi / DEG);
}

/* The configuration set of material m, printed once for all materials on
 * it. */
static void describe_set(const bf_dataset *ds, size_t m, size_t users)
{
    bf_material_summary s;
    size_t j;
    bf_dataset_summary(ds, m, &s);
    printf("Configurations: %zu", s.n_conf);
    if (users > 1) {
        printf(" (shared by %zu materials)", users);
    }
    printf("\n  ");
    range("theta_i", s.theta_i_min, s.theta_i_max);
    printf(", ");
    range("phi_i", s.phi_i_min, s.phi_i_max);
    printf("\n  ");
    range("theta_o", s.theta_o_min, s.theta_o_max);
    printf(", ");
    range("phi_o", s.phi_o_min, s.phi_o_max);
    printf("\n  near the mirror direction (SPEC §1.6): nearest %.2f deg;",
           s.delta_min / DEG);
    for (j = 0; j < BF_SUMMARY_NCONES; j++) {
        printf("%s within %g deg: %zu", j == 0 ? "" : ",",
               bf_summary_cones_deg[j], s.n_cone[j]);
    }
    printf("\n  specular by SPEC §1.4's test (CURET's default exclusion): "
           "%zu\n",
           s.n_specular);
}

static int describe(const char *path, const bf_dataset *ds, int curet)
{
    size_t n = bf_dataset_count(ds);
    size_t m;
    bf_tt *t = bf_tt_alloc(9);
    static const char *const head[9] = {"No.",      "Material", "Channels",
                                        "Min",      "Max",      "Negative",
                                        "Zero",     "Invalid",  "Format"};
    size_t c;
    if (t == NULL) {
        bf_cli_err("out of memory");
        return BF_EXIT_SOFTWARE;
    }
    printf("%s: %s, %zu material%s\n", path,
           curet ? "CURET folder" : bf_format_name(bf_dataset_format(ds, 0)),
           n, n == 1 ? "" : "s");
    for (m = 0; m < n; m++) { /* each configuration set once */
        size_t users = 0;
        size_t q;
        int first = 1;
        for (q = 0; q < n; q++) {
            if (bf_dataset_set(ds, q) == bf_dataset_set(ds, m)) {
                users++;
                first &= q >= m;
            }
        }
        if (first) {
            describe_set(ds, m, users);
        }
    }
    for (c = 0; c < 9; c++) {
        bf_tt_header(t, c, head[c]);
        if (c != 1 && c != 2 && c != 8) {
            bf_tt_right(t, c);
        }
    }
    for (m = 0; m < n; m++) {
        bf_material_summary s;
        size_t nc = bf_dataset_nchannels(ds, m);
        char ch[128];
        bf_dataset_summary(ds, m, &s);
        if (nc == 1) {
            snprintf(ch, sizeof ch, "1 (%s)", bf_dataset_channel(ds, m, 0));
        } else {
            snprintf(ch, sizeof ch, "%zu (%s ... %s)", nc,
                     bf_dataset_channel(ds, m, 0),
                     bf_dataset_channel(ds, m, nc - 1));
        }
        if (bf_tt_add_row(t) != 0) {
            bf_tt_free(t);
            bf_cli_err("out of memory");
            return BF_EXIT_SOFTWARE;
        }
        bf_tt_set(t, 0, "%d", bf_dataset_number(ds, m));
        bf_tt_set(t, 1, "%s", bf_dataset_name(ds, m));
        bf_tt_set(t, 2, "%s", ch);
        bf_tt_set(t, 3, "%.4g", s.value_min);
        bf_tt_set(t, 4, "%.4g", s.value_max);
        bf_tt_set(t, 5, "%zu", s.n_negative);
        bf_tt_set(t, 6, "%zu", s.n_zero);
        if (s.n_invalid == 0) {
            bf_tt_set(t, 7, "0");
        } else {
            bf_tt_set(t, 7, "%zu (in %zu configurations)", s.n_invalid,
                      s.n_conf_invalid);
        }
        bf_tt_set(t, 8, "%s", bf_format_name(bf_dataset_format(ds, m)));
    }
    printf("Materials (values: BRDF, sr^-1):\n\n");
    bf_tt_print(t, stdout);
    bf_tt_free(t);
    return BF_EXIT_OK;
}

int bf_cmd_info(int argc, char **argv)
{
    bf_cli_source src;
    int first;
    int a;
    int rc = bf_cli_file_args("info ", argc, argv, usage, NULL, &src, &first);
    if (rc != 0) {
        return rc < 0 ? BF_EXIT_OK : rc;
    }
    if (first >= argc) {
        return bf_cli_usage_fail(BF_EXIT_NOVALUE, "info ",
                                 "no FILE or DIR given");
    }
    for (a = first; a < argc && rc == BF_EXIT_OK; a++) {
        bf_cli_source one = src;
        bf_cli_inputs in;
        bf_cli_source_path(&one, argv[a]);
        rc = bf_cli_load_data(&one, NULL, NULL, &in);
        if (rc == BF_EXIT_OK) {
            if (a > first) {
                putchar('\n');
            }
            rc = describe(argv[a], in.ds, in.curet);
        }
        bf_cli_free_inputs(&in);
    }
    return rc;
}
