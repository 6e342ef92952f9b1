# Enclosure width / true range against segment length for the four
# benchmark surfaces: interval (dashed) and reduced affine (solid).
# Run by `make bench` as: gnuplot -e "dir='out/bench'; img='docs/img'" bench/interval_surfaces.gp
set terminal svg size 760,460 dynamic font "sans,12"
set output img.'/interval_surfaces.svg'
set datafile separator ','
set logscale xy
set xlabel 'segment length / surface size'
set ylabel 'enclosure width / true range (median)'
set key outside right
set grid
f = dir.'/interval_surfaces.csv'
plot for [s in "tangle barth steiner torus"] '< grep ^'.s.', '.f u 2:3 w lp dt 2 title s.' interval', \
     for [s in "tangle barth steiner torus"] '< grep ^'.s.', '.f u 2:4 w lp dt 1 title s.' affine'
