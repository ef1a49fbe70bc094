# Mode shapes, side view (x-z) of the front face: undeformed (grey) and deformed (colour), one panel
# per mode. Variables: out (PNG), data (CSV: mode,freq_hz,x_m,z_m,xdef_m,zdef_m), first (first mode
# index drawn), nplot (how many).
set terminal pngcairo size 1100,(220 * nplot + 60) enhanced font 'Sans,10'
set output out
set datafile separator ','
set multiplot layout nplot,1 title 'mode shapes (side view, displacements magnified)'
set xlabel 'x [mm]'
set ylabel 'z [mm]'
unset key
freq(m) = real(system(sprintf("awk -F, 'NR>1 && $1==%d {print $2; exit}' '%s'", m, data)))
do for [q=0:nplot-1] {
  m = first + q
  set title sprintf('mode %d, %.1f Hz', m, freq(m))
  plot data skip 1 using ($1 == m ? $3*1e3 : NaN):($1 == m ? $4*1e3 : NaN) with points pt 7 ps 0.2 lc rgb '#bbbbbb', \
       data skip 1 using ($1 == m ? $5*1e3 : NaN):($1 == m ? $6*1e3 : NaN) with points pt 7 ps 0.3 lc rgb '#1f77b4'
}
unset multiplot
