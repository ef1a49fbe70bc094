# Helpers shared by the command-line checks (sourced): ok/bad lines, check, expect_error, close, run files.
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 OMPI_MCA_rmaps_base_oversubscribe=1 OPENBLAS_NUM_THREADS=1
J=bin/jointrom
tmp=$(mktemp -d); trap 'rm -rf "$tmp"' EXIT
# JR_TEST_TIMES=FILE: each check's wall and CPU seconds (since the previous check: the commands it checks; CPU of
# the processes run, which a loaded machine does not inflate as much) appended to FILE as "wall cpu script: check"
jr_cpu() { awk 'NR == 2 {split($0, t, /[ms ]+/); print 60 * t[1] + t[2] + 60 * t[3] + t[4]}' "$1"; } # FILE: the output of times
# (a file per shell: a check may run in the background; $BASHPID read here, not in the $(...) subshell)
jr_reset() { [ -z "$JR_TEST_TIMES" ] || { local f="$tmp/.times.$BASHPID"; jr_t=$EPOCHREALTIME; times > "$f"; jr_c=$(jr_cpu "$f"); }; } # also at the start of a check run in the background
jr_reset
jr_time() {
  [ -n "$JR_TEST_TIMES" ] || return 0
  local t=$EPOCHREALTIME c f="$tmp/.times.$BASHPID"
  times > "$f"; c=$(jr_cpu "$f")
  awk -v a="$t" -v b="$jr_t" -v c="$c" -v d="$jr_c" -v s="$(basename "$0" .sh)" -v n="$1" 'BEGIN{printf "%.1f %.1f %s: %s\n", a - b, c - d, s, n}' >> "$JR_TEST_TIMES"
  jr_reset
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
# run files: a run file's run succeeds and uses every option (no typo). The frf and compare runs on the lap models
# (the FE model with its modes, jenkins_nv fits: a minute each) are long checks (tests/cli_long.sh), the rest quick
run_file_long() { grep -qE '^-task (frf|compare)' "$1" && grep -q '^-model_type lap' "$1"; }
run_file_check() { # run file
  local f=$1 extra o rc out="$tmp/runfile_$(basename "$1" .opts)"
  case $(grep -m1 '^-task' "$f") in
    "-task frf"|"-task compare") extra="-frf_output_file $out -frf_plot 0 -cont_monitor 0"
      grep -q '^-model_type brb' "$f" && extra="$extra -model_mesh_h 0.01 -cont_max_points 40 -cont_allow_partial" # FE: a coarse mesh, the options are what is checked
      grep -q '^-model_type lap' "$f" && extra="$extra -model_mesh_h 0.005 -model_mesh_grade 4 -cont_max_points 40 -cont_allow_partial -modes_static_max 60 -modes_adapt 0" # a compressed basis (the static-complete one of some lap1 files takes minutes a level), not adapted (tests/cli_long.sh checks the adaptation)
      grep -q '^-rom_fit_select first' "$f" && extra="$extra -rom_fit_select_total 1000 -rom_fit_select_case 0" ;; # one pair: the selection runs, quickly (its own checks: cli_rom.sh)
    "-task nlmodes") extra="-nlm_output_file $out -nlm_plot 0 -nlm_points 6"
      grep -q '^-model_type brb' "$f" && extra="$extra -model_mesh_h 0.01" ;; # a coarse mesh: the options are what is checked
    "-task modes") extra="-modes_output_file '' -model_mesh_h 0.01" ;; # a coarse mesh: the options are what is checked
    "-task preload") extra="-preload_output_file '' -model_mesh_h 0.005 -model_mesh_grade 4"
      grep -q '^-model_type brb' "$f" && extra="-preload_output_file '' -model_mesh_h 0.01" ;; # as the other BRB runs
    *) extra="-element_loop ''" ;;
  esac
  o=$(eval $J -options_file "$f" -options_left $extra 2>&1); rc=$?
  check "[ $rc = 0 ] && echo \"\$o\" | grep -q 'There are no unused options'" "run file $f runs (exit $rc) and uses every option"
}
