# Second reduction: each joint's hysteresis loops at the three fit amplitudes, the first-reduction joint (all its
# members, solid) against the m fitted elements (dashed) (thesis Figs 4.19-4.22, 5.65). Variables: out (PNG), data
# (CSV: joint,amplitude,u_m,f_first_reduction_N,f_rom_N), js (the joints drawn, at most 12: those with loops).
nj = words(js)
cols = nj <= 3 ? nj : (nj <= 4 ? 2 : 3)
rows = (nj + cols - 1) / cols
set terminal pngcairo size 420 * cols, 60 + 320 * rows enhanced font 'Sans,9'
set output out
set datafile separator ','
set multiplot layout rows, cols title 'joint hysteresis loops: first reduction (solid) and fitted elements (dashed), three amplitudes'
set xlabel 'u [um]'
set ylabel 'F [N]'
set grid
unset key
do for [i = 1:nj] {
  j = word(js, i) + 0
  set title sprintf('joint %d', j)
  plot for [a = 0:2] data skip 1 using ($1 == j && $2 == a ? $3 * 1e6 : NaN):4 with lines lw 2 lc a+1 dt 1, \
       for [a = 0:2] data skip 1 using ($1 == j && $2 == a ? $3 * 1e6 : NaN):5 with lines lw 2 lc a+1 dt 2
}
unset multiplot
