#!/usr/bin/env bash
# make bench: the bolt preload of the Brake-Reuss beam (3 bolts x 11.5 kN, augmented Lagrangian) under mesh
# refinement on 1 and 2 ranks: DOFs, pairs, share of pairs closed, contact area, peak pressure, the largest
# gap, the sum of the pair loads, Newton iterations, factorisations, solve time (model excluded) and the
# whole run's wall time. Sizes: JR_BENCH_PRELOAD_H (default "0.01 0.005 0.0035 0.0025"; sizes below 3 mm
# run on 2 ranks only, for time). The default condensed solver; JR_BENCH_PRELOAD_ARGS adds options (e.g.
# "-preload_solver full" for Newton on all DOFs).
cd "$(dirname "$0")/../.."
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 OMPI_MCA_rmaps_base_oversubscribe=1
export OPENBLAS_NUM_THREADS=1
sizes=${JR_BENCH_PRELOAD_H:-"0.01 0.005 0.0035 0.0025"}
echo "== bolt preload: Brake-Reuss beam, 3 x 11.5 kN, frictionless contact (augmented Lagrangian) ${JR_BENCH_PRELOAD_ARGS:-}=="
printf "%-6s %-5s %8s %6s %8s %10s %9s %8s %11s %7s %6s %8s %8s\n" h_mm ranks DOFs pairs closed% area_mm2 peak_MPa gap_um sum_N newton facts solve_s wall_s
for h in $sizes; do
  for np in 1 2; do
    [ "$np" = 1 ] && awk -v h="$h" 'BEGIN{exit !(h < 0.003)}' && continue # the finest size: 2 ranks only (time)
    t0=$(date +%s.%N)
    o=$(mpiexec -n $np bin/jointrom -task preload -model_type brb -model_mesh_h "$h" -preload_force 11500 -preload_output_file '' $JR_BENCH_PRELOAD_ARGS 2>&1)
    t1=$(date +%s.%N)
    if ! echo "$o" | grep -q '^preload total_normal_force'; then
      printf "%-6s %-5s failed: %s\n" "$(awk -v h=$h 'BEGIN{print h*1000}')" $np "$(echo "$o" | grep -m1 -E 'ERROR: [A-Z]|Killed|memory' | cut -c1-100)"
      continue
    fi
    echo "$o" | awk -v h="$h" -v np=$np -v w="$(awk -v a=$t0 -v b=$t1 'BEGIN{print b - a}')" '
      /^preload: model/ {d = $3}
      / Newton iterations in / {nw = $2; for (i = 1; i <= NF; i++) {if ($i == "sparse") fa = $(i - 1); if ($i == "s;") s = $(i - 1)}}
      /^preload: contact area/ {a = $4}
      /^preload: peak pressure/ {pk = $4; g = $(NF-1)}
      /^preload total_normal_force/ {t = $3; c = $7; n = $9}
      END {printf "%-6s %-5s %8s %6s %8.1f %10s %9s %8s %11.2f %7s %6s %8s %8.1f\n", h * 1000, np, d, n, 100 * c / n, a, pk, g, t, nw, fa, s, w}'
  done
done
