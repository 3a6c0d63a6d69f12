# imapsim plot: Energy per frame vs modeled frame time, Pareto-optimal points circled (imapsim sweep, model tlm)
# Redraw or restyle: cd to this folder and run gnuplot on this file; another output:
#   gnuplot -e "outfile='plot.svg'" THIS.gp   (.png: pngcairo, .svg: svg)
if (!exists("datafile")) datafile = "whatif_pareto.dat"
if (!exists("outfile")) outfile = "whatif_pareto.png"
if (strlen(outfile) > 4 && outfile[strlen(outfile)-3:] eq ".svg") {
    set terminal svg size 900,600 dynamic font "sans,11" background rgb "white"
} else {
    set terminal pngcairo size 900,600 font "sans,10" background rgb "white"
}
set output outfile
set termoption noenhanced
set encoding utf8
set style textbox opaque noborder
set title "Energy per frame vs modeled frame time, Pareto-optimal points circled (imapsim sweep, model tlm)\nsynthetic scene; roi_size=128x128, D=64, mode=bidir\npoint size: area (yosys cells), largest 3.52 Mcells"
set xlabel "modeled frame time (ms)"
set ylabel "energy per frame (uJ; [A] energy model)"
set grid xtics ytics mxtics mytics lc rgb "#dddddd" lt 1, lc rgb "#eeeeee" lt 1
set border 3 lc rgb "#444444"
set tics nomirror
set logscale x 2
set xrange [2.55484:236.186375]
set yrange [8.645231475:126.0865121]
set key below horizontal
set label 1 "pes=512" at first 3.19355, first 27.84679863 left front point pt 6 ps 3 lw 2 lc rgb "#d62728" offset 1.5,1.5 textcolor rgb "#b01010"
set label 2 "pes=256" at first 3.23175, first 14.82635151 left front point pt 6 ps 3 lw 2 lc rgb "#d62728" offset 1.5,1.5 textcolor rgb "#b01010"
plot datafile index 0 using 1:2:3 with points pt 7 lt 1 ps variable title "design points (size: area)", \
     datafile index 1 using 1:2 with lines lw 1.5 dt 2 lt 1 title "Pareto front (2 of 8)"
