# Contact state of every node-to-node element at the peak of each level's FRF (thesis Figs 5.12-5.19):
# green full separation, black separation with stick-slip, blue stick-slip without separation, red full
# stick; grey: pairs open after the preload (no element). One panel per level, interface seen from above.
# Variables: out (PNG), data (CSV of -task frf: pair,x_m,y_m,z_m,element,state_level_0,...), nlev,
# t1, t2, ...: the panel titles.
rows = nlev <= 2 ? nlev : (nlev + 1) / 2
cols = nlev <= 2 ? 1 : 2
set terminal pngcairo size (cols == 1 ? 1000 : 1500), 120 + 260 * rows enhanced font 'Sans,9'
set output out
set datafile separator ','
set multiplot layout rows, cols title 'contact state at the FRF peak: red full stick, blue stick-slip, black separation with stick-slip, green full separation; grey: pair open after the preload'
set size ratio -1
set xlabel 'x [mm]'
set ylabel 'y [mm]'
unset key
unset colorbox
set palette defined (-1 '#bbbbbb', 0 '#d62728', 1 '#1f77b4', 2 '#000000', 3 '#2ca02c')
set cbrange [-1:3]
do for [l = 1:nlev] {
  set title value(sprintf('t%d', l)) noenhanced
  plot data skip 1 using ($2*1e3):($3*1e3):(column(5 + l)) with points pt 5 ps 1.1 lc palette
}
unset multiplot
