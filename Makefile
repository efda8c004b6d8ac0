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

# Sanitizer configuration: the same tests under ASan and UBSan.
asan: deps
	cmake -S . -B build-asan -DCMAKE_BUILD_TYPE=Debug -DPMECH_SANITIZE=ON
	cmake --build build-asan -j $(JOBS)
	cd build-asan && ASAN_OPTIONS=detect_leaks=1 LSAN_OPTIONS=suppressions=$(CURDIR)/tools/lsan.supp ctest --output-on-failure -j $(JOBS) -LE fuzz

bench: build
	sh bench/run.sh $(BUILD)/pmech --write

clean:
	rm -rf $(BUILD) build-asan

# Runs the verification tests and rewrites docs/verification.md.
verify: build
	sh tools/verify.sh $(BUILD)

# Static analysis and the clang build: both must be silent.
lint: deps
	cppcheck --enable=warning,style,performance --inline-suppr --error-exitcode=1 -q \
	  --suppress=missingIncludeSystem -Iinclude -Isrc src
	CC=clang cmake -S . -B build-clang -DCMAKE_BUILD_TYPE=Release
	cmake --build build-clang -j $(JOBS)
