#!/usr/bin/env bash
# make bench, harmonic balance: frequency-response points per second for a chain of 100 DOF (10 modes)
# with 10^2, 10^4, 10^5 jenkins elements, H = 1 and H = 3; analytic vs finite-difference Jacobian
# measured side by side; 1 vs 2 ranks. Each run: natural continuation, 21 equally spaced points over
# 0.8-1.2 of the first natural frequency, force 50 N at the free end (microslip: about 2 Newton iterations per point). Time = the solve stage only
# (HBM + continuation, from the program's own per-level timer).
# Targets: analytic >= 20x faster than fd at 10^4 elements; 2 ranks >= 1.7x faster at 10^5.
# Then the dense Newton's LU kept as GMRES's preconditioner against a new LU at every iteration, side by side on
# the BRB, lap1 node-to-node and reduced models (the solve stage; the LU and GMRES solves counted); and a condensed
# reduced model's Jacobian by its products against formed at every iteration, side by side; and lap3's reduced model
# with its joints apart eliminated from each LU against the whole matrix factored, side by side.
cd "$(dirname "$0")/../.."
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 OMPI_MCA_rmaps_base_oversubscribe=1
export OPENBLAS_NUM_THREADS=1
out=build/bench
mkdir -p $out
run() { # np E H jac -> "points seconds newton"
  local np=$1 E=$2 H=$3 jac=$4
  mpiexec -n "$np" bin/jointrom -task frf -model_stiffness $out/chain_$E/K.mtx -model_mass $out/chain_$E/M.mtx \
    -model_elements $out/chain_$E/elements.csv -hbm_modes 10 -hbm_gamma 0.01 -frf_dof 99 -frf_force 50 \
    -hbm_harmonics "$H" -hbm_jacobian "$jac" -cont_type natural -cont_points 21 -frf_output_file '' 2>&1 | awk '/ done: /{for(i=1;i<=NF;i++){if($i=="points,")p=$(i-1); if($i=="Newton")n=$(i-1); if($i=="s"||$i=="s,")t=$(i-1)}} END{print p, t, n}'
}
echo "== harmonic balance: chain of 100 DOF, 10 modes, 21 FRF points (points/s of the solve stage) =="
printf "%-9s %-3s %-9s %-6s %8s %10s %10s %8s\n" elements H jacobian ranks points seconds points/s newton
for E in 100 10000 100000; do
  [ -f $out/chain_$E/elements.csv ] || bash share/make_chain.sh $out/chain_$E 100 $E > /dev/null
  for H in 1 3; do
    for np in 1 2; do
      read -r p t n <<<"$(run $np $E $H analytic)"
      printf "%-9s %-3s %-9s %-6s %8s %10s %10.2f %8s\n" $E $H analytic $np "$p" "$t" "$(awk -v p=$p -v t=$t 'BEGIN{print p/t}')" "$n"
      eval "a_${E}_${H}_${np}=$(awk -v p=$p -v t=$t 'BEGIN{print p/t}')"
    done
    if [ "$E" -le 10000 ]; then
      read -r p t n <<<"$(run 1 $E $H fd)"
      printf "%-9s %-3s %-9s %-6s %8s %10s %10.2f %8s\n" $E $H fd 1 "$p" "$t" "$(awk -v p=$p -v t=$t 'BEGIN{print p/t}')" "$n"
      eval "f_${E}_${H}=$(awk -v p=$p -v t=$t 'BEGIN{print p/t}')"
    else
      echo "$E       $H   fd        not run: a finite-difference Jacobian of 10^5 elements takes minutes per point"
    fi
  done
done
echo "-- ratios of the points per second measured above --"
for H in 1 3; do
  for E in 100 10000; do
    eval "fa=\$a_${E}_${H}_1; ff=\$f_${E}_${H}"
    echo "analytic vs fd Jacobian, $E elements, H = $H: $(awk -v a=$fa -v f=$ff 'BEGIN{printf "%.1fx faster", a/f}')"
  done
  for E in 10000 100000; do
    eval "t1=\$a_${E}_${H}_1; t2=\$a_${E}_${H}_2"
    echo "2 ranks vs 1 rank, $E elements, H = $H: $(awk -v a=$t1 -v b=$t2 'BEGIN{printf "%.2fx faster", b/a}')"
  done
done
echo
# The dense Newton's LU kept as GMRES's preconditioner (default) against a new LU at every iteration
# (-hbm_snes_newtondense_reuse_its 0; -rom_hbm_snes_newtondense_reuse_its 0 for a reduced model): the solve stage (harmonic balance, continuation, peaks; stability off),
# interleaved runs, median; the unknowns of each solve and the LU and GMRES counts of the default's run.
lap1="-task frf -model_type lap1 -model_mesh_h 0.008 -preload_force 10000 -interface_element jenkins_nv -interface_kt 1e8 -interface_mu 0.1 -hbm_basis free -hbm_modes 30 -hbm_gamma 0.002 -frf_force 0.0001,0.01,1 -frf_fmin 120 -frf_fmax 160 -cont_monitor 0 -frf_stability 0"
stage() { # np args... -> "solve_seconds lu_count gmres_count unknowns"
  local np=$1
  shift
  mpiexec -n "$np" bin/jointrom "$@" -frf_output_file '' -frf_plot 0 -log_view < /dev/null 2>&1 |
    awk '/JR 6 solve:/{t=$5} /--- Event Stage/{s6=($4=="6:")} s6&&/^JR_DenseLU /{l+=$2} s6&&/^JR_DenseGMRES /{g+=$2} /unknowns instead of/{for(i=1;i<=NF;i++) if($i=="unknowns") u=$(i-1)} /harmonics \+ mean, [0-9]+ unknowns/{for(i=1;i<=NF;i++) if($i=="unknowns;") v=$(i-1)} END{printf "%s %d %d %s\n", t, l, g, u != "" ? u : v}'
}
median() { sort -g | awk '{a[NR]=$1} END{print a[int((NR+1)/2)]}'; }
# side_by_side OPTION: each case of the list on stdin (name|ranks|repetitions|arguments) with OPTION (the other
# way) and without it (the default), interleaved; the medians, their ratio and the default's LU and GMRES counts
side_by_side() {
  local off=$1 name np reps args r new def lu gm un
  while IFS='|' read -r name np reps args; do
    : > /tmp/jr_bench_new.$$
    : > /tmp/jr_bench_kept.$$
    for r in $(seq "$reps"); do
      stage "$np" $args $off >> /tmp/jr_bench_new.$$
      stage "$np" $args >> /tmp/jr_bench_kept.$$
    done
    new=$(awk '{print $1}' /tmp/jr_bench_new.$$ | median)
    def=$(awk '{print $1}' /tmp/jr_bench_kept.$$ | median)
    read -r _ lu gm un < /tmp/jr_bench_kept.$$
    printf "%-46s %-5s %8s %10.4g %10.4g %7.2f %6s %7s\n" "$name" "$np" "$un" "$new" "$def" "$(awk -v a=$new -v b=$def 'BEGIN{print a/b}')" "$lu" "$gm"
  done
  rm -f /tmp/jr_bench_new.$$ /tmp/jr_bench_kept.$$
}
echo "== dense Newton: the LU kept for GMRES against a new LU every iteration, solve stage [s], median of interleaved runs =="
printf "%-46s %-5s %8s %10s %10s %7s %6s %7s\n" case ranks unknowns "new LU" kept speedup LU GMRES
side_by_side "-hbm_snes_newtondense_reuse_its 0" <<LIST
runs/default.opts (BRB, node-to-node)|2|3|-options_file runs/default.opts -task frf -frf_stability 0
lap1 8 mm, 132 jenkins_nv, 30 modes|1|3|$lap1
lap1 8 mm, 132 jenkins_nv, 30 modes|2|3|$lap1
runs/lap3_n2n.opts (506 jenkins_nv, adapted basis)|2|1|-options_file runs/lap3_n2n.opts -frf_stability 0
LIST
# a reduced model's solvers take the prefix rom_
side_by_side "-rom_hbm_snes_newtondense_reuse_its 0" <<LIST
lap1 8 mm, 4 zone joints x 3, linear field|1|3|$lap1 -rom_joints zones -rom_joint_motion linear -rom_elements 3
runs/lap1_rom.opts reduced (24 rows, 109 modes)|2|1|-options_file runs/lap1_rom.opts -task frf -frf_stability 0
runs/lap3_shapes_rom_thesis.opts reduced (86 rows)|2|1|-options_file runs/lap3_shapes_rom_thesis.opts -task frf -frf_stability 0
LIST
echo
# A condensed reduced model's Jacobian by its products through the modes, formed only for an LU (default), against
# formed at every iteration (-hbm_condense_products 0): the solve stage, interleaved runs, median.
echo "== condensed models: the Jacobian by its products against formed every iteration, solve stage [s], median of interleaved runs =="
printf "%-46s %-5s %8s %10s %10s %7s %6s %7s\n" case ranks unknowns formed products speedup LU GMRES
side_by_side "-hbm_condense_products 0" <<LIST
lap1 8 mm, 4 zone joints x 3, linear field|1|3|$lap1 -rom_joints zones -rom_joint_motion linear -rom_elements 3
runs/lap1_rom.opts reduced (24 rows, 109 modes)|2|3|-options_file runs/lap1_rom.opts -task frf -frf_stability 0
runs/lap3_shapes_rom_thesis.opts reduced (86 rows)|1|1|-options_file runs/lap3_shapes_rom_thesis.opts -task frf -frf_stability 0
runs/lap3_shapes_rom_thesis.opts reduced (86 rows)|2|1|-options_file runs/lap3_shapes_rom_thesis.opts -task frf -frf_stability 0
LIST
echo
# The unit columns of the joints whose elements are all apart eliminated before the LU (default) against the whole
# matrix factored (-rom_hbm_snes_newtondense_eliminate 0): lap3's second reduction read back (-rom_load, -modes_load:
# written once per rank count), so that each run is its solve; the solve stage, 5 interleaved runs, median.
echo "== condensed models: joints apart eliminated before the LU against the whole matrix, solve stage [s], median of interleaved runs =="
printf "%-46s %-5s %8s %10s %10s %7s %6s %7s\n" case ranks unknowns whole eliminated speedup LU GMRES
rl=$(mktemp -d)
for np in 1 2; do
  mpiexec -n $np bin/jointrom -options_file runs/lap3_shapes_rom_thesis.opts -task frf -frf_stability 0 -frf_output_file '' -rom_save "$rl/rom$np.h5" -modes_save "$rl/modes$np.h5" < /dev/null > /dev/null 2>&1
done
side_by_side "-rom_hbm_snes_newtondense_eliminate 0" <<LIST
runs/lap3_shapes_rom_thesis.opts reduced, read back (86 rows)|1|5|-options_file runs/lap3_shapes_rom_thesis.opts -task frf -frf_stability 0 -rom_load $rl/rom1.h5 -modes_load $rl/modes1.h5
runs/lap3_shapes_rom_thesis.opts reduced, read back (86 rows)|2|5|-options_file runs/lap3_shapes_rom_thesis.opts -task frf -frf_stability 0 -rom_load $rl/rom2.h5 -modes_load $rl/modes2.h5
LIST
rm -rf "$rl"
