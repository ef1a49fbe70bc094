# Hysteresis loops of a friction element or joint: tangential force vs tangential displacement.
# Variables: out (PNG), data (CSV from -task element, columns level,U_m,theta_rad,u_m,v_m,f_N,n_N),
# nlev (number of amplitudes), ttl (title).
set terminal pngcairo size 900,650 enhanced font 'Sans,11'
set output out
set datafile separator ','
set title ttl
set xlabel 'tangential displacement u [{/Symbol m}m]'
set ylabel 'tangential force f [N]'
set grid
set key outside right top title 'amplitude U'
set xzeroaxis lt -1 lw 0.5
set yzeroaxis lt -1 lw 0.5
plot for [i=0:nlev-1] data skip 1 using ($1 == i ? $4*1e6 : NaN):($1 == i ? $6 : NaN) \
     with lines lw 2 title sprintf('%.3g {/Symbol m}m', real(system(sprintf("awk -F, 'NR>1 && $1==%d {print $2*1e6; exit}' %s", i, data))))
