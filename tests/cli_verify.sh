#!/usr/bin/env bash
# Command-line checks of -frf_verify_points: FRF points checked by time integration (TS) of the same modal equations.
# References independent of the harmonic balance: the exact linear FRF (complex solve here, in awk), the time
# integration of a one-DOF Jenkins oscillator against a converged harmonic balance, and its H = 1 error flagged;
# 1 and 2 ranks; an FE node-to-node model; -help and bad input.
cd "$(dirname "$0")/.."
. tests/cli_lib.sh
mtx() { # file, size, entries "i j v" ...: a symmetric Matrix Market file
  local f=$1 n=$2; shift 2
  { echo '%%MatrixMarket matrix coordinate real symmetric'; echo "$n $n $#"; for e in "$@"; do echo "$e"; done; } > "$f"
}
field() { awk -v k="$1" '{for (i = 1; i < NF; i++) if ($i == k) print $(i + 1)}'; } # value after a key, per line

# a linear 2-DOF system (M = diag(1, 2), K = [2 -1; -1 1] 1e4, C = diag(0.5, 0.2), gamma = 0.01), force at DOF 1,
# response at DOF 0, started from rest: the steady state against x0 = -Z12 F / (Z11 Z22 - Z12^2),
# Z = K (1 + i gamma) - w^2 M + i w C, in physical coordinates (a full mass matrix) and in modes
mtx "$tmp/lK.mtx" 2 "1 1 2e4" "2 1 -1e4" "2 2 1e4"
mtx "$tmp/lM.mtx" 2 "1 1 1" "2 2 2"
mtx "$tmp/lC.mtx" 2 "1 1 0.5" "2 2 0.2"
lin="-task frf -model_stiffness $tmp/lK.mtx -model_mass $tmp/lM.mtx -model_damping $tmp/lC.mtx -hbm_gamma 0.01 -hbm_harmonics 3 -frf_dof 1 -frf_output 0 -frf_force 2 -frf_fmin 5 -frf_fmax 30 -cont_monitor 0 -frf_verify_points 3 -frf_verify_from_rest -frf_verify_periodic_tol 1e-10"
exact() { # freq_hz amp_time -> relative error against the exact FRF
  awk -v f="$1" -v a="$2" 'BEGIN{pi = atan2(0, -1); w = 2 * pi * f; g = 0.01; F = 2
    ar = 2e4 - w * w; ai = 2e4 * g + 0.5 * w; br = -1e4; bi = -1e4 * g; cr = 1e4 - 2 * w * w; ci = 1e4 * g + 0.2 * w
    dr = ar * cr - ai * ci - (br * br - bi * bi); di = ar * ci + ai * cr - 2 * br * bi
    x = F * sqrt(br * br + bi * bi) / sqrt(dr * dr + di * di); e = (a - x) / x; printf "%.2e", e < 0 ? -e : e}'
}
for basis in "" "-hbm_physical"; do
  o=$($J $lin $basis -frf_output_file '' 2>&1)
  worst=$(echo "$o" | grep '^verify level' | while read -r l; do exact "$(echo "$l" | field freq_hz)" "$(echo "$l" | field amplitude_time)"; echo; done | sort -g | tail -1)
  n=$(echo "$o" | grep -c '^verify level')
  check "[ '$n' = 3 ] && awk -v e='$worst' 'BEGIN{exit !(e < 1e-8)}'" "linear 2-DOF ${basis:-modal}, from rest: time integration (RK4, 1000 steps per period) = exact FRF at the peak and 2 points around it (worst relative difference $worst)"
done

# one DOF with a Jenkins element to ground (m = 1 kg, k = kt = 1e4 N/m, c = 0.5657 N s/m, mu n0 = 1 N), 0.1 and 1 N
mtx "$tmp/oK.mtx" 1 "1 1 1e4"
mtx "$tmp/oM.mtx" 1 "1 1 1"
mtx "$tmp/oC.mtx" 1 "1 1 0.5656854249"
printf 'type,dof_a,dof_b,kt,kn,mu,n0,ndof_a,ndof_b\njenkins,0,-1,1e4,,0.1,10,,\n' > "$tmp/oel.csv"
osc="-task frf -model_stiffness $tmp/oK.mtx -model_mass $tmp/oM.mtx -model_damping $tmp/oC.mtx -model_elements $tmp/oel.csv -frf_force 0.1,1 -frf_fmin 12 -frf_fmax 28 -cont_monitor 0 -frf_verify_points 3"
# converged harmonic balance (H = 15, 1024 samples): the time integration agrees to 1e-4 (this checks the verifier)
o=$($J $osc -hbm_harmonics 15 -hbm_samples 1024 -frf_output_file '' 2>&1)
d=$(echo "$o" | grep '^verify level' | field rel_diff | sort -g | tail -1)
n=$(echo "$o" | grep '^verify level' | grep -vc 'higher_harmonics 0.000e+00')
check "[ \$(echo \"\$o\" | grep -c '^verify level') = 6 ] && [ '$n' -ge 3 ] && awk -v d='$d' 'BEGIN{exit !(d < 1e-4)}' && ! echo \"\$o\" | grep -q WARNING" "Jenkins oscillator, H = 15: 6 points (peaks slipping) agree with the time integration within $d"
# H = 1: the peaks' first harmonic is off by more than the tolerance, flagged, and the higher harmonics are seen
o=$($J $osc -hbm_harmonics 1 -frf_output_file '' 2>&1)
p=$(echo "$o" | grep '^verify level 1\. ' | head -1)
d=$(echo "$p" | field rel_diff); s=$(echo "$p" | field higher_harmonics)
check "awk -v d='$d' -v s='$s' 'BEGIN{exit !(d > 1e-2 && s > 5e-3)}' && echo \"\$o\" | grep -q '^verify: WARNING level 1\. .*differs from the harmonic balance'" "Jenkins oscillator, H = 1: the 1 N peak flagged (rel_diff $d, higher harmonics $s of the motion)"

# 1 and 2 ranks: the elements split across the ranks give the same time integration to round-off
bash share/make_chain.sh "$tmp/ch" 30 400 > /dev/null
ch="-task frf -model_stiffness $tmp/ch/K.mtx -model_mass $tmp/ch/M.mtx -model_elements $tmp/ch/elements.csv -hbm_modes 8 -hbm_harmonics 3 -hbm_gamma 0.01 -frf_dof 29 -frf_force 20 -frf_fmin 60 -frf_fmax 200 -cont_monitor 0 -frf_verify_points 2 -frf_verify_max_periods 40"
a=$($J $ch -frf_output_file '' 2>&1 | grep '^verify level' | field amplitude_time)
b=$(mpiexec -n 2 $J $ch -frf_output_file '' 2>&1 | grep '^verify level' | field amplitude_time)
d=$(paste <(echo "$a") <(echo "$b") | awk '{e = ($1 - $2) / $1; if (e < 0) e = -e; if (e > m) m = e; n++} END{if (n != 2) m = 1; printf "%.1e", m}')
check "awk -v d='$d' 'BEGIN{exit !(d < 1e-9)}'" "30-DOF chain, 400 jenkins elements: 1 and 2 ranks, the same time-integrated amplitudes (relative difference $d)"

# an FE node-to-node model (single-bolt lap, coarse mesh, jenkins_nv on every pair, 14 + 14 mixed basis without the static
# correction nor its adaptation, whose stiff local modes would need many more steps per period, 2 ranks)
o=$(mpiexec -n 2 $J -options_file runs/lap1_n2n.opts -model_mesh_h 0.005 -model_mesh_grade 4 -modes_static 0 -modes_adapt 0 -frf_force 0.01 -frf_fmin 120 -frf_fmax 130 -frf_output_file '' -cont_monitor 0 -frf_verify_points 1 -frf_verify_max_periods 60 -frf_verify_periodic_tol 1e-4 2>&1)
l=$(echo "$o" | grep '^verify level')
d=$(echo "$l" | field rel_diff)
check "[ -n '$d' ] && awk -v d='$d' 'BEGIN{exit !(d < 1e-3)}'" "lap1 node-to-node (jenkins_nv, mixed basis, 2 ranks), 0.01 N peak: time integration within $d ($(echo "$l" | field periods) periods, $(echo "$l" | field seconds) s)"

# -help lists the options; bad values are one-line errors
h=$($J $osc -hbm_harmonics 1 -frf_output_file '' -help 2>&1)
miss=""
for x in -frf_verify_points -frf_verify_tol -frf_verify_steps -frf_verify_periodic_tol -frf_verify_max_periods -frf_verify_from_rest; do
  echo "$h" | grep -qE -- "^ *$x[ :]" || miss="$miss $x"
done
check "[ -z '$miss' ]" "-help lists every -frf_verify option${miss:+ (missing:$miss)}"
expect_error "-frf_verify_steps 5" "-frf_verify_steps 5: give 16" $J $osc -frf_output_file '' -frf_verify_steps 5
expect_error "-frf_verify_points -1" "-frf_verify_points -1" $J $osc -frf_output_file '' -frf_verify_points -1
expect_error "-frf_verify_ts_type beuler" "-frf_verify_ts_type beuler: the check steps explicitly" $J $osc -frf_output_file '' -hbm_harmonics 1 -frf_force 1 -frf_verify_ts_type beuler
