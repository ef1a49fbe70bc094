#!/usr/bin/env bash
# jointrom dependency installer (Debian 12).
# Installs what jointrom needs when it is missing: PETSc and SLEPc 3.18 (with MUMPS and parallel
# HDF5), OpenMPI, gnuplot for the PNG plots, the HDF5 tools (h5ls, h5dump) to look into results. Quiet and quick when everything is present.
# Usage: share/install-deps.sh [--check]   (--check: report only, exit 1 if something is missing)
set -u
pkgs="petsc-dev slepc-dev libhdf5-openmpi-dev hdf5-tools gnuplot-nox make gcc g++ libopenblas0-serial"
missing=""
[ -f /usr/lib/petsc/lib/petsc/conf/variables ] || missing="$missing petsc-dev"
[ -f /usr/lib/slepc/lib/slepc/conf/slepc_common ] || missing="$missing slepc-dev"
[ -d /usr/include/hdf5/openmpi ] || missing="$missing libhdf5-openmpi-dev"
command -v mpiexec >/dev/null 2>&1 || missing="$missing petsc-dev"
command -v gnuplot >/dev/null 2>&1 || missing="$missing gnuplot-nox"
# h5ls / h5dump: look into the result files (the tests read them back with h5dump)
command -v h5dump >/dev/null 2>&1 || missing="$missing hdf5-tools"
# an optimised BLAS for the dense harmonic-balance Jacobian (GEMM) and LU; the serial build, so that
# MPI ranks do not oversubscribe the cores with BLAS threads
[ -e /usr/lib/x86_64-linux-gnu/openblas-serial/libblas.so.3 ] || [ "$(uname -m)" != x86_64 ] || missing="$missing libopenblas0-serial"
# PETSc's link line names -lstdc++, which only the C++ compiler package brings
command -v g++ >/dev/null 2>&1 || missing="$missing g++"
[ -z "$missing" ] && exit 0
if [ "${1:-}" = "--check" ]; then
  echo "jointrom: missing Debian packages:$missing (run share/install-deps.sh)" >&2
  exit 1
fi
echo "jointrom: installing missing Debian packages:$missing"
SUDO=""
if [ "$(id -u)" != 0 ]; then
  if command -v sudo >/dev/null 2>&1; then SUDO=sudo; else
    echo "jointrom: need root (or sudo) to install:$missing" >&2; exit 1
  fi
fi
export DEBIAN_FRONTEND=noninteractive
$SUDO apt-get update -q || { echo "jointrom: apt-get update failed" >&2; exit 1; }
# shellcheck disable=SC2086
$SUDO apt-get install -y -q --no-install-recommends $pkgs || { echo "jointrom: apt-get install failed for: $pkgs" >&2; exit 1; }
echo "jointrom: dependencies installed"
