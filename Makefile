# bodyrec: `make run` and `make test` set everything up on a fresh Debian 12 machine.
BUILD    ?= build
JOBS     ?= $(shell nproc)
OUT      ?= out
VTEST    ?= /usr/share/doc/opencv-doc/examples/data/vtest.avi
CMAKE_FLAGS ?=
BIN      := $(BUILD)/bin/bodyrec

.PHONY: all deps configure build program run test test-asan test-data bench clean fuzz fuzz-build reid-model

all: build

deps:
	@scripts/install-deps

# Ninja when present (scripts/install-deps installs it; looked up after deps ran); ccache is picked up by
# CMakeLists.txt.
GENERATOR = $$(command -v ninja >/dev/null 2>&1 && echo -G Ninja)

$(BUILD)/CMakeCache.txt:
	cmake -S . -B $(BUILD) $(GENERATOR) -DCMAKE_BUILD_TYPE=Release -DBODYREC_WERROR=ON $(CMAKE_FLAGS)

configure: $(BUILD)/CMakeCache.txt

# Everything: the program, the tests and the benchmarks.
build: deps configure
	cmake --build $(BUILD) -j $(JOBS)

# The program alone (what `make run` needs).
program: deps configure
	cmake --build $(BUILD) -j $(JOBS) --target bodyrec

# The main job on the built-in default input (vtest.avi from opencv-doc): the whole groups pipeline.
# vtest.avi was recorded at 7 frames/s (its header says 10); the PETS calibration, when the datasets are
# beside the repository, puts distances and speeds on the ground plane.
DATA     ?= $(or $(BODYREC_DATA),../shared/datasets)
CALIB    := $(wildcard $(DATA)/pets09_s2l1/View_001.xml)
run: program
	@mkdir -p $(OUT)
	$(BIN) groups $(VTEST) --fps 7 $(if $(CALIB),--calibration $(CALIB)) --jsonl $(OUT)/groups.jsonl \
	    --mot $(OUT)/groups.mot.txt --annotate $(OUT)/groups.avi
	@echo "bodyrec: wrote $(OUT)/groups.jsonl, $(OUT)/groups.mot.txt and the annotated video $(OUT)/groups.avi"
	$(BIN) report $(OUT)/groups.jsonl --source $(VTEST) --out $(OUT)/report.html
	@echo "bodyrec: open $(abspath $(OUT)/report.html) in a browser (it embeds images of people)"

# The whole suite; tests labelled `data` skip with a message when ../shared/datasets is absent.
test: build
	cd $(BUILD) && ctest --output-on-failure -j $(JOBS)

# The whole suite again, built with AddressSanitizer + UndefinedBehaviorSanitizer (own build folder; any
# report fails the test that triggered it). ASAN_CTEST_ARGS selects tests, e.g. ASAN_CTEST_ARGS="-LE data";
# ASAN_EXCLUDE is a regular expression of tests to leave out (ctest -E). ASAN_TARGET=library_tests builds and
# runs only the library's own tests and the fuzz-input replay (what CI does, to stay within its budget).
ASAN_BUILD ?= build-asan
ASAN_TARGET ?= all
ASAN_CTEST_ARGS ?= $(if $(filter library_tests,$(ASAN_TARGET)),-L unit)
# library_tests does not build landmarks_test and cli_test: leave out their one-process suites too.
ASAN_EXCLUDE ?= $(if $(filter library_tests,$(ASAN_TARGET)),^(TrainedMaskNet|LandmarkCommands)\.AllInOneProcess$$)
test-asan: deps
	cmake -S . -B $(ASAN_BUILD) $(GENERATOR) -DCMAKE_BUILD_TYPE=RelWithDebInfo -DBODYREC_WERROR=ON -DBODYREC_SANITIZE=ON \
	    -DBODYREC_BUILD_BENCH=OFF $(CMAKE_FLAGS)
	cmake --build $(ASAN_BUILD) -j $(JOBS) --target $(ASAN_TARGET)
	cd $(ASAN_BUILD) && ASAN_OPTIONS=detect_leaks=1:abort_on_error=1:strict_string_checks=1 \
	    UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1 ctest --output-on-failure -j $(JOBS) $(ASAN_CTEST_ARGS) \
	    $(if $(ASAN_EXCLUDE),-E '$(ASAN_EXCLUDE)')

# libFuzzer + ASan + UBSan on every parser of outside input (clang; own build folder): each target runs
# FUZZ_SECONDS; crashes land in build-fuzz/crashes/<target>/ (see scripts/fuzz and docs/reliability.md).
FUZZ_BUILD ?= build-fuzz
FUZZ_SECONDS ?= 600
FUZZ_TARGETS ?=
# fuzz-build only builds the targets (CI: the fuzz build lists its parser sources by hand, so a moved
# function breaks it without any other build noticing).
fuzz-build: deps
	CC=clang CXX=clang++ cmake -S . -B $(FUZZ_BUILD) $(GENERATOR) -DCMAKE_BUILD_TYPE=RelWithDebInfo \
	    -DBODYREC_WERROR=ON -DBODYREC_FUZZ=ON $(CMAKE_FLAGS)
	cmake --build $(FUZZ_BUILD) -j $(JOBS)

fuzz: fuzz-build
	scripts/fuzz --build $(FUZZ_BUILD) --seconds $(FUZZ_SECONDS) $(FUZZ_TARGETS)

# The default re-identification metric (models/reid-default.yml.gz, models/README.md) trained again on VIPeR
# from the datasets, in place of the shipped file.
VIPER_ARGS = --root $(DATA)/viper --id-regex '^images/(\d{4})' --cam-regex '^images/\d{4}(\d{4})'
reid-model: program
	$(BIN) train-reid $(VIPER_ARGS) --out models/reid-default.yml.gz

bench: deps configure
	cmake --build $(BUILD) -j $(JOBS)
	@for b in $(BUILD)/bin/*_bench; do echo "== $$b"; $$b --benchmark_counters_tabular=true || exit 1; done

clean:
	rm -rf $(BUILD) $(ASAN_BUILD) build-fuzz
