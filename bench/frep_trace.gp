# Error against run time of fr_trace's methods (bench/bench_frep_trace.c).
# Run as: gnuplot -e "dir='out/bench'; img='docs/img'" bench/frep_trace.gp
set datafile separator ","
set terminal svg size 900,560 dynamic font "sans,11"
set output img."/frep_trace_pareto.svg"
set title "fr\\_trace: error against run time (96x96 primary rays per model, 1 thread)"
set logscale xy
set format y "1e%T"
set xlabel "microseconds per ray"
set ylabel "mean |t - t_{ref}|  (reference: interval bisection to 1e-13)"
set key outside right
set grid
f = dir."/frep_trace.csv"
err(m) = (strcol(1) eq m) ? ($5 > 1e-16 ? $5 : 1e-16) : NaN
plot f every ::1 using (1e6/$3):(err("cup")) with points pt 7 ps 1.2 title "cup", \
     f every ::1 using (1e6/$3):(err("tangle_cube")) with points pt 5 ps 1.2 title "tangle cube", \
     f every ::1 using (1e6/$3):(err("barth_sextic")) with points pt 9 ps 1.2 title "Barth sextic", \
     f every ::1 using (1e6/$3):(err("blended_cylinders")) with points pt 11 ps 1.2 title "blended cylinders", \
     f every ::1 using (1e6/$3):(err("sdf_spheres")) with points pt 13 ps 1.2 title "SDF spheres"
