#!/usr/bin/env bash
# Runs every libFuzzer target (tests/fuzz) for a bounded time under
# AddressSanitizer and UndefinedBehaviorSanitizer; any finding fails.
#
#   scripts/fuzz.sh [SECONDS_PER_TARGET] [--only NAME] [--merge] [--no-build] [--jobs N]
#
# SECONDS_PER_TARGET  how long each target runs (default 30)
# --only NAME         one target: message_parser, http_request, ... (repeatable)
# --merge             afterwards add the inputs that reached new code to the
#                     seed corpus in tests/fuzz/corpus (otherwise it is only read)
# --no-build          use build/fuzz as it is
# --jobs N            targets run N at a time, each on a core of its own
#                     (default: the cores, nproc)
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
jobs=$(nproc)
while [ $# -gt 0 ]; do
  case "$1" in
    --only) only+=("$2"); shift 2 ;;
    --merge) merge=1; shift ;;
    --no-build) build_it=0; shift ;;
    --jobs)
      case "${2:-}" in ''|*[!0-9]*|0) echo "fuzz.sh: --jobs takes a count of 1 or more" >&2; exit 2 ;; esac
      jobs=$2; shift 2 ;;
    -h|--help) sed -n '2,18p' "$0" | sed 's/^# \{0,1\}//'; exit 0 ;;
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

# One target's run; its summary line goes to $run/summary and its exit
# status to $run/status, so that targets can run side by side.
run_target() {
  local name=$1
  local binary="$build/fuzz/fuzz_$name"
  local seeds="tests/fuzz/corpus/$name"
  local run="$build/fuzz-runs/$name"
  rm -rf "$run"
  mkdir -p "$run/corpus" "$run/findings"
  if [ -d "$seeds" ]; then cp -R "$seeds/." "$run/corpus/"; fi
  # A target's own flags (tests/fuzz/NAME.options, # comments) and dictionary.
  local flags=()
  if [ -f "tests/fuzz/$name.options" ]; then read -r -a flags <<< "$(sed 's/#.*//' "tests/fuzz/$name.options" | tr '\n' ' ')"; fi
  if [ -f "tests/fuzz/$name.dict" ]; then flags+=(-dict="tests/fuzz/$name.dict"); fi
  echo "fuzz.sh: $name for ${seconds} s ($(ls "$run/corpus" | wc -l) seeds)"
  local status=0
  "$binary" "$run/corpus" "${flags[@]}" -max_total_time="$seconds" -timeout="$per_input_timeout" \
    -rss_limit_mb="$rss_limit_mb" -print_final_stats=1 -artifact_prefix="$run/findings/" \
    > "$run/log" 2>&1 || status=$?
  local runs rate corpus
  runs=$(sed -n 's/^stat::number_of_executed_units: *//p' "$run/log" | tail -1)
  rate=$(sed -n 's/^stat::average_exec_per_sec: *//p' "$run/log" | tail -1)
  corpus=$(ls "$run/corpus" | wc -l)
  if [ "$status" -eq 0 ]; then
    printf '%-16s %8s runs %7s exec/s  corpus %4s  ok\n' "$name" "${runs:-?}" "${rate:-?}" "$corpus" > "$run/summary"
  else
    local found
    found=$(ls "$run/findings" 2>/dev/null | sed "s|^|$run/findings/|" | tr '\n' ' ')
    printf '%-16s %8s runs %7s exec/s  FOUND (exit %s): %s\n' "$name" "${runs:-?}" "${rate:-?}" "$status" \
      "${found:-see $run/log}" > "$run/summary"
    { echo "fuzz.sh: $name found a problem; the end of its log ($run/log):"
      grep -v '^#[0-9]' "$run/log" | tail -60
      echo "fuzz.sh: reproduce with $binary ${found:-INPUT}"; } > "$run/report"
  fi
  echo "$status" > "$run/status"
}

running=0
for name in "${targets[@]}"; do
  if [ "$running" -ge "$jobs" ]; then wait -n || true; running=$((running - 1)); fi
  run_target "$name" &
  running=$((running + 1))
done
wait

# In the targets' order, whatever order they ended in.
failed=0
summary=()
for name in "${targets[@]}"; do
  run="$build/fuzz-runs/$name"
  summary+=("$(cat "$run/summary" 2>/dev/null || echo "$name: no summary (see $run/log)")")
  if [ "$(cat "$run/status" 2>/dev/null || echo 1)" != 0 ]; then
    failed=1
    if [ -f "$run/report" ]; then cat "$run/report"; fi
  elif [ "$merge" = 1 ]; then
    seeds="tests/fuzz/corpus/$name"
    mkdir -p "$seeds"
    "$build/fuzz/fuzz_$name" -merge=1 "$seeds" "$run/corpus" > "$run/merge.log" 2>&1
    echo "fuzz.sh: $name: $(sed -n 's/.*MERGE-OUTER: \([0-9]*\) new files.*/\1/p' "$run/merge.log") inputs added to $seeds"
  fi
done

echo "fuzz.sh: ${seconds} s a target, ${jobs} at a time on $(nproc) cores"
printf '  %s\n' "${summary[@]}"
exit "$failed"
