#!/usr/bin/env bash
# Bad data gives no answer: a bad number in any input file (Matrix Market, element, joint and preload CSV), a
# mass or stiffness matrix that is not positive (semi)definite, an option without its value, a CSV row with too
# many fields or a file with no rows, a corrupt or truncated HDF5 or Gmsh file, a mesh too fine for the memory:
# each stops the run with exit status 1 and exactly one line "jointrom: error: ..." naming the file and line (or the
# option and value), with no output file written. A UTF-8 byte-order mark is skipped. The estimate of the FE model's
# size before its mesh is built agrees with the model built.
cd "$(dirname "$0")/.."
. tests/cli_lib.sh
osc="-task frf -model_stiffness runs/oscillator/K.mtx -model_mass runs/oscillator/M.mtx -model_elements runs/oscillator/elements.csv -hbm_gamma 0.01 -frf_dof 0 -frf_force 0.5 -frf_fmin 80 -frf_fmax 170 -cont_monitor 0 -frf_plot 0"
brb="-task frf -model_type brb -model_mesh_h 0.01 -interface_kt 1e6 -interface_mu 0.12 -hbm_modes 12 -frf_force 1 -frf_fmin 128 -frf_fmax 138 -cont_monitor 0 -frf_plot 0"
n=0
# refused DESCRIPTION PATTERN COMMAND...: the command, given -frf_output_file (or -element_loop) $tmp/out_<n>, exits 1
# with one line on stderr, "jointrom: error: ..." holding PATTERN, prints no result and writes no file $tmp/out_<n>*
refused() {
  local d=$1 p=$2 o e rc out files
  shift 2
  n=$((n + 1)); out=$tmp/out_$n
  if [ "$1" = -np2 ]; then shift; o=$(mpiexec -n 2 "$@" "$out" 2> "$tmp/err"); rc=$?; e=$(grep '^jointrom' "$tmp/err")
  else o=$("$@" "$out" 2> "$tmp/err"); rc=$?; e=$(cat "$tmp/err"); fi
  files=$(ls "$out"* 2> /dev/null | tr '\n' ' ')
  check "[ $rc = 1 ] && [ \$(echo \"\$e\" | grep -c .) = 1 ] && echo \"\$e\" | grep -q '^jointrom: error: ' && echo \"\$e\" | grep -qF -- \"\$p\" && ! echo \"\$o\" | grep -q '^peak level\|^mode \|^preload total\|^fs ' && [ -z '$files' ]" "$d: exit $rc, one line: $e${files:+ (written: $files)}"
}
k=runs/oscillator/K.mtx m=runs/oscillator/M.mtx el=runs/oscillator/elements.csv
mtx() { printf '%%%%MatrixMarket matrix coordinate real symmetric\n%s\n' "$2" > "$tmp/$1"; } # name, lines
# 1. every number of every input file parsed whole and finite, named by file, line, field and text
mtx Kabc.mtx "2 2 3
1 1 1e4
2 1 abc
2 2 1e4"
refused "Matrix Market value 'abc'" "Matrix Market file $tmp/Kabc.mtx line 4: bad entry '2 1 abc': field 3 (the value) 'abc' is not a finite number" $J $osc -model_stiffness "$tmp/Kabc.mtx" -model_mass "$tmp/Kabc.mtx" -model_elements '' -frf_output_file
mtx Knan.mtx "1 1 1
1 1 nan"
refused "Matrix Market value nan" "$tmp/Knan.mtx line 3: bad entry '1 1 nan': field 3 (the value) 'nan' is not a finite number" $J $osc -model_stiffness "$tmp/Knan.mtx" -frf_output_file
mtx Kidx.mtx "1 1 1
1.5 1 4"
refused "Matrix Market index 1.5" "$tmp/Kidx.mtx line 3: bad entry '1.5 1 4': field 1 (the row) '1.5' is not an integer" $J $osc -model_stiffness "$tmp/Kidx.mtx" -frf_output_file
mtx Kfour.mtx "1 1 1
1 1 4e5 7"
refused "Matrix Market entry with a fourth field" "$tmp/Kfour.mtx line 3: bad entry '1 1 4e5 7': 4 fields" $J $osc -model_stiffness "$tmp/Kfour.mtx" -frf_output_file
mtx Kdup.mtx "2 2 4
1 1 1e4
2 1 -1e3
1 2 -1e3
2 2 1e4"
refused "Matrix Market entry given twice (symmetric: its mirror)" "$tmp/Kdup.mtx line 5: entry (2, 1) is given again (first at line 4)" $J $osc -model_stiffness "$tmp/Kdup.mtx" -model_mass "$tmp/Kdup.mtx" -model_elements '' -frf_output_file
mtx Klong.mtx "1 1 1
1 1 4e5
1 1 4e5"
refused "Matrix Market file with more entries than announced" "$tmp/Klong.mtx line 4: more entries than the 1 the size line announces" $J $osc -model_stiffness "$tmp/Klong.mtx" -frf_output_file
mtx Ksize.mtx "1 1 1x
1 1 4e5"
refused "Matrix Market size line '1 1 1x'" "$tmp/Ksize.mtx: bad size line '1 1 1x'" $J $osc -model_stiffness "$tmp/Ksize.mtx" -frf_output_file
printf 'type,dof_a,dof_b,kt,kn,mu,n0,ndof_a,ndof_b\njenkins,0,-1,3e5,,0.1,100,,\njenkins,0,-1,abc,,0.1,100,,\n' > "$tmp/el_abc.csv"
refused "element CSV value 'abc'" "CSV file $tmp/el_abc.csv line 3, column 4 ('kt'): 'abc' is not a finite number" $J $osc -model_elements "$tmp/el_abc.csv" -frf_output_file
refused "element CSV value 'abc' on 2 ranks" "CSV file $tmp/el_abc.csv line 3, column 4 ('kt'): 'abc' is not a finite number" -np2 $J $osc -model_elements "$tmp/el_abc.csv" -frf_output_file
printf 'type,dof_a,dof_b,kt,kn,mu,n0,ndof_a,ndof_b\njenkins,0,-1,3e5,,0.1,inf,,\n' > "$tmp/el_inf.csv"
refused "element CSV value inf" "CSV file $tmp/el_inf.csv line 2, column 7 ('n0'): 'inf' is not a finite number" $J $osc -model_elements "$tmp/el_inf.csv" -frf_output_file
printf 'type,dof_a,dof_b,kt,kn,mu,n0,ndof_a,ndof_b\njenkins,0.5,-1,3e5,,0.1,100,,\n' > "$tmp/el_dof.csv"
refused "element CSV DOF 0.5" "Element file $tmp/el_dof.csv line 2: column 'dof_a' is '0.5', not a DOF number" $J $osc -model_elements "$tmp/el_dof.csv" -frf_output_file
printf 'kt,mu,n0\n1e6,0.1,1e-1O\n' > "$tmp/joint.csv"
refused "joint CSV value '1e-1O'" "CSV file $tmp/joint.csv line 2, column 3 ('n0'): '1e-1O' is not a finite number" $J -task element -element_joint "$tmp/joint.csv" -element_loop
printf 'x_m,y_m,z_m,N_static_N,v_gap_m\n0.3,0.01,0.0127,12,0\n0.3,0.02,0.0127,-nan,0\n' > "$tmp/pre.csv"
refused "preload CSV value -nan, before the model" "CSV file $tmp/pre.csv line 3, column 4 ('N_static_N'): '-nan' is not a finite number" $J $brb -preload_load "$tmp/pre.csv" -frf_output_file
printf 'x_m,y_m,z_m,N_static_N,v_gap_m\n0.3,0.01,0.0127,12,-1e-6\n' > "$tmp/pre2.csv"
refused "preload CSV negative gap, before the model" "-preload_load $tmp/pre2.csv line 2: v_gap_m = -1e-06; it must be >= 0" $J $brb -preload_load "$tmp/pre2.csv" -frf_output_file
# 2. M positive definite, K positive semidefinite (beyond round-off), by the files' names
mtx Kneg.mtx "1 1 1
1 1 -394784.176"
refused "negative-definite K" "Stiffness matrix $tmp/Kneg.mtx is not positive semidefinite: 1 eigenvalue of K phi = omega^2 M phi (M from $m)" $J $osc -model_stiffness "$tmp/Kneg.mtx" -frf_output_file
mtx Mneg.mtx "1 1 1
1 1 -1"
refused "negative mass" "Mass matrix $tmp/Mneg.mtx is not positive definite" $J $osc -model_mass "$tmp/Mneg.mtx" -frf_output_file
mtx K2.mtx "2 2 3
1 1 1e4
2 1 2e4
2 2 1e4"
mtx M2.mtx "2 2 2
1 1 1
2 2 1"
refused "indefinite K with a positive diagonal" "Stiffness matrix $tmp/K2.mtx is not positive semidefinite" $J $osc -model_stiffness "$tmp/K2.mtx" -model_mass "$tmp/M2.mtx" -model_elements '' -frf_output_file
refused "indefinite M with a positive diagonal" "Mass matrix $tmp/K2.mtx is not positive definite: 1 negative and 0 zero eigenvalues" $J $osc -model_stiffness "$tmp/M2.mtx" -model_mass "$tmp/K2.mtx" -model_elements '' -frf_output_file
refused "indefinite K on 2 ranks" "Stiffness matrix $tmp/K2.mtx is not positive semidefinite" -np2 $J $osc -model_stiffness "$tmp/K2.mtx" -model_mass "$tmp/M2.mtx" -model_elements '' -frf_output_file
# 3. an option that takes a number or a choice, given without one (or a number option given something else)
refused "-frf_force without a value" "-frf_force is given without a value: it takes a number or a list of numbers" $J $osc -frf_force -frf_output_file
refused "-hbm_harmonics without a value" "-hbm_harmonics is given without a value: it takes an integer" $J $osc -hbm_harmonics -frf_output_file
refused "-cont_type without a value" "-cont_type is given without a value: it takes one of the choices" $J $osc -cont_type -frf_output_file
refused "-frf_force 1,2x" "-frf_force 1,2x: '2x' is not a number; it takes a number or a list of numbers" $J $osc -frf_force 1,2x -frf_output_file
refused "-frf_output 0-0 (an empty range)" "-frf_output 0-0: '0-0' is not an integer; it takes an integer or a list of integers" $J $osc -frf_output 0-0 -frf_output_file
printf -- '-task frf\n-hbm_samples\n' > "$tmp/run.opts"
refused "-hbm_samples without a value in an options file" "-hbm_samples is given without a value: it takes an integer" $J $osc -options_file "$tmp/run.opts" -frf_output_file
refused "-task model (not a task)" "Unknown option model for -task. Available options: element frf modes preload compare nlmodes" $J $osc -task model -frf_output_file
refused "-task model on 2 ranks" "Unknown option model for -task" -np2 $J $osc -task model -frf_output_file
refused "-options_file that does not exist" "-options_file $tmp/none.opts: cannot be read (No such file or directory)" $J $osc -options_file "$tmp/none.opts" -frf_output_file
refused "-options_file that does not exist, 2 ranks" "-options_file $tmp/none.opts: cannot be read" -np2 $J $osc -options_file "$tmp/none.opts" -frf_output_file
refused "-frf_stability_select foo" "Unknown option foo for -frf_stability_select. Available options: vector imag" $J $osc -frf_stability_select foo -frf_output_file
refused "-hbm_modes 0" "-hbm_modes 0: at least 1 (unset: every mode up to 200 DOFs, else 10)" $J $osc -hbm_modes 0 -frf_output_file
refused "-model_mesh_hz -1" "-model_mesh_hz -1.: an element size in m, or 0 for -model_mesh_h" $J -task modes -model_type lap1 -model_mesh_hz -1 -modes_output_file
# 4. CSV rows: as many fields as the header, at least one element; a byte-order mark skipped
printf 'type,dof_a,dof_b,kt,kn,mu,n0,ndof_a,ndof_b\njenkins,0,-1,3e5,,0.1,100,,,5\n' > "$tmp/el_extra.csv"
refused "element CSV row with an extra field" "CSV file $tmp/el_extra.csv line 2: 10 fields, but the header has 9 columns" $J $osc -model_elements "$tmp/el_extra.csv" -frf_output_file
printf '# no elements\ntype,dof_a,dof_b,kt,kn,mu,n0,ndof_a,ndof_b\n' > "$tmp/el_head.csv"
refused "element CSV with a header only" "Element file $tmp/el_head.csv line 2: a header but no element rows" $J $osc -model_elements "$tmp/el_head.csv" -frf_output_file
{ printf '\357\273\277'; cat "$el"; } > "$tmp/el_bom.csv"
{ printf '\357\273\277'; cat "$k"; } > "$tmp/K_bom.mtx"
a=$($J $osc -frf_output_file '' 2>&1 | grep '^peak level')
b=$($J $osc -model_elements "$tmp/el_bom.csv" -model_stiffness "$tmp/K_bom.mtx" -frf_output_file "$tmp/bom" 2>&1 | grep '^peak level')
check "[ -n \"\$a\" ] && [ \"\$a\" = \"\$b\" ]" "a UTF-8 byte-order mark at the start of a CSV and a Matrix Market file is skipped: $b"
# 5. corrupt, truncated or foreign HDF5 files, refused when the options are read (before the model)
head -c 100 /dev/urandom > "$tmp/junk.h5"
$J $osc -frf_output_file "$tmp/save" -modes_save "$tmp/modes.h5" > /dev/null 2>&1
head -c 2000 "$tmp/modes.h5" > "$tmp/cut.h5"
refused "-modes_load of a random file" "-modes_load $tmp/junk.h5: not an HDF5 file, or a truncated or corrupt one" $J $osc -modes_load "$tmp/junk.h5" -frf_output_file
refused "-modes_load of a truncated modes file" "-modes_load $tmp/cut.h5: not an HDF5 file, or a truncated or corrupt one" $J $osc -modes_load "$tmp/cut.h5" -frf_output_file
refused "-modes_load of another program's HDF5" "-modes_load $tmp/bom.h5: an HDF5 file without the group /jointrom_modes" $J $osc -modes_load "$tmp/bom.h5" -frf_output_file
head -c 100 /dev/urandom > "$tmp/K.bin"
refused "-model_stiffness of a random PETSc binary file" "the matrix file $tmp/K.bin: " $J $osc -model_stiffness "$tmp/K.bin" -frf_output_file
refused "-rom_load of a random file, before the model" "-rom_load $tmp/junk.h5: not an HDF5 file" $J $brb -rom_load "$tmp/junk.h5" -frf_output_file
refused "-preload_load of a random .h5, before the model" "-preload_load $tmp/junk.h5: not an HDF5 file" $J $brb -preload_load "$tmp/junk.h5" -frf_output_file
refused "-preload_load of a modes file" "-preload_load $tmp/modes.h5: an HDF5 file without the group /preload" $J $brb -preload_load "$tmp/modes.h5" -frf_output_file
# 6. a random or truncated Gmsh file, on one and two ranks
head -c 100 /dev/urandom > "$tmp/junk.msh"
printf '$MeshFormat\n2.2 0 8\n$EndMeshFormat\n$Nodes\n8\n1 0 0 0\n2 1 0 0\n3 1 1 0\n4 0 1 0\n5 0 0 1\n6 1 0 1\n7 1 1 1\n8 0 1 1\n$EndNodes\n$Elements\n1\n1 5 2 1 1 1 2 3 4 5 6 7 8\n$EndElements\n' > "$tmp/box.msh"
head -c 72 "$tmp/box.msh" > "$tmp/cut.msh"
refused "Gmsh file of random bytes" "the Gmsh file $tmp/junk.msh (-model_file): File is not a valid Gmsh file" $J -task modes -model_type gmsh -model_file "$tmp/junk.msh" -modes_output_file
refused "truncated Gmsh file" "the Gmsh file $tmp/cut.msh (-model_file): Insufficient data" $J -task modes -model_type gmsh -model_file "$tmp/cut.msh" -modes_output_file
refused "truncated Gmsh file on 2 ranks" "the Gmsh file $tmp/cut.msh (-model_file): Insufficient data" -np2 $J -task modes -model_type gmsh -model_file "$tmp/cut.msh" -modes_output_file
# 7. a mesh too fine for the memory, refused from its parameters before it is built
t0=$EPOCHREALTIME
refused "brb -model_mesh_h 1e-4" "-model_mesh_h 0.0001: the mesh would have 1.87e+09 nodes (5.6e+09 DOFs), about 2.39e+04 GiB for K and M" $J $brb -model_mesh_h 1e-4 -frf_output_file
refused "lap3 -model_mesh_h 2e-4" "-model_mesh_h 0.0002: the mesh would have" $J -task modes -model_type lap3 -model_mesh_h 2e-4 -modes_output_file
refused "brb over -model_memory_limit 0.05" "GiB in all with the eigensolver's factorisation, more than the 0.05 GiB of -model_memory_limit" $J $brb -model_memory_limit 0.05 -frf_output_file
check "awk -v a=$EPOCHREALTIME -v b=$t0 'BEGIN{exit !(a - b < 10)}'" "the three refused meshes took $(awk -v a=$EPOCHREALTIME -v b=$t0 'BEGIN{printf "%.1f", a - b}') s (under 10 s: nothing was built)"
# the estimate against the model built and its peak memory (brb, h = 1 cm): nodes and nonzeros within 10 per cent,
# the memory within a factor 2
o=$($J -task modes -model_type brb -model_mesh_h 0.01 -model_view -modes_output_file '' 2>&1)
nodes=$(echo "$o" | sed -n 's/.* hexahedra, order 2, \([0-9]*\) nodes.*/\1/p')
est=$(echo "$o" | sed -n 's/.*estimate before the mesh: \([0-9]*\) nodes, \([0-9]*\) nonzeros in K (it has \([0-9]*\)), .* \([0-9.e+-]*\) GiB in all.*/\1 \2 \3 \4/p')
peak=$(echo "$o" | sed -n 's/^modes: peak memory \([0-9]*\) MB per process.*/\1/p')
set -- $est
check "[ -n '$nodes' ] && [ -n '$peak' ] && close '$1' '$nodes' 0.1 && close '$2' '$3' 0.1 && awk -v e='$4' -v p='$peak' 'BEGIN{r = e * 1024 / p; exit !(r > 0.5 && r < 2)}'" "estimate before the mesh: $1 nodes (built: $nodes), $2 nonzeros in K (built: $3), $4 GiB in all (peak: $peak MB)"
# -model_mesh_hz: the beam with 4 instead of 2 cells through each half height has 17 instead of 9 node layers through
# its height (order 2; the lap's doubled contact plane and the holes aside, within 3 per cent), so about 17/9 times
# the nodes, and the same contact pairs; the estimate follows it
o2=$($J -task modes -model_type brb -model_mesh_h 0.01 -model_mesh_hz 0.004 -model_view -modes_nev 4 -modes_output_file '' 2>&1)
nodes2=$(echo "$o2" | sed -n 's/.* hexahedra, order 2, \([0-9]*\) nodes.*/\1/p')
est2=$(echo "$o2" | sed -n 's/.*estimate before the mesh: \([0-9]*\) nodes.*/\1/p')
pairs=$(echo "$o" | sed -n 's/.* \([0-9]*\) facing pairs.*/\1/p') pairs2=$(echo "$o2" | sed -n 's/.* \([0-9]*\) facing pairs.*/\1/p')
check "[ -n '$nodes2' ] && [ -n '$nodes' ] && close '$nodes2' \$(awk -v n='$nodes' 'BEGIN{print n * 17 / 9}') 0.03 && close '$est2' '$nodes2' 0.1 && [ -n '$pairs' ] && [ '$pairs' = '$pairs2' ]" "-model_mesh_hz 0.004: $nodes2 nodes (17/9 of $nodes: $(awk -v n=$nodes 'BEGIN{print n * 17 / 9}')), estimated $est2; $pairs2 pairs (hz default: $pairs)"
