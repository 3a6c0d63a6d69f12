# imapsim plot: Modeled frame time vs PEs (imapsim sweep, model tlm)
# Redraw or restyle: cd to this folder and run gnuplot on this file; another output:
#   gnuplot -e "outfile='plot.svg'" THIS.gp   (.png: pngcairo, .svg: svg)
if (!exists("datafile")) datafile = "whatif_pes.dat"
if (!exists("outfile")) outfile = "whatif_pes.png"
if (strlen(outfile) > 4 && outfile[strlen(outfile)-3:] eq ".svg") {
    set terminal svg size 900,600 dynamic font "sans,11" background rgb "white"
} else {
    set terminal pngcairo size 900,600 font "sans,10" background rgb "white"
}
set output outfile
set termoption noenhanced
set encoding utf8
set style textbox opaque noborder
set title "Modeled frame time vs PEs (imapsim sweep, model tlm)\nsynthetic scene; roi_size=128x128, D=64, mode=bidir"
set xlabel "PEs"
set ylabel "modeled frame time (ms)"
set grid xtics ytics mxtics mytics lc rgb "#dddddd" lt 1, lc rgb "#eeeeee" lt 1
set border 3 lc rgb "#444444"
set tics nomirror
set logscale x 2
set logscale y 10
set xrange [6.4:1280]
set yrange [0.435296875:302.31856]
set xtics ("8" 8, "16" 16, "32" 32, "64" 64, "128" 128, "256" 256, "512" 512, "1024" 1024)
set key top right box opaque samplen 2 width 1 height 0.5
set arrow 1 from graph 0, first 100 to graph 1, first 100 nohead dt 2 lw 1.5 lc rgb "#888888"
set label 1 "real time, 10 fps (100 ms)" at graph 0.01, first 100 left offset 0,0.7 textcolor rgb "#666666"
set arrow 2 from graph 0, first 40 to graph 1, first 40 nohead dt 2 lw 1.5 lc rgb "#888888"
set label 2 "video rate, 25 fps (40 ms)" at graph 0.01, first 40 left offset 0,0.7 textcolor rgb "#666666"
set label 3 "flat beyond 256 PEs: relayout_in falls 26%" at first 256, first 3.23175 left front point pt 6 ps 3 lw 2 lc rgb "#d62728" offset 1.5,1.5 textcolor rgb "#b01010"
plot datafile index 0 using 1:2 with linespoints lw 2 lt 1 pt 7 ps 1.3 title "achieved (firmware)", \
     datafile index 1 using 1:2 with lines lw 1.5 dt 2 lt 1 title "machine bound"
