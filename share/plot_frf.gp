# Frequency-response curves of all excitation levels: first-harmonic amplitude of response 1 (column
# amp_1) vs frequency, log scale; stretches that Hill's method finds unstable dashed. Variables: out (PNG),
# data (CSV from -task frf: level,F_N,omega_rad_s,freq_hz,amp_1,...,stable), nlev, normalize (1: amplitude /
# force), scol (the column of stable: 1 stable, 0 unstable, -1 not computed), ttl (names the response and
# its point).
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
if (!exists("scol")) scol = 0
force(i) = real(system(sprintf("awk -F, 'NR>1 && $1==%d {print $2; exit}' '%s'", i, data)))
y(i) = ($1 == i ? (normalize ? $5/$2 : $5) : NaN)
unst(i) = (scol > 0 && $1 == i ? column(scol) == 0 : 0)
# solid: a point not unstable, or the one after it (so the stretches join); dashed: an unstable point, or the one after it
plot for [i=0:nlev-1] data skip 1 using 4:(u = unst(i), v = (!u || !pu) ? y(i) : NaN, pu = u, v) \
       with lines lw 2 lc i + 1 title sprintf('%g N', force(i)), \
     for [i=0:nlev-1] data skip 1 using 4:(u = unst(i), v = (u || pu) ? y(i) : NaN, pu = u, v) \
       with lines lw 2 dt 2 lc i + 1 notitle
