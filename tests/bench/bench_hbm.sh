#!/usr/bin/env bash
# make bench, harmonic balance: frequency-response points per second for a chain of 100 DOF (10 modes)
# with 10^2, 10^4, 10^5 jenkins elements, H = 1 and H = 3; analytic vs finite-difference Jacobian
# measured side by side; 1 vs 2 ranks. Each run: natural continuation, 21 equally spaced points over
# 0.8-1.2 of the first natural frequency, force 50 N at the free end (microslip: about 2 Newton iterations per point). Time = the solve stage only
# (HBM + continuation, from the program's own per-level timer).
# Targets: analytic >= 20x faster than fd at 10^4 elements; 2 ranks >= 1.7x faster at 10^5.
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
