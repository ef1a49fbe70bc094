#!/usr/bin/env bash
# Command-line checks of the reduced-order joints (-task compare, -rom_*) on the coarse Brake-Reuss beam (10 mm, 133
# jenkins elements), against the node-to-node model computed in the same run (an independent model: every pair its own
# element): every element its own joint reproduces it exactly; the first reduction with mode-shape weights and the
# second reduction (6 joints x 3 elements) within stated errors; the stiffness correction puts the reduced model's stuck
# resonance on the node-to-node one; a saved reduced model reproduces the run that saved it (also without the preload);
# the same two with jenkins_nv elements (normal load following the normal motion) on the coarse single-bolt lap (lap1,
# 132 pairs), at levels where pairs stick, slip and separate: every element its own joint reproduces node-to-node and
# its contact states to round-off and what each element dissipates at the peaks (compare joints), a saved second
# reduction the run that saved it (on the same modes: to round-off), the joints from the slip onsets within 0.1% and
# 2% of node-to-node from microslip through separation; bad regions and files; on the jenkins_nv laps, the joints' linear motion field (-rom_joint_motion linear) between the
# mean's and node-to-node's, and carrying lap1's bending; with the stuck-mode coordinates (-rom_joint_motion mode) the
# mode of interest kept exactly; with the members' residual springs kept (-rom_joint_residual) the stuck model
# node-to-node's. Runs of one model after the first read its preload and modes (-preload_load,
# -modes_load: the same basis, as -task compare's two models share it). The slower end-to-end checks (one-member joints
# with the linear field, mode-shape weights vs the plain average, 6 x 4, 7, 10 elements, save and load of the other
# joint motions, 1 vs 2 ranks, condensation of the first reduction, the auto partition and the stiffness correction's
# warning on the Brake-Reuss beam, each on 1 and 2 ranks): tests/cli_long.sh.
cd "$(dirname "$0")/.."
. tests/cli_lib.sh
brb="-model_type brb -model_mesh_h 0.01 -preload_force 11500 -interface_kt 1e6 -interface_mu 0.12 -hbm_modes 12 -hbm_gamma 0.002 -cont_monitor 0 -frf_plot 0 -frf_fmin 128 -frf_fmax 138"
lev="0.1,5,20,50,200"
field() { echo "$1" | awk -v k="$2" '{for (i = 1; i < NF; i++) if ($i == k) {print $(i+1); exit}}'; }
worst() { echo "$1" | awk '/^compare worst/{print $4, $6}'; }
lt() { awk -v a="$1" -v b="$2" 'BEGIN{exit !(a != "" && a < b)}'; }

# 1. every element its own joint: the node-to-node model exactly (to round-off)
o=$(mpiexec -n 2 $J -task compare $brb -frf_force $lev -rom_joints each -frf_output_file '' 2>&1)
read f a <<< "$(worst "$o")"
check "lt '$f' 1e-9 && lt '$a' 1e-8" "-rom_joints each: reduced = node-to-node at 5 levels, worst peak frequency error $f, amplitude error $a"
# its stiffness correction: every joint's springs hold the mode's strain energy its member's do, so the factor is 1
# to round-off and there is no warning
c=$(field "$(echo "$o" | grep '^rom stiffness_correction')" stiffness_correction); se=$(echo "$o" | grep '^rom stiffness_energy')
sm=$(field "$se" members_share); sj=$(field "$se" joints_share)
check "[ -n '$c' ] && close $c 1 1e-9 && close $sj $sm 1e-12 && ! echo \"\$o\" | grep -q 'WARNING stiffness'" "-rom_joints each: stiffness correction $c (1 to 1e-9), the joints' share of the stuck mode's strain energy $sj = the members' $sm, no warning"

# 2. first reduction, 6 joints (each side of each bolt), members weighted by their motion in the stuck mode
o=$(mpiexec -n 2 $J -task compare $brb -frf_force $lev -rom_joints sides -frf_output_file "$tmp/s0" 2>&1)
read f a <<< "$(worst "$o")"
nj=$(echo "$o" | grep -c '^rom: joint'); ne=$(echo "$o" | awk '/^rom: joint/{s += $4} END{print s}')
check "[ $nj = 6 ] && [ '$ne' = 133 ] && lt '$f' 1e-4 && lt '$a' 1e-2" "first reduction, 6 joints (133 members), mode-shape weights: worst peak error $f (< 1e-4), amplitude $a (< 1%)"
# the joints' report: their loads add up to the preload's total normal force (the preload's own line), their shares
# to 100%, their centroids lie on the lap (0.3 .. 0.42 m), and the partition's summary counts the members
pt=$(field "$(echo "$o" | grep '^preload total_normal_force')" total_normal_force)
jl=$(echo "$o" | grep '^rom: joint [0-9]*:' | sed -E 's/.*normal load ([^ ]+) N \(([0-9.]+)% of the preload\), centroid \(([^,]+),.*/\1 \2 \3/' | awk '{l += $1; p += $2; if ($3 < 0.3 || $3 > 0.42) out++} END{printf "%.8g %.3f %d", l, p, out}')
read jls jsh jout <<< "$jl"
pm=$(echo "$o" | grep '^rom partition '); pj=$(field "$pm" joints)
check "[ -n '$pt' ] && close $jls $pt 1e-5 && close $jsh 100 0.01 && [ '$jout' = 0 ] && [ '$pj' = 6 ]" "joints' report (sides): loads add up to $jls N = the preload's $pt N, shares to $jsh%, centroids on the lap, partition line: $pm"
c=$(echo "$o" | grep '^rom stiffness_correction')
check "[ -f '$tmp/s0_compare.csv' ] && [ \$(grep -c . '$tmp/s0_compare.csv') = 6 ] && [ \$(echo \"\$o\" | grep -c '^compare level') = 5 ]" "compare: BASE_compare.csv with 5 levels and 5 'compare level' lines"
# where the solve time goes: the elements' part of each model's solve lies within that solve (no timing is compared)
ts=$(echo "$o" | awk '/^compare time /{tn = $4; tr = $6} /^compare time_split/{en = $4; er = $8; print tn, tr, en, er, $12}')
read tn tr en er cap <<< "$ts"
check "[ -n '$cap' ] && awk 'BEGIN{exit !($en > 0 && $en <= $tn && $er > 0 && $er <= $tr && $cap >= $tn / $tr)}'" "compare time_split: the elements' time within each solve (node-to-node $en of $tn s, reduced $er of $tr s), speed-up cap $cap"

# 3. second reduction: 6 joints x 3 elements (4 and 7: tests/cli_long.sh)
o=$(mpiexec -n 2 $J -task compare $brb -frf_force $lev -rom_joints sides -rom_elements 3 -frf_output_file "$tmp/s3" 2>&1)
read f a <<< "$(worst "$o")"
ne=$(echo "$o" | awk '/^rom joint/{s += $7} END{print s}')
check "[ -n '$ne' ] && [ '$ne' -ge 6 ] && [ '$ne' -le 18 ] && lt '$f' 5e-3" "second reduction 6 x 3: $ne elements (at most 18: elements the fit leaves without force are dropped), worst peak frequency error $f (< 0.5%)"
# the amplitude at every level (0.1..200 N): the 5% target. Measured with the fit coupled across joints
# (-rom_fit_total_weight 20): 2.6% (6 x 3), 1.3% (6 x 4), 2.2% (6 x 7); each joint alone: 9.2%, 4.5%, 2.2%
aw=$(echo "$o" | awk '/^compare level/ {e = $11 / $9 - 1; if (e < 0) e = -e; if (e > w) w = e} END{print w + 0}')
nc=$(echo "$o" | grep -c '^rom case level .* dissipation_error')
check "lt '$aw' 0.05 && [ '$nc' = 5 ]" "second reduction 6 x 3: amplitude within 0.05 at every level (0.1..200 N): worst $aw; the fit's dissipation error printed for the 5 levels"
# the coupled fit: the energy all joints dissipate together at the case's amplitudes at least 2x closer than with
# each joint fitted alone (which is where it starts); each joint's own rows may give way
cp=$(echo "$o" | grep '^rom coupled')
rt=$(field "$cp" all_joints_energy_residual); rt0=$(field "$cp" each_alone)
check "[ -n '$rt' ] && lt \$(awk -v a='$rt' 'BEGIN{print 2 * a}') '$rt0' && [ -f '$tmp/s3_rom_loops.csv' ]" "second reduction 6 x 3, coupled across joints: all joints' energy residual $rt (each joint alone: $rt0), loops written"
o1=$(mpiexec -n 2 $J -task frf $brb -frf_force $lev -rom_joints sides -rom_elements 3 -rom_fit_total_weight 0 -frf_output_file '' 2>&1)
r=$(echo "$o1" | awk '/^rom joint/{if ($13 > w) w = $13} END{print w}')
r0=$(echo "$o1" | awk '/^rom joint/{if ($15 > w) w = $15} END{print w}')
check "lt '$r' '$r0' && ! echo \"\$o1\" | grep -q '^rom coupled'" "second reduction 6 x 3, each joint alone (-rom_fit_total_weight 0): the fit lowers every joint's residual below the start's (worst $r < $r0)"
cr=$(echo "$o" | grep '^rom stiffness_correction')
# -rom_fit_select first: every pair of weights fitted and solved, the pair nearest the first reduction kept. Checked
# against separate runs: the same weights given directly give the same reduced model, and its peaks against the first
# reduction's (-rom_elements 0) give the error printed for that pair, the smallest printed (one rank, the later runs
# with this run's preload and modes ($b1): the same model bit for bit)
os=$($J -task compare $brb -frf_force $lev -rom_joints sides -rom_elements 3 -rom_fit_select first -frf_output_file "$tmp/b1" 2>&1)
b1="-preload_load $tmp/b1_preload.h5 -modes_load $tmp/b1_modes.h5"
ns=$(echo "$os" | grep -c '^rom select ')
cl=$(echo "$os" | grep '^rom: fit weights chosen')
bt=$(field "$cl" -rom_fit_total_weight); bk=$(field "$cl" -rom_fit_case_weight)
emin=$(echo "$os" | awk '/^rom select /{if (m == "" || $8 < m) {m = $8; t = $4; k = $6}} END{print m, t, k}')
read em et ek <<< "$emin"
nsc=$(echo "$os" | grep '^rom select ' | grep -c 'stiffness_correction [0-9]')
check "[ '$nsc' = 6 ] && [ '$ns' = 6 ] && [ -n '$bt' ] && awk 'BEGIN{exit !($bt == $et && $bk == $ek)}'" "-rom_fit_select first: 6 pairs fitted and solved (each with its stiffness correction printed), the one of the smallest error vs the first reduction chosen (total $bt, case $bk; error $em)"
od=$($J -task compare $brb $b1 -frf_force $lev -rom_joints sides -rom_elements 3 -rom_fit_total_weight $bt -rom_fit_case_weight $bk -frf_output_file '' 2>&1)
o0=$($J -task compare $brb $b1 -frf_force $lev -rom_joints sides -rom_elements 0 -frf_output_file '' 2>&1)
amps() { echo "$1" | awk '/^compare level/{printf "%s ", $11}'; }
dd=$(awk -v a="$(amps "$os")" -v b="$(amps "$od")" 'BEGIN{n = split(a, x); split(b, y); for (i = 1; i <= n; i++) {e = x[i] / y[i] - 1; if (e < 0) e = -e; if (e > m) m = e} print (n == 5 ? m + 0 : "none")}')
e0=$(awk -v a="$(amps "$os")" -v b="$(amps "$o0")" 'BEGIN{n = split(a, x); split(b, y); for (i = 1; i <= n; i++) {e = x[i] / y[i] - 1; if (e < 0) e = -e; if (e > m) m = e} print (n == 5 ? m + 0 : "none")}')
check "lt '$dd' 1e-12 && close '$e0' '$em' 1e-3" "-rom_fit_select first = the chosen weights given directly (peak amplitudes within $dd); its worst amplitude vs a separate first-reduction run $e0 = the printed $em"
# the stiffness correction: the reduced model's stuck resonance (LAPACK, same basis) = the node-to-node one
o=$($J -task frf $brb $b1 -frf_force 0.01 -rom_joints sides -rom_elements 3 -frf_output_file '' 2>&1)
fr=$(field "$(echo "$o" | grep '^stick freq_hz')" freq_hz); fn=$(field "$(echo "$o" | grep '^rom stiffness_correction')" n2n_hz)
check "[ -n '$fr' ] && close $fr $fn 1e-9" "stiffness correction ($(field "$cr" stiffness_correction)): reduced stuck resonance $fr Hz = node-to-node $fn Hz"

# 4. save and load: the loaded model (no preload, no fit) reproduces the run that saved it, on a fixed frequency grid
# (the loading run solves the modes again, to SLEPc's tolerance: amplitudes agree to 1e-7; on the arclength path such
# differences move the points, and the peaks by ~1e-6). At 0.1 and 50 N, as 4b, which reuses the loading run. The
# other joint motions and 1 vs 2 ranks: tests/cli_long.sh
fix="-cont_type natural -cont_points 120"
same() { awk -F, 'NR == FNR {if (FNR > 1) a[$1 " " $4] = $5; next} FNR > 1 && ($1 " " $4) in a {d = $5 / a[$1 " " $4] - 1; if (d < 0) d = -d; n++; if (d > m) m = d} END{printf "%d %.2e\n", n, m}' "$1" "$2"; }
osv=$(mpiexec -n 2 $J -task frf $brb $fix -frf_force 0.1,50 -rom_joints sides -rom_elements 3 -rom_save "$tmp/rom.h5" -frf_output_file "$tmp/sv" 2>&1)
o=$(mpiexec -n 2 $J -task frf $brb $fix -frf_force 0.1,50 -rom_load "$tmp/rom.h5" -frf_output_file "$tmp/ld" 2>&1)
read nm dm <<< "$(same "$tmp/sv.csv" "$tmp/ld.csv" 2>/dev/null)"
check "[ '$nm' -ge 100 ] && lt '$dm' 1e-7 && ! echo \"\$o\" | grep -q '^preload total'" "-rom_load reproduces the saving run (no preload solved): amplitudes at $nm common frequencies within $dm (< 1e-7)"
# on 1 rank, the model and the modes the saving run wrote on 2 (both in the DOFs' natural order): the same model,
# so the same amplitudes to round-off
o1=$($J -task frf $brb $fix -frf_force 0.1,50 -rom_load "$tmp/rom.h5" -modes_load "$tmp/sv_modes.h5" -frf_output_file "$tmp/ld1" 2>&1)
read nm1 dm1 <<< "$(same "$tmp/sv.csv" "$tmp/ld1.csv" 2>/dev/null)"
check "[ '$nm1' -ge 100 ] && lt '$dm1' 1e-9 && echo \"\$o1\" | grep -q '^rom: loaded 18 '" "-rom_load and -modes_load on 1 rank of a model and modes saved on 2: amplitudes at $nm1 common frequencies within $dm1 (< 1e-9)"
cs=$(field "$(echo "$osv" | grep '^rom stiffness_correction')" stiffness_correction); cl=$(echo "$o" | grep '^rom stiffness_correction')
check "[ -n '$cs' ] && close \$(field \"\$cl\" stiffness_correction) $cs 1e-7 && echo \"\$cl\" | grep -q 'file $tmp/rom.h5'" "-rom_load prints the factor in its file: '$cl' (the saving run's $cs)"

# 4a. levels apart: a reduced model's elements are on every rank, so its levels' curves are shared out over the ranks
# (level l on rank l mod 2), each solved by one rank from no kept factors; the points are those of every rank solving
# every level (-cont_levels_parallel 0), byte for byte, at 4 levels on the arclength path, and its peaks those of 1
# rank (the saving run's modes: the same model) to round-off. The same for a node-to-node model whose elements are on
# every rank (-hbm_elements_replicated): its peaks those of its elements split over the ranks to round-off.
l4="-frf_force 0.1,5,20,50"
pk() { echo "$1" | awk '/^peak level/{printf "%s %s %s ", $3, $5, $7}'; }
pkd() { awk -v a="$1" -v b="$2" 'BEGIN{n = split(a, x, " "); m = split(b, y, " "); if (n != m || n == 0) {print 1, 1; exit}; for (i = 1; i <= n; i++) {d = x[i] - y[i]; if (d < 0) d = -d; s = x[i] < 0 ? -x[i] : x[i]; if (s > 0 && i % 3 == 2 && d / s > rf) rf = d / s; if (s > 0 && i % 3 == 0 && d / s > ra) ra = d / s}; printf "%.2e %.2e\n", rf, ra}'; }
ola=$(mpiexec -n 2 $J -task frf $brb $l4 -rom_load "$tmp/rom.h5" -modes_load "$tmp/sv_modes.h5" -frf_output_file "$tmp/la" 2>&1)
ols=$(mpiexec -n 2 $J -task frf $brb $l4 -rom_load "$tmp/rom.h5" -modes_load "$tmp/sv_modes.h5" -cont_levels_parallel 0 -frf_output_file "$tmp/ls" 2>&1)
ol1=$($J -task frf $brb $l4 -rom_load "$tmp/rom.h5" -modes_load "$tmp/sv_modes.h5" -frf_output_file "$tmp/l1" 2>&1)
read d1f d1 <<< "$(pkd "$(pk "$ol1")" "$(pk "$ola")")"; np=$(grep -c . "$tmp/la.csv" 2>/dev/null)
check "[ -s '$tmp/la.csv' ] && cmp -s '$tmp/la.csv' '$tmp/ls.csv' && [ \"\$(pk \"\$ola\")\" = \"\$(pk \"\$ols\")\" ] && [ \$(echo \"\$ola\" | grep -c '^peak level') = 4 ] && lt '$d1f' 1e-6 && lt '$d1' 1e-8" "reduced model, 4 levels shared out over 2 ranks: the CSV ($np lines) and the peaks of every rank solving every level, byte for byte; the peaks of 1 rank within $d1f in frequency (< 1e-6: the top of a peak is flat, so round-off in its amplitude moves its frequency by about the square root) and $d1 in amplitude (< 1e-8)"
ona=$(mpiexec -n 2 $J -task frf $brb $l4 -modes_load "$tmp/sv_modes.h5" -hbm_elements_replicated -frf_output_file '' 2>&1)
ons=$(mpiexec -n 2 $J -task frf $brb $l4 -modes_load "$tmp/sv_modes.h5" -frf_output_file '' 2>&1)
read dnf dn <<< "$(pkd "$(pk "$ons")" "$(pk "$ona")")"
check "[ \$(echo \"\$ona\" | grep -c '^peak level') = 4 ] && lt '$dnf' 1e-6 && lt '$dn' 1e-8" "node-to-node model, its elements on every rank (-hbm_elements_replicated) and its levels shared out: the peaks of its elements split over the ranks within $dnf in frequency (< 1e-6) and $dn in amplitude (< 1e-8; each run solves its preload)"

# 4b. condensation onto the joints (-hbm_condense, on by default for reduced models): the modal equations with the
# modes eliminated exactly, so on the frequencies both solve the amplitudes agree to round-off and solver tolerance.
# At 0.1 and 50 N: at 1 N the peak bends over (a fold near 133.9 Hz, solutions 2.5% apart), where natural continuation
# may land on either branch as the recomputed modes differ at round-off from run to run. The loading run of 4
# (condensed) against the same model not condensed; the first reduction's: tests/cli_long.sh
info=$(echo "$o" | grep -o 'condensed onto.*')
mpiexec -n 2 $J -task frf $brb $fix -frf_force 0.1,50 -rom_load "$tmp/rom.h5" -hbm_condense no -frf_output_file "$tmp/cd_no" > /dev/null 2>&1
read nm dm <<< "$(same "$tmp/cd_no.csv" "$tmp/ld.csv")"
check "[ -n '$info' ] && [ '$nm' -ge 100 ] && lt '$dm' 1e-7" "second reduction (6 x 3, loaded) $info; amplitudes at $nm common frequencies = the modal equations' within $dm (< 1e-7)"

# 4c. 1 and 4 again with jenkins_nv elements (normal load following the normal motion, separation): the single-bolt
# lap of runs/lap1_rom.opts on its coarsest mesh (8 mm, graded: 132 pairs, 74 in contact at rest) and a small basis (8
# stuck + 8 free modes + 30 static vectors: both models share whichever basis), on 2 ranks. At 0.5 N the node-to-node
# peak has pairs in full stick, in stick-slip and separating and closing within the cycle (the contact states' counts
# printed per level), some of the separating ones closed at rest (the preload's CSV against the contact map); every
# element its own joint reproduces it, and every level's states, to round-off. The compare run writes its preload and
# modes, which the saving and the loading runs read (the saving run checks the read basis: within the computing run's
# bounds): on the same basis the
# loaded model (4 zone joints, 3 elements each and, -rom_joint_motion mode, 3 more for each low-load joint's open
# members, each placed half at each of two points: 36 elements) gives the saving run's curves to round-off, not to the
# modes' tolerance as in 4
nv="-model_type lap1 -model_mesh_h 0.008 -model_mesh_grade 4 -preload_force 10000 -interface_element jenkins_nv -interface_kt 1e8 -interface_kn 1e8 -interface_mu 0.1 -hbm_modes 8 -modes_static_max 30 -hbm_gamma 0.002 -frf_fmin 110 -frf_fmax 160 -frf_normalize -frf_plot 0 -cont_monitor 0"
states() { echo "$1" | awk '/^frf summary/{t++} $1 ~ /^[0-9.e+-]+$/ && $(NF-5) == "/" {printf "%s:%s/%s/%s/%s ", t, $(NF-6), $(NF-4), $(NF-2), $NF}'; }
o=$(mpiexec -n 2 $J -task compare $nv -frf_force 0.01,0.5,2 -rom_joints each -frf_output_file "$tmp/nv" 2>&1)
read f a <<< "$(worst "$o")"
nl=$(echo "$o" | grep -c '^compare level')
# (the frequency of a maximum is set only to about the square root of the amplitudes' relative difference, 1e-10,
# times the peak's relative half-width, 1e-3: 1e-8, allowed 1e-7; the amplitude 1e-8)
check "[ '$nl' = 3 ] && lt '$f' 1e-7 && lt '$a' 1e-8" "jenkins_nv lap1, -rom_joints each: reduced = node-to-node at 3 levels (0.01, 0.5, 2 N), worst peak frequency error $f, amplitude error $a"
# where each model dissipates at its peaks, joint by joint (compare joints lines, BASE_compare_joints.csv): every
# element its own joint dissipates what its node-to-node element does, at its own peak and under the node-to-node
# peak's motion (rom_at_n2n_peak_J: the same model on the same unknowns), and the node-to-node shares sum to 1
cj=$(echo "$o" | grep '^compare joints level'); dj=$(echo "$cj" | awk '{d = $8 / $6 - 1; if (d < 0) d = -d; if (d > m) m = d; x = $16 / $6 - 1; if (x < 0) x = -x; if (x > m) m = x; n++} END{printf "%d %.2e", n, m}')
cjs=$(awk -F, 'NR > 1 {s[$1] += $6; r++} END{for (l in s) {d = s[l] - 1; if (d < 0) d = -d; if (d > m) m = d}; printf "%d %.2e", r, m}' "$tmp/nv_compare_joints.csv" 2>/dev/null)
read nj dm <<< "$dj"; read nr sm <<< "$cjs"
check "[ '$nj' = 3 ] && lt '$dm' 1e-6 && lt 0 \$(field \"\$(echo \"\$cj\" | sed -n 2p)\" n2n_J) && [ '$nr' = \$((3 * 132)) ] && lt '$sm' 1e-6" "jenkins_nv lap1, -rom_joints each: every joint dissipates at the peaks what its node-to-node element does (3 levels, worst $dm); the CSV's $nr rows, shares summing to 1 (to $sm)"
cs=$(echo "$o" | grep '^contact level 1 ')
st=$(states "$o"); sn=$(echo "$st" | tr ' ' '\n' | sed -n 's/^1://p' | tr '\n' ' '); sr=$(echo "$st" | tr ' ' '\n' | sed -n 's/^2://p' | tr '\n' ' '); sr=${sr% }; sn=${sn% }
# the pairs closed at rest (preload CSV) that open within the cycle at 0.5 N (contact map), row by row: one per pair
so=$(awk -F, 'FNR == 1 {for (i = 1; i <= NF; i++) c[$i] = i; next} NR == FNR {cl[FNR] = $c["closed"]; next} cl[FNR] == 1 && $c["state_level_1"] >= 2 {s++} END{print s + 0}' "$tmp/nv_preload.csv" "$tmp/nv_contact.csv" 2>/dev/null)
check "[ -n '$cs' ] && [ \$(field '$cs' full_stick) -gt 0 ] && [ \$(field '$cs' stick_slip) -gt 0 ] && [ \$(field '$cs' separation_stick_slip) -gt 0 ] && [ '$so' -gt 0 ] && [ \$(echo '$sn' | wc -w) = 3 ] && [ '$sn' = '$sr' ]" "jenkins_nv lap1, 0.5 N: stick, slip and separation at the node-to-node peak ($cs; $so pairs closed at rest open within the cycle); every element its own joint, the same states at every level (full stick / stick-slip / separating / open): $sr"
bc=$(echo "$o" | grep '^basis check'); r0=$(field "$bc" rho); rm0=$(field "$bc" rho_modes)
nvl="-preload_load $tmp/nv_preload.h5 -modes_load $tmp/nv_modes.h5"
# a reduced model condensed onto its joints (4 zone joints x 3, mean field: 8 joint rows) gets the stability of every
# point by default, its fast modes condensed through the 8 rows (fast_rows); the fast block's inverse at every step
# (-frf_stability_time_lowrank no) flags every point the same
for lr in auto no; do
  ocz=$(mpiexec -n 2 $J -task frf $nv $nvl -frf_force 0.01,0.5 -rom_joints zones -rom_elements 3 -rom_joint_motion mean -frf_stability_time_lowrank $lr -frf_output_file "$tmp/cz_$lr" 2>&1)
  [ $lr = auto ] && czl=$(echo "$ocz" | grep -c '^stability level.* fast_rows 8$') && czc=$(echo "$ocz" | grep -c 'condensed onto 8 joint motions')
done
czf=$(paste -d, "$tmp/cz_auto.csv" "$tmp/cz_no.csv" 2>/dev/null | awk -F, 'NR > 1 {n++; h = NF / 2; if ($h != $NF || $h < 0) d++} END{printf "%d %d", n, d}')
read czn czd <<< "$czf"
check "[ '$czc' = 1 ] && [ '$czl' = 2 ] && [ '${czn:-0}' -gt 100 ] && [ '$czd' = 0 ]" "jenkins_nv lap1, 4 zone joints x 3 condensed onto 8 joint motions: stability by default at both levels through the 8 rows ($czl levels); all $czn points flagged, as by the fast block's inverse ($czd differ or unflagged)"
# the first reduction on the zone joints with the linear field (each member at its own point of its joint's field):
# condensed onto a basis of the joints' rows, at most 3 field functions (1, x, y) x 2 directions = 6 per joint, 24 for
# the 4; on a fixed frequency grid the amplitudes equal those of the modal equations (-hbm_condense no); the monodromy's
# fast modes through a basis of the rows (-frf_stability_time_lowrank yes: fast_rows) flag every point as the fast
# block's LU does; the incremental dissipativity certifies the points where no element changes state on the
# condensed unknowns as on the modal ones (the same flags at the common frequencies)
# the condensed model's Jacobian by its products through the modes, formed only for an LU (default), against formed
# at every iteration (-hbm_condense_products 0): the same model (72 unknowns: GMRES on the kept LU may take 4
# iterations) by arclength continuation to 2 N, the same peaks to Newton's tolerance (the curves' points differ at
# round-off, the peaks are refined on each); the default's GMRES solves counted (the products in use)
pk() { echo "$1" | awk '/^peak level/{print $4, $6}'; }
oa=$(mpiexec -n 2 $J -task frf $nv $nvl -frf_force 0.01,2 -rom_joints zones -rom_joint_motion linear -frf_output_file '' -log_view 2>&1)
ob=$(mpiexec -n 2 $J -task frf $nv $nvl -frf_force 0.01,2 -rom_joints zones -rom_joint_motion linear -frf_output_file '' -hbm_condense_products 0 2>&1)
pg=$(echo "$oa" | awk '/--- Event Stage/{s6=($4=="6:")} s6&&/^JR_DenseGMRES /{g+=$2} END{print g+0}')
pd=$(paste <(pk "$oa") <(pk "$ob") | awk 'NF == 4 {n++; f = ($1 - $3) / $3; a = ($2 - $4) / $4; f = f < 0 ? -f : f; a = a < 0 ? -a : a; if (f > d) d = f; if (a > d) d = a} END{printf "%d %.1e", n, d}')
read pn pdd <<< "$pd"
check "[ '$pn' = 2 ] && lt '$pdd' 1e-6 && [ '$pg' -gt 100 ]" "jenkins_nv lap1, 4 zone joints, linear field, condensed, arclength to 2 N: the Jacobian by its products ($pg GMRES solves on kept LUs) gives the peaks of the Jacobian formed at every iteration within $pdd (< 1e-6, $pn levels)"
for c in yes no lu; do
  case $c in yes) a="-frf_stability_time_lowrank yes" ;; no) a="-hbm_condense no" ;; lu) a="-frf_stability_time_lowrank no" ;; esac
  orl=$(mpiexec -n 2 $J -task frf $nv $nvl -frf_force 0.01,0.5 -rom_joints zones -rom_joint_motion linear -cont_type natural -cont_points 120 $a -frf_output_file "$tmp/rl_$c" 2>&1)
  [ $c = yes ] && rlq=$(echo "$orl" | sed -n 's/.*condensed onto \([0-9]*\) joint motions.*/\1/p') && rlr=$(echo "$orl" | grep '^stability level' | awk '{print $NF}' | sort -u)
  [ $c = lu ] && rlc=$(echo "$orl" | grep '^stability level' | awk '{for (i = 1; i < NF; i++) if ($i == "dissipative") s += $(i+1)} END{print s + 0}')
done
rlsf=$(awk -F, 'NR == FNR {if (FNR > 1) a[$1 " " $4] = $NF; next} FNR > 1 && ($1 " " $4) in a {n++; if (a[$1 " " $4] != $NF || $NF < 0) d++} END{printf "%d %d", n, d}' "$tmp/rl_no.csv" "$tmp/rl_lu.csv" 2>/dev/null)
read rlsn rlsd <<< "$rlsf"
read rln rld <<< "$(same "$tmp/rl_no.csv" "$tmp/rl_yes.csv" 2>/dev/null)"
rlf=$(paste -d, "$tmp/rl_yes.csv" "$tmp/rl_lu.csv" 2>/dev/null | awk -F, 'NR > 1 {n++; h = NF / 2; if ($h != $NF || $h < 0) d++} END{printf "%d %d", n, d}')
read rlfn rlfd <<< "$rlf"
check "[ -n '$rlq' ] && [ '$rlq' -ge 8 ] && [ '$rlq' -le 24 ] && [ '${rln:-0}' -ge 80 ] && lt '$rld' 1e-7" "jenkins_nv lap1, 4 zone joints, linear field (first reduction): condensed onto $rlq rows of the joints' fields (8 to 24); amplitudes at $rln common frequencies = the modal equations' within $rld (< 1e-7)"
check "[ '$rlr' = '$rlq' ] && [ '${rlfn:-0}' -ge 100 ] && [ '$rlfd' = 0 ]" "the same, stability through a basis of the $rlr rows (fast_rows): all $rlfn points flagged as by the fast block's inverse ($rlfd differ or unflagged)"
check "[ '${rlc:-0}' -gt 0 ] && [ '${rlsn:-0}' -ge 80 ] && [ '$rlsd' = 0 ]" "the same condensed: $rlc points certified by the incremental dissipativity; at $rlsn common frequencies the flags of the modal equations' run ($rlsd differ or unflagged)"
osv=$(mpiexec -n 2 $J -task frf $nv $nvl -frf_force 0.01,0.5,2 -rom_joints zones -rom_elements 3 -rom_joint_motion mode -rom_save "$tmp/nvrom.h5" -modes_adapt 0 -frf_output_file "$tmp/nvsv" 2>&1)
# the read basis's check (-modes_adapt 0: the basis was adapted, so a run that reads it does not check it unless
# asked), of the whole basis (its static vectors and adapted vectors included): no more than the computing run's
# without them (a larger span misses less), no less than that run's estimate after them (the next pattern's
# flexibility: a rank-n correction cannot lower the (n+1)-th eigenvalue); without -modes_adapt 0, the check not made
# and the adaptation recorded by the computing run reported instead (its vectors and rounds)
ad0=$(echo "$o" | sed -n 's/^basis adapt: \([0-9]*\) vectors added in \([0-9]*\) rounds.*/\1 \2/p')
nm0=$(echo "$oa" | sed -n 's/^basis check: not made: .*(\([0-9]*\) vectors added in \([0-9]*\) rounds, the last adding none.*/\1 \2/p')
check "[ -n '$ad0' ] && [ '$ad0' = '$nm0' ] && ! echo \"\$oa\" | grep -q '^WARNING basis check'" "jenkins_nv lap1, the adapted basis read back: not checked, the computing run's adaptation reported ($nm0: vectors, rounds; computed $ad0), no warning"
r1=$(field "$(echo "$osv" | grep '^basis check')" rho)
# with the mode's own motion every joint holds its members' share of the mode's strain energy (theory section 10):
# a stiffness correction outside [0.9, 1.1] then names no joint
se=$(echo "$osv" | grep -m1 '^rom stiffness_energy'); sj=$(echo "$osv" | grep -m1 '^rom stiffness_joints')
check "[ -n '$se' ] && awk -v a='$(field "$se" members_share)' -v b='$(field "$se" joints_share)' 'BEGIN{d = a - b; if (d < 0) d = -d; exit !(d < 1e-6 * a)}' && { [ -z '$sj' ] || [ '$(field "$sj" joints)' = none ]; }" "jenkins_nv lap1, 4 zone joints, -rom_joint_motion mode: joints' share of the stuck mode's strain energy = members' ($(field "$se" joints_share)); the correction's warning names no joint (${sj:-no warning})"
check "[ -n '$r1' ] && [ -n '$r0' ] && awk -v a='$r0' -v b='$r1' -v c='$rm0' 'BEGIN{exit !(a <= b * (1 + 1e-6) && b <= c)}'" "jenkins_nv lap1, basis check of the read mixed basis $r1 between the computing run's $r0 (after the static vectors, estimated) and $rm0 (without them)"
# joints from the slip onsets in the stuck mode (-rom_joints onset: bands of equal ratio of the modal amplitude at which
# each member in contact starts to slip, per bolt side, and each side's open pairs joints of their own, here in two
# bands of the amplitude at which they close), the first reduction on the mode's field: within 0.1% and 2% of
# node-to-node from microslip (0.01 N) through separation (2 N) on the basis of the each-joint run (4 zone joints on
# the same field: 1.8% and 28%)
oo=$(mpiexec -n 2 $J -task compare $nv $nvl -frf_force 0.01,0.5,2 -rom_joints onset -rom_onset_open_bands 2 -rom_joint_motion mode -frf_output_file '' 2>&1)
read f a <<< "$(worst "$oo")"; nj=$(field "$(echo "$oo" | grep '^rom partition joints')" joints)
check "lt '$f' 1e-3 && lt '$a' 0.02 && [ -n '$nj' ] && [ '$nj' -gt 4 ]" "jenkins_nv lap1, -rom_joints onset ($nj joints), first reduction on the mode's field: worst peak frequency error $f, amplitude error $a at 0.01, 0.5, 2 N"
# the open pairs' joints: every pair open at rest (132 pairs, those in contact counted from the joints' report) in a
# closing band, 2 per bolt side, none in contact, the bands in order of the closing onset printed
ob=$(echo "$oo" | awk '/^rom: joint [0-9]+:/{n += $4; c += substr($6, 2)} /^rom: joint [0-9]+:.*open pairs, closing band/{m += $4; if (substr($6, 2) != 0) bad = 1; k++} END{printf "%d %d %d %d %d", n, c, m, k, bad}')
read obn obc obm obk obb <<< "$ob"
oc=$(echo "$oo" | grep -o 'the first open member closes at [0-9.e+-]*, 0.9 of them by [0-9.e+-]*' | awk '{print $7, $12}')
check "[ '$obn' = 132 ] && [ '$obm' = \$((132 - obc)) ] && [ '$obk' = 4 ] && [ '$obb' = 0 ] && [ -n '$oc' ] && awk -v a='${oc% *}' -v b='${oc#* }' 'BEGIN{exit !(a > 0 && b > a)}'" "jenkins_nv lap1, -rom_onset_open_bands 2: the $obm pairs open at rest ($obn members, $obc in contact) in $obk closing-band joints, none in contact; closing onsets from $oc"
# the second reduction of those joints, 3 elements each (mode: each element in two halves where its group of members
# is, at the group's mean -/+ spread of stuck-mode motion): within 1% and 8% of node-to-node, and under the
# node-to-node peak's motion (rom_at_n2n_peak_J: the same modal unknowns) its joints dissipate what the members do
# within 15% at every level (an element at its group's root mean square motion alone, or moved to where its spring
# is its group's: 30% high at 0.01 N, from 3 to 20 times too much dissipation)
o3=$(mpiexec -n 2 $J -task compare $nv $nvl -frf_force 0.01,0.5,2 -rom_joints onset -rom_joint_motion mode -rom_elements 3 -frf_output_file '' 2>&1)
read f3 a3 <<< "$(worst "$o3")"
dx=$(echo "$o3" | awk '/^compare joints level/{d = $16 / $6 - 1; if (d < 0) d = -d; if (d > m) m = d; n++} END{printf "%d %.3f", n, m}'); read n3 d3 <<< "$dx"
check "lt '$f3' 0.01 && lt '$a3' 0.08 && [ '$n3' = 3 ] && lt '$d3' 0.15" "jenkins_nv lap1, onset joints x 3 elements (second reduction, mode): worst peak frequency error $f3, amplitude error $a3 at 0.01, 0.5, 2 N; joints' dissipation under the node-to-node peak's motion within $d3 of the members' ($n3 levels)"
# -rom_fit_elements_max: a joint whose 3 elements fit its members' loops worse than -rom_fit_loop_tol gets more, one at
# a time, up to the most given and its members' distinct slip displacements; the others keep 3 (at most their
# members). Against node-to-node the amplitude error falls (measured 4.3% with 3 each, 1.3% with 4 in 3 joints)
oa=$(mpiexec -n 2 $J -task compare $nv $nvl -frf_force 0.01,0.5,2 -rom_joints onset -rom_joint_motion mode -rom_elements 3 -rom_fit_elements_max 6 -rom_fit_loop_tol 0.05 -frf_output_file '' 2>&1)
read fa aa <<< "$(worst "$oa")"
els() { echo "$1" | awk '/^rom joint [0-9]+ members [1-9]/{printf "%s ", $7}'; }
e3=$(els "$o3"); ea=$(els "$oa")
grown=$(awk -v a="$e3" -v b="$ea" 'BEGIN{n = split(a, x, " "); m = split(b, y, " "); if (n != m || !n) {print -1; exit} for (i = 1; i <= n; i++) {if (y[i] < x[i] || y[i] > 6) {print -1; exit} g += y[i] > x[i]} print g}')
check "[ '$grown' -ge 1 ] && lt '$fa' 0.01 && lt '$aa' '$a3'" "-rom_fit_elements_max 6 -rom_fit_loop_tol 0.05: $grown joints grown (elements per joint $ea; with 3: $e3), worst peak frequency error $fa, amplitude error $aa below 3 each's $a3"
# -rom_joint_motion shapes: the tangential field over the members' positions and motions in the stuck mode and in
# released modes (the stuck structure with the members that slip first freed), the normal field over their normal
# motion. On the 4 onset joints (one band per bolt side: its pairs in contact, its open pairs) the stuck mode of
# interest stays exact (the joints hold the members' share of its strain energy; without the positions this coarse
# lap gains a hinge mode at 61 Hz), the slip front inside a joint is carried (the mode field on the same joints: 28% at
# 0.01 N), on fewer rows than the mode field's (40)
osh=$(mpiexec -n 2 $J -task compare $nv $nvl -frf_force 0.01,0.5,2 -rom_joints onset -rom_onset_bands 1 -rom_joint_motion shapes -rom_elements 3 -rom_save "$tmp/shrom.h5" -frf_output_file "$tmp/shsv" -frf_stability 0 2>&1)
osf=$(mpiexec -n 2 $J -task compare $nv $nvl -frf_force 0.01,0.5,2 -rom_joints onset -rom_onset_bands 1 -rom_joint_motion shapes -frf_output_file '' -frf_stability 0 2>&1)
read fs as <<< "$(worst "$osf")"
shq=$(echo "$osf" | grep -o 'condensed onto [0-9]* joint motions' | awk '{print $3}'); shr=$(echo "$osf" | grep -c '^rom: released mode')
# the released modes free ever more members (a fraction that frees the same tied group as the one before adds none)
shi=$(echo "$osf" | awk '/^rom: released mode/{for (i = 1; i <= NF; i++) if ($i == "members") {if ($(i - 1) <= l) bad = 1; l = $(i - 1)}} END{print bad ? "no" : "yes"}')
se=$(echo "$osf" | grep -m1 '^rom stiffness_energy'); shc=$(field "$se" joints_share); shn=$(field "$se" members_share)
c=$(echo "$osf" | grep '^rom stiffness_correction'); fb=$(field "$c" rom_before_hz); fn=$(field "$c" n2n_hz)
check "lt '$fs' 0.002 && lt '$as' 0.03 && [ -n '$shq' ] && [ '$shq' -lt 40 ] && [ '$shr' -ge 4 ] && [ '$shr' -le 6 ] && [ '$shi' = yes ] && close '$shc' '$shn' 1e-9 && close '$fb' '$fn' 1e-8" "jenkins_nv lap1, 4 onset joints, first reduction on the shapes field ($shr released modes, each freeing more members: $shi; $shq rows): worst peak frequency error $fs, amplitude error $as at 0.01, 0.5, 2 N; the joints' share of the stuck mode's strain energy $shc = the members' $shn, its frequency $fb Hz = node-to-node $fn Hz"
# the same on 1 rank (its own preload and modes): the same released modes (the members freed in whole groups of tied
# onsets, which round-off cannot split) and the same peaks
os1=$(mpiexec -n 1 $J -task compare $nv -frf_force 0.01,0.5,2 -rom_joints onset -rom_onset_bands 1 -rom_joint_motion shapes -frf_output_file '' -frf_stability 0 2>&1)
pk=$(paste <(echo "$osf" | grep '^peak level' | tail -3) <(echo "$os1" | grep '^peak level' | tail -3) | awk '{for (i = 5; i <= 7; i += 2) {e = $(i+9) / $i - 1; if (e < 0) e = -e; if (e > m) m = e} n++} END{printf "%d %.2e", n, m}')
read np dp <<< "$pk"
check "[ '$np' = 3 ] && lt '$dp' 1e-6 && [ \"\$(echo \"\$osf\" | grep '^rom: released mode' | sed 's/: [0-9.]* Hz//')\" = \"\$(echo \"\$os1\" | grep '^rom: released mode' | sed 's/: [0-9.]* Hz//')\" ]" "jenkins_nv lap1, 4 onset joints on the shapes field on 1 rank: the same freed members and 3 reduced peaks within $dp of 2 ranks"
# its second reduction saved and loaded (the file's joint motion, and its elements' and members' released coordinates)
# reproduces the saving run; loaded with another joint motion asked for, an error
o=$(mpiexec -n 2 $J -task frf $nv -modes_load $tmp/nv_modes.h5 -modes_check 0 -frf_force 0.01,0.5,2 -rom_load "$tmp/shrom.h5" -frf_stability 0 -frf_output_file "$tmp/shld" 2>&1)
pk=$(paste <(echo "$osh" | grep '^peak level' | tail -3) <(echo "$o" | grep '^peak level') | awk '{for (i = 5; i <= 7; i += 2) {e = $(i+9) / $i - 1; if (e < 0) e = -e; if (e > m) m = e} n++} END{printf "%d %.2e", n, m}')
read np dp <<< "$pk"
check "[ '$np' = 3 ] && lt '$dp' 1e-8 && ! echo \"\$o\" | grep -q '^preload total'" "jenkins_nv lap1, -rom_load of 4 onset joints x 3 on the shapes field reproduces the saving run: 3 peaks within $dp"
expect_error "a shapes model loaded with another joint motion" "was reduced with -rom_joint_motion shapes, not mode" mpiexec -n 2 $J -task frf $nv -modes_load $tmp/nv_modes.h5 -modes_check 0 -frf_force 0.01 -rom_load "$tmp/shrom.h5" -rom_joint_motion mode -frf_output_file ''
o=$(mpiexec -n 2 $J -task frf $nv -modes_load $tmp/nv_modes.h5 -modes_check 0 -frf_force 0.01,0.5,2 -rom_load "$tmp/nvrom.h5" -frf_output_file "$tmp/nvld" 2>&1)
pk=$(paste <(echo "$osv" | grep '^peak level') <(echo "$o" | grep '^peak level') | awk '{for (i = 5; i <= 7; i += 2) {e = $(i+9) / $i - 1; if (e < 0) e = -e; if (e > m) m = e} n++} END{printf "%d %.2e", n, m}')
cv=$(awk -F, 'NR == FNR {a[FNR] = $0; n1 = FNR; next} {n2 = FNR; if (FNR > 1) {split(a[FNR], x, ","); for (i = 4; i <= 6; i++) {d = $i - x[i]; s = x[i] < 0 ? -x[i] : x[i]; d = (d < 0 ? -d : d) / (s > 0 ? s : 1); if (d > m) m = d}}} END{printf "%d %d %.2e", n1, n2, m}' "$tmp/nvsv.csv" "$tmp/nvld.csv" 2>/dev/null)
read np dp <<< "$pk"; read n1 n2 dc <<< "$cv"
sl=$(echo "$(states "$o")" | tr ' ' '\n' | sed -n '2s/^1://p')
check "[ '$np' = 3 ] && lt '$dp' 1e-8 && [ '$n1' -gt 100 ] && [ '$n1' = '$n2' ] && lt '$dc' 1e-8 && echo '$sl' | awk -F/ '{exit !(\$3 > 0)}' && ! echo \"\$o\" | grep -q '^preload total'" "jenkins_nv lap1, -rom_load of 4 zone joints x 3 (mode; $(echo "$osv" | grep -o '[0-9]* elements in [0-9]* joints' | head -1)) reproduces the saving run (no preload solved): 3 peaks within $dp, the curves' $((n1 - 1)) points within $dc; at 0.5 N its elements separate too (states $sl)"

# 5. bad input
expect_error "missing ROM file" "no such file" $J -task frf $brb -frf_force 1 -rom_load "$tmp/none.h5" -frf_output_file ''
expect_error "ROM of another mesh" "another mesh" $J -task frf ${brb/-model_mesh_h 0.01/-model_mesh_h 0.012} -frf_force 1 -rom_load "$tmp/rom.h5" -frf_output_file ''
expect_error "overlapping regions" "the regions overlap" $J -task frf $brb -frf_force 1 -rom_joints boxes -rom_boxes 0,0.37,-1,1,0.33,1,-1,1 -frf_output_file ''
expect_error "element in no region" "lies in no box" $J -task frf $brb -frf_force 1 -rom_joints boxes -rom_boxes 0,0.33,-1,1,0.37,1,-1,1 -frf_output_file ''
expect_error "rings without auto" "-rom_auto_rings needs -rom_joints auto" $J -task frf $brb -frf_force 1 -rom_joints zones -rom_auto_rings 3 -frf_output_file ''
expect_error "no rings" "-rom_auto_rings 0: 1 to 8 rings per bolt" $J -task frf $brb -frf_force 1 -rom_joints auto -rom_auto_rings 0 -frf_output_file ''
expect_error "empty joint" "holds no element: an empty joint" $J -task frf $brb -frf_force 1 -rom_joints boxes -rom_boxes 0,0.36,-1,1,0.36001,1,-1,1,5,6,-1,1 -frf_output_file ''
expect_error "onset bands without onset" "-rom_onset_bands needs -rom_joints onset" $J -task frf $brb -frf_force 1 -rom_joints zones -rom_onset_bands 3 -frf_output_file ''
expect_error "no onset bands" "-rom_onset_bands 0: 1 to 16 bands" $J -task frf $brb -frf_force 1 -rom_joints onset -rom_onset_bands 0 -frf_output_file ''
expect_error "onset fraction" "-rom_onset_upto 1.5: a fraction in (0, 1]" $J -task frf $brb -frf_force 1 -rom_joints onset -rom_onset_upto 1.5 -frf_output_file ''
expect_error "open bands without onset" "-rom_onset_open_bands needs -rom_joints onset" $J -task frf $brb -frf_force 1 -rom_joints zones -rom_onset_open_bands 2 -frf_output_file ''
expect_error "no open bands" "-rom_onset_open_bands 0: 1 to 16 bands" $J -task frf $brb -frf_force 1 -rom_joints onset -rom_onset_open_bands 0 -frf_output_file ''
expect_error "release fractions without a mode field" "-rom_release_fractions needs -rom_joint_motion mode or shapes" $J -task frf $brb -frf_force 1 -rom_joints zones -rom_release_fractions 0.01 -frf_output_file ''
expect_error "release fractions out of order" "-rom_release_fractions: 0.01: the fractions must increase, each in (0, 1)" $J -task frf $brb -frf_force 1 -rom_joints zones -rom_joint_motion shapes -rom_release_fractions 0.1,0.01 -frf_output_file ''
expect_error "compare without joints" "-task compare needs a reduced model" $J -task compare $brb -frf_force 1 -frf_output_file ''
# jenkins_nv with open pairs (lap3, zones, first reduction): a joint moves with the average of its members in
# contact at rest, whose springs it carries; then by Cauchy-Schwarz (k sum u_e^2 >= K (mean u)^2) the reduced
# stuck mode can only be at or below node-to-node's (averaging over all members put it 16% above)
o=$($J -options_file runs/lap3_rom.opts -model_mesh_h 0.005 -model_mesh_grade 4 -rom_elements 0 -rom_joint_motion mean -frf_force 0.001 -cont_max_points 10 -cont_allow_partial -frf_plot 0 -cont_monitor 0 -frf_output_file "$tmp/l3" 2>&1)
l3="-preload_load $tmp/l3_preload.h5 -modes_load $tmp/l3_modes.h5" # the runs of lap3 below: this run's preload and modes
c=$(echo "$o" | grep '^rom stiffness_correction'); fb=$(field "$c" rom_before_hz); fn=$(field "$c" n2n_hz)
check "[ -n '$fb' ] && awk -v b='$fb' -v n='$fn' 'BEGIN{exit !(b <= n * (1 + 1e-9))}'" "jenkins_nv lap3, 12 zone joints over the pairs in contact at rest: reduced stuck mode $fb Hz <= node-to-node $fn Hz"
# -rom_joint_residual: the members' springs on their motion outside the joint's field stay in the structure, so
# the reduced model stuck is node-to-node's stuck (the mean field's residuals sum to 0 over a joint's members, and
# lap3's springs are equal): the same stuck mode without any correction
o=$($J -options_file runs/lap3_rom.opts -model_mesh_h 0.005 -model_mesh_grade 4 $l3 -rom_elements 0 -rom_joint_motion mean -rom_joint_residual -frf_force 0.001 -cont_max_points 10 -cont_allow_partial -frf_plot 0 -cont_monitor 0 -frf_output_file '' 2>&1)
c=$(echo "$o" | grep '^rom stiffness_correction'); fr=$(field "$c" rom_before_hz)
check "[ -n '$fr' ] && close '$fr' '$fn' 1e-9 && close \$(field \"\$c\" stiffness_correction) 1 1e-9" "jenkins_nv lap3, 12 zone joints, mean field with -rom_joint_residual: reduced stuck mode $fr Hz = node-to-node $fn Hz (mean alone: $fb Hz), no correction"
# the stiffness correction's warning names the joints responsible (lap3, coarse, mean motion). Every element its own
# joint: each holds its member's spring on its member's motion, so the factor is 1 to round-off and nothing is
# named. The interface cut into its 41 columns of pairs (2.5 mm apart) except at the lap's end x = 0.35 m, where the 5
# columns x < 0.3615 m are lumped into one joint (joint 0) on purpose: the end, which bends most in this mode, then
# moves with its mean, the factor leaves [0.9, 1.1] and the warning names joint 0 alone; one warning, the same
# lines on 1 and 2 ranks
l3w="-options_file runs/lap3_rom.opts -model_mesh_h 0.005 -model_mesh_grade 4 $l3 -task frf -rom_elements 0 -rom_joint_motion mean -frf_force 0.001 -cont_max_points 5 -cont_allow_partial -frf_plot 0 -cont_monitor 0 -frf_output_file ''"
o=$(eval $J $l3w -rom_joints each 2>&1)
c=$(field "$(echo "$o" | grep '^rom stiffness_correction')" stiffness_correction); se=$(echo "$o" | grep '^rom stiffness_energy')
check "[ -n '$c' ] && close $c 1 1e-9 && close \$(field \"\$se\" joints_share) \$(field \"\$se\" members_share) 1e-12 && ! echo \"\$o\" | grep -q 'WARNING stiffness'" "jenkins_nv lap3, every element its own joint: stiffness correction $c (1 to 1e-9), no warning"
cuts=$(awk 'BEGIN{for (i = 0; i < 40; i++) {x = 0.35125 + 0.0025 * i; if (x > 0.3615) printf "%s%.5f", (n++ ? "," : ""), x}}')
o=$(eval $J $l3w -rom_joints strips -rom_strips $cuts 2>&1)
sj=$(echo "$o" | grep '^rom stiffness_joints'); c=$(field "$sj" factor); nw=$(echo "$o" | grep -c 'WARNING stiffness')
check "[ -n '$c' ] && lt 1.1 '$c' && [ \"\$(field \"\$sj\" joints)\" = 0 ] && [ '$nw' = 1 ]" "jenkins_nv lap3, 36 strips with the lap's end lumped into joint 0: factor $c, one warning naming joint 0 alone: $(echo "$o" | grep -o 'joints too soft.*')"
# the joints' linear motion field (-rom_joint_motion linear: the mean plus the joint's rotation, fitted by least
# squares over the members' positions) is a projection onto a larger space that holds the mean's: the stuck mode lies
# between the mean's and node-to-node's (with equal kt per member)
o=$($J -options_file runs/lap3_rom.opts -model_mesh_h 0.005 -model_mesh_grade 4 $l3 -rom_elements 0 -rom_joint_motion linear -frf_force 0.001 -cont_max_points 10 -cont_allow_partial -frf_plot 0 -cont_monitor 0 -frf_output_file '' 2>&1)
fl=$(field "$(echo "$o" | grep '^rom stiffness_correction')" rom_before_hz)
check "[ -n '$fl' ] && awk -v m='$fb' -v l='$fl' -v n='$fn' 'BEGIN{exit !(m < l && l <= n * (1 + 1e-9))}'" "jenkins_nv lap3, 12 zone joints, linear field: reduced stuck mode mean $fb < linear $fl <= node-to-node $fn Hz"
# -rom_joint_motion mode: the field's coordinates also include each member's tangential and normal motion in the
# stuck mode of interest; those motions then lie in the field's span, so (for equal springs per member) that mode is
# an exact eigenvector of the first reduction, with the node-to-node frequency (no stiffness correction needed)
for model in lap3 lap1; do
  # lap1's run writes its preload and modes for the lap1 runs below
  [ $model = lap3 ] && mo="-options_file runs/lap3_rom.opts -model_mesh_h 0.005 -model_mesh_grade 4 $l3 -frf_force 0.001" mb= || mo="-options_file runs/lap1_rom.opts -model_mesh_h 0.008 -frf_force 0.01" mb=$tmp/l1
  o=$($J $mo -rom_elements 0 -rom_joint_motion mode -cont_max_points 10 -cont_allow_partial -frf_plot 0 -cont_monitor 0 -frf_output_file "$mb" 2>&1)
  c=$(echo "$o" | grep '^rom stiffness_correction'); fb=$(field "$c" rom_before_hz); fn=$(field "$c" n2n_hz)
  check "[ -n '$fb' ] && close $fb $fn 1e-8" "jenkins_nv $model, first reduction with -rom_joint_motion mode: the stuck mode of interest kept exactly, $fb Hz = node-to-node $fn Hz"
done
# the same with the released modes' coordinates added (mode) or in place of the positions (shapes), on lap3's zones
for jm in "mode -rom_release_fractions 0.003,0.01,0.03,0.1" shapes; do
  o=$($J -options_file runs/lap3_rom.opts -model_mesh_h 0.005 -model_mesh_grade 4 $l3 -frf_force 0.001 -rom_elements 0 -rom_joint_motion $jm -cont_max_points 10 -cont_allow_partial -frf_plot 0 -cont_monitor 0 -frf_output_file '' 2>&1)
  c=$(echo "$o" | grep '^rom stiffness_correction'); fb=$(field "$c" rom_before_hz); fn=$(field "$c" n2n_hz); nr=$(echo "$o" | grep -c '^rom: released mode')
  check "[ -n '$fb' ] && close $fb $fn 1e-8 && [ '$nr' -ge 4 ]" "jenkins_nv lap3, first reduction with -rom_joint_motion $jm ($nr released modes): the stuck mode of interest kept exactly, $fb Hz = node-to-node $fn Hz"
done
# lap1 (one bolt, 4 zone joints): the mean motion makes the interface a hinge in bending (stuck mode at half the
# node-to-node one, no stiffness correction can reach it); the linear field, with each fitted element spread over
# three points with its members' second moment, carries the bending (3 elements per joint here; the preload and
# modes of the lap1 run above)
for jm in mean linear; do
  o=$($J -options_file runs/lap1_rom.opts -model_mesh_h 0.008 -preload_load $tmp/l1_preload.h5 -modes_load $tmp/l1_modes.h5 -rom_elements 3 -rom_joint_motion $jm -frf_force 0.01 -cont_max_points 10 -cont_allow_partial -frf_plot 0 -cont_monitor 0 -frf_output_file '' 2>&1)
  c=$(echo "$o" | grep '^rom stiffness_correction'); eval "f_$jm=\$(field \"\$c\" rom_before_hz)"; fn=$(field "$c" n2n_hz)
  [ $jm = linear ] && ne=$(echo "$o" | awk '/^rom: second reduction/{print $4}')
done
check "[ -n '$f_linear' ] && awk -v m='$f_mean' -v l='$f_linear' -v n='$fn' 'BEGIN{exit !(m < 0.6 * n && l <= n * (1 + 1e-9) && l > 0.99 * n)}' && [ '$ne' -le 36 ]" "jenkins_nv lap1, 4 zone joints x 3 elements ($ne spread elements): stuck mode with the mean $f_mean Hz (a hinge), with the linear field $f_linear Hz, node-to-node $fn Hz (within 1%)"

# -rom_joints auto with one ring per bolt is the single bolt's two sides, the partition -rom_joints between cuts at
# the bolt's axis (Fig 5.25) by another path: the same members and loads per joint, the same factor
jb() { $J -options_file runs/lap1_rom.opts -model_mesh_h 0.008 -preload_load $tmp/l1_preload.h5 -modes_load $tmp/l1_modes.h5 -task frf -frf_force 0.01 -cont_max_points 3 -cont_allow_partial -frf_plot 0 -cont_monitor 0 -frf_output_file '' "$@" 2>&1 | grep -E '^rom(: joint [0-9]| stiffness_correction)' | sed 's/ m, .*/ m/'; }
ob=$(jb -rom_joints between); oa=$(jb -rom_joints auto -rom_auto_rings 1)
check "[ \$(echo \"\$ob\" | grep -c '^rom: joint') = 2 ] && [ \"\$ob\" = \"\$oa\" ]" "jenkins_nv lap1, -rom_joints auto with 1 ring = between: $(echo "$oa" | grep -c '^rom: joint') joints, the same members, loads, centroids and factor ($(field "$(echo "$oa" | grep stiffness_correction)" stiffness_correction))"
# -rom_fit_stiffness_weight (1e4): each joint's stuck loop weighed enough holds its members' stuck stiffness (sum k_i
# = sum w^2 kt), so the reduced model's stuck stiffness matrix is the first reduction's and so is its stuck resonance
# (same basis, LAPACK); with a weight of 10 the fit gives a little of it away for the loops
sf() { $J -task frf $brb $b1 -frf_force 0.01 -rom_joints sides "$@" -frf_output_file '' 2>&1 | grep '^rom stiffness_correction'; }
s0=$(sf -rom_elements 0); f0=$(field "$s0" rom_before_hz); fd=$(field "$(sf -rom_elements 3 -rom_fit_stiffness_weight 10)" rom_before_hz); fs=$(field "$(sf -rom_elements 3)" rom_before_hz)
c0=$(field "$s0" stiffness_correction); cn=$(sf -rom_elements 0 -rom_stiffness_correction 0)
check "[ -n '$c0' ] && close \$(field \"\$cn\" needed) $c0 1e-9 && close \$(field \"\$cn\" stiffness_correction) 1 0" "-rom_stiffness_correction 0: '$cn' (the factor the correction applies: $c0)"
check "[ -n '$f0' ] && close $fs $f0 1e-8 && ! close $fd $f0 1e-7" "-rom_fit_stiffness_weight 1e4 (default): 6 x 3 stuck resonance $fs Hz = first reduction's $f0 Hz (weight 10: $fd Hz)"
# jenkins_nv, -rom_joint_motion mode: the fit's error with the normal loads varying in the mode (AFT, one harmonic),
# printed per level, is zero when every member is its own element (the same elements, placed at their own stuck-mode
# motions) and not when three elements stand for a joint's members. The fit weights fixed (those -rom_fit_select first
# picks for the full lap3 run), so every run below fits with the same ones
l3c="-options_file runs/lap3_rom.opts -model_mesh_h 0.005 -model_mesh_grade 4 -task frf -frf_force 0.01,0.05 -cont_max_points 10 -cont_allow_partial -frf_plot 0 -cont_monitor 0 -frf_output_file '' -rom_fit_select none -rom_fit_total_weight 1000 -rom_fit_case_weight 0 $l3"
nvw() { echo "$1" | awk '/dissipation_error_normal_varying/{e = $6; if (e < 0) e = -e; if (e > w) w = e; n++; m = $13} END{print w + 0, n + 0, m + 0}'; }
read w1 n1 s1 <<< "$(nvw "$(eval $J $l3c -rom_elements 200)")"
read w3 n3 s3 <<< "$(nvw "$(eval $J $l3c)")"
check "[ '$n1' = 2 ] && lt '$w1' 1e-12 && lt 0.01 '$s1' && lt 1e-3 '$w3'" "jenkins_nv lap3 (coarse), mode: the fit's dissipation error with the normal load varying, every member its own element: $w1 (members dissipate $s1 of the input); 12 x 3: $w3"
# -rom_fit_normal_passes 2 (defect correction): the fit's error with the normal load varying, which it aims at, at
# least 4x smaller than the plain fit's with the same weights (the worst over both levels; measured: 0.0027 vs 0.043)
read w2 n2 s2 <<< "$(nvw "$(eval $J $l3c -rom_fit_normal_passes 2)")"
check "[ '$n2' = 2 ] && lt \$(awk -v a='$w2' 'BEGIN{print 4 * a}') '$w3'" "jenkins_nv lap3 (coarse), -rom_fit_normal_passes 2: worst error with the normal load varying $w2, at least 4x below the plain fit's $w3 (same weights)"
expect_error "zero stiffness weight" "-rom_fit_stiffness_weight 0.: the weight must be positive" $J -task frf $brb -frf_force 1 -rom_joints sides -rom_elements 3 -rom_fit_stiffness_weight 0 -frf_output_file ''
expect_error "negative normal passes" "-rom_fit_normal_passes -1: 0 or more" $J -task frf $brb -frf_force 1 -rom_joints sides -rom_elements 3 -rom_fit_normal_passes -1 -frf_output_file ''
expect_error "elements max below -rom_elements" "-rom_fit_elements_max 2: at least -rom_elements (3)" $J -task frf $brb -frf_force 1 -rom_joints sides -rom_elements 3 -rom_fit_elements_max 2 -frf_output_file ''
expect_error "loop tolerance without elements max" "-rom_fit_loop_tol needs -rom_fit_elements_max" $J -task frf $brb -frf_force 1 -rom_joints sides -rom_elements 3 -rom_fit_loop_tol 0.05 -frf_output_file ''
expect_error "negative case weight" "-rom_fit_case_weight -1.: the weight must be non-negative" $J -task frf $brb -frf_force 1 -rom_joints sides -rom_elements 3 -rom_fit_case_weight -1 -frf_output_file ''
expect_error "negative total weight" "-rom_fit_total_weight -2.: the weight must be non-negative" $J -task frf $brb -frf_force 1 -rom_joints sides -rom_elements 3 -rom_fit_total_weight -2 -frf_output_file ''
expect_error "elements without joints" "-rom_elements needs joints" $J -task frf $brb -frf_force 1 -rom_elements 3 -frf_output_file ''
expect_error "bad -rom_joint_motion" "rotate" $J -task frf $brb -frf_force 1 -rom_joints sides -rom_joint_motion rotate -frf_output_file ''
expect_error "bad -hbm_condense" "maybe" $J -task frf $brb -frf_force 1 -rom_joints sides -hbm_condense maybe -frf_output_file ''
expect_error "negative selection weight" "-rom_fit_select_total: -1.: the weights must be non-negative" $J -task frf $brb -frf_force 1 -rom_joints sides -rom_elements 3 -rom_fit_select first -rom_fit_select_total 20,-1 -frf_output_file ''
expect_error "bad -rom_fit_select" "best" $J -task frf $brb -frf_force 1 -rom_joints sides -rom_elements 3 -rom_fit_select best -frf_output_file ''
expect_error "save a first reduction" "-rom_save saves a second-reduction model" $J -task frf $brb -frf_force 1 -rom_joints sides -rom_save "$tmp/x.h5" -frf_output_file ''
expect_error "reduced model saved over the results" "-rom_save $tmp/col_rom.h5: this run writes its results to that file (-frf_output_file $tmp/col)" $J -task frf $brb -frf_force 1 -rom_joints sides -rom_elements 3 -rom_save "$tmp/col_rom.h5" -frf_output_file "$tmp/col"
