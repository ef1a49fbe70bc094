#!/usr/bin/env bash
# jointrom test suite: the C test programs (build/tests/test_*) and the command-line checks
# (tests/cli*.sh). Every check prints "ok - ..." or "not ok - ..."; a program that crashes or exits
# non-zero without reporting a failure counts as one failure. Ends with "N passed, M failed".
#   bash tests/run.sh        the suite (make test; minutes)
#   bash tests/run.sh long   the slow end-to-end checks (make test-long, which CI runs after make test):
#                            test_fe and test_basis on 2 ranks, tests/cli_long.sh
# JR_TEST_TIMES=FILE (an absolute path): each program's and each check's wall and CPU seconds appended to FILE.
cd "$(dirname "$0")/.."
part=${1:-quick}
case $part in quick|long) ;; *) echo "usage: bash tests/run.sh [long]" >&2; exit 2 ;; esac
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 OMPI_MCA_rmaps_base_oversubscribe=1
log=$(mktemp -d)
# run NAME COMMAND...: its checks' lines, prefixed with [NAME], printed when it ends (whole, under a lock: two may end
# together); its counts to $log/NAME.count. A program that exits non-zero without a failure line counts one failure.
run() {
  local name=$1; shift
  local t0=$EPOCHREALTIME
  local out="$log/${name// /_}.out"
  : > "$log/${name// /_}.started"
  times > "$out.t0"
  "$@" > "$out" 2>&1
  local rc=$?
  times > "$out.t1"
  [ -n "$JR_TEST_TIMES" ] && awk -v a="$EPOCHREALTIME" -v b="$t0" -v s="$name" 'FNR == 2 {split($0, t, /[ms ]+/); c[++n] = 60 * t[1] + t[2] + 60 * t[3] + t[4]} END{printf "%.1f %.1f %s (all)\n", a - b, c[2] - c[1], s}' "$out.t0" "$out.t1" >> "$JR_TEST_TIMES"
  local p f
  p=$(grep -c '^ok - ' "$out")
  f=$(grep -c '^not ok - ' "$out")
  {
    grep -E '^(ok|not ok) - ' "$out" | sed "s/^/[$name] /"
    if [ "$rc" != 0 ] && [ "$f" = 0 ]; then
      echo "not ok - [$name] exited with status $rc without reporting a failure; its output:"
      tail -20 "$out" | sed 's/^/    /'
      f=1
    fi
  } > "$out.print"
  flock "$log/.lock" cat "$out.print"
  echo "$p $f" > "$log/${name// /_}.count"
}
# the command-line scripts, two at a time (most run one rank; the machine has two cores): the longest first
nrun=0
bg() { # name, command...
  [ $nrun -ge 2 ] && { wait -n; nrun=$((nrun - 1)); }
  nrun=$((nrun + 1))
  run "$@" &
}
if [ "$part" = long ]; then
  [ -x build/tests/test_fe ] && run "test_fe np2" mpiexec -n 2 build/tests/test_fe
  [ -x build/tests/test_basis ] && run "test_basis np2" mpiexec -n 2 build/tests/test_basis
  run cli_long bash tests/cli_long.sh
else
  for t in build/tests/test_*; do
    [ -x "$t" ] || continue
    run "$(basename "$t")" "$t"
  done
  # the parallel pieces again on 2 ranks (elements and matrices split across ranks; test_fe: make test-long)
  for t in test_hbm test_matio test_preload test_peaks test_nlmodes test_stability; do
    [ -x "build/tests/$t" ] && run "$t np2" mpiexec -n 2 "build/tests/$t"
  done
  for c in cli_rom cli_n2n cli cli_frf cli_nlmodes cli_verify cli_modes cli_preload cli_install cli_signal cli_driver cli_baddata; do
    bg $c bash tests/$c.sh
  done
  wait
fi
pass=$(cat "$log"/*.count | awk '{s += $1} END{print s + 0}')
fail=$(cat "$log"/*.count | awk '{s += $2} END{print s + 0}')
for st in "$log"/*.started; do # a run that ended without its counts (killed): one failure
  [ -e "${st%.started}.count" ] || { echo "not ok - [$(basename "${st%.started}")] ended without its results"; fail=$((fail + 1)); }
done
rm -rf "$log"
echo "$pass passed, $fail failed"
[ "$fail" = 0 ]
