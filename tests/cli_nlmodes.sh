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
