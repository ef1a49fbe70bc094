#!/usr/bin/env bash
# make bench: the node-to-node Brake-Reuss beam (5 mm mesh, 430 jenkins elements, 12 stuck modes, 1 harmonic),
# one level (20 N, microslip), 150 equally spaced frequencies 122..134 Hz (natural continuation), solve
# stage only: the FE model, preload and modes are computed once and read back (-preload_load, -modes_load).
# Larger interfaces by -interface_split k (every element as k identical parallel elements: the same FRF,
# k times the work) up to 10^6 elements, on 1 and 2 ranks: solve time, time per point and per Newton
# iteration, peak memory per process and its growth per element. JR_BENCH_N2N_SPLITS sets the k's.
cd "$(dirname "$0")/../.."
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 OMPI_MCA_rmaps_base_oversubscribe=1
export OPENBLAS_NUM_THREADS=1
splits=${JR_BENCH_N2N_SPLITS:-"1 10 100 1000 2326"}
tmp=$(mktemp -d); trap 'rm -rf "$tmp"' EXIT
base="-options_file runs/brb_n2n.opts -frf_force 20 -frf_plot 0 -cont_monitor 0"
echo "== node-to-node FRF: Brake-Reuss beam, 1 level, 150 points, solve stage (HBM + continuation) =="
for np in 1 2; do # the modes' DOF numbering depends on the partition: one modes file per rank count
  mpiexec -n $np bin/jointrom $base -frf_output_file "$tmp/prep$np" > "$tmp/prep$np.log" 2>&1 || { echo "preparation on $np ranks failed:"; tail -5 "$tmp/prep$np.log"; exit 1; }
done
awk '/^frf: node-to-node/{printf "model: %s DOFs, %s pairs; ", $5, $7} /^preload total/{printf "preload %s s; ", $(NF-1)} /^frf: modes and projections/{printf "modes %s s (1 rank, computed once)\n", $5}' "$tmp/prep1.log" | tr -d '()'
printf "%-9s %-5s %8s %7s %9s %12s %13s %12s %10s %12s\n" elements ranks points newton solve_s ms_per_point ms_per_newton peak_Hz mem_MB kB_per_elem
declare -A m0
for k in $splits; do
  for np in 1 2; do
    o=$(mpiexec -n $np bin/jointrom $base -modes_load "$tmp/prep${np}_modes.h5" -preload_load "$tmp/prep1_preload.h5" -cont_type natural -cont_points 150 -interface_split $k -frf_output_file "$tmp/run" 2>&1)
    if ! echo "$o" | grep -q '^peak level'; then
      printf "%-9s %-5s failed: %s\n" "k=$k" $np "$(echo "$o" | grep -m1 -E 'ERROR: [A-Z]|Killed|memory' | cut -c1-100)"; continue
    fi
    ne=$(echo "$o" | awk '/^interface:/{print $2}')
    mem=$(echo "$o" | awk '/peak memory/{print $4}')
    [ "$k" = 1 ] && m0[$np]=$mem
    echo "$o" | awk -v ne=$ne -v np=$np -v mem=$mem -v m0=${m0[$np]:-$mem} '
      /^peak level/ {pk = $5}
      /^frf summary/ {f = 1; next}
      f && $1 ~ /^[0-9.]+$/ {pts = $6; nw = $7; s = $9; f = 0}
      END {printf "%-9s %-5s %8s %7s %9.3f %12.3f %13.3f %12.6f %10.1f %12s\n", ne, np, pts, nw, s, 1e3 * s / pts, 1e3 * s / nw, pk, mem, (ne > 430 ? sprintf("%.2f", (mem - m0) * 1024 / (ne - 430)) : "-")}'
  done
done
echo "(targets: >= 400 elements, 150 points in < 1 s on one core; 10^6 elements < 1 s per Newton iteration on 2 ranks)"
