#!/usr/bin/env bash
# CI after `make test`: the sanitizer build (the fuzz preset: clang with
# AddressSanitizer, UndefinedBehaviorSanitizer and libFuzzer), then in it the
# sanitizer test subset (the server, protocol, put, file parser and detector
# tests) with every fuzz target once over its seed corpus, then each fuzz
# target for a short time (scripts/fuzz.sh). Any finding fails.
#
#   scripts/ci-sanitizers.sh [FUZZ_SECONDS_PER_TARGET]   (default 30)
set -euo pipefail
cd "$(dirname "$0")/.."
seconds=${1:-30}

step_start=0
step() { step_start=$(date +%s); echo "ci-sanitizers: $1"; }
took() { echo "ci-sanitizers: $1 took $(( $(date +%s) - step_start )) s"; }

step "building the fuzz preset (clang, ASan + UBSan + libFuzzer)"
if [ ! -f build/fuzz/build.ninja ]; then cmake --preset fuzz; fi
cmake --build --preset fuzz
took "the build"

step "the sanitizer test subset and the seed corpora"
rm -f build/fuzz/Testing/Temporary/LastTestsFailed.log
ctest --preset fuzz || { scripts/ci-failures.sh build/fuzz 60; exit 1; }
took "the tests"

step "each fuzz target for ${seconds} s"
scripts/fuzz.sh "$seconds" --no-build
took "fuzzing"
