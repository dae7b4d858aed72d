# Tumble's step by stage over the fastest peer's step, written by tumble-bench; run in bench-out
set terminal pngcairo size 900,520 noenhanced font 'DejaVu Sans,10'
set output 'bench-speed-stages.png'
set title 'Tumble (splitting+end-of-step, one thread): step time by stage / fastest peer step time'
set style data histograms
set style histogram rowstacked
set style fill solid 0.8 border -1
set boxwidth 0.7
set key outside right
set grid y
set yrange [0:*]
set xtics rotate by -30
set ylabel 'share of the fastest peer step (1 = level)'
plot 'data/speed-stages.dat' using 2:xtic(1) title 'integrate', \
     '' using 3 title 'broadphase', '' using 4 title 'narrowphase', \
     '' using 5 title 'time of impact', '' using 6 title 'impact solve', \
     '' using 7 title 'contact solve', '' using 8 title 'sleep and the rest', \
     1 with lines linewidth 2 linecolor rgb 'black' title 'fastest peer'
