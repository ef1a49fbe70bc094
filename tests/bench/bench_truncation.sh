#!/usr/bin/env bash
# make bench: the modal truncation study of the node-to-node Brake-Reuss beam (5 mm, 430 jenkins elements):
# for m = 9, 12, 20, 50 modes of the free interface (the thesis's basis), of the stuck structure and mixed
# (m stuck + m free, Ritz), the
# stuck first bending frequency in the basis against the full FE model with the springs (SLEPc), and the
# peaks at 0.1 N (near full stick), 20 N (microslip) and 100 N (towards gross slip). JR_BENCH_TRUNC_MODES
# sets the m's.
cd "$(dirname "$0")/../.."
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 OMPI_MCA_rmaps_base_oversubscribe=1
export OPENBLAS_NUM_THREADS=1
ms=${JR_BENCH_TRUNC_MODES:-"9 12 20 50"}
tmp=$(mktemp -d); trap 'rm -rf "$tmp"' EXIT
echo "== modal truncation: Brake-Reuss beam node-to-node, stuck first bending and FRF peaks vs modes =="
bin/jointrom -options_file runs/brb_n2n.opts -frf_force 0.1 -frf_plot 0 -cont_monitor 0 -frf_output_file "$tmp/prep" > "$tmp/prep.log" 2>&1 || { echo "preparation failed"; tail -3 "$tmp/prep.log"; exit 1; }
printf "%-6s %-5s %12s %12s %12s %11s %11s %11s\n" basis modes stuck_Hz stuckFE_Hz trunc_err peak0.1_Hz peak20_Hz peak100_Hz
for b in free stuck mixed; do
  for m in $ms; do
    o=$(bin/jointrom -options_file runs/brb_n2n.opts -preload_load "$tmp/prep_preload.h5" -hbm_basis $b -hbm_modes $m -frf_force 0.1,20,100 -frf_stick_fe -frf_plot 0 -cont_monitor 0 -frf_output_file '' 2>&1)
    echo "$o" | awk -v b=$b -v m=$m '/^stick_fe/ {fe = $3; mf = $5; e = $7} /^peak level/ {p[++n] = $5} END {printf "%-6s %-5s %12.5f %12.5f %12.2e %11.4f %11.4f %11.4f\n", b, m, mf, fe, e, p[1], p[2], p[3]}'
  done
done
