#!/usr/bin/env bash
# make bench: reduced-order joints against node-to-node (-task compare, runs/brb_rom.opts: the 5 mm Brake-Reuss
# beam, 430 jenkins elements, 6 joints x 3 elements, 7 levels), timed side by side in one run: the solve stage
# (HBM + continuation, every level) of each model, their ratio, the set-up (projections) and the reduction (fit)
# apart; the FE model, preload and modes are shared. Then larger interfaces by -interface_split k (every element as
# k identical parallel elements: the same forces, k times the node-to-node work; a proxy for a finer interface mesh),
# and where the reduced model's time goes (per Newton iteration: the node-to-node model solves 24 modes x 3
# harmonic-balance unknowns, the reduced one is condensed onto its 6 joints x 3; rom_elem_s: the reduced model's
# solve time in its elements, cap: node-to-node's solve over the reduced model's time outside its elements, the
# ratio if its elements cost nothing). Then the three-bolt lap joint (runs/lap3_rom.opts: jenkins_nv, 506 pairs,
# 12 joints x 3 elements on the stuck-mode field, not condensed: its rows outnumber its modes) and the single-bolt lap
# joint (runs/lap1_rom.opts: 4 zone joints on the linear field, first reduction, condensed onto their rows) with the
# same split. On 1 and 2 ranks; the reduced model's levels are shared out over the ranks (its elements are on every
# rank), the node-to-node model's elements split over them; ranks "2r": the node-to-node model's elements on every
# rank too (-hbm_elements_replicated), its levels shared out the same way.
# JR_BENCH_ROM_SPLITS sets the k's.
cd "$(dirname "$0")/../.."
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 OMPI_MCA_rmaps_base_oversubscribe=1
export OPENBLAS_NUM_THREADS=1
splits=${JR_BENCH_ROM_SPLITS:-"1 5 50"}
tmp=$(mktemp -d); trap 'rm -rf "$tmp"' EXIT
base="-options_file runs/brb_rom.opts -frf_plot 0 -cont_monitor 0"
echo "== reduced-order joints vs node-to-node: Brake-Reuss beam 5 mm, 6 joints x 3 elements, 7 levels 0.1..100 N =="
for np in 1 2; do
  mpiexec -n $np bin/jointrom $base -frf_output_file "$tmp/prep$np" > "$tmp/prep$np.log" 2>&1 || { echo "preparation on $np ranks failed:"; tail -5 "$tmp/prep$np.log"; exit 1; }
done
awk '/^compare level/{printf "  F %-5s n2n %.5f Hz rom %.5f Hz (%+.2e)  amp n2n %.4e rom %.4e (%+.2e)\n", $3, $5, $7, $7 / $5 - 1, $9, $11, $11 / $9 - 1}' "$tmp/prep1.log"
grep '^compare worst' "$tmp/prep1.log"
printf "%-9s %-5s %11s %11s %8s %12s %12s %14s %14s %11s %7s\n" n2n_elem ranks n2n_solve_s rom_solve_s speedup n2n_setup_s rom_fit_s n2n_ms_per_it rom_ms_per_it rom_elem_s cap
for k in $splits; do
  for np in 1 2; do
    o=$(mpiexec -n $np bin/jointrom $base -modes_load "$tmp/prep${np}_modes.h5" -preload_load "$tmp/prep1_preload.h5" -interface_split $k -frf_output_file '' 2>&1)
    if ! echo "$o" | grep -q '^compare time'; then
      printf "%-9s %-5s failed: %s\n" "k=$k" $np "$(echo "$o" | grep -m1 -E 'ERROR: [A-Z]|Killed|memory' | cut -c1-100)"; continue
    fi
    echo "$o" | awk -v np=$np '
      /^interface:/ {ne = $2}
      /^frf summary/ {blk++}
      blk && $1 ~ /^[0-9.]+$/ && NF >= 10 {nt[blk] += $7}
      /^compare time / {tn = $4; tr = $6; sp = $8; sn = $10; fit = $14}
      /^compare time_split/ {er = $8; cap = $12}
      END {printf "%-9s %-5s %11.4f %11.4f %8.2f %12.3f %12.3f %14.3f %14.3f %11.4f %7.2f\n", ne, np, tn, tr, sp, sn, fit, 1e3 * tn / nt[1], 1e3 * tr / nt[2], er, cap}'
  done
done
compare_run() { # title, run file: the compare lines on 1 and 2 ranks
  echo
  echo "== reduced-order joints vs node-to-node: $1 =="
  printf "%-5s %11s %11s %8s %13s %13s %13s %13s %7s %9s %9s\n" ranks n2n_solve_s rom_solve_s speedup n2n_elem_s n2n_rest_s rom_elem_s rom_rest_s cap freq_err amp_err
  for np in 1 2 2r; do
    extra=; [ $np = 2r ] && extra=-hbm_elements_replicated
    o=$(mpiexec -n ${np%r} bin/jointrom -options_file $2 -frf_plot 0 -cont_monitor 0 -frf_output_file "$tmp/cmp_$np" $extra 2>&1)
    if ! echo "$o" | grep -q '^compare time_split'; then
      printf "%-5s failed: %s\n" $np "$(echo "$o" | grep -m1 -E 'ERROR: [A-Z]|Killed|memory' | cut -c1-100)"; continue
    fi
    echo "$o" | awk -v np=$np '
      /^compare worst/ {fe = $4; ae = $6}
      /^compare time / {tn = $4; tr = $6; sp = $8}
      /^compare time_split/ {en = $4; rn = $6; er = $8; rr = $10; cap = $12}
      END {printf "%-5s %11.4f %11.4f %8.2f %13.4f %13.4f %13.4f %13.4f %7.2f %9.2e %9.2e\n", np, tn, tr, sp, en, rn, er, rr, cap, fe, ae}'
  done
}
compare_run "three-bolt lap joint (runs/lap3_rom.opts), 506 jenkins_nv pairs, 12 joints x 3 elements, 4 levels" runs/lap3_rom.opts
compare_run "single-bolt lap joint (runs/lap1_rom.opts), 4 zone joints on the linear field (first reduction) condensed onto their rows, 3 levels" runs/lap1_rom.opts
