# imapsim plot: Mean bad>1 (nonocc) against modeled time, headline case
# Redraw or restyle: cd to this folder and run gnuplot on this file; another output:
#   gnuplot -e "outfile='plot.svg'" THIS.gp   (.png: pngcairo, .svg: svg)
if (!exists("datafile")) datafile = "golden_tradeoff.dat"
if (!exists("outfile")) outfile = "golden_tradeoff.png"
if (strlen(outfile) > 4 && outfile[strlen(outfile)-3:] eq ".svg") {
    set terminal svg size 1000,650 dynamic font "sans,11" background rgb "white"
} else {
    set terminal pngcairo size 1000,650 font "sans,10" background rgb "white"
}
set output outfile
set termoption noenhanced
set encoding utf8
set style textbox opaque noborder
set title "Mean bad>1 (nonocc) against modeled time, headline case\nms = firmware (paper + ad-max + joint, measured) + other A.9 options (estimate); 4 scene(s)"
set xlabel "modeled ms per frame (128x128, D=64, 256 PEs, 40 MHz; partly estimated)"
set ylabel "mean bad>1 % (nonocc)"
set grid xtics ytics mxtics mytics lc rgb "#dddddd" lt 1, lc rgb "#eeeeee" lt 1
set border 3 lc rgb "#444444"
set tics nomirror
set xrange [2.466332:23.626718]
set yrange [3.518230246:10.69325017]
set key outside right top vertical
set arrow 1 from graph 0, first 9.173810023 to graph 1, first 9.173810023 nohead dt 2 lw 1.5 lc rgb "#888888"
set label 1 "opencv-bm 9.17% (not on the machine)" at graph 0.01, first 9.173810023 left offset 0,0.7 textcolor rgb "#666666"
set arrow 2 from graph 0, first 5.814179318 to graph 1, first 5.814179318 nohead dt 2 lw 1.5 lc rgb "#888888"
set label 2 "opencv-sgbm 5.81% (not on the machine)" at graph 0.01, first 5.814179318 left offset 0,0.7 textcolor rgb "#666666"
set label 3 "video rate: 40 ms" at graph 0.01, graph 0.03 left front textcolor rgb "#444444"
plot datafile index 0 using 1:2 with linespoints lw 2 lt 1 pt 7 ps 1.3 title "Pareto front", \
     datafile index 1 using 1:2 with linespoints lw 2 lt 2 pt 5 ps 1.3 title "paper", \
     datafile index 2 using 1:2 with linespoints lw 2 lt 3 pt 9 ps 1.3 title "paper-single", \
     datafile index 3 using 1:2 with linespoints lw 2 lt 4 pt 11 ps 1.3 title "paper-joint", \
     datafile index 4 using 1:2 with linespoints lw 2 lt 5 pt 7 ps 1.3 title "joint-agg", \
     datafile index 5 using 1:2 with linespoints lw 2 lt 6 pt 5 ps 1.3 title "joint-census", \
     datafile index 6 using 1:2 with linespoints lw 2 lt 7 pt 9 ps 1.3 title "quality-3x3", \
     datafile index 7 using 1:2 with linespoints lw 2 lt 8 pt 11 ps 1.3 title "quality-3x1", \
     datafile index 8 using 1:2 with linespoints lw 2 lt 9 pt 7 ps 1.3 title "quality-notrunc", \
     datafile index 9 using 1:2 with linespoints lw 2 lt 10 pt 5 ps 1.3 title "quality", \
     datafile index 10 using 1:2 with linespoints lw 2 lt 11 pt 9 ps 1.3 title "quality-5x1", \
     datafile index 11 using 1:2 with linespoints lw 2 lt 12 pt 11 ps 1.3 title "quality-census1", \
     datafile index 12 using 1:2 with linespoints lw 2 lt 13 pt 7 ps 1.3 title "quality-novote", \
     datafile index 13 using 1:2 with linespoints lw 2 lt 14 pt 5 ps 1.3 title "quality-bidir"
