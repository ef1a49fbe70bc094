# Frequency-response curves of all excitation levels: first-harmonic amplitude of response 1 (column
# amp_1) vs frequency, log scale. Variables: out (PNG), data (CSV from -task frf: level,F_N,omega_rad_s,
# freq_hz,amp_1,...), nlev, normalize (1: amplitude / force), ttl (names the response and its point).
set terminal pngcairo size 1000,650 enhanced font 'Sans,11'
set output out
set datafile separator ','
set title ttl noenhanced
set xlabel 'frequency [Hz]'
set ylabel (normalize ? 'amplitude / force [m/N]' : 'amplitude [m]')
set logscale y
set format y '%.0e'
set grid
set key outside right top title 'force F'
force(i) = real(system(sprintf("awk -F, 'NR>1 && $1==%d {print $2; exit}' '%s'", i, data)))
plot for [i=0:nlev-1] data skip 1 using ($1 == i ? $4 : NaN):($1 == i ? (normalize ? $5/$2 : $5) : NaN) \
     with linespoints lw 2 pt 7 ps 0.4 title sprintf('%g N', force(i))
