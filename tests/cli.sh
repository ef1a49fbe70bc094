#!/usr/bin/env bash
# Command-line checks of bin/jointrom -task element: numbers against closed forms computed here,
# joints from CSV, 1 vs 2 ranks, -help, output files, and bad input (clear error, non-zero exit).
cd "$(dirname "$0")/.."
. tests/cli_lib.sh
field() { awk -v k="$1" '/^fs /{for(i=1;i<NF;i++) if($i==k) print $(i+1)}' ; }

# jenkins, stick-slip: kt = 1e6 N/m, mu = 0.12, n0 = 100 N, U = 30 um. Closed forms evaluated by awk:
# energy 4 r (A - r/kt), fc = energy/(pi A) (the loop area), fs = (kt A/pi)(beta - cos(beta) sin(beta))
out=$($J -task element -element_kt 1e6 -element_mu 0.12 -element_n0 100 -element_u 30e-6 2>&1)
read -r efs efc een <<<"$(awk 'BEGIN{pi=atan2(0,-1); k=1e6; r=12; A=30e-6; rho=r/(k*A); cb=1-2*rho; sb=sqrt(1-cb*cb); b=atan2(sb,cb);
  printf "%.12g %.12g %.12g", k*A/pi*(b-cb*sb), 4*r*(A-r/k)/(pi*A), 4*r*(A-r/k)}')"
check "close $(echo "$out" | field energy) $een 1e-9" "element jenkins U = 30 um: energy $(echo "$out" | field energy) J = 4 mu n0 (A - mu n0/kt) = $een J"
check "close $(echo "$out" | field fc) $efc 1e-9 && close $(echo "$out" | field fs) $efs 1e-9" "element jenkins U = 30 um: fs, fc = $(echo "$out" | field fs), $(echo "$out" | field fc) N vs closed form $efs, $efc N"
check "echo '$out' | grep -q 'state stick_slip'" "element jenkins U = 30 um: state stick_slip"
out=$($J -task element -element_kt 1e6 -element_mu 0.12 -element_n0 100 -element_u 5e-6 2>&1)
check "close $(echo "$out" | field fs) 5 1e-12 && echo '$out' | grep -q 'fc 0 energy 0 state full_stick'" "element jenkins U = 5 um < mu n0/kt: full stick, fs = kt U = 5 N, no dissipation"

# jenkins_nv: the analytic path and the AFT path on a fine grid agree
a=$($J -options_file runs/element_nv.opts -element_u 2e-6 -element_loop '' 2>&1 | grep '^fs')
b=$($J -options_file runs/element_nv.opts -element_u 2e-6 -element_loop '' -element_harmonics 1 -contact_method aft -element_samples 8192 2>&1 | grep '^fs')
check "close $(echo "$a" | field fs) $(echo "$b" | field fs) 1e-6 && close $(echo "$a" | field fc) $(echo "$b" | field fc) 1e-6" "element jenkins_nv (separation): analytic '$a' vs AFT N = 8192 '$b'"
b=$($J -options_file runs/element_nv.opts -element_u 2e-6 -element_loop '' -element_harmonics 5 -element_samples 8192 2>&1 | grep '^fs')
check "close $(echo "$a" | field fs) $(echo "$b" | field fs) 1e-6 && close $(echo "$a" | field energy) $(echo "$b" | field energy) 1e-5" "element jenkins_nv: H = 5 AFT has the same first harmonic and energy as the closed form for a single-harmonic motion"

# a joint from CSV equals the sum of its elements run one by one
printf 'kt,mu,n0\n1e6,0.12,300\n2e6,0.1,100\n1.5e6,0.2,50\n' > "$tmp/joint.csv"
j=$($J -task element -element_joint "$tmp/joint.csv" -element_u 40e-6 2>&1 | grep '^fs')
s=$(for row in "1e6 0.12 300" "2e6 0.1 100" "1.5e6 0.2 50"; do set -- $row; $J -task element -element_kt $1 -element_mu $2 -element_n0 $3 -element_u 40e-6 | grep '^fs'; done | awk '{fs+=$2; fc+=$4; e+=$6} END{printf "%.12g %.12g %.12g", fs, fc, e}')
read -r sfs sfc se <<<"$s"
check "close $(echo "$j" | field fs) $sfs 1e-9 && close $(echo "$j" | field fc) $sfc 1e-9 && close $(echo "$j" | field energy) $se 1e-9" "element joint of 3 (CSV) = sum of the 3 elements: $j"

# member states of the demo joint: a jenkins member sticks all cycle iff kt U <= mu n0 (3.20), i.e.
# n0 >= 166.7 N at U = 20 um: 6 of the 8 normal loads in runs/demo_joint.csv; at U = 120 um n0 >= 1000 N: 2
n6=$(awk -F, -v U=20e-6 '!/^#/ && NR>1 && $1+0>0 {if ($1*U <= $2*$3) n++} END{print n+0}' runs/demo_joint.csv)
n2=$(awk -F, -v U=120e-6 '!/^#/ && NR>1 && $1+0>0 {if ($1*U <= $2*$3) n++} END{print n+0}' runs/demo_joint.csv)
o=$($J -task element -element_joint runs/demo_joint.csv -element_u 20e-6,120e-6 2>&1 | grep 'members')
check "echo \"\$o\" | sed -n 1p | grep -q 'full_stick $n6, stick_slip $((8 - n6)),' && echo \"\$o\" | sed -n 2p | grep -q 'full_stick $n2, stick_slip $((8 - n2)),'" "joint member states: $n6 and $n2 of 8 stick at U = 20 and 120 um (kt U <= mu n0)"

# 1 and 2 ranks give the same output
a=$($J -options_file runs/element_nv.opts -element_loop '' 2>&1 | grep '^fs')
b=$(mpiexec -n 2 $J -options_file runs/element_nv.opts -element_loop '' 2>&1 | grep '^fs')
check "[ -n '$a' ] && [ '$a' = '$b' ]" "element jenkins_nv: 1 and 2 ranks print the same results"

# -contact_view reports the batch
o=$($J -task element -contact_view -element_joint runs/demo_joint.csv 2>&1)
check "echo \"\$o\" | grep -q 'JRContact: type jenkins, analytic path, H = 1' && echo \"\$o\" | grep -q 'elements: 8 on 1 rank'" "-contact_view reports type, path and element count"

# outputs: loop CSV (header + closed loop per amplitude) and PNG
$J -task element -element_u 10e-6,20e-6 -element_loop "$tmp/loop" -element_loop_samples 100 > /dev/null 2>&1
check "[ \$(wc -l < '$tmp/loop.csv') = 203 ] && head -1 '$tmp/loop.csv' | grep -q '^level,U_m,theta_rad,u_m,v_m,f_N,n_N$'" "element loop CSV: header and 2 x 101 rows"
if command -v gnuplot > /dev/null; then
  check "[ \"\$(head -c 4 '$tmp/loop.png' | tail -c 3)\" = PNG ]" "element loop PNG written"
fi
check "[ -z \"\$(ls '$tmp' | grep tmp)\" ]" "no temporary files left behind"
check "[ ! -e .csv ] && [ ! -e .png ]" "-element_loop '' writes no loop files"

# run files: every option used, no typo (the frf and compare runs on the lap models: tests/cli_long.sh)
for f in runs/*.opts; do
  run_file_long "$f" || run_file_check "$f"
done

# -help lists every option
h=$($J -task element -help 2>&1)
miss=""
for o in -task -contact_type -contact_method -contact_view -element_kt -element_kn -element_mu -element_n0 -element_u -element_v -element_phase -element_harmonics -element_samples -element_joint -element_loop -element_loop_samples; do
  echo "$h" | grep -qE -- "^ *$o[ :]" || miss="$miss $o"
done
check "[ -z '$miss' ]" "-help lists every option${miss:+ (missing:$miss)}"

# bad input: non-zero exit and a message naming the option or file
expect_error "negative stiffness" "-element_kt -1.: the tangential stiffness must be positive" $J -task element -element_kt -1
expect_error "negative friction coefficient" "-element_mu -0.1: the friction coefficient must be non-negative" $J -task element -element_mu -0.1
expect_error "negative normal stiffness" "-element_kn -5.: the normal stiffness must be non-negative" $J -task element -contact_type jenkins_nv -element_kn -5
expect_error "NaN amplitude" "-element_u nan.: the tangential amplitude must be finite" $J -task element -element_u nan
expect_error "infinite amplitude" "-element_u inf.: the tangential amplitude must be finite" $J -task element -element_u inf
expect_error "infinite normal amplitude" "-element_v inf.: the normal amplitude must be finite" $J -task element -contact_type jenkins_nv -element_v inf
expect_error "N < 2H+1" "-element_samples 5: the number of time samples must be at least 2H+1 = 7" $J -task element -element_harmonics 3 -element_samples 5
expect_error "zero harmonics" "-element_harmonics 0: the number of harmonics must be between 1 and" $J -task element -element_harmonics 0
expect_error "unknown contact type" "Unknown contact element type 'coulomb'" $J -task element -contact_type coulomb
expect_error "analytic path with H > 1" "The analytic path (-contact_method analytic) is single-harmonic" $J -task element -contact_method analytic -element_harmonics 3
expect_error "jenkins with negative n0" "-element_n0 -5.: the normal load of a jenkins element must be non-negative" $J -task element -element_n0 -5
expect_error "unknown task" "Unknown option frobnicate for -task" $J -task frobnicate
printf 'kt,mu\n1e6,0.1\n' > "$tmp/nomu.csv"
expect_error "joint CSV without the n0 column" "no column 'n0'" $J -task element -element_joint "$tmp/nomu.csv"
printf 'kt,mu,n0\n1e6,0.1,abc\n' > "$tmp/nan.csv"
expect_error "joint CSV with a non-number" "line 2, column 3 ('n0'): 'abc' is not a finite number" $J -task element -element_joint "$tmp/nan.csv"
printf 'kt,mu,n0\n1e6,0.1,10\n1e6,0.1\n' > "$tmp/short.csv"
expect_error "joint CSV with a short row" "line 3: 2 fields, but the header has 3 columns" $J -task element -element_joint "$tmp/short.csv"
printf 'kt,mu,n0\n-1e6,0.1,10\n' > "$tmp/negkt.csv"
expect_error "joint CSV with negative kt" "kt = -1e+06 must be positive" $J -task element -element_joint "$tmp/negkt.csv"
printf 'kt,mu,n0\n1e6,0.1,10\n' > "$tmp/nokn.csv"
expect_error "jenkins_nv joint CSV without kn" "no column 'kn'" $J -task element -contact_type jenkins_nv -element_joint "$tmp/nokn.csv"
printf '' > "$tmp/empty.csv"
expect_error "empty joint CSV" "is empty" $J -task element -element_joint "$tmp/empty.csv"
printf 'kt,mu,n0\n' > "$tmp/header.csv"
expect_error "joint CSV without rows" "no element rows" $J -task element -element_joint "$tmp/header.csv"
expect_error "missing joint CSV" "Cannot open the CSV file $tmp/none.csv" $J -task element -element_joint "$tmp/none.csv"
expect_error "unwritable loop file" "-element_loop /nonexistent/dir/loop: cannot write in the directory /nonexistent/dir" $J -task element -element_loop /nonexistent/dir/loop
