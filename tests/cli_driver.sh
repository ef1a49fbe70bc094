#!/usr/bin/env bash
# The driver's checks before any work: a misspelled or unused option, a bad value and an output directory that
# cannot be written stop the run at once (no model, no preload) with one message, no PETSc traceback, exit 1;
# -help lists every option of each task without a model and exits 0, with no garbage default; the reduced
# model's nested solvers have their own prefix (-rom_hbm_snes_*), so -task compare tunes the two models apart.
cd "$(dirname "$0")/.."
. tests/cli_lib.sh
brb="-model_type brb -model_mesh_h 0.01 -preload_force 11500 -interface_kt 1e6 -interface_mu 0.12 -hbm_modes 12 -hbm_gamma 0.002 -cont_monitor 0 -frf_plot 0 -frf_fmin 128 -frf_fmax 138"
# quick CMD...: the run fails before the model is built (it would print "frf: node-to-node contact model") with
# exactly one line on stderr that starts "jointrom: error:" and holds PATTERN; prints the line
quick() { # description, pattern, command...
  local d=$1 p=$2 o e rc
  shift 2
  o=$("$@" 2> "$tmp/err"); rc=$?
  e=$(cat "$tmp/err")
  check "[ $rc = 1 ] && [ \$(echo \"\$e\" | grep -c .) = 1 ] && echo \"\$e\" | grep -q '^jointrom: error:' && echo \"\$e\" | grep -qF -- \"$p\" && ! echo \"\$o\" | grep -q 'contact model\\|^preload' && ! echo \"\$e\" | grep -q 'PETSC ERROR'" "$d: exit $rc, before the model, one line: $e"
}
quick "misspelled option" "unknown option -frf_forse (did you mean -frf_force?)" $J -task frf $brb -frf_forse 5 -frf_output_file ''
quick "misspelled reduction option" "did you mean -rom_elements?" $J -task compare $brb -frf_force 1 -rom_joints sides -rom_elemnts 3 -frf_output_file ''
quick "an option of another model" "-rom_joints is not used by -task frf on a matrices model" $J -options_file runs/oscillator_frf.opts -rom_joints sides -frf_output_file ''
quick "bad value" "-rom_fit_stiffness_weight 0.: the weight must be positive" $J -task compare $brb -frf_force 1 -rom_joints sides -rom_elements 3 -rom_fit_stiffness_weight 0 -frf_output_file ''
quick "bad preload stiffness" "-preload_kv -1.: zero or a positive stiffness" $J -task frf $brb -frf_force 1 -preload_kv -1 -frf_output_file ''
quick "output directory that cannot be made" "cannot write in the directory $tmp/no/such" $J -task frf $brb -frf_force 1 -frf_output_file "$tmp/no/such/x"
quick "missing -rom_load file" "-rom_load $tmp/none.h5: no such file" $J -task frf $brb -frf_force 1 -rom_load "$tmp/none.h5" -frf_output_file ''
quick "element task, misspelled" "did you mean -element_kt?" $J -task element -element_ktt 1e6
quick "modes task, unused option" "-frf_force is not used by -task modes" $J -task modes -model_type brb -frf_force 1 -modes_output_file ''
# an option no part of the run reads is a warning at the end; -options_left and -options_view, which PETSc reads after
# it (in PetscFinalize), are not
o=$($J -options_file runs/oscillator_frf.opts -cont_monitor 0 -frf_plot 0 -frf_output_file '' -options_left -options_view -snes_monitr 2>&1)
w=$(echo "$o" | grep '^jointrom: warning:')
check "[ \"\$w\" = 'jointrom: warning: unknown option -snes_monitr' ] && echo \"\$o\" | grep -q '^#PETSc Option Table entries'" "an unread option warned about at the end ($w), not -options_left or -options_view (PETSc's, read after)"
# a missing output directory one level down is made
$J -options_file runs/oscillator_frf.opts -cont_monitor 0 -frf_plot 0 -frf_output_file "$tmp/new/osc" > /dev/null 2>&1
check "[ -s '$tmp/new/osc.csv' ]" "a missing output directory (one level) is made: $tmp/new/osc.csv written"
# -help for every task: exit 0 without a model, every option of the task listed, no garbage default
for t in element frf compare modes preload; do
  h=$($J -task $t -help 2>&1); rc=$?
  g=$(echo "$h" | grep -E -- '^ +-[a-z_]+ <[^>]*([0-9]{9,}|e-3[0-9][0-9])' | head -2 | tr '\n' ' ')
  case $t in
  element) want="-element_kt -element_u -contact_type" ;;
  frf | compare) want="-frf_force -frf_at -interface_kt -rom_joints -rom_fit_total_weight -hbm_harmonics -cont_type -modes_nev -preload_force -hbm_snes_rtol -rom_hbm_snes_rtol -modes_eps_type -rom_tao_type" ;;
  modes) want="-modes_nev -model_type -modes_eps_type" ;;
  preload) want="-preload_force -preload_kv -preload_snes_rtol" ;;
  esac
  miss=""
  for w in $want; do echo "$h" | grep -q -- " $w[ <:]" || miss="$miss $w"; done
  check "[ $rc = 0 ] && [ -z '$miss' ] && [ -z '$g' ]" "-task $t -help: exit $rc without a model, lists $want${miss:+ (missing:$miss)}${g:+ (garbage: $g)}"
done
h=$($J -task modes -model_type brb -help 2>&1); rc=$?
check "[ $rc = 0 ] && echo \"\$h\" | grep -q -- ' -model_mesh_h <0.005'" "-task modes -model_type brb -help: the FE model's options with their defaults (-model_mesh_h <0.005 ...>)"
# -task compare: -rom_hbm_snes_* reaches the reduced model's solvers only, -hbm_snes_* the node-to-node model's
o=$($J -task compare $brb -frf_force 1 -rom_joints sides -frf_output_file '' -rom_hbm_snes_monitor 2>&1)
n1=$(echo "$o" | sed -n '/^compare: node-to-node model/,/^compare: reduced model/p' | grep -c 'SNES Function norm')
n2=$(echo "$o" | sed -n '/^compare: reduced model/,$p' | grep -c 'SNES Function norm')
check "[ '$n1' = 0 ] && [ '$n2' -gt 0 ]" "-rom_hbm_snes_monitor: $n2 monitor lines in the reduced model's solve, $n1 in the node-to-node one's"
o=$($J -task compare $brb -frf_force 1 -rom_joints sides -frf_output_file '' -hbm_snes_monitor 2>&1)
n1=$(echo "$o" | sed -n '/^compare: node-to-node model/,/^compare: reduced model/p' | grep -c 'SNES Function norm')
n2=$(echo "$o" | sed -n '/^compare: reduced model/,$p' | grep -c 'SNES Function norm')
check "[ '$n1' -gt 0 ] && [ '$n2' = 0 ]" "-hbm_snes_monitor: $n1 monitor lines in the node-to-node model's solve, $n2 in the reduced model's"
# an internal error keeps PETSc's traceback; -error_trace adds it to a user error
o=$($J -task frf $brb -frf_forse 5 -error_trace -frf_output_file '' 2>&1)
check "echo \"\$o\" | grep -q 'PETSC ERROR'" "-error_trace: the traceback of a user error"
