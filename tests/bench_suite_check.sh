#!/usr/bin/env bash
# scripts/bench-gpu-suite on this build, at a tiny size on whatever Vulkan device there is (lavapipe in CI):
# the ten JSON files, each with its variant's flags, and the internals folder; FLAGS after -- reach every run; a failing run stops
# the suite with a non-zero exit and leaves no JSON of its own. Exit 77 (skipped) without a Vulkan device.
# Arguments: source dir, build dir, scratch dir.
source "$(dirname "$0")/check_common.sh"
check_setup bench_suite_check "$@"
skip_without_vulkan

tiny=(--sizes 24x16 --frames 2 --warmup 0 --inputs 1)
"$src/scripts/bench-gpu-suite" "$tool" "$work/out" -- "${tiny[@]}" 2>"$work/log" || fail "the suite failed: $(cat "$work/log")"
expect() {  # file, then the text each must hold
  local file=$work/out/$1
  shift
  [ -s "$file" ] || fail "$file is missing"
  for needle in "$@"; do grep -q -- "$needle" "$file" || fail "$file lacks $needle"; done
}
expect default.json '"bent_normals": true' '"gtao_sampling": "planar"' '"case": "alchemy"' '"width": 24' '"frames": 2'
expect ao.json '"bent_normals": false' '"gtao_sampling": "planar"' '"case": "gtao-temporal-half"' '"case": "gtao-half"'
expect ao-nearest.json '"bent_normals": false' '"gtao_sampling": "nearest"' 'nearest-pixel samples'
expect ao-mip.json '"bent_normals": false' '"gtao_sampling": "mip"' ', depth MIP samples'
expect ao-planar-mip.json '"bent_normals": false' '"gtao_sampling": "planar-mip"' 'planar + depth MIP samples'
expect ao-planar-nearest.json '"bent_normals": false' '"gtao_sampling": "planar-nearest"' 'planar samples within 14 px'
expect ao-lightest.json '"packed_history": true' '"keep_previous_depth": true' '"case": "gtao-temporal"' '"case": "gtao-temporal-grid"'
if grep -q '"case": "alchemy"' "$work/out/ao-lightest.json"; then fail "ao-lightest ran more than the temporal cases"; fi
expect ao-half-2d.json '"half_blur": "2d"' '"case": "gtao-half"' '2-D bilateral there'
if grep -q '"case": "gtao"' "$work/out/ao-half-2d.json"; then fail "ao-half-2d ran more than the gtao-half case"; fi
expect ao-r025.json '"gtao_radius_m": 0.25' '"case": "gtao-spatial"' 'r 0.25 m'
if grep -q '"case": "gtao-temporal' "$work/out/ao-r025.json"; then fail "ao-r025 ran more than the GTAO cases"; fi
expect pipelines.json '"pipeline_statistics": ' '"gtao_sampling": "planar-nearest"' '"case": "alchemy"'
if grep -q '"pipeline_statistics": false' "$work/out/pipelines.json"; then
  expect pipelines.json 'VK_KHR_pipeline_executable_properties'
else
  expect pipelines.json '"pipelines": ' '"statistics": '
fi
[ -d "$work/out/internals" ] || fail "no internals folder"
[ "$(ls -A "$work/out" | wc -l)" -eq 11 ] || fail "expected exactly 10 files and internals/, got: $(ls -A "$work/out")"

# A bad flag fails the first run: non-zero exit, its one-line error, nothing written.
if "$src/scripts/bench-gpu-suite" "$tool" "$work/bad" -- --frames 0 2>"$work/err"; then fail "--frames 0 did not fail"; fi
grep -q -- "--frames" "$work/err" || fail "the error does not name --frames: $(cat "$work/err")"
[ -z "$(ls -A "$work/bad")" ] || fail "a failed run left files: $(ls -A "$work/bad")"
if "$src/scripts/bench-gpu-suite" "$work/no-such-tool" "$work/none" 2>"$work/err"; then fail "a missing tool did not fail"; fi
[ "$(wc -l <"$work/err")" -eq 1 ] || fail "expected a one-line error, got: $(cat "$work/err")"
echo "bench_suite_check: ok"
