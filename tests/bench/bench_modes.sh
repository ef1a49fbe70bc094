#!/usr/bin/env bash
# make bench, FE models and modes: the Brake-Reuss beam (-model_type brb) at mesh sizes h from 10 mm
# down, 1 and 2 ranks: DOFs, model time (mesh, distribution, K and M assembly, bolts, pairs), eigensolve
# time (12 modes: 6 rigid supplied + 6 elastic, shift-and-invert with MUMPS LDL^T), peak resident memory
# (largest process and all processes), and the frequencies of modes 7 and 9 (the first two z-bending modes,
# thesis 126 / 532 Hz, its model without contact) and 12 (a lateral mode; the third z-bending mode is 13). Sizes: JR_BENCH_MODES_H (default "0.01 0.005 0.0035 0.0025").
# In-core MUMPS factors outgrow a 24 GiB machine before 10^6 DOFs (8.7 GB at 0.5e6); the sizes in
# JR_BENCH_MODES_OOC (default "0.0018": 1.23e6 DOFs) run with out-of-core factors, -mat_mumps_icntl_22 1
# (about 13 GB of files in $MUMPS_OOC_TMPDIR, default /tmp). The whole table takes about 70 minutes on
# 2 cores; JR_BENCH_MODES_OOC= skips the largest size.
cd "$(dirname "$0")/../.."
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 OMPI_MCA_rmaps_base_oversubscribe=1
export OPENBLAS_NUM_THREADS=1
sizes=${JR_BENCH_MODES_H:-"0.01 0.005 0.0035 0.0025"}
ooc=${JR_BENCH_MODES_OOC-"0.0018"}
echo "== FE model + modes: Brake-Reuss beam, 12 modes (f7, f9: z-bending, thesis 126 / 532 Hz; f12: lateral) =="
printf "%-7s %-5s %9s %8s %10s %11s %11s %9s %9s %9s %9s\n" h_mm ranks DOFs model_s eigen_s MB_max/proc MB_all f7_Hz f9_Hz f12_Hz note
for h in $sizes $ooc; do
  extra=""; note="in-core"
  case " $ooc " in *" $h "*) extra="-modes_st_mat_mumps_icntl_22 1"; note="out-of-core" ;; esac
  for np in 1 2; do
    o=$(mpiexec -n $np bin/jointrom -task modes -model_type brb -model_mesh_h "$h" -modes_nev 12 -modes_output_file '' $extra 2>&1)
    if ! echo "$o" | grep -q '^mode 12 '; then
      printf "%-7s %-5s failed: %s\n" "$(awk -v h=$h 'BEGIN{print h*1000}')" $np "$(echo "$o" | grep -m1 -E 'ERROR: [A-Z]|Killed|memory' | cut -c1-100)"
      continue
    fi
    echo "$o" | awk -v h="$h" -v np=$np -v note="$note" '
      /^modes: [0-9]+ DOFs/ {d = $2; m = $5; e = $8}
      /^modes: peak memory/ {mx = $4; al = $(NF-3)}
      /^mode 7 / {f7 = $3} /^mode 9 / {f9 = $3} /^mode 12 / {f12 = $3}
      END {printf "%-7s %-5s %9s %8s %10s %11s %11s %9.2f %9.2f %9.2f %9s\n", h * 1000, np, d, m, e, mx, al, f7, f9, f12, note}'
  done
done
