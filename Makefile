# The two commands of wisp: `make demo` (install, build, render) and `make test`.
BUILD   ?= build
JOBS    ?= $(shell nproc)
CMAKE_FLAGS ?=

.PHONY: all deps configure build demo test test-asan bench format clean

all: build

deps:
	./scripts/install-deps

$(BUILD)/CMakeCache.txt:
	cmake -S . -B $(BUILD) -DCMAKE_BUILD_TYPE=Release $(CMAKE_FLAGS)

configure: deps $(BUILD)/CMakeCache.txt

build: configure
	cmake --build $(BUILD) -j $(JOBS)

# Until the render pipeline lands, the demo renders the sample drawings.
demo: build
	@mkdir -p out/demo
	@for f in data/drawings/*.xml data/drawings/external/*.xml; do \
	  n=$$(basename $$f .xml); \
	  $(BUILD)/bin/wisp diffuse $$f -o out/demo/$$n.png --stats out/demo/$$n.json || exit 1; \
	done
	@echo "demo: images written to $(CURDIR)/out/demo/"

test: build
	cd $(BUILD) && ctest --output-on-failure -j $(JOBS)

# Same suite under AddressSanitizer + UndefinedBehaviorSanitizer, in its own build folder.
test-asan: deps
	cmake -S . -B build-asan -DCMAKE_BUILD_TYPE=RelWithDebInfo -DWISP_SANITIZE=ON -DWISP_BUILD_BENCH=OFF
	cmake --build build-asan -j $(JOBS)
	cd build-asan && ASAN_OPTIONS=detect_leaks=1 UBSAN_OPTIONS=print_stacktrace=1 \
	  ctest --output-on-failure -j $(JOBS)

bench: build
	$(BUILD)/bin/wisp-bench all

format:
	clang-format -i $$(git ls-files '*.cpp' '*.hpp')

clean:
	rm -rf $(BUILD) build-asan out
