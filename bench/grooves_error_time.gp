# grooves.h against supersampled geometry: displayed-image RMSE against time
# per frame, log-log, one panel per scene. Input: out/bench/grooves_error_time.csv
# from bench_grooves. Run: gnuplot -e "dir='out/bench'; img='docs/img'" bench/grooves_error_time.gp
if (!exists("dir")) dir = 'out/bench'
if (!exists("img")) img = 'docs/img'
f = dir.'/grooves_error_time.csv'
set terminal svg size 1050,360 dynamic font "sans,11"
set output img.'/grooves_error_time.svg'
set datafile separator ","
set logscale xy
set grid
set key top right
set xlabel "seconds per frame (80x50, 2 threads)"
set ylabel "RMSE vs 4096-spp geometry"
set multiplot layout 1,3
do for [s in "parallel curves scratches"] {
    set title s
    plot f using (strcol(1) eq s && strcol(2) eq "geometry" ? $4 : 1/0):5 with linespoints pt 7 lc rgb "#555555" title "geometry 1-256 spp", \
         f using (strcol(1) eq s && strcol(2) eq "paper" ? $4 : 1/0):5 with points pt 9 ps 2 lc rgb "#c0392b" title "§4 as the paper, 1 spp", \
         f using (strcol(1) eq s && strcol(2) eq "ours" ? $4 : 1/0):5 with points pt 5 ps 1.5 lc rgb "#2874a6" title "grooves.h, 1 spp"
}
unset multiplot
