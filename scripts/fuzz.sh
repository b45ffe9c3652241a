#!/usr/bin/env bash
# Runs every libFuzzer target (tests/fuzz) for a bounded time under
# AddressSanitizer and UndefinedBehaviorSanitizer; any finding fails.
#
#   scripts/fuzz.sh [SECONDS_PER_TARGET] [--only NAME] [--merge] [--no-build]
#
# SECONDS_PER_TARGET  how long each target runs (default 30)
# --only NAME         one target: message_parser, http_request, ... (repeatable)
# --merge             afterwards add the inputs that reached new code to the
#                     seed corpus in tests/fuzz/corpus (otherwise it is only read)
# --no-build          use build/fuzz as it is
#
# Each target starts from a copy of its seed corpus in
# build/fuzz/fuzz-runs/NAME/corpus; a crash, leak, UB, timeout or
# out-of-memory leaves the input under build/fuzz/fuzz-runs/NAME/findings/,
# which the summary names. Prints each target's executions per second.
set -euo pipefail
cd "$(dirname "$0")/.."

seconds=30
only=()
merge=0
build_it=1
while [ $# -gt 0 ]; do
  case "$1" in
    --only) only+=("$2"); shift 2 ;;
    --merge) merge=1; shift ;;
    --no-build) build_it=0; shift ;;
    -h|--help) sed -n '2,16p' "$0" | sed 's/^# \{0,1\}//'; exit 0 ;;
    ''|*[!0-9]*) echo "fuzz.sh: unknown argument '$1' (--help)" >&2; exit 2 ;;
    *) seconds=$1; shift ;;
  esac
done

build=build/fuzz
if [ "$build_it" = 1 ]; then
  if [ ! -f "$build/build.ninja" ]; then cmake --preset fuzz; fi
  cmake --build --preset fuzz
fi

# Every finding is fatal and reported with its stack.
export ASAN_OPTIONS="${ASAN_OPTIONS:-detect_leaks=1:detect_stack_use_after_return=1:strict_string_checks=1}"
export UBSAN_OPTIONS="${UBSAN_OPTIONS:-halt_on_error=1:print_stacktrace=1}"

targets=()
for binary in "$build"/fuzz/fuzz_*; do
  [ -x "$binary" ] || continue
  name=$(basename "$binary"); name=${name#fuzz_}
  if [ ${#only[@]} -gt 0 ] && [[ ! " ${only[*]} " == *" $name "* ]]; then continue; fi
  targets+=("$name")
done
if [ ${#targets[@]} -eq 0 ]; then
  echo "fuzz.sh: no fuzz target to run in $build/fuzz (cmake --build --preset fuzz; --only names one)" >&2
  exit 2
fi

# One input that runs this long is a finding (a hang); so is 2.5 GB of memory.
per_input_timeout=60
rss_limit_mb=2560

failed=0
summary=()
for name in "${targets[@]}"; do
  binary="$build/fuzz/fuzz_$name"
  seeds="tests/fuzz/corpus/$name"
  run="$build/fuzz-runs/$name"
  rm -rf "$run"
  mkdir -p "$run/corpus" "$run/findings"
  if [ -d "$seeds" ]; then cp -R "$seeds/." "$run/corpus/"; fi
  # A target's own flags (tests/fuzz/NAME.options, # comments) and dictionary.
  flags=()
  if [ -f "tests/fuzz/$name.options" ]; then read -r -a flags <<< "$(sed 's/#.*//' "tests/fuzz/$name.options" | tr '\n' ' ')"; fi
  if [ -f "tests/fuzz/$name.dict" ]; then flags+=(-dict="tests/fuzz/$name.dict"); fi
  echo "fuzz.sh: $name for ${seconds} s ($(ls "$run/corpus" | wc -l) seeds)"
  status=0
  "$binary" "$run/corpus" "${flags[@]}" -max_total_time="$seconds" -timeout="$per_input_timeout" \
    -rss_limit_mb="$rss_limit_mb" -print_final_stats=1 -artifact_prefix="$run/findings/" \
    > "$run/log" 2>&1 || status=$?
  runs=$(sed -n 's/^stat::number_of_executed_units: *//p' "$run/log" | tail -1)
  rate=$(sed -n 's/^stat::average_exec_per_sec: *//p' "$run/log" | tail -1)
  corpus=$(ls "$run/corpus" | wc -l)
  if [ "$status" -eq 0 ]; then
    summary+=("$(printf '%-16s %8s runs %7s exec/s  corpus %4s  ok' "$name" "${runs:-?}" "${rate:-?}" "$corpus")")
    if [ "$merge" = 1 ]; then
      mkdir -p "$seeds"
      "$binary" -merge=1 "$seeds" "$run/corpus" > "$run/merge.log" 2>&1
      echo "fuzz.sh: $name: $(sed -n 's/.*MERGE-OUTER: \([0-9]*\) new files.*/\1/p' "$run/merge.log") inputs added to $seeds"
    fi
  else
    failed=1
    found=$(ls "$run/findings" 2>/dev/null | sed "s|^|$run/findings/|" | tr '\n' ' ')
    summary+=("$(printf '%-16s %8s runs %7s exec/s  FOUND (exit %s): %s' "$name" "${runs:-?}" "${rate:-?}" "$status" "${found:-see $run/log}")")
    echo "fuzz.sh: $name found a problem; the end of its log ($run/log):"
    grep -v '^#[0-9]' "$run/log" | tail -60
    echo "fuzz.sh: reproduce with $binary ${found:-INPUT}"
  fi
done

echo "fuzz.sh: ${seconds} s a target, $(nproc) cores"
printf '  %s\n' "${summary[@]}"
exit "$failed"
