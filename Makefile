# bodyrec: `make run` and `make test` set everything up on a fresh Debian 12 machine.
BUILD    ?= build
JOBS     ?= $(shell nproc)
OUT      ?= out
VTEST    ?= /usr/share/doc/opencv-doc/examples/data/vtest.avi
CMAKE_FLAGS ?=
BIN      := $(BUILD)/bin/bodyrec

.PHONY: all deps configure build run test test-data bench clean

all: build

deps:
	@scripts/install-deps

$(BUILD)/CMakeCache.txt:
	cmake -S . -B $(BUILD) -DCMAKE_BUILD_TYPE=Release -DBODYREC_WERROR=ON $(CMAKE_FLAGS)

configure: $(BUILD)/CMakeCache.txt

build: deps configure
	cmake --build $(BUILD) -j $(JOBS)

# The main job on the built-in default input (vtest.avi from opencv-doc).
run: build
	@mkdir -p $(OUT)
	$(BIN) detect $(VTEST) --jsonl $(OUT)/detect.jsonl --mot $(OUT)/detect.mot.txt --annotate $(OUT)/detect.avi
	@echo "bodyrec: wrote $(OUT)/detect.jsonl, $(OUT)/detect.mot.txt and the annotated video $(OUT)/detect.avi"

# The whole suite; tests labelled `data` skip with a message when ../shared/datasets is absent.
test: build
	cd $(BUILD) && ctest --output-on-failure -j $(JOBS)

bench: build
	@for b in $(BUILD)/bin/*_bench; do echo "== $$b"; $$b --benchmark_counters_tabular=true || exit 1; done

clean:
	rm -rf $(BUILD)
