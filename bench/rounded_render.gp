# Error against render time for every way to round edges (bench_rounded_render).
# Run: gnuplot -e "dir='out/bench'; img='docs/img'" bench/rounded_render.gp
set terminal svg size 1100,380 dynamic font "sans,11"
set output img."/rounded_render.svg"
set datafile separator ","
set multiplot layout 1,3 title "Rounded edges: image RMSE against render time (relative to sharp), per mode"
set xlabel "render time / sharp"
set ylabel "RMSE vs tessellated reference"
set logscale x
set key off
set grid
do for [s in "article blocks cornell"] {
    set title s
    plot dir."/rounded_render.csv" using (strcol(1) eq s ? $8 : 1/0):10 with points pt 7 ps 0.8 lc rgb "#3060a0", \
         ''                          using (strcol(1) eq s ? $8 : 1/0):10:2 with labels offset 0,0.7 font "sans,8"
}
unset multiplot
