#!/usr/bin/env bash
# make bench, stability: the solve stage (harmonic balance, continuation, peaks, and the stability when on) with
# the stability off and on, side by side in interleaved runs (median of 3), and the sums of the `stability level`
# lines' seconds and curve fields of the runs with it on; 1 and 2 ranks.
# Target: the stability adds at most 2x to the solve (ratio on / off <= 2).
cd "$(dirname "$0")/../.."
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 OMPI_MCA_rmaps_base_oversubscribe=1
export OPENBLAS_NUM_THREADS=1
lap1="-task frf -model_type lap1 -model_mesh_h 0.008 -preload_force 10000 -interface_element jenkins_nv -interface_kt 1e8 -interface_mu 0.1 -hbm_basis free -hbm_modes 30 -hbm_gamma 0.002 -frf_force 0.0001,0.01,1 -frf_fmin 120 -frf_fmax 160 -cont_monitor 0"
slip=$(awk 'BEGIN{for(i=0;i<=20;i++) printf "%s%g", i ? "," : "", 0.5 + 0.125 * i}') # 21 levels of 0.5-3 N: gross slip
solve() { # np stab args... -> "solve_seconds stability_seconds curve_seconds"
  local np=$1 st=$2
  shift 2
  mpiexec -n "$np" bin/jointrom "$@" -frf_output_file '' -frf_plot 0 -frf_stability "$st" -log_view < /dev/null 2>&1 |
    awk '/JR 6 solve:/{t=$5} /^stability level/{for(i=1;i<=NF;i++){if($i=="seconds")s+=$(i+1); if($i=="(curve")c+=$(i+1)}} END{printf "%s %.4g %.4g\n", t, s, c}'
}
median() { sort -g | awk '{a[NR]=$1} END{print a[int((NR+1)/2)]}'; }
echo "== stability: solve stage [s], off and on, median of 3 interleaved runs (runs/lap3_n2n.opts, runs/lap1_rom.opts and lap3_shapes_rom_thesis: one each, their set-up 15 s-1 min per run) =="
printf "%-44s %-5s %10s %10s %7s %12s %12s\n" case ranks off on ratio stability curve
while IFS='|' read -r name np reps args; do
  : > /tmp/jr_bench_off.$$
  : > /tmp/jr_bench_on.$$
  for r in $(seq "$reps"); do
    solve "$np" 0 $args | awk '{print $1}' >> /tmp/jr_bench_off.$$
    solve "$np" 1 $args >> /tmp/jr_bench_on.$$
  done
  off=$(median < /tmp/jr_bench_off.$$)
  on=$(awk '{print $1}' /tmp/jr_bench_on.$$ | median)
  st=$(awk '{print $2}' /tmp/jr_bench_on.$$ | median)
  cu=$(awk '{print $3}' /tmp/jr_bench_on.$$ | median)
  printf "%-44s %-5s %10.4g %10.4g %7.2f %12.4g %12.4g\n" "$name" "$np" "$off" "$on" "$(awk -v a=$on -v b=$off 'BEGIN{print a/b}')" "$st" "$cu"
done <<EOF
runs/chain_frf.opts|1|3|-options_file runs/chain_frf.opts
runs/chain_frf.opts|2|3|-options_file runs/chain_frf.opts
runs/duffing_frf.opts|1|3|-options_file runs/duffing_frf.opts
runs/oscillator_frf.opts|1|3|-options_file runs/oscillator_frf.opts
runs/default.opts (BRB)|2|3|-options_file runs/default.opts
lap1 8 mm, 132 jenkins_nv, 30 modes|1|3|$lap1
lap1 8 mm, 132 jenkins_nv, 30 modes|2|3|$lap1
lap1 8 mm, 4 zone joints condensed (228 el.)|1|3|$lap1 -rom_joints zones -rom_joint_motion mean
lap1 8 mm, 4 zone joints condensed (228 el.)|2|3|$lap1 -rom_joints zones -rom_joint_motion mean
lap1 8 mm, 4 zone joints x 3 condensed|1|3|$lap1 -rom_joints zones -rom_joint_motion mean -rom_elements 3
lap1 8 mm, 4 zone joints x 3 condensed|2|3|$lap1 -rom_joints zones -rom_joint_motion mean -rom_elements 3
runs/lap3_n2n.opts, 506 jenkins_nv, 88 modes|2|1|-options_file runs/lap3_n2n.opts
runs/lap1_rom.opts reduced, linear field, 24 rows|2|1|-options_file runs/lap1_rom.opts -task frf
lap1 8 mm, 4 zone joints x 3, 21 levels 0.5-3 N|1|3|$lap1 -rom_joints zones -rom_joint_motion mean -rom_elements 3 -frf_force $slip
runs/lap3_shapes_rom_thesis.opts reduced, 86 rows|1|1|-options_file runs/lap3_shapes_rom_thesis.opts -task frf
runs/lap3_shapes_rom_thesis.opts reduced, 86 rows|2|1|-options_file runs/lap3_shapes_rom_thesis.opts -task frf
EOF
rm -f /tmp/jr_bench_off.$$ /tmp/jr_bench_on.$$
