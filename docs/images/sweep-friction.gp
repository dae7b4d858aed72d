# The figure of docs/sweeps.md: a sweep's summary.csv plotted against the closed form.
#   tumble sweep resources/scenes/sliding-block.json --vary block.friction=0.1:1.5:15 \
#       --vary ground.friction=1 --out fr --metric final_x,rest_time
#   gnuplot -e "summary='fr/summary.csv'" docs/images/sweep-friction.gp
if (!exists("summary")) summary = 'fr/summary.csv'
set terminal pngcairo size 800,480 font "DejaVu Sans,11"
set output 'docs/images/sweep-friction.png'
set datafile separator ','
set key top right
set grid
set xlabel 'block.friction  (the pair: mu = sqrt(block x ground), ground 1)'
set ylabel 'where the block stops, x (m)'
set title 'A block thrown at 3 m/s: one sweep of 15 variants'
# The stop distance v^2 / (2 mu g), mu = sqrt(block.friction * 1).
stop(x) = 9.0 / (2 * 9.81 * sqrt(x))
plot [0:1.6] stop(x) title 'closed form v^2/(2 mu g)' lw 2 lc rgb '#888888', \
     summary using 2:7 skip 1 with points pt 7 ps 1.3 lc rgb '#d95f02' title 'tumble sweep: block.final\_x'
