#!/usr/bin/env bash
# jointrom test suite: the C test programs (build/tests/test_*) and the command-line checks
# (tests/cli.sh). Every check prints "ok - ..." or "not ok - ..."; a program that crashes or exits
# non-zero without reporting a failure counts as one failure. Ends with "N passed, M failed".
cd "$(dirname "$0")/.."
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 OMPI_MCA_rmaps_base_oversubscribe=1
pass=0; fail=0
log=$(mktemp -d)
run() { # name, command...
  local name=$1; shift
  "$@" > "$log/$name.out" 2>&1
  local rc=$?
  local p f
  p=$(grep -c '^ok - ' "$log/$name.out")
  f=$(grep -c '^not ok - ' "$log/$name.out")
  grep -E '^(ok|not ok) - ' "$log/$name.out" | sed "s/^/[$name] /"
  if [ "$rc" != 0 ] && [ "$f" = 0 ]; then
    echo "not ok - [$name] exited with status $rc without reporting a failure; its output:"
    tail -20 "$log/$name.out" | sed 's/^/    /'
    f=1
  fi
  pass=$((pass + p)); fail=$((fail + f))
}
for t in build/tests/test_*; do
  [ -x "$t" ] || continue
  run "$(basename "$t")" "$t"
done
run cli bash tests/cli.sh
rm -rf "$log"
echo "$pass passed, $fail failed"
[ "$fail" = 0 ]
