# pmech: the two commands a new user needs.
#   make demo   install what is missing (as root), build, run the default example
#   make test   install what is missing (as root), build, run every test
BUILD ?= build
JOBS ?= $(shell nproc 2>/dev/null || echo 2)
DEMO ?= examples/elastic_disks/case.json
PREFIX ?= /usr/local

.PHONY: all deps build test demo install asan fuzz bench clean verify lint

all: build

deps:
	@sh tools/install-deps.sh

$(BUILD)/CMakeCache.txt:
	cmake -S . -B $(BUILD) -DCMAKE_BUILD_TYPE=Release -DCMAKE_INSTALL_PREFIX=$(PREFIX)

build: deps $(BUILD)/CMakeCache.txt
	cmake --build $(BUILD) -j $(JOBS)

test: build
	cd $(BUILD) && ctest --output-on-failure -j $(JOBS)

demo: build
	@sh tools/demo.sh $(BUILD)/pmech $(DEMO)

# PREFIX is read at install time (not only at the first configure), so `make install PREFIX=DIR` always
# installs into DIR
install: build
	cmake --install $(BUILD) --prefix $(PREFIX)

# Sanitizer configuration: every test under ASan and UBSan, the fuzz tests included (the corpus replayed
# by the gcc build, libFuzzer in its clang build); the verification tests that take minutes in a release
# build run their small variants (PMECH_VERIFY_SMALL, docs/testing.md).
asan: deps
	cmake -S . -B build-asan -DCMAKE_BUILD_TYPE=Debug -DPMECH_SANITIZE=ON
	cmake --build build-asan -j $(JOBS)
	cd build-asan && PMECH_VERIFY_SMALL=1 ASAN_OPTIONS=detect_leaks=1 \
	  LSAN_OPTIONS=suppressions=$(CURDIR)/tools/lsan.supp ctest --output-on-failure -j $(JOBS)

# Fuzzing (docs/testing.md): clang builds the library instrumented for libFuzzer with ASan and UBSan in
# build-fuzz, then every target runs for FUZZ_SECONDS; failing inputs land in build-fuzz/fuzz-crashes.
FUZZ_SECONDS ?= 600
FUZZ_TARGETS ?= case_sim gmsh driver
fuzz: deps
	cmake -S . -B build-fuzz -DCMAKE_C_COMPILER=clang -DCMAKE_BUILD_TYPE=Debug -DPMECH_FUZZ=ON
	cmake --build build-fuzz -j $(JOBS) --target fuzz_targets
	sh tools/fuzz.sh build-fuzz $(FUZZ_SECONDS) $(FUZZ_TARGETS)

bench: build
	sh bench/run.sh $(BUILD)/pmech --write

clean:
	rm -rf $(BUILD) build-asan build-fuzz

# Runs the verification tests and rewrites docs/verification.md.
verify: build
	JOBS=$(JOBS) sh tools/verify.sh $(BUILD)

# Static analysis and the clang build: both must be silent.
lint: deps
	cppcheck --enable=warning,style,performance --inline-suppr --error-exitcode=1 -q \
	  --suppress=missingIncludeSystem -Iinclude -Isrc src
	CC=clang cmake -S . -B build-clang -DCMAKE_BUILD_TYPE=Release
	cmake --build build-clang -j $(JOBS)
