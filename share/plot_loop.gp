# Hysteresis loops of a friction element or joint: tangential force vs tangential displacement,
# and for jenkins_nv (normal=1) the force and the normal load over the cycle beside it.
# Variables: out (PNG), data (CSV from -task element: level,U_m,theta_rad,u_m,v_m,f_N,n_N),
# nlev (number of amplitudes), ttl (title), normal (0/1).
if (!exists("normal")) normal = 0
set terminal pngcairo size (normal ? 1400 : 900),650 enhanced font 'Sans,11'
set output out
set datafile separator ','
set grid
set xzeroaxis lt -1 lw 0.5
set yzeroaxis lt -1 lw 0.5
amp(i) = real(system(sprintf("awk -F, 'NR>1 && $1==%d {print $2*1e6; exit}' '%s'", i, data)))
if (normal) { set multiplot layout 1,2 title ttl noenhanced } else { set title ttl noenhanced }
set xlabel 'tangential displacement u [{/Symbol m}m]'
set ylabel 'tangential force f [N]'
set key outside right top title 'amplitude U'
plot for [i=0:nlev-1] data skip 1 using ($1 == i ? $4*1e6 : NaN):($1 == i ? $6 : NaN) \
     with lines lw 2 title sprintf('%.3g {/Symbol m}m', amp(i))
if (normal) {
  set title 'over the cycle: tangential force (colours), normal load (black; 0 = separated)'
  set xlabel 'phase {/Symbol q} [deg]'
  set ylabel 'tangential force f [N]'
  set y2label 'normal load n [N]'
  set y2tics
  set ytics nomirror
  set xrange [0:360]
  set xtics 60
  set key inside right top
  plot for [i=0:nlev-1] data skip 1 using ($1 == i ? $3*180/pi : NaN):($1 == i ? $6 : NaN) \
       with lines lw 2 title sprintf('f, %.3g {/Symbol m}m', amp(i)), \
       data skip 1 using ($1 == 0 ? $3*180/pi : NaN):($1 == 0 ? $7 : NaN) axes x1y2 with lines lw 2 dt 2 lc rgb 'black' title 'n'
  unset multiplot
}
