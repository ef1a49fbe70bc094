#!/usr/bin/env bash
# Command-line checks of bin/jointrom -task preload: the summary line against equilibrium, the outputs
# (CSV, HDF5, XDMF, PNG), a re-run from the written file (-preload_load), 1 vs 2 ranks, the run files on a
# coarse mesh, -help, bad input (negative preload, a force per unknown bolt, a pairs file that does not
# match, a tied interface, a model without an interface).
cd "$(dirname "$0")/.."
. tests/cli_lib.sh
lap="-task preload -model_type lap -model_length_a 0.1 -model_length_b 0.1 -model_lap_length 0.05 -model_width 0.025 -model_height 0.02 -model_nbolts 2 -model_bolt_pitch 0.022 -model_bolt_diameter 0.006 -model_hole_diameter 0.0065 -model_washer_diameter 0.012 -model_mesh_h 0.005 -model_mesh_grade 2"

# equilibrium: the pair loads add up to the pretensions (given per bolt)
o=$($J $lap -preload_force 6000,4000 -preload_kv 1e8 -preload_output_file "$tmp/p" 2>&1)
line=$(echo "$o" | grep '^preload total_normal_force')
tot=$(echo "$line" | awk '{print $3}'); bs=$(echo "$line" | awk '{print $5}'); nc=$(echo "$line" | awk '{print $7}'); np=$(echo "$line" | awk '{print $9}')
check "close '$bs' 10000 1e-12 && close '$tot' 10000 5e-3 && [ '$nc' -gt 0 ] && [ '$nc' -lt '$np' ]" "-task preload, two bolts at 6 and 4 kN: 'preload total_normal_force $tot bolt_force_sum $bs pairs_in_contact $nc pairs $np' (equilibrium within 0.5%)"
# the CSV adds up to the same total; pressure = N / area; no tension; N gap = 0
s=$(awk -F, 'NR > 1 {t += $6; if ($6 < 0) neg = 1; if ($6 > 0 && $8 > 0) comp = 1; d = ($7 * $5 - $6) / (1 + $6); if (d < 0) d = -d; if (d > e) e = d; x = $11 - ($6 - 1e8 * $8); if (x < 0) x = -x; if (x > 1e-6 * (1 + $6)) n0 = 1} END{printf "%.10g %d %d %g %d", t, neg, comp, e, n0}' "$tmp/p.csv")
check "close '$(echo $s | cut -d' ' -f1)' '$tot' 1e-8 && [ \"\$(echo $s | cut -d' ' -f2,3)\" = '0 0' ] && awk 'BEGIN{exit !($(echo $s | cut -d' ' -f4) < 1e-6)}' && [ '$(echo $s | cut -d' ' -f5)' = 0 ]" "preload CSV: the loads add up to the printed total, pressure x area = load, no tension, no load across a gap, n0_N = N - kv gap"
if command -v h5ls > /dev/null; then
  ls=$(h5ls -r "$tmp/p.h5" 2>&1)
  check "echo \"\$ls\" | grep -q \"^/preload/N_static_N .*{$np}\" && echo \"\$ls\" | grep -q \"^/preload/x_m .*{$np, 3}\" && echo \"\$ls\" | grep -q '^/vertex_fields/preload_displacement' && echo \"\$ls\" | grep -q '^/preload/n0_N'" "preload HDF5: /preload/N_static_N, v_gap_m, x_m ($np pairs), n0_N, and the displacement field"
fi
check "grep -q 'p.h5:/preload/pressure_Pa' '$tmp/p.xdmf' && grep -q 'Polyvertex' '$tmp/p.xdmf' && grep -q 'preload_displacement' '$tmp/p.xdmf'" "preload XDMF for ParaView: the deformed assembly and the interface pairs with N, pressure, gap"
if command -v gnuplot > /dev/null; then check "[ \"\$(head -c 4 '$tmp/p.png' | tail -c 3)\" = PNG ]" "preload PNG: pressure and gap maps, mid-section profile"; fi

# read back instead of solving: the same line
r=$($J $lap -preload_force 6000,4000 -preload_load "$tmp/p.csv" -preload_output_file '' 2>&1 | grep '^preload total_normal_force')
check "[ \"\$(echo '$r' | awk '{print \$7, \$9}')\" = '$nc $np' ] && close \"\$(echo '$r' | awk '{print \$3}')\" '$tot' 1e-8" "-preload_load of the written CSV: the same total, $nc of $np pairs closed"

# 1 and 2 ranks: the same result
r2=$(mpiexec -n 2 $J $lap -preload_force 6000,4000 -preload_output_file "$tmp/p2" 2>&1 | grep '^preload total_normal_force')
d=$(paste -d, <(cut -d, -f6 "$tmp/p.csv") <(cut -d, -f6 "$tmp/p2.csv") | awk -F, 'NR > 1 {d = $1 - $2; if (d < 0) d = -d; if (d > e) e = d; if ($1 > m) m = $1} END{printf "%.1e", e / m}')
check "[ \"\$(echo '$r2' | awk '{print \$7, \$9}')\" = '$nc $np' ] && awk 'BEGIN{exit !($d < 1e-8)}'" "1 and 2 ranks: the same pairs closed and the same loads (largest difference $d of the peak)"

# the run files parse and run (coarse mesh here; the full runs are the bench's job)
check "$J -options_file runs/brb_preload.opts -model_mesh_h 0.01 -preload_output_file '' 2>&1 | grep -q '^preload total_normal_force'" "runs/brb_preload.opts runs (coarse mesh here)"
check "$J -options_file runs/lap1_preload.opts -model_mesh_h 0.005 -model_mesh_grade 4 -preload_output_file '' 2>&1 | grep -q '^preload total_normal_force'" "runs/lap1_preload.opts runs (graded mesh here)"

# -help lists the preload options with their units
h=$($J -task preload -model_type brb -model_mesh_h 0.01 -preload_output_file '' -help 2>&1) # a coarse mesh: the help is what is checked
miss=""
for o in -preload_force -preload_method -preload_penalty -preload_rtol -preload_max_it -preload_support -preload_open_start -preload_kv -preload_load -preload_output_file -preload_snes_; do
  echo "$h" | grep -q -- "$o" || miss="$miss $o"
done
check "[ -z '$miss' ] && echo \"\$h\" | grep -q 'pretension \[N\]' && echo \"\$h\" | grep -q 'N/m^3'" "-help lists the preload options with units${miss:+ (missing:$miss)}"

# bad input
expect_error "negative preload" "a pretension is a tension" $J $lap -preload_force -5000 -preload_output_file ''
expect_error "a force for an unknown third bolt" "has 3 values but the model has 2 bolts" $J $lap -preload_force 1,2,3 -preload_output_file ''
head -20 "$tmp/p.csv" > "$tmp/short.csv"
expect_error "pairs file with too few rows" "19 rows, but the model's interface has $np pairs" $J $lap -preload_load "$tmp/short.csv" -preload_output_file ''
expect_error "pairs file that does not exist" "nowhere.csv" $J $lap -preload_load "$tmp/nowhere.csv" -preload_output_file ''
expect_error "tied interface" "needs the free interface" $J $lap -model_interface tied -preload_output_file ''
expect_error "model without an interface" "needs an FE model with a contact interface" $J -task preload -model_type beam -model_mesh_h 0.02 -preload_output_file ''
expect_error "unknown support" "-preload_support" $J $lap -preload_support hinge -preload_output_file ''
expect_error "PETSc's own LU on 2 ranks (it factors only sequential matrices)" "on more than one rank use mumps" mpiexec -n 2 $J $lap -preload_pc_factor_mat_solver_type petsc -preload_output_file ''
