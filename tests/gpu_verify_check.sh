#!/usr/bin/env bash
# scripts/gpu-verify --small --jobs 2 on this build and whatever Vulkan device there is (lavapipe in CI): every
# case renders both ways and agrees, in the list's order; and scripts/exrdiff.py, which it relies on, reports a
# difference it is given and refuses files it cannot compare. Exit 77 (skipped) without a Vulkan device or python3.
# Arguments: source dir, build dir, scratch dir.
source "$(dirname "$0")/check_common.sh"
check_setup gpu_verify_check "$@"
command -v python3 >/dev/null || { echo "gpu_verify_check: no python3"; exit 77; }
skip_without_vulkan

"$src/scripts/gpu-verify" "$tool" --small --jobs 2 >"$work/out" 2>&1 || fail "gpu-verify failed: $(cat "$work/out")"
[ "$(grep -c 'values > 2e-3: 0 of' "$work/out")" -eq 29 ] || fail "expected 29 planes within 2e-3: $(cat "$work/out")"
# Its cases run side by side (--jobs, two at least here), yet print in the list's order, each bent-normal line
# under its own case.
sed -n "/^done <<'LIST'$/,/^LIST$/p" "$src/scripts/gpu-verify" | sed '1d;$d' |
  sed 's/1280x720/128x72/g; s/1333x757/133x77/g; s/ | \(.*\)/ (GPU: \1)/' >"$work/cases"
[ "$(wc -l <"$work/cases")" -eq 24 ] || fail "read $(wc -l <"$work/cases") cases from gpu-verify's list, not 24"
grep -v '^  bent normal' "$work/out" | sed 's/ *mean |diff|.*//' | diff "$work/cases" - >"$work/order" ||
  fail "gpu-verify's lines are not in its list's order: $(cat "$work/order")"
[ "$(grep -A1 -e '--ao-output all' -e '--ao-output bent-normal' "$work/out" | grep -c '^  bent normal')" -eq 5 ] ||
  fail "not a bent-normal line under each case with bent normals: $(cat "$work/out")"
if "$src/scripts/gpu-verify" "$tool" --jobs 0 >"$work/jobs" 2>&1; then fail "gpu-verify ran with --jobs 0"; fi
grep -q "jobs needs a whole number" "$work/jobs" || fail "gpu-verify --jobs 0: $(cat "$work/jobs")"
grep -q "(GPU: --gpu-packed-normals --gpu-packed-output)" "$work/out" || fail "no case with the packed formats: $(cat "$work/out")"
grep -q "(GPU: --gpu-packed-normals --gpu-packed-output --gpu-fused-temporal)" "$work/out" ||
  fail "no case with the fused spatio-temporal pass: $(cat "$work/out")"
grep -q "ao alchemy (GPU: --gpu-packed-normals --gpu-tiled-blur)" "$work/out" || fail "no Alchemy case with packed normals: $(cat "$work/out")"

# exrdiff: a known difference between two AO planes of different scenes, then two refusals.
"$tool" render plane --size 16x8 --ao gtao -q -o "$work/a.png" --aov-dir "$work/a" >/dev/null
"$tool" render corner --size 16x8 --ao gtao -q -o "$work/b.png" --aov-dir "$work/b" >/dev/null
line=$(python3 "$src/scripts/exrdiff.py" "$work/a/ao.exr" "$work/b/ao.exr" planes)
case "$line" in planes*"values > 2e-3: "[1-9]*" of 128") ;; *) fail "plane against corner: $line" ;; esac
line=$(python3 "$src/scripts/exrdiff.py" "$work/a/ao.exr" "$work/a/ao.exr" same)
case "$line" in same*"max 0.00e+00"*"values > 2e-3: 0 of 128") ;; *) fail "a plane against itself: $line" ;; esac
if python3 "$src/scripts/exrdiff.py" "$work/a/ao.exr" "$work/a/normal.exr" 2>"$work/err"; then fail "ao against normals compared"; fi
grep -q "differ in channels or size" "$work/err" || fail "$(cat "$work/err")"
head -c 100 "$work/a/ao.exr" >"$work/cut.exr"
if python3 "$src/scripts/exrdiff.py" "$work/a/ao.exr" "$work/cut.exr" 2>"$work/err"; then fail "a cut file compared"; fi
grep -q "cut.exr" "$work/err" || fail "the error does not name the file: $(cat "$work/err")"
echo "gpu_verify_check: ok"
