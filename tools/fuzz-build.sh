#!/bin/sh
# Builds the libFuzzer targets for ctest (test fuzz.build): a clang build of the whole library with
# libFuzzer's coverage counters, ASan and UBSan (-DPMECH_FUZZ=ON) in BUILD_DIR. Without clang or its
# libFuzzer runtime it says so and builds nothing; the fuzz.<target> tests are then skipped.
# usage: tools/fuzz-build.sh SOURCE_DIR BUILD_DIR
set -eu
src=$1 dir=$2
if ! command -v clang >/dev/null 2>&1; then
  echo "fuzz: clang is not installed (tools/install-deps.sh installs it): no libFuzzer targets, fuzzing skipped"
  exit 0
fi
probe=$(mktemp -d)
trap 'rm -rf "$probe"' EXIT
printf 'int LLVMFuzzerTestOneInput(const unsigned char *d, unsigned long n) { return d && n; }\n' >"$probe/p.c"
if ! clang -fsanitize=fuzzer,address,undefined "$probe/p.c" -o "$probe/p" >"$probe/log" 2>&1; then
  echo "fuzz: clang cannot link libFuzzer (Debian package libclang-rt-dev): fuzzing skipped"
  cat "$probe/log"
  exit 0
fi
jobs=$(nproc 2>/dev/null || echo 2)
mkdir -p "$dir"
cmake -S "$src" -B "$dir" -DCMAKE_C_COMPILER=clang -DCMAKE_BUILD_TYPE=Debug -DPMECH_FUZZ=ON >"$dir/configure.log" 2>&1 ||
  { cat "$dir/configure.log"; exit 1; }
cmake --build "$dir" -j "$jobs" --target fuzz_targets
