# imapsim plot: Modeled frame time vs ROI width (pixels) (imapsim sweep, model tlm)
# Redraw or restyle: cd to this folder and run gnuplot on this file; another output:
#   gnuplot -e "outfile='plot.svg'" THIS.gp   (.png: pngcairo, .svg: svg)
if (!exists("datafile")) datafile = "whatif_roi_d.dat"
if (!exists("outfile")) outfile = "whatif_roi_d.png"
if (strlen(outfile) > 4 && outfile[strlen(outfile)-3:] eq ".svg") {
    set terminal svg size 900,600 dynamic font "sans,11" background rgb "white"
} else {
    set terminal pngcairo size 900,600 font "sans,10" background rgb "white"
}
set output outfile
set termoption noenhanced
set encoding utf8
set style textbox opaque noborder
set title "Modeled frame time vs ROI width (pixels) (imapsim sweep, model tlm)\nsynthetic scene"
set xlabel "ROI width (pixels), height 128"
set ylabel "modeled frame time (ms)"
set grid xtics ytics mxtics mytics lc rgb "#dddddd" lt 1, lc rgb "#eeeeee" lt 1
set border 3 lc rgb "#444444"
set tics nomirror
set logscale y 10
set xrange [23.04:264.96]
set yrange [0.103890625:160]
set xtics ("32" 32, "64" 64, "128" 128, "256" 256)
set key outside right top vertical
set arrow 1 from graph 0, first 100 to graph 1, first 100 nohead dt 2 lw 1.5 lc rgb "#888888"
set label 1 "real time, 10 fps (100 ms)" at graph 0.01, first 100 left offset 0,0.7 textcolor rgb "#666666"
set arrow 2 from graph 0, first 40 to graph 1, first 40 nohead dt 2 lw 1.5 lc rgb "#888888"
set label 2 "video rate, 25 fps (40 ms)" at graph 0.01, first 40 left offset 0,0.7 textcolor rgb "#666666"
set label 3 "3 points that do not fit / cannot run not shown" at graph 0.01, graph 0.03 left front textcolor rgb "#444444"
plot datafile index 0 using 1:2 with linespoints lw 2 lt 1 pt 7 ps 1.3 title "D=16", \
     datafile index 1 using 1:2 with linespoints lw 2 lt 2 pt 5 ps 1.3 title "D=32", \
     datafile index 2 using 1:2 with linespoints lw 2 lt 3 pt 9 ps 1.3 title "D=64", \
     datafile index 3 using 1:2 with linespoints lw 2 lt 4 pt 11 ps 1.3 title "D=128", \
     datafile index 4 using 1:2 with lines lw 1.5 dt 2 lt 1 title "D=16: machine bound", \
     datafile index 5 using 1:2 with lines lw 1.5 dt 2 lt 2 title "D=32: machine bound", \
     datafile index 6 using 1:2 with lines lw 1.5 dt 2 lt 3 title "D=64: machine bound", \
     datafile index 7 using 1:2 with lines lw 1.5 dt 2 lt 4 title "D=128: machine bound"
