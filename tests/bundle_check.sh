#!/usr/bin/env bash
# scripts/bundle on this build: the archive unpacks to a tool that runs and loads its libraries from the
# bundle (LD_DEBUG names each library as it is initialised), and a bad build folder fails with one line
# and no archive. Arguments: source dir, build dir, scratch dir.
source "$(dirname "$0")/check_common.sh"
check_setup bundle_check "$@"

"$src/scripts/bundle" "$build" "$work/bundle.tar.gz"
tar -C "$work" -xzf "$work/bundle.tar.gz"
tool=$work/obscura-bundle/obscura
libs=$(LD_DEBUG=libs "$tool" render --size 32x18 --ao alchemy -q -o "$work/frame.png" 2>&1 >/dev/null)
[ -s "$work/frame.png" ] || fail "the bundled tool wrote no frame"
# A here-string, not `echo | grep -q`: grep -q exits at the first match, and under pipefail the echo still
# writing into a full pipe would die of SIGPIPE and fail the check for a library that was loaded.
for lib in libembree3.so.3 libtbb.so.12 libOpenEXR-3_1.so.30; do
  grep -qF "calling init: $work/obscura-bundle/lib/$lib" <<<"$libs" || fail "$lib was not loaded from the bundle"
done

if "$src/scripts/bundle" "$work/no-such-build" "$work/none.tar.gz" 2>"$work/err"; then
  fail "a missing build folder did not fail"
fi
[ "$(wc -l <"$work/err")" -eq 1 ] || fail "expected a one-line error, got: $(cat "$work/err")"
[ ! -e "$work/none.tar.gz" ] || fail "a failed run left an archive"
echo "bundle_check: ok ($(du -h "$work/bundle.tar.gz" | cut -f1))"
