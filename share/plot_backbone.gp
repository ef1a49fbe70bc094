# Backbone of a nonlinear mode (EPMC): frequency and damping ratio against the first-harmonic amplitude of
# response 1, log scale. Variables: out (PNG), data (CSV from -task nlmodes: point,q,omega_rad_s,freq_hz,
# damping_ratio,xi,amp_1,...), ttl (names the mode).
set terminal pngcairo size 900,800 enhanced font 'Sans,11'
set output out
set datafile separator ','
set multiplot layout 2,1 title ttl noenhanced
set logscale x
set format x '%.0e'
set grid
unset key
set ylabel 'frequency [Hz]'
plot data skip 1 using 7:4 with linespoints lw 2 pt 7 ps 0.5
set xlabel 'amplitude of response 1 [m]'
set ylabel 'damping ratio [%]'
plot data skip 1 using 7:($5 * 100) with linespoints lw 2 pt 7 ps 0.5 lc 2
unset multiplot
