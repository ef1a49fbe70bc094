# Node-to-node against reduced-order joint model (-task compare): the FRF of every level, node-to-node solid,
# reduced dashed, same colour per level (thesis Figs 4.14-4.25, 5.26-5.68), of response 1 (column amp_1).
# Variables: out (PNG), n2n and rom (CSVs of -task frf: level,F_N,omega_rad_s,freq_hz,amp_1,...), nlev, ttl.
set terminal pngcairo size 1100,680 enhanced font 'Sans,11'
set output out
set datafile separator ','
set title ttl noenhanced
set xlabel 'frequency [Hz]'
set ylabel 'response 1: amplitude / force [m/N]'
set logscale y
set format y '%.0e'
set grid
set key outside right top title 'F: n2n / rom'
force(i) = real(system(sprintf("awk -F, 'NR>1 && $1==%d {print $2; exit}' '%s'", i, n2n)))
plot for [i=0:nlev-1] n2n skip 1 using ($1 == i ? $4 : NaN):($1 == i ? $5/$2 : NaN) with lines lw 2 lc i+1 dt 1 title sprintf('%g N n2n', force(i)), \
     for [i=0:nlev-1] rom skip 1 using ($1 == i ? $4 : NaN):($1 == i ? $5/$2 : NaN) with lines lw 2 lc i+1 dt 2 title sprintf('%g N rom', force(i))
