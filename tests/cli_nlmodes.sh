#!/usr/bin/env bash
# Command-line checks of bin/jointrom -task nlmodes: outputs and lines, the backbone's limits on the one-DOF
# oscillator, 1 vs 2 ranks, -help, and bad input.
cd "$(dirname "$0")/.."
. tests/cli_lib.sh
osc="-task nlmodes -model_stiffness runs/oscillator/K.mtx -model_mass runs/oscillator/M.mtx -model_elements runs/oscillator/elements.csv -hbm_gamma 0.01"

# the oscillator (k = kt, m = 1 kg, slip at 25 um): from the stuck mode sqrt(2k/m) = 141.42 Hz, whose damping ratio is
# gamma k / (2 (k + kt)) = 0.25% (structural damping acts on the structure's own stiffness, not on the element's),
# towards the free one (100 Hz) as the element slips; outputs written
o=$($J $osc -hbm_harmonics 3 -nlm_amp_min 1e-6 -nlm_amp_max 1e-2 -nlm_points 25 -nlm_continuation natural -nlm_output_file "$tmp/osc" 2>&1); rc=$?
f=$(echo "$o" | awk '/^backbone point/{print $7}' | tr '\n' ' ')
z=$(echo "$o" | awk '/^backbone point/{print $9}' | tr '\n' ' ')
check "[ $rc = 0 ] && [ \$(echo \"\$o\" | grep -c '^backbone point [0-9]* amplitude [0-9.e+-]* freq_hz [0-9.e+-]* damping_ratio [0-9.e+-]*') = 25 ] && echo '$f' | awk '{ok = (\$1 > 141.4 && \$1 < 141.43 && \$NF > 100 && \$NF < 101); for (i = 2; i <= NF; i++) if (\$i > \$(i-1) + 1e-6) ok = 0; exit !ok}' && echo '$z' | awk '{exit !(\$1 > 0.0024999 && \$1 < 0.0025001)}'" "oscillator, H = 3: 25 'backbone point' lines, frequency falls from 141.42 Hz (stuck) to near 100 Hz (slipping): $(echo $f | awk '{print $1, "..", $NF}') Hz; damping ratio at the smallest amplitude gamma k / (2 (k + kt)) = 0.0025: $(echo $z | awk '{print $1}')"
check "[ \"\$(head -c 4 '$tmp/osc.h5' | tail -c 3)\" = HDF ] && head -1 '$tmp/osc.csv' | grep -q '^point,q,omega_rad_s,freq_hz,damping_ratio,xi,amp_1,newton,balance$' && [ \$(wc -l < '$tmp/osc.csv') = 26 ] && awk -F, 'NR>1 && \$9 > 1e-8 {bad=1} END{exit bad}' '$tmp/osc.csv'" "nlmodes outputs: HDF5, CSV with header and 25 points, each point's energy balance (negative-damping work against the dissipation) within 1e-8"
if command -v gnuplot > /dev/null; then check "[ \"\$(head -c 4 '$tmp/osc.png' | tail -c 3)\" = PNG ]" "nlmodes plot PNG written"; fi

# 1 rank and 2 ranks: the same backbone (400 elements split across the ranks, pseudo-arclength through the region
# near 1.4e-4 where natural continuation in log q fails at H = 3), to round-off
bash share/make_chain.sh "$tmp/ch" 30 400 > /dev/null
args="-task nlmodes -model_stiffness $tmp/ch/K.mtx -model_mass $tmp/ch/M.mtx -model_elements $tmp/ch/elements.csv -hbm_modes 8 -hbm_harmonics 3 -hbm_gamma 0.01 -frf_dof 29 -nlm_points 20 -nlm_plot 0"
$J $args -nlm_output_file "$tmp/np1" > "$tmp/np1.out" 2>&1
mpiexec -n 2 $J $args -nlm_output_file "$tmp/np2" > "$tmp/np2.out" 2>&1
d=$(paste -d, "$tmp/np1.csv" "$tmp/np2.csv" | awk -F, 'NR>1{n=NF/2; for(i=2;i<=7;i++){a=$i; b=$(i+n); e=(a-b)/(a==0?1:a); if(e<0)e=-e; if(e>m)m=e}; c++} END{printf "%.1e %d", m, c}')
r=$(grep '^nlmodes: [0-9]* points' "$tmp/np1.out" | sed 's/.*frequency/frequency/; s/, [0-9]* solves.*//')
check "[ -s '$tmp/np2.csv' ] && [ \$(wc -l < '$tmp/np1.csv') -ge 21 ] && grep -q '^nlmodes: [0-9]* points, ' '$tmp/np1.out' && [ \$(wc -l < '$tmp/np1.csv') = \$(wc -l < '$tmp/np2.csv') ] && awk -v d='${d% *}' 'BEGIN{exit !(d < 1e-9)}'" "30-DOF chain, 400 jenkins elements, H = 3: 1 and 2 ranks give the same backbone (${d#* } points, q, frequency, damping, xi and amplitude within ${d% *}; $r)"

# -help lists the options; bad input is one line
o=$($J -task nlmodes -help 2>&1)
check "(for x in -nlm_mode -nlm_amp_min -nlm_amp_max -nlm_points -nlm_step_max -nlm_output_file -nlm_plot; do echo \"\$o\" | grep -q -- \"\$x[ :]\" || exit 1; done)" "-task nlmodes -help lists -nlm_mode, -nlm_amp_min, -nlm_amp_max, -nlm_points, -nlm_step_max, -nlm_output_file, -nlm_plot"
expect_error "-nlm_points 1" "-nlm_points 1: between 2 and 100000" $J $osc -nlm_points 1 -nlm_output_file ''
expect_error "-nlm_amp_max below -nlm_amp_min" "-nlm_amp_max 1e-06 must exceed -nlm_amp_min 1e-05" $J $osc -nlm_amp_min 1e-5 -nlm_amp_max 1e-6 -nlm_output_file ''
expect_error "-nlm_mode 3 on one DOF" "-nlm_mode 3: the stuck structure has 1 elastic modes" $J $osc -nlm_mode 3 -nlm_output_file ''
expect_error "a misspelled option" "unknown option -nlm_amp_mx" $J $osc -nlm_amp_mx 1 -nlm_output_file ''

# an incomplete backbone is an error, what was computed written: natural continuation in log q on that chain stalls
# near q = 1.4e-4 at H = 3 (Newton fails from the secant predictor however short the step)
o=$($J $args -nlm_continuation natural -nlm_output_file "$tmp/nat" 2>&1); rc=$?
n=$(($(wc -l < "$tmp/nat.csv") - 1))
check "[ $rc = 1 ] && [ \$(echo \"\$o\" | grep -c 'jointrom: error') = 1 ] && echo \"\$o\" | grep -q 'the backbone did not reach -nlm_amp_max' && [ $n -ge 1 ] && [ $n -lt 20 ]" "natural continuation that stalls (the chain at H = 3): exit $rc, one error line, its $n points written"

# -task compare -compare_nlmodes: the node-to-node backbone and the reduced model's beside it, on the coarse
# Brake-Reuss beam (10 mm, 133 jenkins elements, the model of tests/cli_rom.sh with 8 + 8 modes), the backbones alone
# (-compare_frf 0). Every element its own joint is the node-to-node model again: both CSVs the same to round-off
# (2 ranks; its preload and modes are read back by the 2-rank runs below)
brb="-task compare -compare_frf 0 -compare_nlmodes -model_type brb -model_mesh_h 0.01 -preload_force 11500 -interface_kt 1e6 -interface_mu 0.12 -hbm_modes 8 -hbm_gamma 0.002 -hbm_harmonics 3 -frf_fmin 128 -frf_fmax 138 -frf_force 0.1,5,20,50,200 -nlm_points 20 -frf_plot 0"
# the largest relative difference of columns 2-5 (q, omega, frequency, damping ratio) of two backbone CSVs, and the
# count of rows compared ("none" if the row counts differ)
csvdiff() { paste -d, "$1" "$2" | awk -F, 'NR > 1 {n = NF / 2; for (i = 2; i <= 5; i++) {a = $i; b = $(i + n); e = (a - b) / (a == 0 ? 1 : a); if (e < 0) e = -e; if (e > m) m = e}; c++} END{printf "%.1e %d\n", m, c}'; }
o=$(mpiexec -n 2 $J $brb -rom_joints each -frf_output_file "$tmp/ea" 2>&1); rc=$?
b2="-preload_load $tmp/ea_preload.h5 -modes_load $tmp/ea_modes.h5"
read d n <<< "$(csvdiff "$tmp/ea_n2n_nlmodes.csv" "$tmp/ea_rom_nlmodes.csv")"
w=$(echo "$o" | awk '/^compare backbone worst/{print $5, $7}')
check "[ $rc = 0 ] && [ \$(wc -l < '$tmp/ea_n2n_nlmodes.csv') = \$(wc -l < '$tmp/ea_rom_nlmodes.csv') ] && [ '$n' -ge 20 ] && awk -v d='$d' 'BEGIN{exit !(d < 1e-9)}' && echo '$w' | awk '{exit !(\$1 < 1e-9 && \$2 < 1e-12)}'" "compare -compare_nlmodes, -rom_joints each (2 ranks, H = 3): the reduced backbone is node-to-node's, $n points within $d (q, frequency, damping); printed worst differences $w"

# the second reduction (6 joints x 3 elements), condensed onto its joints by default: its backbone in the modal
# unknowns, the same to round-off as with -hbm_condense no given (-task nlmodes on the reduced model alone, over the
# compare run's amplitude range); at the smallest amplitude both models are stuck, where the stiffness correction puts
# the reduced resonance on node-to-node's; the printed worst differences are those of the two CSVs interpolated here
o=$(mpiexec -n 2 $J $brb $b2 -rom_joints sides -rom_elements 3 -frf_output_file "$tmp/s3" 2>&1); rc=$?
range=$(awk -F, 'NR == 2 {a = $2} END{print a, $2}' "$tmp/s3_n2n_nlmodes.csv")
o2=$(mpiexec -n 2 $J ${brb/-task compare -compare_frf 0 -compare_nlmodes/-task nlmodes} $b2 -rom_joints sides -rom_elements 3 -hbm_condense no -nlm_amp_min ${range% *} -nlm_amp_max ${range#* } -nlm_plot 0 -nlm_output_file "$tmp/s3no" 2>&1)
read d n <<< "$(csvdiff "$tmp/s3_rom_nlmodes.csv" "$tmp/s3no.csv")"
f0=$(awk -F, 'FNR == 2 {printf "%s ", $4}' "$tmp/s3_n2n_nlmodes.csv" "$tmp/s3_rom_nlmodes.csv")
# the reduced backbone at each node-to-node amplitude, linear in log q: the worst |f_rom / f_n2n - 1| and |D_rom - D_n2n|
wa=$(awk -F, 'FNR == 1 {next} NR == FNR {q[++n] = $2; f[n] = $4; d[n] = $5; next}
  {for (j = 1; j < n; j++) if ($2 >= q[j] * (1 - 1e-12) && $2 <= q[j + 1] * (1 + 1e-12)) {t = (log($2) - log(q[j])) / (log(q[j + 1]) - log(q[j])); t = t < 0 ? 0 : t > 1 ? 1 : t
     ef = (f[j] + t * (f[j + 1] - f[j])) / $4 - 1; ed = d[j] + t * (d[j + 1] - d[j]) - $5; ef = ef < 0 ? -ef : ef; ed = ed < 0 ? -ed : ed
     if (ef > wf) wf = ef; if (ed > wd) wd = ed; c++; break}}
  END{printf "%.4e %.4e %d\n", wf, wd, c}' "$tmp/s3_rom_nlmodes.csv" "$tmp/s3_n2n_nlmodes.csv")
wp=$(echo "$o" | awk '/^compare backbone worst/{print $5, $7, $11}')
read wf wd wc <<< "$wa"; read pf pd pc <<< "$wp"
check "[ $rc = 0 ] && echo \"\$o\" | grep -q '^nlmodes: the reduced model.s backbone in its modal unknowns.*not condensed onto 6 joint motions' && [ '$n' -ge 20 ] && awk -v d='$d' 'BEGIN{exit !(d < 1e-9)}'" "second reduction 6 x 3 (condensed by default): its backbone in the modal unknowns = -hbm_condense no's, $n points within $d"
check "echo '$f0' | awk '{e = \$2 / \$1 - 1; exit !(e < 1e-8 && e > -1e-8)}' && [ '$wc' = '$pc' ] && close '$pf' '$wf' 1e-3 && close '$pd' '$wd' 1e-3 && awk -v f='$pf' -v d='$pd' 'BEGIN{exit !(f < 1e-3 && d < 5e-4)}'" "6 x 3: stuck frequencies $f0 Hz equal; worst differences printed $pf (frequency), $pd (damping ratio) over $pc points = interpolated here $wf, $wd; within 1e-3 and 5e-4"
check "[ \"\$(head -c 4 '$tmp/s3_rom_nlmodes.h5' | tail -c 3)\" = HDF ] && [ \"\$(head -c 4 '$tmp/s3_n2n_nlmodes.h5' | tail -c 3)\" = HDF ] && head -1 '$tmp/s3_nlmodes_compare.csv' | grep -q '^point,q,n2n_freq_hz,rom_freq_hz,freq_rel_diff,n2n_damping_ratio,rom_damping_ratio,damping_diff' && [ \$(echo \"\$o\" | grep -c '^compare backbone point') = \$((\$(wc -l < '$tmp/s3_nlmodes_compare.csv') - 1)) ] && echo \"\$o\" | grep -q '^compare backbone range n2n_freq_hz [0-9.]* [0-9.]* n2n_damping_ratio' && echo \"\$o\" | grep -q '^compare backbone time n2n_s'" "compare -compare_nlmodes outputs: both backbones' HDF5 and CSV, BASE_nlmodes_compare.csv with a 'compare backbone point' line per row, range and time lines"

# 1 rank against 2: the first reduction's backbones (6 joints; each rank count with its own preload and modes)
o1=$($J $brb -rom_joints sides -rom_nlm_snes_monitor -frf_output_file "$tmp/p1" 2>&1)
mpiexec -n 2 $J $brb $b2 -rom_joints sides -frf_output_file "$tmp/p2" > /dev/null 2>&1
read dn nn <<< "$(csvdiff "$tmp/p1_n2n_nlmodes.csv" "$tmp/p2_n2n_nlmodes.csv")"
read dr nr <<< "$(csvdiff "$tmp/p1_rom_nlmodes.csv" "$tmp/p2_rom_nlmodes.csv")"
check "[ '$nn' -ge 20 ] && [ '$nr' -ge 20 ] && awk -v a='$dn' -v b='$dr' 'BEGIN{exit !(a < 1e-7 && b < 1e-7)}'" "compare -compare_nlmodes, first reduction (6 joints): 1 and 2 ranks give the same backbones (node-to-node $nn points within $dn, reduced $nr within $dr)"

# the reduced model's correctors have their own prefix (the 1-rank run): -rom_nlm_snes_monitor reaches them only
mn=$(echo "$o1" | awk '/^compare: node-to-node model, nonlinear mode/{s = 1} /^compare: reduced model, nonlinear mode/{s = 2} /SNES Function norm/{c[s]++} END{print c[1] + 0, c[2] + 0}')
check "echo '$mn' | awk '{exit !(\$1 == 0 && \$2 > 0)}'" "-rom_nlm_snes_monitor: monitor lines in the node-to-node and the reduced backbone's solves: $mn"

# bad combinations: one line, before any work
for bad in "-hbm_condense yes|-hbm_condense yes: nonlinear modes (EPMC) need the modal unknowns" "-compare_nlmodes 0|nothing to compare; add -compare_nlmodes" "-nlm_output_file $tmp/x|drop -nlm_output_file"; do
  o=$(mpiexec -n 2 $J $brb -rom_joints sides -rom_elements 3 ${bad%%|*} -frf_output_file "$tmp/bad" 2>&1); rc=$?
  check "[ $rc != 0 ] && [ \$(echo \"\$o\" | grep -c '^jointrom: error') = 1 ] && echo \"\$o\" | grep -q -- '${bad#*|}' && ! echo \"\$o\" | grep -q '^preload total'" "bad input, compare -compare_nlmodes with ${bad%%|*}: exit $rc, one line before the preload: '${bad#*|}'"
done
