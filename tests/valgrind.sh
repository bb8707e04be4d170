#!/bin/sh
# valgrind.sh: runs every test executable of a build folder under valgrind,
# following the children (Criterion runs each test in a child process, and
# the CLI tests exec build/brdffit; system programs the tests run, such as
# sh and ls, are not followed). Any memory error or any leaked block
# (definite, indirect or possible) fails the run with valgrind's report.
#
#   tests/valgrind.sh BUILD [JOBS]
#
# JOBS executables run at once (default: the number of cores); their
# verdicts are printed in the executables' order.
#
# Left out (VALGRIND_SKIP, space-separated): whole executables by name, or
# single tests as suite/test (Criterion globs). These are the sweeps and
# full-data runs that repeat, tens of millions of times, code paths the
# remaining tests already run under valgrind; at valgrind's ~50x slow-down
# they would take most of an hour. ASan+UBSan runs all of them (make test).
# WNO-R's quadrature (about 6 400 facets per value, plain) makes the
# runs over every fitted model on real data (grid/..._61_samples,
# grid/round_trip_recovers_every_model..., whose WNO-R grid is the rule at
# 448 points, test_refine) the slowest, and wno_r/the_engines_tables...
# compares 40 of the rule's curves with both of the engine's tables; the
# rule and the tables run under valgrind in test_wno_r's other tests (its
# round trip builds and reads a table) and in test_cli; the other models'
# grid round trips in grid/round_trip_with_fixed_seed_noise... and test_cli.
# test_uncertainty repeats 200 fits per model for its coverage checks; the
# profile and bootstrap code it covers runs under valgrind in test_cli_exact
# (compare --fit exact --bootstrap 30: both intervals for every fit).
# intervals/cover_... , intervals/the_objectives_own_profile... and
# intervals/the_bootstrap_covers_... simulate 200 data sets each (and the
# bootstrap 99 refits of each): their code runs under valgrind in the
# other intervals tests (calibrate on a known material, the flat
# profiles, the bootstrap's bad input) and in test_cli_exact.
# test_coverage repeats hundreds of analyses per model (interval
# coverage), test_before analyses all 61 samples x 10 models, and
# cli_analysis/results_do_not_depend_on_the_thread_count runs the CLI's
# analysis six times: their code paths run under valgrind in test_writers,
# test_policy, test_rank and the rest of test_cli_analysis.
# main_job/runs_from_a_bare_clone... runs `make run` on the 24 study samples
# through make and sh (valgrind follows every child, every figure
# process); the report code runs under valgrind in test_cmd_report, the
# data script in the other two main_job tests.
# The readers' unit tests with many small cases (test_table, test_brdf,
# test_sample_table, test_pbrt, test_astm, test_csv: 132 tests, each a
# process whose start under valgrind costs about 1.3 s of CPU, most of
# their time): the readers' error paths run under valgrind through the
# CLI in test_corpus (84 committed malformed files of every text format
# and the cases made at test time: binary garbage, MERL headers), their
# success paths in every test that loads data, and the readers are fuzzed
# under ASan+UBSan (make fuzz).
# The readers' sweeps: test_merl's runs over whole 35 MB tables (every cell
# or tens of thousands of lookups, analytic tables fitted back), the MERL
# all-cells load of test_format, test_csv's hundreds of thousands of random
# angles, and test_convert's fits of the five Cornell files in three
# formats; the smaller tests of the same files run every reader path under
# valgrind. inputs/every_cornell_file... runs compare, report --stats and
# rank on the five Cornell files (1379 configurations each); the same
# commands run under valgrind on smaller data in test_cli_inputs' other
# tests and in test_cmd_report; so do those of inputs/channel_each... (31
# channels) and inputs/cornell_as_brdf_csv_and_astm... (three --stats runs
# on 1379 configurations). The repeated runs that compare outputs
# (report/gives_the_same_files..., report/gives_byte_identical...,
# cli/thread_count...) run code that the other tests of their files run
# once under valgrind; cli/all_61_samples... fits every model to every
# sample (WNO-R's quadrature included), code test_cli's smaller runs and
# test_wno_r cover. keep_scale's recovery and Cornell tests fit every
# model through the CLI under the scale-keeping objectives (about 5 s of
# CPU plain); the objectives' code runs under valgrind in keep_scale's
# library tests.
# composite's recovery and Cornell tests fit composites through the CLI
# (the Cornell one 20 fits on 1439 configurations, about 25 s of CPU
# plain); the composites' values and the CLI's checks of their names run
# under valgrind in composite's other tests; its dense recovery (72,000
# configurations through the CLI) likewise, and its check of the folds'
# fits (cv_folds_fit_at_least...: 15 folds of LAMBERT+LAFORTUNE on 1439
# configurations, each fitted twice, about 4 s of CPU plain;
# cv_folds_with_the_gloss_peak...: 20 folds of two composites on cayman,
# 74 s under valgrind) -- the folds' grid and fits run under valgrind in
# every compare of a composite with its default ten folds in composite's
# other tests.
# composite/lafortune_fits_reach_the_truths_basin fits 100 simulated data
# sets twice (about 5 s of CPU plain); composite/a_lafortune_fit... runs
# the first of them under valgrind.
# spec_intervals/a_profile_stays_inside_where_the_model_overflows fits and
# profiles mystique's 1439 configurations with thresholds some 3000 times
# the usual (about 1.4 s plain, many inner fits); ASan runs it.
# specular_options' recovery and separable-height tests fit six composites
# and lobes through the CLI (about 1.1 s of CPU plain); the same paths run
# under valgrind in its fits.csv, description and bad-option tests.
# The specular models' albedo checks (specular_models/ggx_without... and
# ward_gmd...: 50 albedo quadratures) run the code of
# specular_models/albedo_of_a_known_integral, which stays.
# joint/report_draws... draws every figure of a joint fit's report; the
# joint fit itself runs under valgrind in joint's other tests.
# plane_abs/description_under_ngan runs the report through the CLI on a
# Cornell file (1439 configurations, every figure); the figure data it
# describes are checked under valgrind by plane_abs's library tests.
# The repeated fits of the grid's round trip over every model and of its
# thread-count check (grid/round_trip_recovers..., grid/study_results...),
# WNO-R's sweeps against the quadrature and its fit back
# (wno_r/the_engines_evaluation..., wno_r/fits_its_own_curve...),
# calibrate's CLI run over
# every fitted parameter (cli_calibrate/writes_coverage...) and the
# report's figure check without --stats (report/writes_every_figure...)
# repeat, for many parameters or sizes, code that the other tests of their
# files run under valgrind once (grid/round_trip_with_fixed_seed_noise...,
# wno_r/matches_the_integral..., cli_calibrate's error tests and
# intervals/calibrate_reports..., report/stats_add...). test_stream's one
# test streams a large K in blocks (seconds of fitting); ASan runs it.
# spec_intervals' coverage tests simulate 200 fits per case (about 15 s
# of CPU plain each; AS alone's 11 s), its CLI runs on krylon_blue (bootstrap, calibrate's
# 10 simulations; calibrate's note on mystique and krylon_blue, 7 s plain)
# repeat on 1439 configurations the code its library tests (the flat F0
# profile, the Cornell intervals) and report_calibrate's thread test run
# under valgrind.
# test_oom preloads its own allocator (tests/oom/oom_shim.c), which
# valgrind's replaces; it runs in the plain build only.
# test_cli_matrix runs report, compare and rank over every combination of
# samples, models, --stats and data set (over a hundred CLI runs); each
# code path it reaches runs under valgrind in test_cli, test_cli_inputs and
# test_cmd_report, and ASan runs a diagonal of the matrix.
# report_calibrate/covers_a_known_material... simulates 200 measurements
# twice (report and calibrate); the same code runs under valgrind in
# report_calibrate's thread test (20 simulations, two reports).
# Four single tests whose time under valgrind (its --verbose log) is
# their own sweep, not start-up: wno_r/is_finite_and_non_negative... (45 s;
# WNO-R over its whole domain) and wno_r/matches_gsls_adaptive... (22 s;
# the rule against GSL's quadrature), whose code the other wno_r tests run;
# report_calibrate/many_panels... (38 s), whose figure code its thread
# test runs; dispersion/krylon_blue_mean_index... (18 s, 31 channels of a
# real file), whose code dispersion's synthetic tests run.
# spec_intervals/dense_profile_ends_are_roots_on_all_the_data profiles and
# refits LAMBERT+GGX on 72,000 configurations (114 s under valgrind, half
# the file's time): the dense path (above BF__DENSE_K configurations: the
# predicted steps and the narrowed bracket of profile.c) has no smaller
# case; ASan runs it.
# neyman/the_default_intervals_cover... and
# neyman/every_parameters_construction... simulate 200 measurements, each
# with its Neyman construction (100 simulations per threshold: about 45 s
# plain each), and neyman/agrees_with_the_F_threshold... one with 200 per
# threshold (8 s plain); the construction runs under valgrind in
# cli_exact/neyman_intervals_are_named_and_reproducible and, where a
# second minimum competes (the default), in
# cli_analysis/a_split_interval_is_written_as_two_segments.
# Set VALGRIND_SKIP= to run everything. tests/valgrind.supp suppresses only
# leaks allocated inside the system libraries the report's figures load
# (fontconfig, pango, glib, ltdl, cairo).
set -eu

build=$1
jobs=${2:-$(nproc 2>/dev/null || echo 1)}
here=$(cd "$(dirname "$0")" && pwd)
skip=${VALGRIND_SKIP-"test_model_sweep
    test_table
    test_brdf
    test_sample_table
    test_pbrt
    test_astm
    test_csv
    test_oom
    test_cli_matrix
    report_calibrate/covers_a_known_material_as_calibrate_says
    test_uncertainty
    test_coverage
    test_before
    intervals/cover_under_relative_noise_and_the_max_objective
    intervals/cover_under_absolute_noise_and_the_max_objective
    intervals/cover_under_absolute_noise_and_the_scale_objective
    intervals/cover_under_relative_noise_and_the_log_objective
    intervals/the_objectives_own_profile_undercovers_under_max
    intervals/the_bootstrap_covers_under_relative_noise_and_max
    intervals/the_bootstrap_covers_under_absolute_noise_and_max
    cli_analysis/results_do_not_depend_on_the_thread_count
    grid/study_path_finds_the_plain_optimum_on_all_61_samples
    grid/round_trip_recovers_every_model_exactly_at_grid_values
    wno_r/the_engines_tables_interpolate_the_rule_to_2e_10
    test_refine
    neyman/the_default_intervals_cover_where_the_F_threshold_falls_short
    neyman/every_parameters_construction_covers_there_too
    neyman/agrees_with_the_F_threshold_where_the_likelihood_is_regular
    bk/every_variant_is_finite_and_non_negative_on_the_closed_hemisphere
    bk/vernold_harvey_and_fresnel_variants_peak_in_the_forward_plane
    bk/original_beckmann_peaks_at_specular_below_the_slope_threshold
    oren_nayar/is_finite_and_non_negative_everywhere_for_every_rho_and_sigma
    determinism/every_model_on_every_sample_gives_byte_identical_outputs
    main_job/runs_from_a_bare_clone_with_the_curet_files_fetched_and_verified
    merl/the_lookup_finds_the_cell_of_its_half_and_difference_angles
    merl/swapping_incidence_and_view_finds_the_same_cell
    merl/every_valid_cell_gives_its_centre_which_maps_back_to_it
    merl/models_are_fitted_back_exactly_at_cell_centres
    merl/models_are_fitted_back_within_the_lookup_error_elsewhere
    merl/an_all_cells_table_is_fitted_back_exactly
    format/a_merl_table_needs_its_configurations
    degrees/random_angles_round_trip_bit_for_bit_in_at_most_17_digits
    degrees/the_writer_uses_the_fewest_digits
    convert/cornell_files_as_csv_read_back_identically
    convert/cornell_files_as_astm_read_back_identically
    inputs/every_cornell_file_runs_through_compare_report_and_rank
    inputs/channel_each_gives_one_set_of_rows_per_wavelength
    inputs/cornell_as_brdf_csv_and_astm_gives_identical_fits
    report/gives_the_same_files_for_one_and_two_drawing_processes
    report/gives_byte_identical_outputs_when_run_twice
    cli/thread_count_does_not_change_the_outputs
    cli/all_61_samples_give_finite_results_for_every_model
    keep_scale/recovery_ngan_through_csv_and_cli
    keep_scale/recovery_cuberoot_and_log1p
    keep_scale/cornell_lambert_at_most_the_peers_e
    composite/recovery_ngan_through_csv_and_cli
    composite/cornell_every_fit_at_most_the_peers_e
    specular_options/recovery_ngan_through_csv_and_cli
    specular_options/separable_and_height_fits_differ
    composite/dense_recovery_through_the_subsample
    composite/cv_folds_fit_at_least_as_well_as_fresh_fits
    composite/cv_folds_with_the_gloss_peak_held_out
    composite/lafortune_fits_reach_the_truths_basin
    spec_intervals/a_profile_stays_inside_where_the_model_overflows
    specular_models/ggx_without_fresnel_conserves_energy
    specular_models/ward_gmd_is_bounded_and_ward_duer_is_not
    grid/round_trip_recovers_every_model_exactly_at_grid_values
    grid/study_results_do_not_depend_on_the_thread_count
    wno_r/the_engines_evaluation_is_the_quadrature_to_rounding
    wno_r/fits_its_own_curve_back_to_the_parameters
    test_stream
    cli_calibrate/writes_coverage_and_bias_of_every_fitted_parameter
    plane_abs/description_under_ngan
    spec_intervals/lambert_ggx_covers_at_the_cornell_geometry
    spec_intervals/lambert_ggx_and_ward_cover_at_random_geometry
    spec_intervals/the_robust_factor_mends_a_wrong_noise_model
    spec_intervals/as_covers_at_the_cornell_geometry
    spec_intervals/cornell_intervals_are_finite_and_hold_the_estimate
    spec_intervals/calibrate_runs_on_a_composite
    spec_intervals/calibrate_says_when_the_noise_power_is_at_its_bound
    joint/report_draws_every_channel_from_the_shared_shape
    report/writes_every_figure_valid_and_sized_as_the_page_says
    wno_r/is_finite_and_non_negative_over_the_hemisphere_and_domain
    wno_r/matches_gsls_adaptive_quadrature_to_1e_8_of_the_value
    report_calibrate/many_panels_are_split_into_figures_that_fit_a_page
    dispersion/krylon_blue_mean_index_is_a_binders
    spec_intervals/dense_profile_ends_are_roots_on_all_the_data"}

# run_one EXE: runs EXE under valgrind, writes its verdict line to
# BUILD/valgrind-NAME.verdict and its log to BUILD/valgrind-NAME.log.
run_one() {
    exe=$1
    name=$(basename "$exe")
    filter=""
    whole=0
    for s in $skip; do
        case $s in
        */*) filter="$filter|$s" ;;
        "$name") whole=1 ;;
        esac
    done
    verdict=$build/valgrind-$name.verdict
    if [ $whole -eq 1 ]; then
        echo "valgrind: $name skipped (VALGRIND_SKIP)" > "$verdict"
        return 0
    fi
    log=$build/valgrind-$name.log
    # --verbose: the log keeps each test's time under valgrind (what the
    # skip list above is weighed by)
    set -- "$exe" --jobs=1 --verbose
    [ -n "$filter" ] && set -- "$@" --filter="!(${filter#|})"
    # A report in a Criterion child does not reach the parent's exit status
    # (the child's error exit only marks nothing), so any valgrind line in
    # the log ("==PID== ...", printed only for errors and leaks under -q)
    # fails the run too.
    rc=0
    start=$(date +%s)
    valgrind -q --trace-children=yes --error-exitcode=99 \
        --trace-children-skip='/bin/*,/usr/bin/*' \
        --suppressions="$here/valgrind.supp" \
        --leak-check=full --show-leak-kinds=definite,indirect,possible \
        --errors-for-leak-kinds=definite,indirect,possible \
        "$@" > "$log" 2>&1 || rc=$?
    secs=$(($(date +%s) - start))
    if [ $rc -eq 0 ] && ! grep -q '^==[0-9]*==' "$log"; then
        echo "valgrind: $name ok ($(tail -n 1 "$log" | sed 's/.*Tested: \([0-9]*\).*/\1 tests/'), $secs s)" > "$verdict"
    else
        echo "valgrind: $name FAILED after $secs s (log: $log)" > "$verdict"
    fi
}

# JOBS at a time, each started as soon as one ends (xargs -P), each one by
# this script again (BF_VALGRIND_ONE=1: run_one of its third argument).
if [ "${BF_VALGRIND_ONE:-}" = 1 ]; then
    run_one "$3"
    exit 0
fi
for exe in "$build"/tests/test_*; do
    [ -x "$exe" ] && printf '%s\n' "$exe"
done | BF_VALGRIND_ONE=1 xargs -P "$jobs" -I{} sh "$0" "$build" 1 {} || true

status=0
for exe in "$build"/tests/test_*; do
    [ -x "$exe" ] || continue
    name=$(basename "$exe")
    verdict=$build/valgrind-$name.verdict
    if [ ! -f "$verdict" ]; then
        echo "valgrind: $name gave no verdict" >&2
        status=1
        continue
    fi
    if grep -q FAILED "$verdict"; then
        cat "$build/valgrind-$name.log" >&2
        cat "$verdict" >&2
        status=1
    else
        cat "$verdict"
    fi
    rm -f "$verdict"
done
exit $status
