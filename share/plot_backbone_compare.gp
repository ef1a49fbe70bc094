# Backbones of a nonlinear mode (EPMC) of two models (-task compare -compare_nlmodes): frequency and damping ratio
# against the modal amplitude q of the mass-normalised stuck mode, node-to-node solid, reduced dashed.
# Variables: out (PNG), n2n and rom (CSVs of the two backbones: point,q,omega_rad_s,freq_hz,damping_ratio,...), ttl.
set terminal pngcairo size 900,800 enhanced font 'Sans,11'
set output out
set datafile separator ','
set multiplot layout 2,1 title ttl noenhanced
set logscale x
set format x '%.0e'
set grid
set key bottom left
set ylabel 'frequency [Hz]'
plot n2n skip 1 using 2:4 with linespoints lw 2 pt 7 ps 0.5 lc 1 dt 1 title 'node-to-node', \
     rom skip 1 using 2:4 with linespoints lw 2 pt 6 ps 0.6 lc 2 dt 2 title 'reduced'
set key top left
set xlabel 'modal amplitude q [m kg^{1/2}]'
set ylabel 'damping ratio [%]'
plot n2n skip 1 using 2:($5 * 100) with linespoints lw 2 pt 7 ps 0.5 lc 1 dt 1 title 'node-to-node', \
     rom skip 1 using 2:($5 * 100) with linespoints lw 2 pt 6 ps 0.6 lc 2 dt 2 title 'reduced'
unset multiplot
