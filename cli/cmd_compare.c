/* cmd_compare.c: `brdffit compare` -- the study of SPEC §7 on any data:
 * fits every selected model to every selected sample, prints Table 2
 * (parameters) and Table 3 (the LSE, E or S of the objective) in the
 * paper's layout and writes fits.csv, table2.md and table3.md atomically
 * into the output folder. */
#include <string.h>

#include "setup.h"
#include "tables.h"

static void usage(FILE *fp)
{
    fputs(
"Usage: brdffit compare [OPTIONS] [FILE...]\n"
"\n"
"Fit reflectance models to measured BRDF data (a CURET folder, or --input\n"
"files: pbrt-v2/Cornell .brdf, ASTM E1392, MERL .binary, tidy CSV) with\n"
"the protocol of Ragheb & Hancock (SPEC §7): max-normalised radiance over\n"
"the used configurations (the specular ones left out), LSE as a sum,\n"
"501-point grids. Prints Table 2 (fitted parameters) and Table 3 (the LSE;\n"
"E under --objective ngan, S under the others) and writes fits.csv,\n"
"table2.md and table3.md into the output folder. With\n"
"specular models, the energy table after Table 3: each fit's albedo at\n"
"theta_i 0, 30, 60, 80 deg, OVER 1 where it exceeds 1. With a fitted\n"
"refractive index (--fresnel dielectric, or ABC's ior) on channels with a\n"
"wavelength (--channel each or joint on spectral data), also\n"
"dispersion.csv: n against wavelength with its 95% interval.\n"
"\n"
"Options:\n",
        fp);
    bf_cli_opts_usage(fp);
    bf_cli_exit_usage(fp);
}

int bf_cmd_compare(int argc, char **argv)
{
    bf_rep_study st;
    bf_cli_run r;
    int rc;

    memset(&st, 0, sizeof st);
    memset(&r, 0, sizeof r);
    st.cmd = "compare";
    rc = bf_cli_opts_parse(st.cmd, argc, argv, usage, NULL, &r.opts);
    if (rc != 0) {
        return rc < 0 ? BF_EXIT_OK : rc;
    }
    rc = bf_cli_study_setup(st.cmd, &r, &st);
    if (rc == BF_EXIT_OK) {
        rc = bf_rep_study_run(&st);
    }
    if (rc == BF_EXIT_OK) {
        rc = bf_rep_study_write_tables(&st);
    }
    bf_rep_study_free(&st);
    bf_cli_run_free(&r);
    return rc;
}
