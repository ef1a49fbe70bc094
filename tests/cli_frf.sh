#!/usr/bin/env bash
# Command-line checks of bin/jointrom -task frf: the run files, outputs, 1 vs 2 ranks, SNES options
# reaching the solver (-hbm_snes_test_jacobian), the sphere constraint, -help, and bad input.
cd "$(dirname "$0")/.."
. tests/cli_lib.sh
osc="-task frf -model_stiffness runs/oscillator/K.mtx -model_mass runs/oscillator/M.mtx -model_elements runs/oscillator/elements.csv -hbm_gamma 0.01 -cont_monitor 0"

# the oscillator run file: outputs written, one peak line per level, in the order of the levels
o=$($J -options_file runs/oscillator_frf.opts -frf_output_file "$tmp/osc" -cont_monitor 0 2>&1)
check "[ \$(echo \"\$o\" | grep -c '^peak level') = 5 ]" "oscillator_frf.opts: one 'peak level' line per force level"
check "[ \"\$(head -c 4 '$tmp/osc.h5' | tail -c 3)\" = HDF ] && head -1 '$tmp/osc.csv' | grep -q '^level,F_N,omega_rad_s,freq_hz,amp_1,stable$' && [ \$(wc -l < '$tmp/osc.csv') -gt 100 ]" "frf outputs: HDF5 file, CSV with header and the points"
if command -v gnuplot > /dev/null; then check "[ \"\$(head -c 4 '$tmp/osc.png' | tail -c 3)\" = PNG ]" "frf plot PNG written"; fi
# the stability by default on a model whose points the certificate decides (a jenkins element): a stability line
# per level, every point of the CSV flagged stable (1), none left undecided (-1)
ns=$(echo "$o" | grep -c '^stability level'); nu=$(awk -F, 'NR > 1 && $NF != 1' "$tmp/osc.csv" | wc -l)
check "[ '$ns' = 5 ] && [ '$nu' = 0 ]" "oscillator_frf.opts without -frf_stability: stability computed by default ($ns 'stability level' lines), $nu points of the CSV not flagged stable"
if command -v h5dump > /dev/null; then check "h5dump -a /response_1/dof '$tmp/osc.h5' | grep -q '(0): 0\$' && h5dump -a /response_1/name '$tmp/osc.h5' | grep -q '\"response 1 at DOF 0\"'" "frf HDF5: response 1 named by its DOF on a matrices model (/response_1 dof 0)"; fi
# peak frequencies fall from sqrt((k+kt)/m) = 141.4 Hz towards sqrt(k/m) = 100 Hz as the force grows
f=$(echo "$o" | awk '/^peak level/{print $5}' | tr '\n' ' ')
check "echo '$f' | awk '{ok = (\$1 > 139 && \$5 < 102); for (i = 2; i <= NF; i++) if (\$i > \$(i-1) + 1e-3) ok = 0; exit !ok}'" "oscillator peaks move down with the force: $f Hz"

# 1 rank and 2 ranks: the same curves (elements split across ranks), to round-off
bash share/make_chain.sh "$tmp/ch" 30 400 > /dev/null
args="-task frf -model_stiffness $tmp/ch/K.mtx -model_mass $tmp/ch/M.mtx -model_elements $tmp/ch/elements.csv -hbm_modes 8 -hbm_harmonics 3 -hbm_gamma 0.01 -frf_dof 29 -frf_force 20 -cont_monitor 0 -frf_plot 0"
$J $args -frf_output_file "$tmp/np1" > /dev/null 2>&1
mpiexec -n 2 $J $args -frf_output_file "$tmp/np2" > /dev/null 2>&1
d=$(paste -d, "$tmp/np1.csv" "$tmp/np2.csv" | awk -F, 'NR>1{n=NF/2; for(i=3;i<=n;i++){a=$i; b=$(i+n); e=(a-b)/(a==0?1:a); if(e<0)e=-e; if(e>m)m=e}; c++} END{printf "%.1e %d", m, c}')
check "[ -s '$tmp/np2.csv' ] && [ \$(wc -l < '$tmp/np1.csv') = \$(wc -l < '$tmp/np2.csv') ] && awk -v d='${d% *}' 'BEGIN{exit !(d < 1e-8)}'" "30-DOF chain, 400 jenkins elements, H = 3: 1 and 2 ranks give the same curve (${d#* } points, max relative difference ${d% *})"

# a curve is complete or the run fails loudly: chain_frf's 1 N curve reaches the end of its range through the stuck
# resonance (207 Hz); a curve cut short by -cont_max_points is an error naming the level (exit 1, the points written)
# unless -cont_allow_partial
o=$($J -options_file runs/chain_frf.opts -frf_output_file "$tmp/chain" -frf_plot 0 -cont_monitor 0 2>&1); rc=$?
r=$(echo "$o" | awk '/^frf summary/{f=1; next} f && $1 ~ /^[0-9.]+$/ {if ($10 > m) m = $10} END{print m + 0}')
p1=$(echo "$o" | awk '/^peak level 1. /{print $5}')
check "[ $rc = 0 ] && ! echo \"\$o\" | grep -q incomplete && awk -v r='$r' -v p='$p1' 'BEGIN{exit !(r <= 1e-8 && p > 206.5 && p < 207.5)}'" "chain_frf.opts: every curve complete (exit $rc), largest residual of every point $r (<= 1e-8), the 1 N peak at the stuck resonance: $p1 Hz"
# a refined peak that is a computed point already (both responses peak at one kink at 200 N) is not added again:
# no two rows of a level at the same frequency and amplitude to 1e-9
tw=$(awk -F, 'NR > 1 && $1 == l {d = ($4 - f) / f; e = ($5 - a) / a; if (d < 0) d = -d; if (e < 0) e = -e; if (d < 1e-9 && e < 1e-9) n++} NR > 1 {l = $1; f = $4; a = $5} END{print n + 0}' "$tmp/chain.csv" 2>/dev/null)
check "[ -s '$tmp/chain.csv' ] && [ '$tw' = 0 ]" "chain_frf.opts: no point of a curve written twice (twins: $tw)"
# the printed peak is the curve's largest maximum whatever the points: at 200 N chain_frf's curve has two maxima
# 0.14 Hz apart within 0.01% in amplitude, and the largest computed point lies beside one or the other with the step;
# every local maximum of the points near the largest is refined, so the default step, -cont_step 0.007 and 0.013 and
# 1 and 2 ranks print the same peak, to 1e-9 in amplitude
pk=$(echo "$o" | awk '/^peak level 200\. /{print $5, $7}')
for v in "-cont_step 0.007" "-cont_step 0.013" "-n2"; do
  if [ "$v" = -n2 ]; then q=$(mpiexec -n 2 $J -options_file runs/chain_frf.opts -frf_force 200 -frf_stability 0 -frf_output_file '' -frf_plot 0 -cont_monitor 0 2>&1)
  else q=$($J -options_file runs/chain_frf.opts -frf_force 200 -frf_stability 0 $v -frf_output_file '' -frf_plot 0 -cont_monitor 0 2>&1); fi
  pk="$pk / $(echo "$q" | awk '/^peak level 200\. /{print $5, $7}')"
done
check "echo '$pk' | awk -F' / ' '{split(\$1, a, \" \"); ok = NF == 4; for (i = 2; i <= NF; i++) {split(\$i, b, \" \"); d = b[2] / a[2] - 1; if (d < 0) d = -d; if (d > 1e-9 || b[1] - a[1] > 1e-4 || a[1] - b[1] > 1e-4) ok = 0}; exit !ok}'" "chain_frf.opts 200 N: the same peak (freq_hz, amp) at the default step, -cont_step 0.007, 0.013 and on 2 ranks: $pk"
# stability of chain_frf's 1 N curve on 1 and 2 ranks: every point stable, which the time integration of its peak
# (the stuck resonance, 207 Hz, where Hill's method with the periodic Jacobian flagged unstable stretches) confirms
for n in 1 2; do
  o=$(mpiexec -n $n $J -options_file runs/chain_frf.opts -frf_force 1 -frf_stability -frf_verify_points 1 -frf_output_file '' -frf_plot 0 -cont_monitor 0 2>&1)
  s=$(echo "$o" | awk '/^stability level 1\. unstable_points/{print $5, $7}')
  v=$(echo "$o" | awk '/^verify level 1\./{print $11}')
  check "[ '${s% *}' = 0 ] && [ -n '$v' ] && ! echo \"\$o\" | grep -q 'not periodic' && awk -v d='$v' 'BEGIN{exit !(d < 1e-2)}'" "chain_frf.opts 1 N on $n rank(s), -frf_stability: ${s% *} of ${s#* } points unstable; the peak by time integration stays on its response (rel_diff $v)"
done
o=$($J $osc -frf_force 2 -cont_max_points 10 -frf_plot 0 -frf_output_file "$tmp/part" 2>&1); rc=$?
check "[ $rc = 1 ] && [ \$(echo \"\$o\" | grep -c 'jointrom: error') = 1 ] && echo \"\$o\" | grep -q 'level 1 (F = 2. N): the curve is incomplete: -cont_max_points 10 reached' && [ \$(wc -l < '$tmp/part.csv') = 11 ]" "a curve cut short (-cont_max_points 10): exit $rc, one error line naming the level, its 10 points written"
o=$($J $osc -frf_force 2 -cont_max_points 10 -cont_allow_partial -frf_plot 0 -frf_output_file "$tmp/part" 2>&1); rc=$?
check "[ $rc = 0 ] && echo \"\$o\" | grep -q '(incomplete)'" "the same with -cont_allow_partial: exit $rc, the summary marks it incomplete"

# SNES options reach the solver: the analytic Jacobian against PETSc's finite-difference test
o=$($J $osc -frf_force 40 -frf_fmin 120 -frf_fmax 121 -cont_type natural -hbm_snes_test_jacobian -frf_output_file '' 2>&1)
r=$(echo "$o" | grep -o '||J - Jfd||_F/||J||_F = [0-9.e+-]*' | awk '{print $NF}' | sort -g | tail -1)
check "[ -n '$r' ] && awk -v r='$r' 'BEGIN{exit !(r < 1e-5)}'" "-hbm_snes_test_jacobian: ||J - Jfd||/||J|| <= $r"
o=$($J $osc -frf_force 40 -frf_fmin 120 -frf_fmax 121 -cont_type natural -hbm_snes_monitor -frf_output_file '' 2>&1)
check "echo \"\$o\" | grep -q 'SNES Function norm'" "-hbm_snes_monitor reaches the harmonic-balance SNES"

# the default Newton (newtondense: LAPACK LU, backtracking) and PETSc's newtonls + LU trace the same curves: the
# oscillator run file's 5 levels, arclength through the stick-slip kinks, peaks to 1e-9
a=$($J -options_file runs/oscillator_frf.opts -frf_output_file '' -frf_plot 0 -cont_monitor 0 2>&1 | awk '/^peak level/{print $5, $7}')
b=$($J -options_file runs/oscillator_frf.opts -frf_output_file '' -frf_plot 0 -cont_monitor 0 -hbm_snes_type newtonls 2>&1 | awk '/^peak level/{print $5, $7}')
d=$(paste <(echo "$a") <(echo "$b") | awk '{for (i = 1; i <= 2; i++) {e = ($i - $(i + 2)) / $(i + 2); if (e < 0) e = -e; if (e > m) m = e}; n++} END{if (n != 5) m = 1; printf "%.1e", m}')
check "awk -v d='$d' 'BEGIN{exit !(d < 1e-9)}'" "newtondense = newtonls: 5 peaks (frequency, amplitude) within $d"
expect_error "line-search parameter out of range" "-hbm_snes_newtondense_alpha 0.7: give a value in (0, 0.5)" $J $osc -frf_force 40 -frf_fmin 120 -frf_fmax 121 -hbm_snes_newtondense_alpha 0.7 -frf_output_file ''
# its LU kept as GMRES's preconditioner, each step to 1e-3 of the residual that stops Newton (the default), and a new
# LU at every iteration (-hbm_snes_newtondense_reuse_its 0): the same peaks to within Newton's tolerance (the 30-DOF
# chain, 56 unknowns, three levels), and fewer LU
a=$($J $args -frf_force 5,20,80 -frf_output_file '' -log_view 2>&1)
b=$($J $args -frf_force 5,20,80 -frf_output_file '' -log_view -hbm_snes_newtondense_reuse_its 0 2>&1)
d=$(paste <(echo "$a" | awk '/^peak level/{print $5, $7}') <(echo "$b" | awk '/^peak level/{print $5, $7}') | awk '{for (i = 1; i <= 2; i++) {e = ($i - $(i + 2)) / $(i + 2); if (e < 0) e = -e; if (e > m) m = e}; n++} END{if (n != 3) m = 1; printf "%.1e", m}')
la=$(echo "$a" | awk '/--- Event Stage/{s = ($4 == "6:")} s && /^JR_DenseLU /{n += $2} END{print n + 0}')
lb=$(echo "$b" | awk '/--- Event Stage/{s = ($4 == "6:")} s && /^JR_DenseLU /{n += $2} END{print n + 0}')
check "awk -v d='$d' -v a='$la' -v b='$lb' 'BEGIN{exit !(d < 1e-7 && a < b)}'" "newtondense, the LU kept vs a new LU each iteration: 3 peaks within $d; $la against $lb LU"
expect_error "GMRES iterations out of range" "-hbm_snes_newtondense_reuse_its 100: give 0 (a new LU at every iteration) to 60" $J $osc -frf_force 40 -frf_fmin 120 -frf_fmax 121 -hbm_snes_newtondense_reuse_its 100 -frf_output_file ''

# the thesis's sphere constraint passes the Duffing folds too
a=$($J -options_file runs/duffing_frf.opts -frf_force 2 -cont_monitor 0 -frf_output_file '' 2>&1 | grep '^peak')
b=$($J -options_file runs/duffing_frf.opts -frf_force 2 -cont_monitor 0 -frf_output_file '' -cont_constraint sphere 2>&1 | grep '^peak')
check "[ -n '$b' ] && awk -v a='$(echo $a | awk '{print $7}')' -v b='$(echo $b | awk '{print $7}')' 'BEGIN{d=(a-b)/a; if(d<0)d=-d; exit !(d < 1e-3)}'" "Duffing: sphere constraint (2.28) reaches the same peak as pseudo-arclength ($b)"

# -help lists the options of the frf task
h=$($J $osc -frf_force 1 -frf_fmin 100 -frf_fmax 101 -frf_output_file '' -help 2>&1)
miss=""
for o in -model_type -model_stiffness -model_mass -model_damping -model_elements -model_view -hbm_harmonics -hbm_samples -hbm_modes -hbm_physical -hbm_gamma -hbm_zeta -hbm_jacobian -hbm_view -frf_dof -frf_force_file -frf_output -frf_force -frf_omega_min -frf_omega_max -frf_fmin -frf_fmax -frf_output_file -frf_plot -frf_normalize -cont_type -cont_constraint -cont_step -cont_step_min -cont_step_max -cont_max_points -cont_points -cont_newton_target -cont_predictor -cont_monitor; do
  echo "$h" | grep -qE -- "^ *$o[ :]" || miss="$miss $o"
done
check "[ -z '$miss' ]" "-help lists every frf option${miss:+ (missing:$miss)}"

# bad input: non-zero exit and a message naming the file or option
printf '%%%%MatrixMarket matrix coordinate real general\n2 2 3\n1 1 2\n1 2 1\n2 2 2\n' > "$tmp/nonsym.mtx"
printf '%%%%MatrixMarket matrix coordinate real symmetric\n2 2 2\n1 1 2\n2 2 2\n' > "$tmp/two.mtx"
printf '%%%%MatrixMarket matrix array real general\n1 1\n1\n' > "$tmp/array.mtx"
printf '%%%%MatrixMarket matrix coordinate real symmetric\n1 1 1\n1 2 5\n' > "$tmp/badidx.mtx"
printf 'type,dof_a,dof_b,kt,kn,mu,n0,ndof_a,ndof_b\njenkins,5,-1,1e5,,0.1,10,,\n' > "$tmp/el_range.csv"
printf 'type,dof_a,dof_b,kt,kn,mu,n0,ndof_a,ndof_b\ncoulomb,0,-1,1e5,,0.1,10,,\n' > "$tmp/el_type.csv"
printf 'type,dof_a,dof_b,kt,kn,mu,n0,ndof_a,ndof_b\njenkins,0,-1,abc,,0.1,10,,\n' > "$tmp/el_num.csv"
printf 'type,dof_a,dof_b,kt,kn,mu,n0,ndof_a,ndof_b\njenkins,0,-1,1e5,,0.1,10,0,\n' > "$tmp/el_normal.csv"
printf 'type,dof_a,dof_b,kt,kn,mu,n0\njenkins_nv,0,-1,1e5,1e5,0.1,10\n' > "$tmp/el_nvdofs.csv"
printf 'type,dof_a,kt,mu,n0\njenkins,0,1e5,0.1,10\n' > "$tmp/el_col.csv"
M=runs/oscillator/M.mtx; K=runs/oscillator/K.mtx
expect_error "no mass matrix" "needs -model_mass FILE" $J -task frf -model_stiffness $K
expect_error "missing matrix file" "Cannot open matrix file $tmp/none.mtx" $J -task frf -model_stiffness $tmp/none.mtx -model_mass $M
expect_error "mismatched sizes" "is 1 x 1, the stiffness matrix is 2 x 2" $J -task frf -model_stiffness $tmp/two.mtx -model_mass $M
expect_error "non-symmetric stiffness" "Stiffness matrix $tmp/nonsym.mtx is not symmetric" $J -task frf -model_stiffness $tmp/nonsym.mtx -model_mass $tmp/two.mtx
expect_error "dense Matrix Market file" "the first line must be" $J -task frf -model_stiffness $tmp/array.mtx -model_mass $M
expect_error "Matrix Market index out of range" "line 3: bad entry" $J -task frf -model_stiffness $tmp/badidx.mtx -model_mass $M
expect_error "unknown matrix extension" "unknown extension '.csv'" $J -task frf -model_stiffness runs/oscillator/elements.csv -model_mass $M
expect_error "element DOF out of range" "line 2: dof_a = 5 is out of range: DOFs are 0..0" $J -task frf -model_stiffness $K -model_mass $M -model_elements $tmp/el_range.csv
expect_error "unknown element type" "line 2: unknown element type 'coulomb'" $J -task frf -model_stiffness $K -model_mass $M -model_elements $tmp/el_type.csv
expect_error "non-numeric element value" "line 2, column 4 ('kt'): 'abc' is not a finite number" $J -task frf -model_stiffness $K -model_mass $M -model_elements $tmp/el_num.csv
expect_error "normal DOFs on a jenkins element" "normal DOFs are only for jenkins_nv" $J -task frf -model_stiffness $K -model_mass $M -model_elements $tmp/el_normal.csv
expect_error "jenkins_nv without normal DOFs" "a jenkins_nv element needs normal DOFs" $J -task frf -model_stiffness $K -model_mass $M -model_elements $tmp/el_nvdofs.csv
expect_error "element table without dof_b" "has no column 'dof_b'" $J -task frf -model_stiffness $K -model_mass $M -model_elements $tmp/el_col.csv
expect_error "excitation DOF out of range" "-frf_dof 3 is out of range" $J $osc -frf_dof 3
expect_error "output DOF out of range" "-frf_output 7 is out of range" $J $osc -frf_output 0,7
expect_error "samples below 2H+1" "-hbm_samples 4 must be at least 2H+1 = 5" $J $osc -hbm_harmonics 2 -hbm_samples 4
expect_error "reversed frequency range" "need 0 < min < max" $J $osc -frf_fmin 200 -frf_fmax 100
expect_error "half a frequency range" "Give both ends of the frequency range" $J $osc -frf_fmin 100
expect_error "negative force level" "-frf_force -1.: excitation levels must be positive" $J $osc -frf_force 1,-1
expect_error "too many modes" "-hbm_modes 4: the model has only 1 DOFs" $J $osc -hbm_modes 4
expect_error "modal damping in physical coordinates" "-hbm_zeta (modal damping) needs modal coordinates" $J $osc -hbm_physical -hbm_zeta 0.01
