#!/usr/bin/env bash
# Write a chain model for -model_type matrices: N masses m [kg] in a line joined by springs k [N/m],
# the first one to ground, and E jenkins elements (kt [N/m], mu, normal loads spread over n0 [N])
# joining random pairs of masses or a mass and ground. Deterministic (seeded).
# Usage: share/make_chain.sh DIR N E [type] [k] [m] [kt] [mu] [n0]
set -eu
dir=$1; N=$2; E=$3; type=${4:-jenkins}; k=${5:-1e7}; m=${6:-0.1}; kt=${7:-1e5}; mu=${8:-0.1}; n0=${9:-50}
mkdir -p "$dir"
awk -v N="$N" -v k="$k" 'BEGIN{
  print "%%MatrixMarket matrix coordinate real symmetric"; print N, N, 2*N-1;
  for (i=1;i<=N;i++) { d = (i<N) ? 2*k : k; print i, i, d; if (i>1) print i, i-1, -k } }' > "$dir/K.mtx"
awk -v N="$N" -v m="$m" 'BEGIN{
  print "%%MatrixMarket matrix coordinate real symmetric"; print N, N, N;
  for (i=1;i<=N;i++) print i, i, m }' > "$dir/M.mtx"
awk -v N="$N" -v E="$E" -v t="$type" -v kt="$kt" -v mu="$mu" -v n0="$n0" 'BEGIN{
  srand(12345); print "type,dof_a,dof_b,kt,kn,mu,n0,ndof_a,ndof_b";
  for (e=0;e<E;e++) { a = int(rand()*N); b = int(rand()*(N+1)) - 1; if (b == a) b = -1;
    nl = n0 * (0.2 + 1.6*rand());
    if (t == "jenkins_nv") { na = int(rand()*N); nb = (na+1) % N; printf "%s,%d,%d,%.6g,%.6g,%.4g,%.6g,%d,%d\n", t, a, b, kt, kt, mu, nl, na, nb }
    else printf "%s,%d,%d,%.6g,,%.4g,%.6g,,\n", t, a, b, kt/E*100, mu, nl/E*100 } }' > "$dir/elements.csv"
