#!/usr/bin/env bash
# Screens' own fields: can every screen show a field generated for it alone
# (the generator's 64 x 36 binary fields, one seed per screen) without the
# detector reading worse than on the shipped b4-64x36, and does a requester
# looking for one screen's field ever take a point from another's?
#
#   scripts/bench-screen-fields.sh [BUILD_DIR] [FIELDS] [FRAMES] [OUT] [PAIRS]
#
# FIELDS (default 20) fields of seeds 1001.. are generated and verified; each,
# and the shipped field, goes through the detector benchmark on the tuning and
# the held-out set (general, perspective and low light; opacity 0.15 and 0.3;
# 640 x 480; FRAMES frames each, default 40). Then, for PAIRS screens
# (default FIELDS), field i is looked for on frames of screen i + 1 (the
# last screen's frames with the first field), on both sets: every frame
# found there is a wrong take, and every frame the detector says shows
# another field ("another field") is one where the requester can tell the
# user so. Last, the first field is looked for on the pages alone (opacity
# 0.001, no field to see): a frame said to show another field there would be
# a false "another screen". The summary goes to
# OUT/screen_fields.md and .json (default docs/benchmarks).
set -euo pipefail
build=${1:-build/release}
fields=${2:-20}
frames=${3:-40}
out=${4:-docs/benchmarks}
pairs=${5:-$fields}
bench="$build/tests/umf_benchmark"
tool="$build/bin/umf-field"
work=$(mktemp -d /tmp/umf-screen-fields-XXXXXX)
trap 'rm -rf "$work"' EXIT
common=(--no-aruco --no-video --pulse-frames 0 --frames "$frames" --categories general,perspective,low_light
        --resolutions 640x480 --opacities 0.15,0.3 --threads "$(nproc)")
started=$(date +%s)

for i in $(seq "$fields"); do
  seed=$((1000 + i))
  "$tool" generate --width 64 --height 36 --window 4 --colors 2 --seed "$seed" --quiet --out "$work/screen-$i.json" >/dev/null
  "$tool" verify "$work/screen-$i.json" >/dev/null || { echo "field of seed $seed does not verify"; exit 1; }
done
echo "generated and verified $fields fields" >&2

run() {  # NAME FIELD [SHOWN [MORE...]]
  local name=$1 field=$2 shown=${3:-}
  shift $(( $# < 3 ? $# : 3 ))
  "$bench" "${common[@]}" "$@" --field "$field" ${shown:+--shown-field "$shown"} --out "$work/$name/tuning" 2>/dev/null
  "$bench" --set heldout "${common[@]}" "$@" --field "$field" ${shown:+--shown-field "$shown"} --out "$work/$name/heldout" 2>/dev/null
  echo "$name done after $(( $(date +%s) - started )) s" >&2
}
run shipped b4-64x36.json
for i in $(seq "$fields"); do run "own-$i" "$work/screen-$i.json"; done
for i in $(seq "$pairs"); do run "cross-$i" "$work/screen-$i.json" "$work/screen-$(( i % fields + 1 )).json"; done
run page-alone "$work/screen-1.json" "" --opacities 0.001

mkdir -p "$out"
python3 - "$work" "$fields" "$frames" "$out" "$(( $(date +%s) - started ))" "$pairs" <<'PY'
import json, os, statistics, sys
work, n, frames, out, seconds = sys.argv[1], int(sys.argv[2]), int(sys.argv[3]), sys.argv[4], int(sys.argv[5])
pairs = int(sys.argv[6])

def load(name, kind):
    path = os.path.join(work, name, kind, 'detector.json' if kind == 'tuning' else 'heldout.json')
    configs = json.load(open(path))['configurations']
    umf = [c['methods']['umf'] for c in configs]
    reasons = {}
    for u in umf:
        for r, k in u.get('reasons', {}).items(): reasons[r] = reasons.get(r, 0) + k
    ms = [u['ms_per_frame']['median'] for u in umf if u.get('ms_per_frame', {}).get('median') is not None]
    return {'evaluated': sum(u['evaluated'] for u in umf), 'found': sum(u['found'] for u in umf),
            'success': sum(u['success'] for u in umf), 'false': sum(u['false_location'] for u in umf),
            'reasons': reasons, 'another': reasons.get('another field', 0), 'ms': ms}

pct = lambda a, b: 100.0 * a / b if b else float('nan')
summary = {'fields': n, 'pairs': pairs, 'frames_per_configuration': frames, 'wall_s': seconds, 'sets': {}}
lines = [f'# Screens\' own fields', '',
         f'`scripts/bench-screen-fields.sh build/release {n} {frames} {out} {pairs}` on {os.cpu_count()} cores, {seconds / 60:.0f} min. '
         f'{n} generated 64 x 36 binary fields (4 x 4 windows, seeds 1001-{1000 + n}) against the shipped b4-64x36; '
         'general, perspective and low light at opacity 0.15 and 0.3, 640 x 480, '
         f'{frames} frames each, per set.', '',
         '| set | shipped: success | own fields: success pooled | per field: min / median / max | wrong places: shipped / own |',
         '|---|---|---|---|---|']
for kind in ('tuning', 'heldout'):
    shipped = load('shipped', kind)
    own = [load(f'own-{i}', kind) for i in range(1, n + 1)]
    cross = [load(f'cross-{i}', kind) for i in range(1, pairs + 1)]
    per = [pct(o['success'], o['evaluated']) for o in own]
    pooled = pct(sum(o['success'] for o in own), sum(o['evaluated'] for o in own))
    wrong = sum(o['false'] for o in own)
    cross_found = sum(c['found'] for c in cross)
    cross_frames = sum(c['evaluated'] for c in cross)
    cross_reasons = {}
    for c in cross:
        for r, k in c['reasons'].items(): cross_reasons[r] = cross_reasons.get(r, 0) + k
    page = load('page-alone', kind)
    median_ms = lambda runs: statistics.median([m for r in runs for m in r['ms']]) if any(r['ms'] for r in runs) else float('nan')
    summary['sets'][kind] = {'shipped_success_pct': pct(shipped['success'], shipped['evaluated']),
                             'shipped_wrong_places': shipped['false'],
                             'own_success_pct_pooled': pooled, 'own_success_pct_per_field': per,
                             'own_wrong_places': wrong, 'own_said_another': sum(o['another'] for o in own),
                             'own_frames': sum(o['evaluated'] for o in own), 'own_median_ms': median_ms(own),
                             'another_screen_frames': cross_frames,
                             'another_screen_found': cross_found, 'another_screen_reasons': cross_reasons,
                             'another_screen_said': cross_reasons.get('another field', 0),
                             'another_screen_median_ms': median_ms(cross),
                             'page_alone_frames': page['evaluated'], 'page_alone_said_another': page['another']}
    lines.append(f'| {kind} | {pct(shipped["success"], shipped["evaluated"]):.1f} % of {shipped["evaluated"]} | '
                 f'{pooled:.1f} % of {sum(o["evaluated"] for o in own)} | {min(per):.1f} / {statistics.median(per):.1f} / '
                 f'{max(per):.1f} % | {shipped["false"]} / {wrong} |')
lines += ['', f'Another screen: field i looked for on frames of screen i + 1, for {pairs} screens. '
          '"Said another field": the search failed after a grid under the aim read as a field but not as this one '
          '(what the requester turns into "This is another screen"). Own screen: the same, wrongly, on frames of '
          'the paired screen; page alone: on the pages with no field to see (opacity 0.001). Times: the median '
          'of the configurations\' median detection times.', '',
          '| set | frames | points taken (wrong takes) | said another field | median ms | own screen: said another field / median ms | page alone: said another field | why the others were not found |',
          '|---|---|---|---|---|---|---|---|']
for kind, s in summary['sets'].items():
    why = ', '.join(f'{r}: {k}' for r, k in sorted(s['another_screen_reasons'].items(), key=lambda x: -x[1]))
    lines.append(f'| {kind} | {s["another_screen_frames"]} | {s["another_screen_found"]} | '
                 f'{s["another_screen_said"]} ({pct(s["another_screen_said"], s["another_screen_frames"]):.1f} %) | '
                 f'{s["another_screen_median_ms"]:.1f} | {s["own_said_another"]} of {s["own_frames"]} / {s["own_median_ms"]:.1f} | '
                 f'{s["page_alone_said_another"]} of {s["page_alone_frames"]} | {why} |')
open(os.path.join(out, 'screen_fields.md'), 'w').write('\n'.join(lines) + '\n')
json.dump(summary, open(os.path.join(out, 'screen_fields.json'), 'w'), indent=2)
print('\n'.join(lines))
PY
