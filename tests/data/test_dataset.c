/* test_dataset.c: the format-neutral dataset (src/data/dataset.c), its
 * selection and radiance (src/data/select.c), the CURET reader that makes
 * one (src/data/curet.c) and the study's targets (src/fit/targets.c):
 * SPEC §1.4-§1.6, §2. */
#include <criterion/criterion.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "support.h"

#define PI 3.14159265358979323846
#define DEG (PI / 180.0)

/* Three configurations in the measurement frame (SPEC §1.5), chosen by
 * hand: 0 exactly at the mirror direction of (30 deg, 20 deg); 1 at 3 deg
 * from it (theta_o 33 deg on the same plane); 2 backscatter. */
static const double angles3[12] = {
    30 * DEG, 20 * DEG, 30 * DEG, 200 * DEG, /* mirror: phi_o = phi_i + pi */
    30 * DEG, 20 * DEG, 33 * DEG, 200 * DEG, /* 3 deg off, in plane */
    30 * DEG, 20 * DEG, 30 * DEG, 20 * DEG}; /* backscatter: 60 deg off */

/* A dataset of one material on angles3 with two channels; value (k, c) =
 * 0.1 (k + 1) + c, and channel 1 of configuration 2 invalid. */
static bf_dataset *small_dataset(void)
{
    bf_dataset *ds = bf_dataset_alloc();
    const char *ch[2] = {"R", "G"};
    double v[6] = {0.1, 1.1, 0.2, 1.2, 0.3, -1.0};
    unsigned char ok[6] = {1, 1, 1, 1, 1, 0};
    bf_material_desc d;
    size_t set;
    size_t idx;
    cr_assert_not_null(ds);
    cr_assert_eq(bf_dataset_add_configs(ds, 3, angles3, &set, NULL), BF_OK);
    memset(&d, 0, sizeof d);
    d.name = "paint";
    d.format = BF_FORMAT_MEMORY;
    d.source = "mem";
    d.set = set;
    d.n_channels = 2;
    d.channel = ch;
    d.values = v;
    d.valid = ok;
    cr_assert_eq(bf_dataset_add_material(ds, &d, &idx), BF_OK);
    cr_assert_eq(idx, 0u);
    return ds;
}

Test(dataset, copies_what_it_is_given_and_converts_to_beckmanns_frame)
{
    bf_dataset *ds = small_dataset();
    const bf_geom *g = bf_dataset_geom(ds, 0);
    cr_assert_eq(bf_dataset_count(ds), 1u);
    cr_assert_str_eq(bf_dataset_name(ds, 0), "paint");
    cr_assert_eq(bf_dataset_number(ds, 0), 1); /* its position */
    cr_assert_eq(bf_dataset_nconf(ds, 0), 3u);
    cr_assert_eq(bf_dataset_nchannels(ds, 0), 2u);
    cr_assert_str_eq(bf_dataset_channel(ds, 0, 1), "G");
    cr_assert(isnan(bf_dataset_wavelength(ds, 0, 0)));
    cr_assert_eq(memcmp(bf_dataset_angles(ds, 0), angles3, sizeof angles3),
                 0);
    /* SPEC §1.5: phi_s = wrap(phi_o - phi_i - pi): 200 - 20 - 180 = 0 */
    bf_assert_abs(g[0].phi_s, 0.0, TOL1);
    bf_assert_rel(g[0].phi_i, PI, TOL0);
    bf_assert_rel(g[1].theta_s, 33 * DEG, TOL0);
    bf_assert_rel(fabs(g[2].phi_s), PI, TOL1); /* backscatter: phi_s = pi */
    cr_assert_not_null(bf_dataset_valid(ds, 0));
    cr_assert_null(bf_dataset_name(ds, 1));
    bf_dataset_free(ds);
}

Test(dataset, measurement_frame_conversion_is_curets_with_the_view_as_o)
{
    /* CURET's configuration 1, as its table.txt gives it (SPEC §1.3) */
    bf_geom a = bf_geom_from_curet(1.389566, 1.570796, 1.374447, 3.114159);
    bf_geom b = bf_geom_from_measurement(1.374447, 3.114159, 1.389566,
                                         1.570796);
    cr_assert_eq(memcmp(&a, &b, sizeof a), 0);
}

Test(dataset, mirror_angle_is_the_angle_to_the_mirror_direction)
{
    bf_dataset *ds = small_dataset();
    const bf_geom *g = bf_dataset_geom(ds, 0);
    bf_geom grazing = {PI / 2, PI, PI / 2, PI}; /* both grazing, opposite */
    bf_assert_abs(bf_geom_mirror_angle(&g[0]), 0.0, TOL2);
    bf_assert_rel(bf_geom_mirror_angle(&g[1]), 3 * DEG, TOL2);
    /* backscatter at 30 deg: the mirror direction is 2 x 30 = 60 deg away
     * (both directions lie in one plane through the normal) */
    bf_assert_rel(bf_geom_mirror_angle(&g[2]), 60 * DEG, TOL2);
    bf_assert_rel(bf_geom_mirror_angle(&grazing), PI, TOL2);
    bf_dataset_free(ds);
}

Test(dataset, the_mean_needs_every_channel_and_one_channel_is_its_own_mean)
{
    bf_dataset *ds = small_dataset();
    double v;
    cr_assert_eq(bf_dataset_value(ds, 0, 1, BF_CHANNEL_MEAN, &v), 1);
    bf_assert_rel(v, (0.2 + 1.2) / 2.0, TOL0);
    cr_assert_eq(bf_dataset_value(ds, 0, 2, BF_CHANNEL_MEAN, &v), 0);
    cr_assert_eq(bf_dataset_value(ds, 0, 2, 0, &v), 1);
    cr_assert_eq(v, 0.3);
    cr_assert_eq(bf_dataset_value(ds, 0, 2, 1, &v), 0);
    bf_dataset_free(ds);
}

Test(dataset, channels_are_found_by_name_wavelength_or_mean)
{
    bf_dataset *ds = bf_dataset_alloc();
    const char *ch[2] = {"400", "410"};
    double wl[2] = {400.0, 410.0};
    double v[2] = {0.5, 0.6};
    bf_material_desc d;
    size_t set;
    size_t c = 99;
    double one[4] = {0.1, 0.2, 0.3, 0.4};
    cr_assert_eq(bf_dataset_add_configs(ds, 1, one, &set, NULL), BF_OK);
    memset(&d, 0, sizeof d);
    d.name = "spectral";
    d.set = set;
    d.n_channels = 2;
    d.channel = ch;
    d.wavelength = wl;
    d.values = v;
    cr_assert_eq(bf_dataset_add_material(ds, &d, NULL), BF_OK);
    cr_assert_eq(bf_dataset_channel_find(ds, 0, "410", &c), BF_OK);
    cr_assert_eq(c, 1u);
    cr_assert_eq(bf_dataset_channel_find(ds, 0, "4.1e2", &c), BF_OK);
    cr_assert_eq(c, 1u, "a wavelength written another way");
    cr_assert_eq(bf_dataset_channel_find(ds, 0, "MEAN", &c), BF_OK);
    cr_assert_eq(c, BF_CHANNEL_MEAN);
    cr_assert_eq(bf_dataset_channel_find(ds, 0, "R", &c), BF_ENOTFOUND);
    bf_assert_rel(bf_dataset_wavelength(ds, 0, 1), 410.0, TOL0);
    bf_dataset_free(ds);
}

Test(dataset, bad_configurations_and_materials_are_refused)
{
    bf_dataset *ds = bf_dataset_alloc();
    double bad[8] = {0.1, 0.0, 0.2, 0.0, 1.6, 0.0, 0.2, 0.0};
    double nan_az[4] = {0.1, NAN, 0.2, 0.0};
    double v[1] = {NAN};
    bf_material_desc d;
    size_t set = 7;
    size_t row = 0;
    cr_assert_eq(bf_dataset_add_configs(ds, 2, bad, &set, &row), BF_EINVAL);
    cr_assert_eq(row, 1u, "theta_i = 1.6 > pi/2 is row 1");
    cr_assert_eq(bf_dataset_add_configs(ds, 1, nan_az, &set, &row),
                 BF_EINVAL);
    cr_assert_eq(bf_dataset_add_configs(ds, 1, bad, &set, NULL), BF_OK);
    memset(&d, 0, sizeof d);
    d.name = "x";
    d.set = set;
    d.n_channels = 1;
    d.values = v;
    cr_assert_eq(bf_dataset_add_material(ds, &d, NULL), BF_EINVAL,
                 "a valid NaN");
    d.set = 5;
    cr_assert_eq(bf_dataset_add_material(ds, &d, NULL), BF_EINVAL,
                 "no such set");
    cr_assert_eq(bf_dataset_count(ds), 0u);
    bf_dataset_free(ds);
}

Test(dataset, numbers_are_unique_and_append_renumbers_by_position)
{
    bf_dataset *a = small_dataset();
    bf_dataset *b = small_dataset();
    bf_material_desc d;
    double v[3] = {1, 2, 3};
    memset(&d, 0, sizeof d);
    d.name = "explicit";
    d.number = 1; /* material 0 of a is already number 1 (its position) */
    d.set = 0;
    d.n_channels = 1;
    d.values = v;
    cr_assert_eq(bf_dataset_add_material(a, &d, NULL), BF_EINVAL);
    cr_assert_eq(bf_dataset_append(a, b), BF_OK);
    cr_assert_eq(bf_dataset_count(a), 2u);
    cr_assert_eq(bf_dataset_number(a, 1), 2);
    cr_assert_eq(bf_dataset_find(a, 2), 1);
    cr_assert_neq(bf_dataset_set(a, 0), bf_dataset_set(a, 1));
    cr_assert_eq(bf_dataset_nconf(a, 1), 3u);
    d.number = 2; /* now taken by b's material */
    cr_assert_eq(bf_dataset_add_material(a, &d, NULL), BF_EINVAL);
    bf_dataset_free(a);
    bf_dataset_free(b);
}

Test(dataset, selection_leaves_out_invalid_values_the_cone_and_exclusions)
{
    bf_dataset *ds = small_dataset();
    bf_select s;
    size_t sel[3];
    size_t n = 9;
    size_t cone = 9;
    size_t ex[1] = {3};
    bf_select_init(&s);
    /* default on non-CURET data: no cone; the mean drops configuration 2 */
    cr_assert_eq(bf_dataset_select(ds, 0, BF_CHANNEL_MEAN, &s, sel, &n,
                                   &cone),
                 BF_OK);
    cr_assert_eq(n, 2u);
    cr_assert_eq(cone, 0u);
    cr_assert_eq(bf_dataset_select(ds, 0, 0, &s, sel, &n, NULL), BF_OK);
    cr_assert_eq(n, 3u, "channel R is valid everywhere");
    s.cone = 2 * DEG; /* drops the mirror configuration only */
    cr_assert_eq(bf_dataset_select(ds, 0, 0, &s, sel, &n, &cone), BF_OK);
    cr_assert_eq(n, 2u);
    cr_assert_eq(cone, 1u);
    cr_assert_eq(sel[0], 1u);
    s.cone = 4 * DEG; /* and the one 3 deg away */
    cr_assert_eq(bf_dataset_select(ds, 0, 0, &s, sel, &n, &cone), BF_OK);
    cr_assert_eq(n, 1u);
    cr_assert_eq(cone, 2u);
    s.cone = 0.0;
    s.exclude = ex;
    s.n_exclude = 1;
    cr_assert_eq(bf_dataset_select(ds, 0, 0, &s, sel, &n, NULL), BF_OK);
    cr_assert_eq(n, 2u);
    cr_assert_eq(sel[1], 1u);
    ex[0] = 4;
    cr_assert_eq(bf_dataset_select(ds, 0, 0, &s, sel, &n, NULL),
                 BF_ENOTFOUND);
    s.n_exclude = 0;
    s.max_theta = 31 * DEG; /* theta_o = 33 deg is left out */
    cr_assert_eq(bf_dataset_select(ds, 0, 0, &s, sel, &n, NULL), BF_OK);
    cr_assert_eq(n, 2u);
    bf_dataset_free(ds);
}

Test(dataset, radiance_is_brdf_times_cos_theta_i_over_its_maximum)
{
    bf_dataset *ds = small_dataset();
    size_t sel[2] = {0, 1};
    double out[2];
    cr_assert_eq(bf_dataset_radiance(ds, 0, 0, 2, sel, out), BF_OK);
    /* SPEC §2: same theta_i, so cos cancels: 0.1/0.2, 0.2/0.2 */
    bf_assert_rel(out[0], 0.5, TOL1);
    bf_assert_rel(out[1], 1.0, TOL0);
    sel[0] = 2;
    cr_assert_eq(bf_dataset_radiance(ds, 0, BF_CHANNEL_MEAN, 2, sel, out),
                 BF_EDOM, "an invalid value is never used");
    bf_dataset_free(ds);
}

/* CURET read as a dataset: SPEC §1.4's 7 configurations by default, the
 * cone of SPEC §1.6 giving the same 7 below 4.5 deg and dropping 203 at 5
 * deg (SPEC §1.6 states 203 is 4.53 deg from the mirror direction). */
Test(dataset, curet_cone_below_4_5_degrees_is_the_seven_and_5_adds_203)
{
    bf_dataset *ds = NULL;
    bf_error err;
    bf_select s;
    size_t sel[205];
    size_t n;
    size_t cone;
    size_t k;
    static const size_t seven[7] = {54, 97, 131, 161, 183, 196, 202};
    const double cones[4] = {0.5, 1.0, 3.0, 4.4};
    size_t i;
    cr_assert_eq(bf_curet_load(BF_CURET_DIR, NULL, &ds, &err), BF_OK,
                 "%s: %s", err.file, err.msg);
    cr_assert_eq(bf_dataset_count(ds), 61u);
    cr_assert_str_eq(bf_dataset_name(ds, 0), "Felt");
    cr_assert_eq(bf_dataset_format(ds, 0), BF_FORMAT_CURET);
    cr_assert_str_eq(bf_dataset_channel(ds, 0, 0), "mean");
    cr_assert_eq(bf_dataset_set(ds, 0), bf_dataset_set(ds, 60));
    bf_select_init(&s);
    cr_assert_eq(bf_dataset_select(ds, 4, BF_CHANNEL_MEAN, &s, sel, &n,
                                   &cone),
                 BF_OK);
    cr_assert_eq(n, 198u);
    cr_assert_eq(cone, 7u);
    for (i = 0; i < 4; i++) {
        unsigned char used[205] = {0};
        size_t j = 0;
        s.cone = cones[i] * DEG;
        cr_assert_eq(bf_dataset_select(ds, 4, BF_CHANNEL_MEAN, &s, sel, &n,
                                       &cone),
                     BF_OK);
        cr_assert_eq(n, 198u, "cone %g deg", cones[i]);
        for (k = 0; k < n; k++) {
            used[sel[k]] = 1;
        }
        for (k = 0; k < 205; k++) {
            if (!used[k]) {
                cr_assert_eq(k + 1, seven[j], "cone %g deg", cones[i]);
                j++;
            }
        }
    }
    s.cone = 5.0 * DEG;
    cr_assert_eq(bf_dataset_select(ds, 4, BF_CHANNEL_MEAN, &s, sel, &n,
                                   &cone),
                 BF_OK);
    cr_assert_eq(n, 197u);
    for (k = 0; k < n; k++) {
        cr_assert_neq(sel[k], 202u, "configuration 203 left out at 5 deg");
    }
    bf_dataset_free(ds);
}

Test(dataset, curet_reports_a_table_and_rows_of_different_counts_by_both_files)
{
    char dir[] = "/tmp/brdffit-ds-XXXXXX";
    char path[512];
    FILE *fp;
    bf_dataset *ds = (bf_dataset *)&ds;
    bf_error err;
    cr_assert_not_null(mkdtemp(dir));
    snprintf(path, sizeof path, "%s/table.txt", dir);
    fp = fopen(path, "w");
    fputs("1 0.2 0.0 0.3 1.0\n2 0.5 2.0 0.6 0.5\n", fp);
    fclose(fp);
    snprintf(path, sizeof path, "%s/abrdf.dat", dir);
    fp = fopen(path, "w");
    fputs("1 0.3 0.2 0.1\n2 0.3 0.2 0.1\n", fp);
    fclose(fp);
    cr_assert_eq(bf_curet_load(dir, NULL, &ds, &err), BF_EPARSE);
    cr_assert_null(ds);
    cr_assert_str_eq(err.file, path);
    cr_assert_eq(err.line, 1);
    cr_assert(strstr(err.msg, "have 3 values") != NULL, "%s", err.msg);
    cr_assert(strstr(err.msg, "table.txt has 2 configurations") != NULL,
              "%s", err.msg);
}

Test(dataset, targets_expand_each_channel_and_refuse_a_missing_one)
{
    bf_dataset *ds = small_dataset();
    bf_target *t = NULL;
    size_t n = 0;
    bf_error err;
    cr_assert_eq(bf_study_targets(ds, NULL, 0, "each", &t, &n, &err), BF_OK);
    cr_assert_eq(n, 2u);
    cr_assert_eq(t[1].channel, 1u);
    free(t);
    cr_assert_eq(bf_study_targets(ds, NULL, 0, NULL, &t, &n, &err), BF_OK);
    cr_assert_eq(n, 1u);
    cr_assert_eq(t[0].channel, BF_CHANNEL_MEAN);
    free(t);
    cr_assert_eq(bf_study_targets(ds, NULL, 0, "B", &t, &n, &err),
                 BF_ENOTFOUND);
    cr_assert(strstr(err.msg, "no channel 'B'") != NULL, "%s", err.msg);
    bf_dataset_free(ds);
}

/* Two materials on the same configurations share the model curves: each
 * fit equals the fit of that material alone, bit for bit; a material's K
 * follows its own valid values. */
Test(dataset, study_on_two_configuration_sets_fits_each_as_alone)
{
    bf_dataset *ds = small_dataset();
    bf_dataset *more = small_dataset();
    const bf_model_type *models[2] = {bf_model_lftg, bf_model_lambert};
    bf_target t[2] = {{0, 0, 0}, {1, BF_CHANNEL_MEAN, 0}};
    bf_study_row rows[4];
    bf_study_row alone[2];
    bf_study_spec spec;
    bf_error err;
    cr_assert_eq(bf_dataset_append(ds, more), BF_OK);
    memset(&spec, 0, sizeof spec);
    spec.data = ds;
    bf_select_init(&spec.select);
    spec.targets = t;
    spec.n_targets = 2;
    spec.models = models;
    spec.n_models = 2;
    spec.n_default = BF_DEFAULT_N;
    cr_assert_eq(bf_study_run(&spec, rows, &err), BF_OK, "%s", err.msg);
    cr_assert_eq(rows[0].k, 3u);
    cr_assert_eq(rows[2].k, 2u, "the mean is invalid at configuration 3");
    cr_assert_eq(rows[2].sample, 2);
    cr_assert_eq(rows[3].target, 1u);
    spec.targets = &t[1];
    spec.n_targets = 1;
    cr_assert_eq(bf_study_run(&spec, alone, &err), BF_OK, "%s", err.msg);
    cr_assert_eq(memcmp(&alone[0].fit, &rows[2].fit, sizeof alone[0].fit),
                 0);
    cr_assert_eq(memcmp(&alone[1].fit, &rows[3].fit, sizeof alone[1].fit),
                 0);
    bf_dataset_free(ds);
    bf_dataset_free(more);
}
