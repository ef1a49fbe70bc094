# Bolt preload over the interface (thesis Figs 4.2, 5.3, 5.4, 5.21): maps of the contact pressure and of
# the gap over the contact surface (x-y, every pair a square), and the mid-section profile of both along x.
# Variables: out (PNG), data (CSV of -task preload: pair,x_m,y_m,z_m,area_m2,N_static_N,pressure_Pa,
# v_gap_m,closed,mid[,n0_N]), ymid (the mid-section's y in mm).
set terminal pngcairo size 1100,1000 enhanced font 'Sans,10'
set output out
set datafile separator ','
set multiplot layout 3,1 title 'bolt preload: interface normal pressure and gap'
set size ratio -1
set xlabel 'x [mm]'
set ylabel 'y [mm]'
unset key
set palette defined (0 '#ffffff', 1 '#fde725', 2 '#35b779', 3 '#31688e', 4 '#440154')
set title 'contact pressure [MPa] (white: open)'
set cbrange [0:*]
plot data skip 1 using ($2*1e3):($3*1e3):($7*1e-6) with points pt 5 ps 0.9 lc palette
set palette defined (0 '#ffffff', 1 '#fcbba1', 2 '#ef3b2c', 3 '#67000d')
set title 'gap [um] (white: closed)'
plot data skip 1 using ($2*1e3):($3*1e3):($8*1e6) with points pt 5 ps 0.9 lc palette
set size noratio
set title sprintf('mid-section y = %.2f mm', ymid)
set ylabel 'pressure [MPa]'
set y2label 'gap [um]'
set ytics nomirror
set y2tics
set key top right
plot data skip 1 using ($10 == 1 ? $2*1e3 : NaN):($7*1e-6) with linespoints pt 7 ps 0.5 lc rgb '#31688e' title 'pressure', \
     data skip 1 using ($10 == 1 ? $2*1e3 : NaN):($8*1e6) axes x1y2 with linespoints pt 6 ps 0.5 lc rgb '#ef3b2c' title 'gap'
unset multiplot
