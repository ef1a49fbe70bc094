#!/usr/bin/env bash
# Command-line checks of bin/jointrom -task modes: the 'mode <i> <Hz>' lines, the outputs (HDF5 with
# every mode and omega, XDMF, PNG, shapes CSV), -model_view, 1 vs 2 ranks, the run file, -help, bad input.
cd "$(dirname "$0")/.."
. tests/cli_lib.sh
beam="-task modes -model_type beam -model_mesh_h 0.02 -modes_nev 10"

# free-free beam 800 x 40 x 20 mm (defaults): 6 rigid modes at 0, then the first z-bending mode,
# Euler-Bernoulli f = 4.730041^2 / (2 pi L^2) sqrt(E H^2 / (12 rho)) = 166.14 Hz (2%)
o=$($J $beam -modes_output_file "$tmp/b" -model_view 2>&1)
n=$(echo "$o" | grep -c '^mode [0-9]* [0-9.e+-]*$')
z=$(echo "$o" | awk '/^mode [1-6] /{if ($3 != 0) bad = 1} END{print bad ? "no" : "yes"}')
f7=$(echo "$o" | awk '/^mode 7 /{print $3}')
eb=$(awk 'BEGIN{pi = 3.141592653589793; print 4.730041^2 / (2 * pi * 0.64) * sqrt(210e9 * 0.0004 / (12 * 7850))}')
check "[ '$n' = 10 ] && [ '$z' = yes ] && close '$f7' '$eb' 0.02" "-task modes: 10 'mode <i> <Hz>' lines, 6 rigid at 0, mode 7 = $f7 Hz vs Euler-Bernoulli $eb Hz"
check "echo \"\$o\" | grep -q 'mass 5.024 kg from M, density x volume 5.024 kg'" "-model_view reports the mass from M and density x volume (5.024 kg)"
# HDF5: every DOF of every mode, omega and Hz; the values equal the printed ones
if command -v h5dump > /dev/null; then
  ls=$(h5ls -r "$tmp/b.h5" 2>&1)
  check "echo \"\$ls\" | grep -q '^/fields/mode_10 .*{1215, 3}' && echo \"\$ls\" | grep -q '^/modes/omega_rad_s .*{10}' && echo \"\$ls\" | grep -q '^/vertex_fields/mode_10_displacement' && echo \"\$ls\" | grep -q '^/viz/topology/cells .*{80, 8}'" "modes HDF5: /fields/mode_i (1215 nodes x 3), /vertex_fields, /viz/topology (80 hexahedra), /modes/omega_rad_s"
  w7=$(h5dump -m '%.12g' -d /modes/omega_rad_s "$tmp/b.h5" | tr -d ',' | awk '$1 == "(6):" {print $2}')
  w7e=$(awk -v f="$f7" 'BEGIN{printf "%.12g", 2 * 3.141592653589793 * f}')
  check "close '$w7' '$w7e' 1e-8" "modes HDF5: omega_7 = $w7 rad/s = 2 pi x the printed mode 7"
fi
check "grep -q 'b.h5:/vertex_fields/mode_7_displacement' '$tmp/b.xdmf' && grep -q 'NumberOfElements=\"80\"' '$tmp/b.xdmf'" "modes XDMF for ParaView: the hexahedra and each mode shape from the HDF5 file"
if command -v gnuplot > /dev/null; then check "[ \"\$(head -c 4 '$tmp/b.png' | tail -c 3)\" = PNG ] && head -1 '$tmp/b_shapes.csv' | grep -q '^mode,freq_hz,x_m,z_m,xdef_m,zdef_m$'" "mode-shape plot PNG and its CSV written"; fi

# without the supplied rigid basis: six near-zero modes computed, the same elastic frequencies
o2=$($J $beam -modes_rigid_basis 0 -modes_output_file '' 2>&1)
a=$(echo "$o2" | awk '/^mode [1-6] /{if ($3 < 1) c++} END{print c + 0}')
g7=$(echo "$o2" | awk '/^mode 7 /{print $3}')
check "[ '$a' = 6 ] && close '$g7' '$f7' 1e-8" "-modes_rigid_basis 0: $a modes below 1 Hz computed, mode 7 $g7 Hz = $f7 Hz"

# 1 and 2 ranks: the same frequencies (a bolted lap: bolts, pairs and the mesh split across ranks)
lap="-task modes -model_type lap -model_length_a 0.1 -model_length_b 0.1 -model_lap_length 0.04 -model_width 0.02 -model_height 0.02 -model_mesh_h 0.005 -model_mesh_grade 2 -model_bolt_diameter 0.006 -model_hole_diameter 0.0065 -model_washer_diameter 0.012 -model_nbolts 1 -modes_nev 12"
p1=$($J $lap -modes_output_file '' 2>&1 | awk '/^mode /{print $3}' | tr '\n' ' ')
p2=$(mpiexec -n 2 $J $lap -modes_output_file '' 2>&1 | awk '/^mode /{print $3}' | tr '\n' ' ')
d=$(echo "$p1|$p2" | awk -F'|' '{n = split($1, a, " "); m = split($2, b, " "); if (n != m || n != 12) {print 1; exit} for (i = 7; i <= n; i++) {e = (a[i] - b[i]) / a[i]; if (e < 0) e = -e; if (e > x) x = e} printf "%.1e", x}')
check "awk -v d='$d' 'BEGIN{exit !(d < 1e-8)}'" "bolted lap on 1 and 2 ranks: the same 12 frequencies (max relative difference $d)"

# cubic elements (8 nodes, 24 DOFs, in a cell): set up, and the same frequencies on 1 and 2 ranks (to the eigensolver's
# tolerance)
cub="-task modes -model_type beam -model_mesh_h 0.04 -model_fe_order 3 -modes_nev 8 -modes_output_file ''"
c1=$($J $cub 2>&1 | awk '/^mode [78] /{print $3}' | tr '\n' ' ')
c2=$(mpiexec -n 2 $J $cub 2>&1 | awk '/^mode [78] /{print $3}' | tr '\n' ' ')
d=$(echo "$c1|$c2" | awk -F'|' '{n = split($1, a, " "); m = split($2, b, " "); if (n != 2 || m != 2) {print 1; exit} for (i = 1; i <= n; i++) {e = (a[i] - b[i]) / a[i]; if (e < 0) e = -e; if (e > x) x = e} printf "%.1e", x}')
check "awk -v d='$d' 'BEGIN{exit !(d < 1e-7)}'" "-model_fe_order 3 on 1 and 2 ranks: modes 7 and 8 at ${c1}Hz (max relative difference $d)"

# the run file of the Brake-Reuss beam parses and names what it runs (its run is the bench's job)
check "grep -q '^-model_type brb' runs/brb_modes.opts && $J -options_file runs/brb_modes.opts -model_mesh_h 0.01 -modes_nev 7 -modes_output_file '' 2>&1 | grep -q '^mode 7 '" "runs/brb_modes.opts runs (coarse mesh here)"

# -help lists the model options with their units
h=$($J -task modes -model_type brb -model_mesh_h 0.01 -modes_nev 7 -modes_output_file '' -help 2>&1) # a coarse mesh: the help is what is checked
miss=""
for o in -model_E -model_nu -model_rho -model_fe_order -model_clamp -model_mesh_h -model_length_a -model_length_b -model_width -model_height -model_lap_length -model_nbolts -model_bolt_pitch -model_hole_diameter -model_washer_diameter -model_bolt_diameter -model_bolt_tie -model_interface -model_pair_tol -model_tangent -modes_nev -modes_rigid_basis -modes_output_file -modes_plot; do
  echo "$h" | grep -q -- "$o" || miss="$miss $o"
done
check "[ -z '$miss' ] && echo \"\$h\" | grep -q 'SI units' && echo \"\$h\" | grep -q 'modulus \[Pa\]'" "-help lists the FE model and modes options with units${miss:+ (missing:$miss)}"

# bad input
# a sparse factorisation package that cannot factor the distributed matrix (PETSc's own is sequential), or no package
expect_error "sequential factorisation package on 2 ranks" "-modes_st_pc_factor_mat_solver_type petsc: 'petsc' has no Cholesky factorisation of this mpiaij matrix: PETSc's own LU and Cholesky factor only sequential matrices, so on more than one rank use mumps" mpiexec -n 2 $J $lap -modes_output_file '' -modes_st_pc_factor_mat_solver_type petsc
expect_error "unknown factorisation package" "-modes_st_pc_factor_mat_solver_type mumsp: no such factorisation package in this PETSc; use mumps" $J $lap -modes_output_file '' -modes_st_pc_factor_mat_solver_type mumsp
printf 'this is not a mesh\n' > "$tmp/junk.msh"
expect_error "missing mesh file" "Cannot open the Gmsh file $tmp/none.msh" $J -task modes -model_type gmsh -model_file "$tmp/none.msh"
expect_error "invalid mesh file" "junk.msh" $J -task modes -model_type gmsh -model_file "$tmp/junk.msh"
cat > "$tmp/one.msh" << 'EOF'
$MeshFormat
2.2 0 8
$EndMeshFormat
$PhysicalNames
2
3 1 "body"
2 2 "contact_a"
$EndPhysicalNames
$Nodes
8
1 0 0 0
2 1 0 0
3 1 1 0
4 0 1 0
5 0 0 1
6 1 0 1
7 1 1 1
8 0 1 1
$EndNodes
$Elements
2
1 5 2 1 1 1 2 3 4 5 6 7 8
2 3 2 2 2 5 6 7 8
$EndElements
EOF
expect_error "missing physical group" "has no physical group 'contact_b'" $J -task modes -model_type gmsh -model_file "$tmp/one.msh"
expect_error "negative modulus" "-model_E -1.9e+11: Young's modulus must be positive" $J -task modes -model_type brb -model_E -190e9
expect_error "negative dimension" "-model_width -0.01: must be positive" $J -task modes -model_type brb -model_width -0.01
expect_error "bolt outside the lap" "reaches outside the lap" $J -task modes -model_type brb -model_bolt_pitch 0.06
expect_error "unknown model type" "Unknown model type 'bolt'" $J -task modes -model_type bolt
expect_error "unknown bolt tie" "-model_bolt_tie" $J -task modes -model_type lap1 -model_bolt_tie glued
expect_error "too few modes for the rigid ones" "more than the 6 rigid-body modes" $J -task modes -model_type beam -modes_nev 6
