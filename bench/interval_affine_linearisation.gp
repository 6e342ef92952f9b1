# The linearisation methods of interval.h's non-affine affine operations
# (bench_interval_surfaces, CSV interval_affine_linearisation.csv): left,
# overestimation of f(t) - k t relative to its true range, per case and
# method (log scale; lower is better); right, enclosure width / true range
# on the sphere and blob surfaces against segment length.
# Run by `make bench` as:
#   gnuplot -e "dir='out/bench'; img='docs/img'" bench/interval_affine_linearisation.gp
set terminal svg size 1100,520 dynamic font "sans,11"
set output img.'/interval_affine_linearisation.svg'
set datafile separator ','
f = dir.'/interval_affine_linearisation.csv'
set multiplot layout 1,2 title 'affine forms of exp log sqrt recip pow\_n atan: Taylor, Chebyshev, min-range and the default choice'

set size 0.62,0.95
set origin 0,0
set title 'overestimation / true range of f(t) - k t, t over [a, b]'
set style data histograms
set style histogram clustered gap 1
set style fill solid 0.8 border -1
set boxwidth 0.9
set logscale y
set yrange [1e-15:10]
set format y '10^{%L}'
set ytics nomirror
set grid ytics
set xtics rotate by -60 font ',9' nomirror
set key above horizontal font ',10'
cases = '< grep -v -e "^case," -e "^surface," -e "^sphere," -e "^blob," '.f
lab(c) = sprintf('%s [%s,%s] k=%s', strcol(1), strcol(2), strcol(3), strcol(4))
# a width below 1e-15 of the range (rounding only) is drawn at the floor
rel(c) = (column(c) / column(5) > 1e-15 ? column(c) / column(5) : 1e-15)
plot cases u (rel(6)):xtic(lab(0)) title 'Taylor', \
     '' u (rel(7)) title 'Chebyshev', \
     '' u (rel(8)) title 'min-range', \
     '' u (rel(9)) title 'default'

set size 0.38,0.95
set origin 0.62,0
set title 'surfaces: enclosure width / true range (median)'
unset style
set style data linespoints
unset logscale y
set autoscale y
set format y '%g'
set logscale x
set xrange [0.025:0.36]
set xtics (0.03, 0.1, 0.3) rotate by 0 font ',10'
set xlabel 'segment length / surface size'
set key inside top left font ',10'
plot for [s in "sphere blob"] '< grep ^'.s.', '.f u 2:3 dt 2 pt 1 title s.' Taylor', \
     for [s in "sphere blob"] '< grep ^'.s.', '.f u 2:4 dt 1 pt 2 title s.' Chebyshev', \
     for [s in "sphere blob"] '< grep ^'.s.', '.f u 2:5 dt 3 pt 4 title s.' min-range', \
     for [s in "sphere blob"] '< grep ^'.s.', '.f u 2:6 dt 1 lw 2 pt 7 title s.' default'
unset multiplot
