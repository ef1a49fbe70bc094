#!/usr/bin/env bash
# make bench: element evaluation rates on 1 and 2 ranks (10^6 elements, with derivatives), then the
# harmonic-balance FRF rates (tests/bench/bench_hbm.sh), then the FE model and modes sizes and times
# (tests/bench/bench_modes.sh), then the bolt preload under mesh refinement (tests/bench/bench_preload.sh), then
# the node-to-node FRF from 430 to 10^6 contact elements (tests/bench/bench_n2n.sh) and its modal truncation
# study (tests/bench/bench_truncation.sh), the reduced-order joints against node-to-node (tests/bench/bench_rom.sh),
# and the stability of every FRF point off and on (tests/bench/bench_stability.sh).
# Targets: analytic jenkins >= 1e7/s per core, analytic jenkins_nv >= 2e6/s, AFT (H=3, N=64) >= 1e6/s.
cd "$(dirname "$0")/../.."
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 OMPI_MCA_rmaps_base_oversubscribe=1
echo "== contact element evaluation, 10^6 elements with derivatives =="
for np in 1 2; do
  mpiexec -n $np build/bench/bench_contact -elements 1000000 -repeat 3
done
echo
bash tests/bench/bench_hbm.sh
echo
bash tests/bench/bench_modes.sh
echo
bash tests/bench/bench_preload.sh
echo
bash tests/bench/bench_n2n.sh
echo
bash tests/bench/bench_truncation.sh
echo
bash tests/bench/bench_rom.sh
echo
bash tests/bench/bench_stability.sh
