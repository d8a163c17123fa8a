#!/usr/bin/env bash
# The shader candidates of bench/gpu-candidates and the scripts that time them (scripts/gpu-candidates,
# scripts/gpu-ab), on this build and whatever Vulkan device there is (lavapipe in CI):
# - every patch applies to this checkout and compiles, and changes the shaders it edits (and those that
#   include a file it edits);
# - each candidate agrees with the CPU path (scripts/gpu-verify --small, whose list has the fused Alchemy
#   pass; a combination through its parts), and with the embedded shaders, the fused pass included: to the bit
#   where its header says "the same bits", else within 1e-5;
# - with no patch waiting, gpu-candidates refuses to run and says so;
# - gpu-ab times two variants against each other and writes its JSON; it refuses a missing folder;
# - the probes of bench/gpu-probes (wrong by design, timed only) apply, compile and run in gpu-waiting, each in
#   the cases of probes-ab whose frames dispatch a shader it replaces, and in the spatio-temporal target's
#   configuration (probes-grid-ab) when it replaces a shader of that frame (with none waiting, both parts run on
#   the build's own alchemy.spv and gtao.spv);
# - gpu-waiting (run on a few of the candidates: the first, one with a parts file, one that reaches the
#   spatio-temporal target's frame, so that this check's time does not grow with their number) writes every
#   part's file (candidates.txt too: each candidate's verdict), times each candidate
#   in the cases whose frames run a shader it replaces (bench's list of each case's shaders), and again with
#   the spatio-temporal target's flags where it replaces a shader of that frame (candidates-grid-ab), a
#   candidate whose patch has a `Parts:` line (its folder's parts file) only in the parts it names, the
#   target's configuration against its fused pass and its history's depth copy (fused-ab), and names a part
#   that fails while the others run; with --parts it runs only the parts named, and refuses a name it does not
#   know or a part with nothing to time; it checks the candidates that pay first, then the mixed ones.
# Exit 77 (skipped) without a Vulkan device, python3 or glslc. Arguments: source dir, build dir, scratch dir.
source "$(dirname "$0")/check_common.sh"
check_setup gpu_candidates_check "$@"
command -v python3 >/dev/null || { echo "gpu_candidates_check: no python3"; exit 77; }
command -v glslc >/dev/null || { echo "gpu_candidates_check: no glslc"; exit 77; }
skip_without_vulkan

shopt -s nullglob
patches=("$src"/bench/gpu-candidates/*.patch)
if [ ${#patches[@]} -eq 0 ]; then
  # None waiting: gpu-candidates says so, and gpu-ab is checked below with a folder holding the build's own
  # alchemy.spv, the module the library embeds.
  if "$src/scripts/gpu-candidates" "$work/spv" >"$work/built" 2>&1; then fail "gpu-candidates ran without a patch"; fi
  grep -q "no patch in" "$work/built" || fail "gpu-candidates: $(cat "$work/built")"
  mkdir -p "$work/spv/same"
  cp "$build/shaders/alchemy.spv" "$work/spv/same/" || fail "the build has no shaders/alchemy.spv"
else
  "$src/scripts/gpu-candidates" "$work/spv" >"$work/built" 2>&1 || fail "gpu-candidates failed: $(cat "$work/built")"
fi
# PATCH KEY: the words of PATCH's header line `KEY: ...` (before its first diff), or nothing. Read here apart
# from gpu-candidates, whose reading of them this check holds to.
header_line() { sed -n "/^diff --git/q; s/^$2: *//p" "$1"; }
# The shaders compiled into folder DIR, sorted, on one line.
built_shaders() { (cd "$1" && ls ./*.spv | sed 's|^\./||; s|\.spv$||' | sort | tr '\n' ' '); }
# PATCH DIR LOG APPLIED: every shader PATCH edits changed and was compiled into DIR (an edited include changes
# its includers too, so DIR may hold more); LOG is what gpu-candidates printed. A combination (APPLIED: the
# words of its `Applies:` line, naming other patches of its folder) is checked against what its parts edit, and
# must hold every shader that one of its parts, built beside it in DIR's parent, holds.
check_built() {
  local name got shader applied=$4 part timing files=("$1")
  name=$(basename "$1" .patch)
  [ -d "$2" ] || fail "$name: no folder built: $(cat "$3")"
  got=$(built_shaders "$2")
  [ -n "$got" ] || fail "$name: no shader changed"
  # A patch without hunks is a combination; were its Applies: line read as nothing, the parts' checks below
  # would be skipped without a word.
  grep -q '^diff --git' "$1" || [ -n "$applied" ] || fail "$name: no hunk of its own, and no Applies: line read"
  for part in $applied; do
    [ -d "$(dirname "$2")/$part" ] || fail "$name: its part $part was not built"
    for shader in $(built_shaders "$(dirname "$2")/$part"); do
      case " $got" in *" $shader "*) ;; *) fail "$name: built only '$got', without $part's $shader" ;; esac
    done
    files+=("$(dirname "$1")/$part.patch")
  done
  for shader in $(cat "${files[@]}" | grep '^+++ b/src/gpu/shaders/.*\.comp' | sed 's|.*/||; s|\.comp.*||'); do
    case " $got" in *" $shader "*) ;; *) fail "$name: the patch edits $shader.comp, built only '$got'" ;; esac
  done
  # A `Parts:` line (the timing parts of gpu-waiting that time it) goes into the folder's parts file.
  timing=$(header_line "$1" Parts)
  if [ -n "$timing" ]; then
    [ "$(cat "$2/parts" 2>/dev/null)" = "$timing" ] || fail "$name: Parts: $timing, but its folder's parts file: $(cat "$2/parts" 2>&1)"
  elif [ -e "$2/parts" ]; then
    fail "$name: a parts file without a Parts: line"
  fi
}
# The renders each candidate is held to the embedded shaders on; the embedded shaders' are made once, into e<i>.
# The last is wide enough (a 300-pixel grid) for blocks of 128 grid pixels, which a change of the GTAO pass's
# mapping of invocations to pixels may take, to be whole.
renders=("demo --size 133x77 --ao alchemy" "demo --size 133x77 --ao gtao"
         "stairs --size 120x70 --ao alchemy --blur-radius 32"
         "stairs --size 120x70 --ao alchemy --ao-guard-band 8 --gpu-fused-blur"
         "stairs --size 97x63 --ao gtao --frames 3"
         "demo --size 133x77 --ao gtao --frames 4 --gtao-half-res --gtao-grid-history --gtao-alternating-window"
         "stairs --size 97x63 --ao gtao --frames 5 --gtao-half-res --gtao-grid-history --gtao-packed-history --gtao-alternating-window --gtao-alternating-window-size 2"
         "demo --size 133x77 --ao gtao --frames 5 --gtao-half-res --gtao-grid-history --gtao-packed-history --gtao-alternating-window --gtao-alternating-window-size 2 --gpu-fused-temporal"
         "cabinet --size 600x340 --ao gtao --frames 2 --gtao-half-res --gtao-grid-history --gtao-packed-history --gtao-alternating-window --gtao-alternating-window-size 2 --gtao-sampling planar-nearest")
if [ ${#patches[@]} -gt 0 ]; then
  for i in "${!renders[@]}"; do
    # shellcheck disable=SC2086  # the list's words are separate arguments
    "$tool" render ${renders[$i]} -q --gpu -o "$work/e$i.png" --aov-dir "$work/e$i" >/dev/null
  done
fi
count=0
for patch in "${patches[@]}"; do
  name=$(basename "$patch" .patch)
  dir=$work/spv/$name
  applied=$(header_line "$patch" Applies)
  check_built "$patch" "$dir" "$work/built" "$applied"

  # A combination's parts are each held to the CPU here; the combination is held to the embedded shaders below
  # (and on the device to the CPU, by gpu-waiting).
  if [ -z "$applied" ]; then
    OBSCURA_SHADER_DIR=$dir "$src/scripts/gpu-verify" "$tool" --small >"$work/verify" 2>&1 ||
      fail "$name: gpu-verify failed: $(cat "$work/verify")"
  fi

  limit=1e-5
  grep -q '^Results: the same bits' "$patch" && limit=0
  pairs=()
  for i in "${!renders[@]}"; do
    rm -rf "$work/c$i"
    # shellcheck disable=SC2086  # the list's words are separate arguments
    OBSCURA_SHADER_DIR=$dir "$tool" render ${renders[$i]} -q --gpu -o "$work/c.png" --aov-dir "$work/c$i" >/dev/null
    pairs+=("${renders[$i]}" "$work/e$i/ao.exr" "$work/c$i/ao.exr")
  done
  # One process compares all the renders: a Python start costs about 0.3 s on a 2-core machine, a comparison at
  # these sizes far less. exrdiff.py's reading and differences.
  python3 - "$src/scripts" "$name" "$limit" "${pairs[@]}" <<'EOF' || fail "$name: against the embedded shaders"
import sys
sys.path.insert(0, sys.argv[1])
from exrdiff import difference, read_exr
name, limit, rest = sys.argv[2], float(sys.argv[3]), sys.argv[4:]
failed = False
for args, embedded, candidate in zip(rest[0::3], rest[1::3], rest[2::3]):
    worst = difference(read_exr(embedded), read_exr(candidate))[1]
    if worst > limit:
        print(f"{name}: {args}: against the embedded shader, max {worst:.2e} > {limit:g}", file=sys.stderr)
        failed = True
sys.exit(1 if failed else 0)
EOF
  count=$((count + 1))
done

# gpu-ab: the embedded shaders against the first candidate (or the build's alchemy.spv), two rounds, at a tiny
# size.
first=$(ls "$work/spv" | head -1)
"$src/scripts/gpu-ab" --obscura "$tool" --rounds 2 --json "$work/ab.json" embedded "cand=$work/spv/$first" \
  -- --sizes 64x32 --cases alchemy --frames 3 --warmup 0 --inputs 1 >"$work/ab" 2>"$work/ab.err" ||
  fail "gpu-ab failed: $(cat "$work/ab.err")"
grep -Eq '^alchemy +64x32 +frame +[0-9.]+ +[0-9.]+ +[0-9.]+$' "$work/ab" || fail "no frame row: $(cat "$work/ab")"
grep -Eq '^alchemy +64x32 +blur +[0-9.]+ +[0-9.]+ +[0-9.]+$' "$work/ab" || fail "no blur row: $(cat "$work/ab")"
python3 - "$work/ab.json" <<'EOF' || fail "gpu-ab's JSON: $(cat "$work/ab.json")"
import json, sys
d = json.load(open(sys.argv[1]))
assert [v["name"] for v in d["variants"]] == ["embedded", "cand"]
assert all(len(v["rounds_ms"]) == 2 and v["median_ms"] for v in d["variants"])
assert all(m["ms"] > 0 for v in d["variants"] for m in v["median_ms"])
# frame_spread (gpu-candidates-report reads it): the frame's two rounds apart, over their median.
for v in d["variants"]:
    a, b = (m["ms"] for r in v["rounds_ms"] for m in r if m["pass"] == "frame")
    assert abs(v["frame_spread"] - abs(a - b) / ((a + b) / 2)) < 1e-12, (v["frame_spread"], a, b)
EOF
# A variant that is a flag: --flags-for reaches that variant's runs alone (bench says so in its JSON).
"$src/scripts/gpu-ab" --obscura "$tool" --rounds 1 --json "$work/flags.json" two tiled --flags-for "tiled=--blur-tiled" \
  -- --sizes 64x32 --cases alchemy --frames 2 --warmup 0 --inputs 1 >"$work/ab" 2>"$work/ab.err" ||
  fail "gpu-ab --flags-for failed: $(cat "$work/ab.err")"
python3 - "$work/flags.json" <<'EOF' || fail "gpu-ab --flags-for's JSON: $(cat "$work/flags.json")"
import json, sys
d = json.load(open(sys.argv[1]))
assert [(v["name"], v["flags"]) for v in d["variants"]] == [("two", []), ("tiled", ["--blur-tiled"])]
EOF
if "$src/scripts/gpu-ab" --obscura "$tool" two "--flags-for=nobody=--blur-tiled" >"$work/ab" 2>"$work/ab.err"; then
  fail "gpu-ab took --flags-for a variant it does not have"
fi
grep -q "no variant named 'nobody'" "$work/ab.err" || fail "$(cat "$work/ab.err")"
if "$src/scripts/gpu-ab" --obscura "$tool" embedded "gone=$work/missing" >"$work/ab" 2>"$work/ab.err"; then
  fail "gpu-ab ran with a missing folder"
fi
grep -q "gone: $work/missing is not a folder" "$work/ab.err" || fail "$(cat "$work/ab.err")"
# A variant whose run fails (a shader the driver refuses) is named and left out; the others' rounds are kept and
# written, and the exit status says one failed. It used to throw every variant's timings away.
mkdir -p "$work/broken"
head -c 64 /dev/zero >"$work/broken/alchemy.spv"
if "$src/scripts/gpu-ab" --obscura "$tool" --rounds 2 --json "$work/broken.json" embedded "cand=$work/spv/$first" \
  "broken=$work/broken" -- --sizes 64x32 --cases alchemy --frames 2 --warmup 0 --inputs 1 >"$work/ab" 2>"$work/ab.err"; then
  fail "gpu-ab succeeded with a broken variant"
fi
grep -q "broken left out" "$work/ab.err" || fail "no word of the broken variant: $(cat "$work/ab.err")"
python3 - "$work/broken.json" <<'EOF' || fail "gpu-ab's JSON with a broken variant: $(cat "$work/broken.json")"
import json, sys
d = json.load(open(sys.argv[1]))
assert [v["name"] for v in d["variants"]] == ["embedded", "cand"]
assert all(len(v["rounds_ms"]) == 2 for v in d["variants"])
EOF
# The probes: each built into its folder, with the shaders its patch edits.
probes=("$src"/bench/gpu-probes/*.patch)
if [ ${#probes[@]} -gt 0 ]; then
  "$src/scripts/gpu-candidates" --probes "$work/probes" >"$work/built-probes" 2>&1 ||
    fail "gpu-candidates --probes failed: $(cat "$work/built-probes")"
  for patch in "${probes[@]}"; do
    check_built "$patch" "$work/probes/$(basename "$patch" .patch)" "$work/built-probes" "$(header_line "$patch" Applies)"
  done
else
  # None waiting: probes-ab and probes-grid-ab still run, on a folder holding the build's own alchemy.spv and
  # gtao.spv, as the candidates' parts do above, so that the parts are checked whether or not a probe waits.
  mkdir -p "$work/probes/same"
  cp "$build/shaders/alchemy.spv" "$build/shaders/gtao.spv" "$work/probes/same/" ||
    fail "the build has no shaders/alchemy.spv or gtao.spv"
fi
# The shaders of the spatio-temporal target's frame, as this check knows them apart from gpu-waiting.
targetShaders="gtao gtao_temporal upsample_depth_aware"
# Whether candidate folder DIR replaces one of them.
in_target() {
  local shader
  for shader in $targetShaders; do [ -f "$1/$shader.spv" ] && return 0; done
  return 1
}
# gpu-waiting's own logic is checked on a few of the candidates, so that this check's time does not grow with
# their number (each was held to the CPU and the embedded shaders above): the first in name order, the first
# with a parts file, the first without one that replaces a shader of the target's frame, and grid-only.
mkdir -p "$work/wspv"
pickedParts="" pickedTarget=""
for n in $(ls "$work/spv"); do
  pick=0
  if [ "$n" = "$first" ]; then pick=1; fi  # gpu-ab's, above
  if [ -f "$work/spv/$n/parts" ] && [ -z "$pickedParts" ]; then pick=1; pickedParts=$n; fi
  if [ ! -f "$work/spv/$n/parts" ] && [ -z "$pickedTarget" ] && in_target "$work/spv/$n"; then pick=1; pickedTarget=$n; fi
  if [ $pick = 1 ]; then cp -r "$work/spv/$n" "$work/wspv/"; fi
done
# And a folder timed only in the target's configuration (what a patch's `Parts: candidates-grid-ab` makes): the
# build's own gtao.spv, which the default cases' frames dispatch too; check_reach below holds gpu-waiting to
# leaving it out of candidates-ab.
mkdir -p "$work/wspv/grid-only"
cp "$build/shaders/gtao.spv" "$work/wspv/grid-only/" || fail "the build has no shaders/gtao.spv"
echo candidates-grid-ab >"$work/wspv/grid-only/parts"
# gpu-waiting: every part, each into its file, at a tiny size, with one round.
"$src/scripts/gpu-waiting" --obscura "$tool" --candidates "$work/wspv" --probes "$work/probes" --rounds 1 --small "$work/waiting" \
  -- --sizes 48x32 --frames 2 --warmup 0 --inputs 1 2>"$work/waiting.err" || fail "gpu-waiting: $(cat "$work/waiting.err")"
for f in verify.txt grid-ab.txt grid-ab.json fused-ab.txt fused-ab.json pipelines-fused.json pipelines-target.json \
  tiled-ab.txt tiled-ab.json normals-ab.txt normals-ab.json pipelines.json internals candidates.txt; do
  [ -e "$work/waiting/$f" ] || fail "gpu-waiting wrote no $f: $(ls "$work/waiting")"
done
# candidates.txt (gpu-candidates-report) has a verdict for every candidate, and the device's gpu-verify passed
# for each, except one that lost or did not change in the timings (lavapipe's are noise), whose check gpu-waiting
# leaves out and says so.
for n in $(ls "$work/wspv"); do
  verdict=$(grep -E "^$n: " "$work/waiting/candidates.txt" | cut -d' ' -f2-) ||
    fail "candidates.txt: no verdict for $n: $(cat "$work/waiting/candidates.txt")"
  case "$verdict" in
    loses|"no change")
      grep -q "gpu-verify with $n left out: $verdict" "$work/waiting.err" || fail "no word of $n's check left out"
      [ ! -e "$work/waiting/verify-$n.txt" ] || fail "verify-$n.txt for a candidate that $verdict" ;;
    *)
      sed -n "/^$n: /,/^\$/p" "$work/waiting/candidates.txt" | grep -q "gpu-verify on the device: passed" ||
        fail "candidates.txt: $n ($verdict) without a passed gpu-verify: $(cat "$work/waiting/candidates.txt")"
      [ -s "$work/waiting/verify-$n.txt" ] || fail "gpu-waiting wrote no verify-$n.txt" ;;
  esac
done
# FILE: a statistics run in the spatio-temporal target's configuration (lavapipe reports no statistics, so the
# run's own record of its flags is what can be checked here).
has_target_flags() {  # FILE [SAMPLING: the target's planar-nearest unless given]
  python3 - "$1" "${2:-planar-nearest}" <<'PY' || fail "$1 is not a run in the target's configuration"
import json, sys
r = json.load(open(sys.argv[1]))
want = {"alternating_window": True, "alternating_window_size": 2, "packed_history": True, "packed_normals": True,
        "packed_output": True, "keep_previous_depth": True, "bent_normals": False, "fused_temporal": False,
        "gtao_sampling": sys.argv[2]}
got = {k: r.get(k) for k in want}
cases = sorted({c["case"] for c in r["cases"]})
sys.exit(0 if got == want and cases == ["gtao-temporal-grid"] else f"{got} {cases}")
PY
}
has_target_flags "$work/waiting/pipelines-target.json"
has_target_flags "$work/waiting/pipelines-target-nearest.json" nearest
if [ ${#patches[@]} -gt 0 ]; then
  for n in $(ls "$work/wspv"); do
    [ -s "$work/waiting/pipelines-$n.json" ] || fail "gpu-waiting wrote no pipelines-$n.json"
    # A candidate that changes a shader of the spatio-temporal target's frame has its statistics there too.
    if in_target "$work/wspv/$n"; then
      has_target_flags "$work/waiting/pipelines-$n-target.json"
    elif [ -e "$work/waiting/pipelines-$n-target.json" ]; then
      fail "pipelines-$n-target.json for a candidate outside the target's frame"
    fi
  done
fi
grep -q "^alchemy " "$work/waiting/candidates-ab.txt" || fail "candidates-ab.txt: $(cat "$work/waiting/candidates-ab.txt")"
grep -q "^gtao-temporal-grid .* upsample " "$work/waiting/candidates-grid-ab.txt" ||
  fail "candidates-grid-ab.txt: $(cat "$work/waiting/candidates-grid-ab.txt")"
# PART FOLDER CASES [BENCH_FLAGS...]: each variant of folder FOLDER (a candidate or a probe) timed in PART.json
# in exactly the cases of CASES whose frames dispatch a shader it replaces (bench's own list of a case's
# shaders, read here apart from gpu-waiting), the embedded shaders in all of them; and in PART's grid twin
# (PART with "-ab" made "-grid-ab") with the target's flags exactly when it replaces a shader of that frame
# ($targetShaders).
check_reach() {
  local part=$1 folder=$2 list=$3
  shift 3
  "$tool" bench --gpu --json --sizes 48x32 --frames 1 --warmup 0 --inputs 1 --visibility-only "$@" \
    --cases "$list" >"$work/reach-$part.json" || fail "bench for the shaders of $part's cases failed"
  python3 - "$work/waiting" "$folder" "$work/reach-$part.json" "$targetShaders" "$part" <<'EOF' ||
import json, os, sys
out, folder, reach, target, part = sys.argv[1:]
target = set(target.split())
shaders = {c["case"]: set(c["shaders"]) for c in json.load(open(reach))["cases"]}
replaced = {n: {f[:-4] for f in os.listdir(os.path.join(folder, n)) if f.endswith(".spv")} for n in os.listdir(folder)}
# A folder's parts file names the only parts that time it.
def timed(n, p):
    f = os.path.join(folder, n, "parts")
    return not os.path.exists(f) or p in open(f).read().split()
gridPart = part.replace("-ab", "-grid-ab")
def cases(variant):
    return {m["case"] for m in variant["median_ms"]}
ab = json.load(open(os.path.join(out, part + ".json")))["variants"]
assert ab[0]["name"] == "embedded" and cases(ab[0]) == set(shaders), (ab[0]["name"], cases(ab[0]))
want = {n: {c for c, s in shaders.items() if s & replaced[n]} for n in sorted(replaced) if timed(n, part)}
got = {v["name"]: cases(v) for v in ab[1:]}
assert got == {n: c for n, c in want.items() if c}, (got, want)
grid = json.load(open(os.path.join(out, gridPart + ".json")))["variants"]
names = [v["name"] for v in grid]
assert names[0] == "embedded" and sorted(names[1:]) == [n for n in sorted(replaced)
                                                        if replaced[n] & target and timed(n, gridPart)], names
held = ("--packed-output", "--alternating-window-size", "--keep-previous-depth")
assert all(f in v["flags"] for v in grid for f in held), [v["flags"] for v in grid]
EOF
    fail "$part did not time each of $folder in the cases it reaches: $(cat "$work/waiting/$part.json")"
}
# check_reach holds grid-only (a parts file) out of candidates-ab and in candidates-grid-ab; the call says so.
check_reach candidates-ab "$work/wspv" alchemy,alchemy-fused,gtao,gtao-half,gtao-temporal-grid
grep -q "candidate grid-only is timed only in candidates-grid-ab (its Parts: line): not in candidates-ab" \
  "$work/waiting.err" || fail "no word of grid-only left out of candidates-ab: $(cat "$work/waiting.err")"
grep -q "^alchemy .* alchemy " "$work/waiting/probes-ab.txt" || fail "probes-ab.txt: $(cat "$work/waiting/probes-ab.txt")"
grep -q "^gtao-temporal-grid .* upsample " "$work/waiting/probes-grid-ab.txt" ||
  fail "probes-grid-ab.txt: $(cat "$work/waiting/probes-grid-ab.txt")"
check_reach probes-ab "$work/probes" alchemy,alchemy-fused,gtao-half --gtao-sampling planar-nearest
grep -q "^gtao-half " "$work/waiting/tiled-ab.txt" || fail "tiled-ab.txt: $(cat "$work/waiting/tiled-ab.txt")"
grep -q "^alchemy " "$work/waiting/normals-ab.txt" || fail "normals-ab.txt: $(cat "$work/waiting/normals-ab.txt")"
grep -q "^gtao-temporal-grid .* upsample " "$work/waiting/grid-ab.txt" || fail "grid-ab.txt: $(cat "$work/waiting/grid-ab.txt")"
grep -q "planar-nearest-window2 ms.*planar-nearest-window2-packed-normals ms.*planar-nearest-window2-packed-all ms" \
  "$work/waiting/grid-ab.txt" || fail "grid-ab.txt, 2x2 windows: $(cat "$work/waiting/grid-ab.txt")"
grep -q "planar-nearest-window2-packed-all ms  *planar-nearest-window2-packed-all-fused ms" "$work/waiting/fused-ab.txt" ||
  fail "fused-ab.txt: $(cat "$work/waiting/fused-ab.txt")"
# The history's depth copy against the caller's previous depth: only the copy's runs lack the flag.
python3 - "$work/waiting/fused-ab.json" <<'EOF' || fail "fused-ab.json: $(cat "$work/waiting/fused-ab.json")"
import json, sys
v = {x["name"]: x["flags"] for x in json.load(open(sys.argv[1]))["variants"]}
base = "planar-nearest-window2-packed-all"
assert list(v) == [base, base + "-fused", base + "-depth-copy"], list(v)
assert ["--keep-previous-depth" in v[n] for n in v] == [True, True, False], v
assert all("--packed-output" in f and "--alternating-window-size" in f for f in v.values()), v
EOF
# The fused variant has no gtao pass of its own: its column there is "-".
grep -q "^gtao-temporal-grid  *[0-9x]*  *gtao  *[0-9.]*  *- " "$work/waiting/fused-ab.txt" ||
  fail "fused-ab.txt: a gtao pass in the fused variant: $(cat "$work/waiting/fused-ab.txt")"
grep -q "gpu-verify: ok\|max" "$work/waiting/verify.txt" || fail "verify.txt: $(cat "$work/waiting/verify.txt")"
# A part that fails is named and the others still run: a bad --frames fails both timings, not the statistics
# (one frame of their own) nor gpu-verify; the exit status says so.
if "$src/scripts/gpu-waiting" --obscura "$tool" --small "$work/w3" -- --sizes 16x8 --frames 0 2>"$work/waiting.err"; then
  fail "gpu-waiting exited 0 with a failing part"
fi
grep -q "grid history's timing FAILED" "$work/waiting.err" || fail "no failure named: $(cat "$work/waiting.err")"
grep -q "fused pass's timing FAILED" "$work/waiting.err" || fail "no failure named: $(cat "$work/waiting.err")"
grep -q "tiled blur's timing FAILED" "$work/waiting.err" || fail "no failure named: $(cat "$work/waiting.err")"
grep -q "packed normals' timing FAILED" "$work/waiting.err" || fail "no failure named: $(cat "$work/waiting.err")"
for f in pipelines.json verify.txt; do [ -s "$work/w3/$f" ] || fail "after a failed part, no $f: $(ls "$work/w3")"; done
if "$src/scripts/gpu-waiting" --obscura "$tool" --candidates "$work/missing" "$work/w2" 2>"$work/waiting.err"; then
  fail "gpu-waiting ran with a missing candidates folder"
fi
grep -q "is not a folder" "$work/waiting.err" || fail "$(cat "$work/waiting.err")"
if "$src/scripts/gpu-waiting" --obscura "$tool" --probes "$work/missing" "$work/w4" 2>"$work/waiting.err"; then
  fail "gpu-waiting ran with a missing probes folder"
fi
grep -q "probes .* is not a folder" "$work/waiting.err" || fail "$(cat "$work/waiting.err")"
# --parts: only the parts named run (targets.txt is always written); an unknown name, or a part with nothing to
# time, is refused before anything runs.
"$src/scripts/gpu-waiting" --obscura "$tool" --parts fused-ab --rounds 1 "$work/w5" \
  -- --sizes 48x32 --frames 2 --warmup 0 --inputs 1 2>"$work/waiting.err" || fail "gpu-waiting --parts: $(cat "$work/waiting.err")"
[ "$(cd "$work/w5" && ls | tr '\n' ' ')" = "fused-ab.json fused-ab.txt targets.txt " ] ||
  fail "gpu-waiting --parts fused-ab wrote: $(ls "$work/w5")"
grep -q "planar-nearest-window2-packed-all-depth-copy ms" "$work/w5/fused-ab.txt" || fail "$(cat "$work/w5/fused-ab.txt")"
if "$src/scripts/gpu-waiting" --obscura "$tool" --parts fused-ab,grids-ab "$work/w6" 2>"$work/waiting.err"; then
  fail "gpu-waiting ran an unknown part"
fi
grep -q "no part 'grids-ab'" "$work/waiting.err" || fail "$(cat "$work/waiting.err")"
[ ! -e "$work/w6" ] || fail "gpu-waiting refused --parts but made $work/w6"
if "$src/scripts/gpu-waiting" --obscura "$tool" --parts probes-ab "$work/w7" 2>"$work/waiting.err"; then
  fail "gpu-waiting ran probes-ab without probes"
fi
grep -q "names probes-ab but no --probes" "$work/waiting.err" || fail "$(cat "$work/waiting.err")"
# gpu-verify's order: the candidates that pay first, then the mixed ones, none that loses, whatever their names'
# order (the verdicts are written here, as gpu-candidates-report would after timings that said so).
mkdir -p "$work/order/a-mixed" "$work/order/b-pays" "$work/order/c-loses" "$work/w8"
for n in a-mixed b-pays c-loses; do cp "$build/shaders/gtao.spv" "$work/order/$n/"; done
printf 'a-mixed: mixed\n\nb-pays: pays\n\nc-loses: loses\n' >"$work/w8/candidates.txt"
"$src/scripts/gpu-waiting" --obscura "$tool" --candidates "$work/order" --parts verify --small "$work/w8" \
  2>"$work/waiting.err" || fail "gpu-waiting --parts verify: $(cat "$work/waiting.err")"
[ "$(sed -n 's/.*gpu-verify with \([a-z-]*\)$/\1/p' "$work/waiting.err" | tr '\n' ' ')" = "b-pays a-mixed " ] ||
  fail "gpu-verify's order: $(grep 'gpu-verify with' "$work/waiting.err")"
grep -q "gpu-verify with c-loses left out: loses" "$work/waiting.err" || fail "no word of c-loses left out"
# Without candidates.txt (no timing part ran, or every one failed) a candidate has no verdict and is verified:
# a failed read of the file ended the script under set -e before any verify, with no word.
mkdir -p "$work/nov/only" "$work/w9"
cp "$build/shaders/gtao.spv" "$work/nov/only/"
"$src/scripts/gpu-waiting" --obscura "$tool" --candidates "$work/nov" --parts verify --small "$work/w9" \
  2>"$work/waiting.err" || fail "gpu-waiting --parts verify without candidates.txt: $(cat "$work/waiting.err")"
[ -s "$work/w9/verify-only.txt" ] && [ -s "$work/w9/verify.txt" ] ||
  fail "gpu-waiting without candidates.txt wrote: $(ls "$work/w9"); $(cat "$work/waiting.err")"
echo "gpu_candidates_check: ok ($count candidates)"
