#!/usr/bin/env bash
# Command-line checks of the node-to-node pipeline (-task frf on FE models): the coarse Brake-Reuss beam
# (10 mm, 133 jenkins elements) against independent truths: the stuck structure's natural frequency by
# LAPACK in the same modal basis and by SLEPc on the full FE model with the springs, the Rayleigh-Ritz
# bound of the modal basis, the gross-slip limit (the free interface's mode from -task modes), softening
# and damping growth, energy balance, 1 vs 2 ranks, modes reuse, contact maps, and bad input.
cd "$(dirname "$0")/.."
. tests/cli_lib.sh
brb="-task frf -model_type brb -model_mesh_h 0.01 -preload_force 11500 -interface_kt 1e6 -interface_mu 0.12 -hbm_modes 12 -hbm_gamma 0.002 -cont_monitor 0 -frf_plot 0"
field() { echo "$1" | awk -v k="$2" '{for (i = 1; i < NF; i++) if ($i == k) {print $(i+1); exit}}'; }

# 1. free basis: the FRF peak at 1 mN (every element stuck) = the stuck resonance, eigenvalue of
#    Phi^T (K + sum kt r r^T) Phi by LAPACK; and the modal stuck frequency bounds the full FE one from above
o=$($J $brb -hbm_basis free -frf_force 0.001 -frf_fmin 130 -frf_fmax 139 -frf_stick_fe -frf_output_file "$tmp/free" 2>&1)
s=$(echo "$o" | grep '^stick freq_hz'); c=$(echo "$o" | grep '^contact level 0')
fs=$(field "$s" freq_hz); fp=$(field "$s" lowest_level_peak_hz)
check "[ -n '$fs' ] && [ \"\$(field '$c' full_stick)\" = 133 ] && close $fp $fs 1e-3" "free modal basis, 1 mN: all 133 elements stuck, FRF peak $fp Hz = stuck resonance $fs Hz (LAPACK, same basis) within 0.1%"
e=$(echo "$o" | grep '^stick_fe'); ffe=$(field "$e" freq_hz); e12=$(field "$e" truncation_error)
check "[ -n '$ffe' ] && awk -v e=$e12 'BEGIN{exit !(e >= 0 && e < 5e-3)}'" "free basis of 12 modes: stuck resonance $fs Hz >= full FE with the springs (SLEPc) $ffe Hz (Rayleigh-Ritz), truncation error $e12"
o30=$($J $brb -hbm_basis free -hbm_modes 30 -frf_force 0.001 -frf_fmin 130 -frf_fmax 139 -frf_stick_fe -frf_output_file '' 2>&1)
e30=$(field "$(echo "$o30" | grep '^stick_fe')" truncation_error)
check "[ -n '$e30' ] && awk -v a=$e30 -v b=$e12 'BEGIN{exit !(a >= 0 && a < b)}'" "more modes, smaller truncation error: 12 modes $e12, 30 modes $e30"

# 2. stuck basis: the 1 mN peak = the full FE model's stuck resonance by SLEPc
o=$($J $brb -hbm_basis stuck -frf_force 0.001 -frf_fmin 130 -frf_fmax 139 -frf_stick_fe -frf_output_file "$tmp/st" 2>&1)
fp=$(field "$(echo "$o" | grep '^stick freq_hz')" lowest_level_peak_hz); ffe=$(field "$(echo "$o" | grep '^stick_fe')" freq_hz)
check "[ -n '$ffe' ] && close $fp $ffe 1e-3" "stuck modal basis, 1 mN: FRF peak $fp Hz = full FE model with the stuck springs (SLEPc) $ffe Hz within 0.1%"

# 3. levels: softening and damping growth through microslip, energy balance, the gross-slip limit
lev="0.1,5,20,50,1000"
o=$($J $brb -frf_force $lev -frf_fmin 128 -frf_fmax 138 -frf_output_file "$tmp/lev" 2>&1)
pk=$(echo "$o" | awk '/^peak level/{printf "%s ", $5}')
check "echo '$pk' | awk '{ok = NF == 5; for (i = 2; i <= NF; i++) if (\$i >= \$(i-1)) ok = 0; exit !ok}'" "peaks fall with the level (softening): $pk Hz"
z=$(echo "$o" | awk '/^frf summary/{f=1; next} f && $1 ~ /^[0-9.]+$/ {printf "%s ", $5}')
check "echo '$z' | awk '{exit !(NF == 5 && \$1 < \$2 && \$2 < \$3)}'" "equivalent damping ratio grows through microslip (0.1, 5, 20 N): $z"
b=$(echo "$o" | awk '/^frf summary/{f=1; next} f && $1 ~ /^[0-9.]+$/ {if ($11 > m) m = $11} END{print m}')
check "awk -v b=$b 'BEGIN{exit !(b < 1e-8)}'" "energy balance W_in = W_damping + W_contact at every point of every level: worst $b"
g=$($J $brb -hbm_basis free -frf_force 1000 -frf_fmin 128 -frf_fmax 138 -frf_output_file '' 2>&1 | awk '/^peak level/{print $5}')
m=$($J -task modes -model_type brb -model_mesh_h 0.01 -modes_nev 7 -modes_output_file '' 2>&1 | awk '/^mode 7 /{print $3}')
check "[ -n '$m' ] && [ -n '$g' ] && close $g $m 1e-3" "gross slip (1000 N, free basis): peak $g Hz -> the free interface's first bending mode $m Hz (-task modes) within 0.1%"
# the mixed basis (default; 12 stuck + 12 free modes, Ritz vectors) holds both limits: stuck at 1 mN, free at 1000 N
om=$($J $brb -frf_force 0.001,1000 -frf_fmin 128 -frf_fmax 138 -frf_output_file '' 2>&1)
p1=$(echo "$om" | awk '/^peak level 0.001/{print $5}'); p2=$(echo "$om" | awk '/^peak level 1000/{print $5}')
check "[ -n '$p1' ] && [ -n '$p2' ] && close $p1 $ffe 1e-3 && close $p2 $m 1e-3" "mixed basis: 1 mN peak $p1 Hz = FE stuck $ffe Hz and 1000 N peak $p2 Hz = free interface $m Hz, both within 0.1%"
# contact map: one row per pair, the counts printed equal the CSV's
n=$(($(wc -l < "$tmp/lev_contact.csv") - 1))
c4=$(awk -F, 'NR>1 && $10 == 1{c++} END{print c+0}' "$tmp/lev_contact.csv")
check "[ $n = 175 ] && [ \"\$(field \"\$(echo \"\$o\" | grep '^contact level 4')\" stick_slip)\" = $c4 ]" "contact map CSV: 175 pairs, level 5 stick-slip count $c4 as printed"
check "[ \"\$(head -c 4 '$tmp/lev.h5' | tail -c 3)\" = HDF ] && [ -s '$tmp/lev_preload.csv' ] && [ -s '$tmp/lev_modes.h5' ]" "stage results written: FRF HDF5, preload CSV, modes HDF5"

# 4. 1 and 2 ranks: the same peaks
a=$(echo "$o" | grep '^peak level')
b2=$(mpiexec -n 2 $J $brb -frf_force $lev -frf_fmin 128 -frf_fmax 138 -frf_output_file "$tmp/np2" 2>&1 | grep '^peak level')
d=$(paste <(echo "$a") <(echo "$b2") | awk '{for (i = 5; i <= 9; i += 2) {x = $i; y = $(i+9); e = (x-y)/x; if (e < 0) e = -e; if (e > m) m = e}} END{printf "%.1e", m+0}')
check "[ \$(echo \"\$b2\" | wc -l) = 5 ] && awk -v d=$d 'BEGIN{exit !(d < 1e-8)}'" "1 and 2 ranks: the same peaks (max relative difference $d)"
# the responses are named by index and point, not by the DOF numbers of a partition
h1=$(head -1 "$tmp/lev.csv"); h2=$(head -1 "$tmp/np2.csv")
check "[ '$h1' = 'level,F_N,omega_rad_s,freq_hz,amp_1,amp_2,stable' ] && [ '$h2' = '$h1' ]" "1 and 2 ranks: the same CSV header, responses by index: $h2"
if command -v h5dump > /dev/null; then
  n1=$(h5dump -a /response_1/name "$tmp/lev.h5" | grep -o '"response 1 [^"]*"'); n2=$(h5dump -a /response_1/name "$tmp/np2.h5" | grep -o '"response 1 [^"]*"')
  x2=$(h5dump -a /response_1/x_m "$tmp/np2.h5" | awk '/\(0\):/{print $2}')
  check "[ '$n1' = '\"response 1 along z at (0.72, 0.0127, 0.0254) m\"' ] && [ '$n2' = '$n1' ] && [ '$x2' = 0.72 ]" "1 and 2 ranks: HDF5 /response_1 the same point, $n2 (x_m $x2)"
fi

# -interface_split 70: 70 identical elements in parallel (kt/70, n0/70) per pair: the same curves (9,310 elements:
# the projection rows are gathered in two chunks)
sp=$($J $brb -frf_force $lev -frf_fmin 128 -frf_fmax 138 -interface_split 70 -frf_output_file '' 2>&1 | grep '^peak level')
d=$(paste <(echo "$a") <(echo "$sp") | awk '{for (i = 5; i <= 9; i += 2) {x = $i; y = $(i+9); e = (x-y)/x; if (e < 0) e = -e; if (e > m) m = e}} END{printf "%.1e", m+0}')
check "[ \$(echo \"\$sp\" | wc -l) = 5 ] && awk -v d=$d 'BEGIN{exit !(d < 1e-7)}'" "-interface_split 70 (9,310 elements): the same peaks as 133 elements (max relative difference $d)"

# 5. reuse: -modes_load reproduces the run that saved the modes; bad files are refused
r=$($J $brb -frf_force $lev -frf_fmin 128 -frf_fmax 138 -modes_load "$tmp/lev_modes.h5" -frf_output_file "$tmp/re" 2>&1 | grep '^peak level')
check "[ -n '$r' ] && [ \"\$r\" = \"\$a\" ]" "-modes_load: the same peaks as the run that saved the modes"
expect_error "modes of another interface" "this run needs a mixed basis of this interface" $J $brb -interface_kt 2e6 -frf_force 1 -modes_load "$tmp/lev_modes.h5" -frf_output_file ''
# saved on 1 rank, read on 2: the file holds the modes in the DOFs' natural order (the mesh's points as built), which
# the 2 ranks' numbering maps back; the same modes, so the peaks agree to the 2 ranks' round-off
r2=$(mpiexec -n 2 $J $brb -frf_force $lev -frf_fmin 128 -frf_fmax 138 -modes_load "$tmp/lev_modes.h5" -frf_output_file '' 2>&1 | grep '^peak level')
d=$(paste <(echo "$a") <(echo "$r2") | awk '{for (i = 5; i <= 9; i += 2) {x = $i; y = $(i+9); e = (x-y)/x; if (e < 0) e = -e; if (e > m) m = e}} END{printf "%.1e", m+0}')
check "[ \$(echo \"\$r2\" | wc -l) = 5 ] && awk -v d=$d 'BEGIN{exit !(d < 2e-7)}'" "-modes_load on 2 ranks of modes saved on 1: the same 5 peaks (max relative difference $d)"
# -task modes saves in the same order: its free modes, saved on 2 ranks, give the free basis's peak on 1
mpiexec -n 2 $J -task modes -model_type brb -model_mesh_h 0.01 -modes_nev 12 -modes_save "$tmp/tm.h5" -modes_output_file '' > /dev/null 2>&1
fr=$($J $brb -hbm_basis free -frf_force 1 -frf_fmin 128 -frf_fmax 138 -frf_output_file '' 2>&1 | grep '^peak level')
fl=$($J $brb -hbm_basis free -frf_force 1 -frf_fmin 128 -frf_fmax 138 -modes_load "$tmp/tm.h5" -frf_output_file '' 2>&1 | grep '^peak level')
d=$(paste <(echo "$fr") <(echo "$fl") | awk '{for (i = 5; i <= 7; i += 2) {x = $i; y = $(i+9); e = (x-y)/x; if (e < 0) e = -e; if (e > m) m = e}} END{printf "%.1e", m+0}')
check "[ -n '$fl' ] && awk -v d=$d 'BEGIN{exit !(d < 1e-6)}'" "-task modes -modes_save on 2 ranks, read by a free-basis frf on 1: its peak as with the modes solved there (relative difference $d)"
expect_error "modes file missing" "-modes_load $tmp/none.h5: cannot read the file" $J $brb -frf_force 1 -modes_load "$tmp/none.h5" -frf_output_file ''
expect_error "excitation outside the model" "-frf_at (1., 0., 0.) m: the nearest node is" $J $brb -frf_force 1 -frf_at 1,0,0 -frf_output_file ''
expect_error "negative contact stiffness" "-interface_kt -1.: the tangential stiffness must be positive" $J $brb -frf_force 1 -interface_kt -1 -frf_output_file ''
expect_error "zero friction" "-interface_mu 0.: the friction coefficient must be positive" $J $brb -frf_force 1 -interface_mu 0 -frf_output_file ''
expect_error "a DOF number on an FE model" "-frf_dof: on an FE model the DOF numbers depend on the partition" $J $brb -frf_force 1 -frf_dof 3 -frf_output_file ''
expect_error "two coordinates" "-frf_at needs three coordinates" $J $brb -frf_force 1 -frf_at 0,0 -frf_output_file ''

# 6. jenkins_nv (the single-bolt specimen, coarse): 1 mN peak = stuck resonance in the free basis, energy balance.
#    Newton to 1e-12 of the predictor's residual: at the default 1e-10 the worst point's balance is set by where the
#    steps land (1e-8 or 3e-9 on two equally converged paths), not by the contact law's energy; at 1e-12, 4e-12.
o=$($J -task frf -model_type lap1 -model_mesh_h 0.008 -preload_force 10000 -interface_element jenkins_nv -interface_kt 1e8 -interface_mu 0.1 -hbm_basis free -hbm_modes 30 -hbm_gamma 0.002 -hbm_snes_rtol 1e-12 -frf_force 0.0001,0.01 -frf_fmin 120 -frf_fmax 160 -cont_monitor 0 -frf_plot 0 -frf_output_file '' 2>&1)
s=$(echo "$o" | grep '^stick freq_hz'); fs=$(field "$s" freq_hz); fp=$(field "$s" lowest_level_peak_hz)
b=$(echo "$o" | awk '/^frf summary/{f=1; next} f && $1 ~ /^[0-9.e-]+$/ {if ($11 > m) m = $11} END{print m+0}')
check "[ -n '$fs' ] && close $fp $fs 1e-3" "jenkins_nv lap1, 0.1 mN: FRF peak $fp Hz = stuck resonance (tangential and normal springs of the closed pairs) $fs Hz within 0.1%"
check "awk -v b=$b 'BEGIN{exit !(b < 1e-10)}'" "jenkins_nv lap1: energy balance at every point, worst $b (< 1e-10)"
# an FE model with jenkins_nv elements: the stability is computed by default (the monodromy matrix in time, its fast
# modes condensed), every point of both levels decided, those of 10 mN with elements changing state in time
sn=$(echo "$o" | grep -c '^stability: not computed'); sl=$(echo "$o" | grep -c '^stability level')
s1=$(echo "$o" | grep '^stability level 0.01 ')
st=$(field "$s1" time); so=$(echo "$s1" | awk '{for(i=1;i<NF;i++) if($i=="of") print $(i+1)}'); sd=$(field "$s1" dissipative)
check "[ '$sn' = 0 ] && [ '$sl' = 2 ] && [ -n '$st' ] && [ '$st' -gt 0 ] && [ \$(( st + sd )) = '$so' ]" "jenkins_nv lap1 without -frf_stability: stability computed by default ($sl levels; at 10 mN $st of $so points by the monodromy matrix in time, $sd certified)"

# the monodromy in time with the fast modes condensed, on the Brake-Reuss beam (jenkins elements: incremental
# dissipativity proves every point stable; here the certificate is switched off, -frf_stability_dissipative 0, so the
# monodromy decides): no point unstable at any of the five levels, with modes condensed
o=$(mpiexec -n 2 $J -options_file runs/default.opts -frf_stability_dissipative 0 -frf_output_file '' -frf_plot 0 -cont_monitor 0 2>&1)
su=$(echo "$o" | awk '/^stability level/{u += $5; n += $7; for (i = 1; i < NF; i++) {if ($i == "time") t += $(i + 1); if ($i == "fast_modes" && $(i + 1) > f) f = $(i + 1)}} END{printf "%d %d %d %d", u, n, t, f}')
read su sn stm sf <<< "$su"
check "[ '$sn' -gt 300 ] && [ '$su' = 0 ] && [ '$stm' = '$sn' ] && [ '$sf' -gt 0 ]" "BRB (jenkins) with the certificate off: every one of $sn points decided by the monodromy in time ($stm), up to $sf fast modes condensed, $su unstable (incremental dissipativity: none)"

# 7. first reduction: every element its own joint reproduces the node-to-node
#    model exactly; six strips run; bad region definitions are refused
r=$($J $brb -frf_force $lev -frf_fmin 128 -frf_fmax 138 -rom_joints each -frf_output_file '' 2>&1 | grep '^peak level')
check "[ -n '$r' ] && [ \"\$r\" = \"\$a\" ]" "-rom_joints each: exactly the node-to-node peaks"
o=$($J $brb -frf_force 20 -frf_fmin 128 -frf_fmax 138 -rom_joints strips -rom_strips 0.33,0.345,0.36,0.375,0.39 -frf_output_file '' 2>&1)
nj=$(echo "$o" | grep -c '^rom: joint'); ne=$(echo "$o" | awk '/^rom: joint/{s += $4} END{print s}')
check "[ $nj = 6 ] && [ '$ne' = 133 ] && echo \"\$o\" | grep -q '^peak level 20'" "-rom_joints strips: 6 joints holding all 133 elements, FRF computed"
expect_error "cuts not increasing" "-rom_strips: the cuts must increase" $J $brb -frf_force 1 -rom_joints strips -rom_strips 0.36,0.33 -frf_output_file ''
expect_error "empty region" "holds no element" $J $brb -frf_force 1 -rom_joints strips -rom_strips 0.33,0.331 -frf_output_file ''
expect_error "strips without cuts" "-rom_joints strips needs the cuts" $J $brb -frf_force 1 -rom_joints strips -frf_output_file ''
expect_error "cuts without strips" "-rom_strips needs -rom_joints strips" $J $brb -frf_force 1 -rom_strips 0.35 -frf_output_file ''
