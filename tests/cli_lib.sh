# Helpers shared by the command-line checks (sourced): ok/bad lines, check, expect_error, close.
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 OMPI_MCA_rmaps_base_oversubscribe=1 OPENBLAS_NUM_THREADS=1
J=bin/jointrom
tmp=$(mktemp -d); trap 'rm -rf "$tmp"' EXIT
# JR_TEST_TIMES=FILE: each check's wall and CPU seconds (since the previous check: the commands it checks; CPU of
# the processes run, which a loaded machine does not inflate as much) appended to FILE as "wall cpu script: check"
jr_cpu() { awk 'NR == 2 {split($0, t, /[ms ]+/); print 60 * t[1] + t[2] + 60 * t[3] + t[4]}' "$tmp/.times"; } # after times > $tmp/.times
[ -n "$JR_TEST_TIMES" ] && { jr_t=$EPOCHREALTIME; times > "$tmp/.times"; jr_c=$(jr_cpu); }
jr_time() {
  [ -n "$JR_TEST_TIMES" ] || return 0
  local t=$EPOCHREALTIME c
  times > "$tmp/.times"; c=$(jr_cpu)
  awk -v a="$t" -v b="$jr_t" -v c="$c" -v d="$jr_c" -v s="$(basename "$0" .sh)" -v n="$1" 'BEGIN{printf "%.1f %.1f %s: %s\n", a - b, c - d, s, n}' >> "$JR_TEST_TIMES"
  jr_t=$EPOCHREALTIME; times > "$tmp/.times"; jr_c=$(jr_cpu)
}
ok() { echo "ok - $*"; jr_time "$*"; }
bad() { echo "not ok - $*"; jr_time "$*"; }
check() { if eval "$1"; then ok "$2"; else bad "$2"; fi; }
# |a - b| <= t |b|
close() { awk -v a="$1" -v b="$2" -v t="$3" 'BEGIN{d=a-b; if(d<0)d=-d; s=(b<0?-b:b); if(s<1e-300)s=1; exit !(d<=t*s)}'; }
# bad input: a non-zero exit and a message with the pattern (which must come from our message, not
# from PETSc's echo of the option table)
expect_error() { # description, pattern, command...
  local d=$1 p=$2; shift 2
  local o rc
  o=$("$@" 2>&1); rc=$?
  if [ $rc != 0 ] && echo "$o" | grep -q -- "$p"; then ok "bad input, $d: exit $rc, says '$p'"
  else bad "bad input, $d: exit $rc, expected '$p'; got: $(echo "$o" | grep -m2 'PETSC ERROR: [^-#]' | tail -1)"; fi
}
