# Sourced by the tests/*_check.sh scripts, which ctest runs with three arguments: source dir, build dir,
# scratch dir. `check_setup NAME "$@"` sets src, build, work (emptied) and tool (the build's obscura);
# fail prints its message after NAME and exits 1; skip_without_vulkan exits 77 (ctest's skip) with the
# probe's error when no Vulkan device runs a one-frame bench.
set -euo pipefail

check_setup() {
  check_name=$1
  src=$2 build=$3 work=$4
  rm -rf "$work"
  mkdir -p "$work"
  tool=$build/obscura
}

fail() { echo "$check_name: $*" >&2; exit 1; }

skip_without_vulkan() {
  if ! "$tool" bench --gpu --sizes 8x8 --cases gtao --frames 1 --warmup 0 --inputs 1 >/dev/null 2>"$work/probe"; then
    echo "$check_name: no Vulkan device: $(cat "$work/probe")"
    exit 77
  fi
}
