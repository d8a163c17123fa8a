#!/usr/bin/env bash
# scripts/gpu-candidates-report on gpu-waiting files made up here, with ratios on both sides of the noise: each
# candidate's verdict follows its frame ratios (in both timing files; one within the noise takes no side), the
# passes that moved are named, a gpu-verify past its bound and a register count that changed are reported, a
# missing file is "not run", and a corrupt file or a folder without timings fails in one line naming it.
# Arguments: source dir, build dir, scratch dir. Exit 77 (skipped) without python3.
source "$(dirname "$0")/check_common.sh"
check_setup gpu_candidates_report_check "$@"
command -v python3 >/dev/null || { echo "gpu_candidates_report_check: no python3"; exit 77; }
report=$src/scripts/gpu-candidates-report

python3 - "$work" <<'PY'
import json, os, sys
out = sys.argv[1]
def figures(rows):
    return [{"case": c, "size": s, "pass": p, "ms": ms} for c, s, p, ms in rows]
def variant(name, rows, spread=0.0):
    """A gpu-ab variant with these medians in each of its 3 rounds, and gpu-ab's frame_spread."""
    return {"name": name, "flags": [], "shaders": f"/x/{name}" if name != "embedded" else "",
            "median_ms": figures(rows), "rounds_ms": [figures(rows)] * 3, "frame_spread": spread}
def alchemy(frame, estimator, blur, size="1920x1080"):
    return [("alchemy", size, "frame", frame), ("alchemy", size, "alchemy", estimator), ("alchemy", size, "blur", blur)]
base = alchemy(0.1000, 0.0500, 0.0500) + alchemy(0.4000, 0.2000, 0.2000, "3840x2160")
json.dump({"device": "NVIDIA H100 80GB HBM3", "bench_flags": [], "rounds": 3, "variants": [
    variant("embedded", base),
    # The blur 10% faster at both sizes: the frame 0.95; a frame's rounds 5% apart.
    variant("fast", alchemy(0.0950, 0.0500, 0.0450) + alchemy(0.3800, 0.2000, 0.1800, "3840x2160"), 0.05),
    variant("slow", alchemy(0.1050, 0.0550, 0.0500) + alchemy(0.4200, 0.2200, 0.2000, "3840x2160")),
    variant("same", alchemy(0.1005, 0.0502, 0.0503) + alchemy(0.3990, 0.1995, 0.1995, "3840x2160")),
    variant("mixed", alchemy(0.0950, 0.0450, 0.0500) + alchemy(0.4200, 0.2200, 0.2000, "3840x2160")),
    # Faster at one size and within the noise at the other, or slower and within: a side all the same.
    variant("faster-once", alchemy(0.0950, 0.0450, 0.0500) + alchemy(0.4010, 0.2010, 0.2000, "3840x2160")),
    variant("slower-once", alchemy(0.1005, 0.0505, 0.0500) + alchemy(0.4200, 0.2200, 0.2000, "3840x2160")),
]}, open(os.path.join(out, "candidates-ab.json"), "w"))
grid = lambda f: [("gtao-temporal-grid", "3840x2160", "frame", f)]
json.dump({"device": "NVIDIA H100 80GB HBM3", "bench_flags": [], "rounds": 3, "variants": [
    variant("embedded", grid(0.170), 0.03), variant("fast", grid(0.160)), variant("only-grid", grid(0.150))]},
    open(os.path.join(out, "candidates-grid-ab.json"), "w"))
def stats(regs):
    return {"pipeline_statistics": True, "pipelines": [
        {"pipeline": p, "error": "", "executables": [{"name": "CS", "statistics": [
            {"name": "Register Count", "description": "", "value": float(n)}]}]} for p, n in regs.items()]}
json.dump(stats({"alchemy<0>": 27, "bilateral_separable<0,0>": 30}), open(os.path.join(out, "pipelines.json"), "w"))
json.dump(stats({"alchemy<0>": 27, "bilateral_separable<0,0>": 38}), open(os.path.join(out, "pipelines-fast.json"), "w"))
json.dump(stats({"alchemy<0>": 27, "bilateral_separable<0,0>": 30}), open(os.path.join(out, "pipelines-same.json"), "w"))
json.dump(stats({"alchemy<0>": 27}), open(os.path.join(out, "pipelines-target.json"), "w"))
json.dump(stats({"gtao<1>": 48}), open(os.path.join(out, "pipelines-same-target.json"), "w"))
# gpu-verify's lines: a plane past its bound ends with its mark (scripts/gpu-verify), which decides alone.
line = "demo --size 133x77 --ao alchemy      mean |diff| 1e-07  max 2e-05  values > 2e-3: {} of 10241{}\n"
mark = "  FAILS: more than 0.1% of values beyond 2e-3"
open(os.path.join(out, "verify-fast.txt"), "w").write(line.format(1, "") * 3)
open(os.path.join(out, "verify-slow.txt"), "w").write(line.format(0, "") + line.format(11, mark))
PY
"$report" "$work" >"$work/out" 2>&1 || fail "gpu-candidates-report failed: $(cat "$work/out")"
# BLOCK: the lines of candidate NAME's block (its verdict line to the next blank line).
block() { sed -n "/^$1: /,/^\$/p" "$work/out"; }
expect() {  # NAME PATTERN: a line of NAME's block matches PATTERN (grep -E)
  block "$1" | grep -Eq -- "$2" || fail "$1: no line matching '$2' in: $(block "$1")"
}
expect fast "^fast: pays$"
expect fast "alchemy 1080p: frame 0\.950 \(0\.0950 ms\); blur 0\.900$"
expect fast "alchemy 2160p: frame 0\.950 \(0\.3800 ms\); blur 0\.900$"
expect fast "gtao-temporal-grid 2160p: frame 0\.941 .*\(the spatio-temporal target's flags\)"
expect fast "candidates-ab: its rounds spread by up to 5\.0%"
expect fast "gpu-verify on the device: passed \(3 planes compared\)"
expect fast "registers: bilateral_separable<0,0> 30 -> 38$"
expect slow "^slow: loses$"
expect slow "gpu-verify on the device: FAILED \(1 of 2: demo --size 133x77 --ao alchemy\)"
expect same "^same: no change$"
expect same "registers: the same as the embedded shaders'"
expect same "registers in the target's frame: no pipeline in common"
expect same "gpu-verify on the device: not run"
expect mixed "^mixed: mixed$"
expect mixed "alchemy 1080p: frame 0\.950 \(0\.0950 ms\); alchemy 0\.900$"
expect faster-once "^faster-once: pays$"
expect slower-once "^slower-once: loses$"
# Timed in the target's configuration alone: its verdict comes from that file.
expect only-grid "^only-grid: pays$"
# No pass moved beyond the noise in `same`: its lines name none; nor do the other blocks list `embedded`.
block same | grep -q "blur 1\.0" && fail "same: a pass within the noise was named: $(block same)"
grep -q "^embedded:" "$work/out" && fail "the embedded shaders reported as a candidate: $(cat "$work/out")"
grep -q "^7 candidate(s)" "$work/out" || fail "not 7 candidates: $(head -1 "$work/out")"
# The baseline's own spread is said once per timing file, where it passes the noise (the grid file's 3%).
grep -q "^candidates-grid-ab: the embedded shaders' rounds spread by up to 3\.0%" "$work/out" ||
  fail "the embedded shaders' spread not reported: $(head -3 "$work/out")"
grep -q "^candidates-ab: the embedded shaders'" "$work/out" && fail "a spread within the noise reported: $(head -3 "$work/out")"
# --noise: with 0.06 the 5% changes are noise.
"$report" --noise 0.06 "$work" >"$work/out" 2>&1 || fail "--noise 0.06 failed: $(cat "$work/out")"
expect fast "^fast: no change$"
if "$report" --noise 2 "$work" >"$work/out" 2>&1; then fail "--noise 2 was taken"; fi
grep -q "noise must be in" "$work/out" || fail "--noise 2: $(cat "$work/out")"

# A corrupt file fails in one line naming it; a folder without either timing file fails too.
echo '{"variants": [{"name": "x"}]}' >"$work/candidates-grid-ab.json"
if "$report" "$work" >"$work/out" 2>&1; then fail "a corrupt file was read: $(cat "$work/out")"; fi
grep -q "candidates-grid-ab.json: not a gpu-ab JSON file" "$work/out" || fail "corrupt file: $(cat "$work/out")"
[ "$(wc -l <"$work/out")" -eq 1 ] || fail "not one line: $(cat "$work/out")"
rm "$work/candidates-ab.json" "$work/candidates-grid-ab.json"
if "$report" "$work" >"$work/out" 2>&1; then fail "ran without a timing file: $(cat "$work/out")"; fi
grep -q "holds neither candidates-ab.json nor candidates-grid-ab.json" "$work/out" || fail "$(cat "$work/out")"
echo "gpu_candidates_report_check: passed"
