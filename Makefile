# The two commands of wisp: `make demo` (install, build, render) and `make test`.
BUILD   ?= build
JOBS    ?= $(shell nproc)
CMAKE_FLAGS ?=

.PHONY: all deps configure build demo test test-asan fuzz bench format format-check clean

all: build

deps:
	./scripts/install-deps

$(BUILD)/CMakeCache.txt:
	cmake -S . -B $(BUILD) -DCMAKE_BUILD_TYPE=Release $(CMAKE_FLAGS)

configure: deps $(BUILD)/CMakeCache.txt

build: configure
	cmake --build $(BUILD) -j $(JOBS)

# The main job on the default scene (simulate, render every frame, video, contact sheet), plus
# the diffusion-curve drawings of data/drawings/.
demo: build
	$(BUILD)/bin/wisp render data/scenes/default.json -o out/demo
	@mkdir -p out/demo/drawings
	@for f in data/drawings/*.xml data/drawings/external/*.xml; do \
	  n=$$(basename $$f .xml); \
	  $(BUILD)/bin/wisp diffuse $$f -o out/demo/drawings/$$n.png || exit 1; \
	done
	@echo "demo: frames, preview.mp4, contact.png and stats.json in $(CURDIR)/out/demo/"
	@echo "demo: diffusion-curve drawings in $(CURDIR)/out/demo/drawings/"

test: build format-check
	cd $(BUILD) && ctest --output-on-failure -j $(JOBS)

# Same suite under AddressSanitizer + UndefinedBehaviorSanitizer, in its own build folder.
test-asan: deps
	cmake -S . -B build-asan -DCMAKE_BUILD_TYPE=RelWithDebInfo -DWISP_SANITIZE=ON -DWISP_BUILD_BENCH=OFF
	cmake --build build-asan -j $(JOBS)
	cd build-asan && ASAN_OPTIONS=detect_leaks=1 UBSAN_OPTIONS=print_stacktrace=1 \
	  LSAN_OPTIONS=suppressions=$(CURDIR)/tests/lsan.supp \
	  ctest --output-on-failure -j $(JOBS)

# Every fuzz target (tests/fuzz, docs/robustness.md) for FUZZ_SECONDS each, one after the other,
# built with clang, libFuzzer, ASan and UBSan in build-fuzz/ (needs Debian's clang and
# libfuzzer-14-dev). New inputs go to build-fuzz/corpus/<target>; a crash stops the run and is
# saved as build-fuzz/crash-<target>-*: add it to tests/fuzz/corpus/<target> once fixed.
FUZZ_SECONDS ?= 600
FUZZ_TARGETS = scene_json style_json strand_json scenexml curvesetxml hair_file obj wsim ramp_png frame
fuzz:
	cmake -S . -B build-fuzz -DCMAKE_BUILD_TYPE=RelWithDebInfo -DCMAKE_CXX_COMPILER=clang++ \
	  -DWISP_FUZZ=ON -DWISP_WERROR=OFF -DWISP_BUILD_BENCH=OFF
	cmake --build build-fuzz -j $(JOBS) --target fuzz_all
	@for t in $(FUZZ_TARGETS); do \
	  mkdir -p build-fuzz/corpus/$$t; \
	  echo "fuzz: $$t for $(FUZZ_SECONDS) s"; \
	  build-fuzz/bin/fuzz_$$t -max_total_time=$(FUZZ_SECONDS) -timeout=20 -rss_limit_mb=4096 \
	    -print_final_stats=1 -artifact_prefix=build-fuzz/crash-$$t- \
	    build-fuzz/corpus/$$t tests/fuzz/corpus/$$t || exit 1; \
	done

bench: build
	$(BUILD)/bin/wisp-bench all

# Every C++ file tracked or new (not ignored) in the repo, formatted by .clang-format.
SOURCES = $(shell git ls-files --cached --others --exclude-standard '*.cpp' '*.hpp')

format:
	clang-format -i $(SOURCES)

# Fails, naming the files, when any would change under `make format`.
format-check: deps
	@clang-format --dry-run --Werror $(SOURCES) 2>&1 | grep -o '^[^:]*\.[ch]pp' | sort -u \
	  | sed 's/^/format-check: needs clang-format: /' | grep . && exit 1 || true

clean:
	rm -rf $(BUILD) build-asan build-fuzz out
