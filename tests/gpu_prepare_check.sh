#!/usr/bin/env bash
# scripts/gpu-prepare's call script, without building: the copy in bench/gpu-candidates/README.md is what
# `--print-waiting` writes for the patches waiting now; another folder is named everywhere in place of .gl;
# the script is valid bash and runs gpu-waiting on parts it knows, the targets' configurations among them, with
# the folders of the patches that wait;
# a folder outside the repository's root is refused in one line.
# Arguments: source dir, build dir, scratch dir. Exit 77 (skipped) without python3.
source "$(dirname "$0")/check_common.sh"
check_setup gpu_prepare_check "$@"
command -v python3 >/dev/null || { echo "gpu_prepare_check: no python3"; exit 77; }
prepare=$src/scripts/gpu-prepare

"$prepare" --print-waiting >"$work/waiting.sh" || fail "--print-waiting failed"
python3 - "$src/bench/gpu-candidates/README.md" >"$work/readme.sh" <<'PY' || fail "the README has no waiting.sh block"
import re, sys
text = open(sys.argv[1]).read()
start = text.index("which `scripts/gpu-prepare` writes")
print(re.search(r"```\n(.*?)```", text[start:], re.S).group(1), end="")
PY
diff "$work/readme.sh" "$work/waiting.sh" >"$work/diff" ||
  fail "bench/gpu-candidates/README.md's waiting.sh is not what scripts/gpu-prepare writes: $(head -5 "$work/diff")"
bash -n "$work/waiting.sh" || fail "waiting.sh is not valid bash"

# The parts it names are gpu-waiting's, and the folders those of the patches that wait.
parts=$(sed -n 's/^ *--parts \([^ ]*\) .*/\1/p' "$work/waiting.sh")
[ -n "$parts" ] || fail "waiting.sh names no --parts"
# gpu-waiting lists its parts when asked for one it does not know.
"$src/scripts/gpu-waiting" --obscura /bin/true --parts no-such-part "$work/w" 2>"$work/parts" && fail "gpu-waiting took --parts no-such-part"
known=$(sed -n 's/.*(the parts: \(.*\))$/\1/p' "$work/parts")
[ -n "$known" ] || fail "gpu-waiting did not list its parts: $(cat "$work/parts")"
for part in ${parts//,/ }; do
  [[ " $known " == *" $part "* ]] || fail "waiting.sh runs part '$part', which gpu-waiting does not know ($known)"
done
# Every call times the tree's shaders in the targets' configurations, so that targets.txt answers all four.
for part in grid-ab normals-ab; do
  [[ ",$parts," == *",$part,"* ]] || fail "waiting.sh does not run $part, which the targets need"
done
shopt -s nullglob
for kind in candidates probes; do
  folder=gpu-$kind
  patches=("$src/bench/$folder"/*.patch)
  if [ ${#patches[@]} -gt 0 ]; then
    grep -q -- "--$kind .gl/$kind" "$work/waiting.sh" || fail "patches wait in bench/$folder, but waiting.sh has no --$kind"
    [[ ",$parts," == *",$kind-ab,"* ]] || fail "patches wait in bench/$folder, but waiting.sh does not run $kind-ab"
  else
    ! grep -q -- "--$kind" "$work/waiting.sh" || fail "no patch waits in bench/$folder, but waiting.sh passes --$kind"
  fi
done

# Another folder, named everywhere .gl was.
"$prepare" --print-waiting carried/gpu >"$work/other.sh" || fail "--print-waiting carried/gpu failed"
! grep -q '\.gl' "$work/other.sh" || fail "with DIR carried/gpu, waiting.sh still names .gl: $(grep '\.gl' "$work/other.sh" | head -1)"
[ "$(sed 's|carried/gpu|.gl|g' "$work/other.sh")" = "$(cat "$work/waiting.sh")" ] ||
  fail "with DIR carried/gpu, waiting.sh differs from .gl's by more than the folder"

for bad in /tmp/gl ../gl gl/../.. . "a b"; do
  if "$prepare" --print-waiting "$bad" >"$work/out" 2>"$work/err"; then fail "DIR '$bad' was taken"; fi
  [ "$(wc -l <"$work/err")" -eq 1 ] && grep -q "^gpu-prepare: " "$work/err" ||
    fail "DIR '$bad': not a one-line error: $(cat "$work/err")"
done
if "$prepare" --frobnicate >/dev/null 2>"$work/err"; then fail "an unknown option was taken"; fi
"$prepare" --help | grep -q "print-waiting" || fail "--help does not describe --print-waiting"
echo "gpu_prepare_check: ok"
