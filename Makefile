# Makefile: one target per task; CMake does the work (STYLE §8).
#   make        install missing Debian packages, build into build/
#   make run    the main job: the full model comparison on the CURET data,
#               with every figure and out/report.html (builds only the
#               library and the CLI; fetches CURET's two files into the
#               per-user cache when they are not in CURET=DIR)
#   make rank   model selection (AIC, BIC, CV) over all 61 CURET samples
#   make report-all  the report for all 61 samples and every model
#   make test   build and run every test, plain and with ASan+UBSan
#   make bench  run the speed benchmarks, bench_study and bench_merl (never
#               part of the tests; the numpy baselines run when
#               /usr/bin/python3 has numpy, the numpy/scipy peer of the
#               analysis when it has scipy too)
#   make bench-glossy  the ten specular models on the five Cornell paints
#               (issue 17 item 11) against the scipy peer (bench_glossy)
#   make screenshot  open out/report.html in headless Chromium (installed if
#               missing), check every image loaded, save a screenshot
#   make fuzz   run every libFuzzer target for FUZZ_SECONDS each (clang)
#   make valgrind  run the test suite under valgrind (no leak, no error)
#   make coverage  build with gcov instrumentation into build-cov/, run the
#               test suite there and print the line and branch coverage of
#               src/ as the last line (gcovr; build-cov/coverage.txt has
#               the lines each file leaves uncovered); not part of make test

SHARED   ?= ../shared
CURET    ?= $(SHARED)/data/curet
REFERENCE ?= $(SHARED)/reference
# The study's Oren-Nayar inputs (the paper's Table 2), shipped in data/.
ON_PARAMS ?= data/oren_nayar_params.tsv
OUT      ?= out
# The CLI the main jobs run, and what they build first (RUN_DEPS= runs a
# CLI built elsewhere: the test of the main job on a bare clone does).
BRDFFIT  ?= $(BUILD)/brdffit
RUN_DEPS ?= cli
JOBS     ?= $(shell nproc 2>/dev/null || echo 2)
CMAKE_FLAGS ?=
FUZZ_SECONDS ?= 60
FUZZ_MAX_LEN ?= 4096

BUILD      = build
BUILD_ASAN = build-asan
BUILD_FUZZ = build-fuzz
BUILD_COV  = build-cov
CONFIGURE  = cmake -S . -DBF_SHARED_DIR="$(abspath $(SHARED))" \
             -DBF_CURET_DIR="$(abspath $(CURET))" \
             -DBF_REFERENCE_DIR="$(abspath $(REFERENCE))" $(CMAKE_FLAGS)

.PHONY: all deps build cli run rank report-all test test-plain test-asan asan bench bench-glossy \
        install format tidy clean screenshot fuzz fuzz-build valgrind \
        coverage

all: build

deps:
	@scripts/install-deps.sh

build: deps
	@$(CONFIGURE) -B $(BUILD) -DCMAKE_BUILD_TYPE=RelWithDebInfo >/dev/null
	@cmake --build $(BUILD) -j $(JOBS)

# Only what the main jobs need: the library and the CLI (no tests, no bench).
cli: deps
	@$(CONFIGURE) -B $(BUILD) -DCMAKE_BUILD_TYPE=RelWithDebInfo >/dev/null
	@cmake --build $(BUILD) -j $(JOBS) --target brdffit

# The main job: the paper's study with the analysis, every figure drawn by
# one process per core, report.html.
run: $(RUN_DEPS)
	data=$$(scripts/curet-data.sh "$(CURET)") && \
	$(BRDFFIT) report --data "$$data" --samples paper --stats \
	    --on-params "$(ON_PARAMS)" --out "$(OUT)" --threads 0

rank: $(RUN_DEPS)
	data=$$(scripts/curet-data.sh "$(CURET)") && \
	$(BRDFFIT) rank --data "$$data" --on-params "$(ON_PARAMS)" --out "$(OUT)"

# All 61 CURET samples, every model, with the analysis (ON where CURET's
# parameters are given): tables, ranking section and figures.
report-all: $(RUN_DEPS)
	data=$$(scripts/curet-data.sh "$(CURET)") && \
	$(BRDFFIT) report --data "$$data" --samples all --models all \
	    --stats --on-params "$(ON_PARAMS)" --out "$(OUT)-all" --threads 0

test: test-plain test-asan

test-plain: build
	cd $(BUILD) && ctest --output-on-failure -j $(JOBS)

asan: deps
	@$(CONFIGURE) -B $(BUILD_ASAN) -DCMAKE_BUILD_TYPE=Debug \
	    -DBF_SANITIZERS=ON >/dev/null
	@cmake --build $(BUILD_ASAN) -j $(JOBS)

test-asan: asan
	cd $(BUILD_ASAN) && ASAN_OPTIONS=detect_leaks=1:abort_on_error=1 \
	    UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1 \
	    ctest --output-on-failure -j $(JOBS)

screenshot: run
	scripts/screenshot.sh "$(OUT)/report.html" "$(OUT)/report-screenshot.png"

# libFuzzer targets (fuzz/): clang, ASan+UBSan, seeds from the real files.
fuzz-build:
	@scripts/install-deps.sh fuzz
	@CC=clang $(CONFIGURE) -B $(BUILD_FUZZ) -DBF_FUZZ=ON \
	    -DBF_BUILD_TESTS=OFF -DBF_BUILD_CLI=OFF \
	    -DCMAKE_BUILD_TYPE=RelWithDebInfo >/dev/null
	@cmake --build $(BUILD_FUZZ) -j $(JOBS)

fuzz: fuzz-build
	fuzz/run.sh $(BUILD_FUZZ) $(FUZZ_SECONDS) "$(CURET)" "$(REFERENCE)" \
	    $(FUZZ_MAX_LEN) $(JOBS)

# The plain build's test suite under valgrind (tests/valgrind.sh).
valgrind: build
	@scripts/install-deps.sh valgrind
	tests/valgrind.sh $(BUILD)

# gcov counts of the optimised build (RelWithDebInfo, as make build) for
# the whole suite but test_install (its consumers would need libgcov);
# a failing test fails the target. The summary covers src/ only.
coverage: deps
	@scripts/install-deps.sh coverage
	@$(CONFIGURE) -B $(BUILD_COV) -DCMAKE_BUILD_TYPE=RelWithDebInfo \
	    -DCMAKE_C_FLAGS=--coverage >/dev/null
	@cmake --build $(BUILD_COV) -j $(JOBS)
	@find $(BUILD_COV) -name '*.gcda' -delete
	cd $(BUILD_COV) && ctest -j $(JOBS) --timeout 3600 -E '^test_install$$' \
	    --output-on-failure >ctest.log || { tail -50 ctest.log; exit 1; }
	@gcovr -r . --object-directory $(BUILD_COV) --filter 'src/' \
	    -o $(BUILD_COV)/coverage.txt --print-summary | awk \
	    '{gsub(/[()]/, "")} \
	     /^lines:/ {l = $$2 " (" $$3 " of " $$6 " lines)"} \
	     /^branches:/ {b = $$2 " (" $$3 " of " $$6 " branches)"} \
	     END {print "coverage of src/ by the test suite: " l ", " b}'

bench: build
	@scripts/install-deps.sh bench
	OMP_WAIT_POLICY=passive $(BUILD)/bench/bench_study --data "$(CURET)" --reference "$(REFERENCE)" \
	    --cli $(BUILD)/brdffit --numpy bench/numpy_baseline.py \
	    --peer ../shared/peers/rank_baseline.py
	OMP_WAIT_POLICY=passive $(BUILD)/bench/bench_merl --data "$(CURET)" \
	    --numpy bench/numpy_cells.py

# make bench-glossy: issue 17 item 11, the ten specular models on the five
# Cornell paints (whole compare, CPU and wall) against the scipy peer
bench-glossy: build
	@scripts/install-deps.sh bench
	OMP_WAIT_POLICY=passive $(BUILD)/bench/bench_glossy --cli $(BUILD)/brdffit \
	    --data ../shared/data/cornell-pbrt-v2 --peer ../shared/peers/glossy_peer.py

# make install [PREFIX=DIR] [DESTDIR=STAGE]: libraries, header, brdffit.pc,
# the CMake package, the CLI and its man page (default prefix /usr/local).
install: build
	cmake --install $(BUILD) $(if $(PREFIX),--prefix "$(PREFIX)")

# make format: clang-format (.clang-format) on the lines changed since the
# last commit, staged or not; the rest of each file keeps its hand layout.
format:
	@scripts/install-deps.sh format
	git clang-format --force --extensions c,h

tidy: build
	clang-tidy -p $(BUILD) src/*.c src/*/*.c cli/*.c

clean:
	rm -rf $(BUILD) $(BUILD_ASAN) $(BUILD_FUZZ)
