set terminal svg size 800,500 dynamic noenhanced font 'sans,11'
set output 'reports/latest/pareto.svg'
set title 'run time against error (every family)'
set xlabel 'ns per solve, median, generic cases'
set ylabel '1 + t error in ulps of its precision (the *32 solvers: float)'
set logscale y
set grid
set key outside bottom center horizontal
set offsets graph 0.15, graph 0.15, graph 0.1, graph 0.1
plot 'reports/latest/pareto.dat' using 2:3:1 with labels offset 0,1 notitle, '' using 2:3 with points pt 7 ps 1.5 title 'max', '' using 2:4 with points pt 5 ps 1.5 title 'p99'
set terminal pngcairo size 800,500 noenhanced font 'sans,10'
set output 'reports/latest/pareto.png'
replot
unset output
set terminal svg size 800,500 dynamic noenhanced font 'sans,11'
set output 'reports/latest/difficulty_apex.svg'
set title 'apex: error and misclassification against k'
set xlabel 'k (difficulty 2^-k)'
set ylabel '1 + max t error (ulps)'
set logscale y
set y2label 'fraction of cases misclassified'
set y2range [0:1]
set y2tics
set ytics nomirror
set grid
set key outside right
plot 'reports/latest/difficulty_apex_batch.dat' using 1:4 with linespoints lw 2 title 'batch max error', 'reports/latest/difficulty_apex_batch.dat' using 1:3 axes x1y2 with lines dt 2 title 'batch misclassified', 'reports/latest/difficulty_apex_certified.dat' using 1:4 with linespoints lw 2 title 'certified max error', 'reports/latest/difficulty_apex_certified.dat' using 1:3 axes x1y2 with lines dt 2 title 'certified misclassified', 'reports/latest/difficulty_apex_correct.dat' using 1:4 with linespoints lw 2 title 'correct max error', 'reports/latest/difficulty_apex_correct.dat' using 1:3 axes x1y2 with lines dt 2 title 'correct misclassified', 'reports/latest/difficulty_apex_correct32.dat' using 1:4 with linespoints lw 2 title 'correct32 max error', 'reports/latest/difficulty_apex_correct32.dat' using 1:3 axes x1y2 with lines dt 2 title 'correct32 misclassified', 'reports/latest/difficulty_apex_seed.dat' using 1:4 with linespoints lw 2 title 'seed max error', 'reports/latest/difficulty_apex_seed.dat' using 1:3 axes x1y2 with lines dt 2 title 'seed misclassified', 'reports/latest/difficulty_apex_seed32.dat' using 1:4 with linespoints lw 2 title 'seed32 max error', 'reports/latest/difficulty_apex_seed32.dat' using 1:3 axes x1y2 with lines dt 2 title 'seed32 misclassified', 'reports/latest/difficulty_apex_stable.dat' using 1:4 with linespoints lw 2 title 'stable max error', 'reports/latest/difficulty_apex_stable.dat' using 1:3 axes x1y2 with lines dt 2 title 'stable misclassified', 'reports/latest/difficulty_apex_stable32.dat' using 1:4 with linespoints lw 2 title 'stable32 max error', 'reports/latest/difficulty_apex_stable32.dat' using 1:3 axes x1y2 with lines dt 2 title 'stable32 misclassified'
set terminal pngcairo size 800,500 noenhanced font 'sans,10'
set output 'reports/latest/difficulty_apex.png'
replot
unset output
set terminal svg size 800,500 dynamic noenhanced font 'sans,11'
set output 'reports/latest/difficulty_axis_parallel.svg'
set title 'axis_parallel: error and misclassification against k'
set xlabel 'k (difficulty 2^-k)'
set ylabel '1 + max t error (ulps)'
set logscale y
set y2label 'fraction of cases misclassified'
set y2range [0:1]
set y2tics
set ytics nomirror
set grid
set key outside right
plot 'reports/latest/difficulty_axis_parallel_batch.dat' using 1:4 with linespoints lw 2 title 'batch max error', 'reports/latest/difficulty_axis_parallel_batch.dat' using 1:3 axes x1y2 with lines dt 2 title 'batch misclassified', 'reports/latest/difficulty_axis_parallel_certified.dat' using 1:4 with linespoints lw 2 title 'certified max error', 'reports/latest/difficulty_axis_parallel_certified.dat' using 1:3 axes x1y2 with lines dt 2 title 'certified misclassified', 'reports/latest/difficulty_axis_parallel_correct.dat' using 1:4 with linespoints lw 2 title 'correct max error', 'reports/latest/difficulty_axis_parallel_correct.dat' using 1:3 axes x1y2 with lines dt 2 title 'correct misclassified', 'reports/latest/difficulty_axis_parallel_correct32.dat' using 1:4 with linespoints lw 2 title 'correct32 max error', 'reports/latest/difficulty_axis_parallel_correct32.dat' using 1:3 axes x1y2 with lines dt 2 title 'correct32 misclassified', 'reports/latest/difficulty_axis_parallel_seed.dat' using 1:4 with linespoints lw 2 title 'seed max error', 'reports/latest/difficulty_axis_parallel_seed.dat' using 1:3 axes x1y2 with lines dt 2 title 'seed misclassified', 'reports/latest/difficulty_axis_parallel_seed32.dat' using 1:4 with linespoints lw 2 title 'seed32 max error', 'reports/latest/difficulty_axis_parallel_seed32.dat' using 1:3 axes x1y2 with lines dt 2 title 'seed32 misclassified', 'reports/latest/difficulty_axis_parallel_stable.dat' using 1:4 with linespoints lw 2 title 'stable max error', 'reports/latest/difficulty_axis_parallel_stable.dat' using 1:3 axes x1y2 with lines dt 2 title 'stable misclassified', 'reports/latest/difficulty_axis_parallel_stable32.dat' using 1:4 with linespoints lw 2 title 'stable32 max error', 'reports/latest/difficulty_axis_parallel_stable32.dat' using 1:3 axes x1y2 with lines dt 2 title 'stable32 misclassified'
set terminal pngcairo size 800,500 noenhanced font 'sans,10'
set output 'reports/latest/difficulty_axis_parallel.png'
replot
unset output
set terminal svg size 800,500 dynamic noenhanced font 'sans,11'
set output 'reports/latest/difficulty_cap_axis.svg'
set title 'cap_axis: error and misclassification against k'
set xlabel 'k (difficulty 2^-k)'
set ylabel '1 + max t error (ulps)'
set logscale y
set y2label 'fraction of cases misclassified'
set y2range [0:1]
set y2tics
set ytics nomirror
set grid
set key outside right
plot 'reports/latest/difficulty_cap_axis_batch.dat' using 1:4 with linespoints lw 2 title 'batch max error', 'reports/latest/difficulty_cap_axis_batch.dat' using 1:3 axes x1y2 with lines dt 2 title 'batch misclassified', 'reports/latest/difficulty_cap_axis_certified.dat' using 1:4 with linespoints lw 2 title 'certified max error', 'reports/latest/difficulty_cap_axis_certified.dat' using 1:3 axes x1y2 with lines dt 2 title 'certified misclassified', 'reports/latest/difficulty_cap_axis_correct.dat' using 1:4 with linespoints lw 2 title 'correct max error', 'reports/latest/difficulty_cap_axis_correct.dat' using 1:3 axes x1y2 with lines dt 2 title 'correct misclassified', 'reports/latest/difficulty_cap_axis_correct32.dat' using 1:4 with linespoints lw 2 title 'correct32 max error', 'reports/latest/difficulty_cap_axis_correct32.dat' using 1:3 axes x1y2 with lines dt 2 title 'correct32 misclassified', 'reports/latest/difficulty_cap_axis_seed.dat' using 1:4 with linespoints lw 2 title 'seed max error', 'reports/latest/difficulty_cap_axis_seed.dat' using 1:3 axes x1y2 with lines dt 2 title 'seed misclassified', 'reports/latest/difficulty_cap_axis_seed32.dat' using 1:4 with linespoints lw 2 title 'seed32 max error', 'reports/latest/difficulty_cap_axis_seed32.dat' using 1:3 axes x1y2 with lines dt 2 title 'seed32 misclassified', 'reports/latest/difficulty_cap_axis_stable.dat' using 1:4 with linespoints lw 2 title 'stable max error', 'reports/latest/difficulty_cap_axis_stable.dat' using 1:3 axes x1y2 with lines dt 2 title 'stable misclassified', 'reports/latest/difficulty_cap_axis_stable32.dat' using 1:4 with linespoints lw 2 title 'stable32 max error', 'reports/latest/difficulty_cap_axis_stable32.dat' using 1:3 axes x1y2 with lines dt 2 title 'stable32 misclassified'
set terminal pngcairo size 800,500 noenhanced font 'sans,10'
set output 'reports/latest/difficulty_cap_axis.png'
replot
unset output
set terminal svg size 800,500 dynamic noenhanced font 'sans,11'
set output 'reports/latest/difficulty_cap_plane.svg'
set title 'cap_plane: error and misclassification against k'
set xlabel 'k (difficulty 2^-k)'
set ylabel '1 + max t error (ulps)'
set logscale y
set y2label 'fraction of cases misclassified'
set y2range [0:1]
set y2tics
set ytics nomirror
set grid
set key outside right
plot 'reports/latest/difficulty_cap_plane_batch.dat' using 1:4 with linespoints lw 2 title 'batch max error', 'reports/latest/difficulty_cap_plane_batch.dat' using 1:3 axes x1y2 with lines dt 2 title 'batch misclassified', 'reports/latest/difficulty_cap_plane_certified.dat' using 1:4 with linespoints lw 2 title 'certified max error', 'reports/latest/difficulty_cap_plane_certified.dat' using 1:3 axes x1y2 with lines dt 2 title 'certified misclassified', 'reports/latest/difficulty_cap_plane_correct.dat' using 1:4 with linespoints lw 2 title 'correct max error', 'reports/latest/difficulty_cap_plane_correct.dat' using 1:3 axes x1y2 with lines dt 2 title 'correct misclassified', 'reports/latest/difficulty_cap_plane_correct32.dat' using 1:4 with linespoints lw 2 title 'correct32 max error', 'reports/latest/difficulty_cap_plane_correct32.dat' using 1:3 axes x1y2 with lines dt 2 title 'correct32 misclassified', 'reports/latest/difficulty_cap_plane_seed.dat' using 1:4 with linespoints lw 2 title 'seed max error', 'reports/latest/difficulty_cap_plane_seed.dat' using 1:3 axes x1y2 with lines dt 2 title 'seed misclassified', 'reports/latest/difficulty_cap_plane_seed32.dat' using 1:4 with linespoints lw 2 title 'seed32 max error', 'reports/latest/difficulty_cap_plane_seed32.dat' using 1:3 axes x1y2 with lines dt 2 title 'seed32 misclassified', 'reports/latest/difficulty_cap_plane_stable.dat' using 1:4 with linespoints lw 2 title 'stable max error', 'reports/latest/difficulty_cap_plane_stable.dat' using 1:3 axes x1y2 with lines dt 2 title 'stable misclassified', 'reports/latest/difficulty_cap_plane_stable32.dat' using 1:4 with linespoints lw 2 title 'stable32 max error', 'reports/latest/difficulty_cap_plane_stable32.dat' using 1:3 axes x1y2 with lines dt 2 title 'stable32 misclassified'
set terminal pngcairo size 800,500 noenhanced font 'sans,10'
set output 'reports/latest/difficulty_cap_plane.png'
replot
unset output
set terminal svg size 800,500 dynamic noenhanced font 'sans,11'
set output 'reports/latest/difficulty_degenerate_frame.svg'
set title 'degenerate_frame: error and misclassification against k'
set xlabel 'k (difficulty 2^-k)'
set ylabel '1 + max t error (ulps)'
set logscale y
set y2label 'fraction of cases misclassified'
set y2range [0:1]
set y2tics
set ytics nomirror
set grid
set key outside right
plot 'reports/latest/difficulty_degenerate_frame_batch.dat' using 1:4 with linespoints lw 2 title 'batch max error', 'reports/latest/difficulty_degenerate_frame_batch.dat' using 1:3 axes x1y2 with lines dt 2 title 'batch misclassified', 'reports/latest/difficulty_degenerate_frame_certified.dat' using 1:4 with linespoints lw 2 title 'certified max error', 'reports/latest/difficulty_degenerate_frame_certified.dat' using 1:3 axes x1y2 with lines dt 2 title 'certified misclassified', 'reports/latest/difficulty_degenerate_frame_correct.dat' using 1:4 with linespoints lw 2 title 'correct max error', 'reports/latest/difficulty_degenerate_frame_correct.dat' using 1:3 axes x1y2 with lines dt 2 title 'correct misclassified', 'reports/latest/difficulty_degenerate_frame_correct32.dat' using 1:4 with linespoints lw 2 title 'correct32 max error', 'reports/latest/difficulty_degenerate_frame_correct32.dat' using 1:3 axes x1y2 with lines dt 2 title 'correct32 misclassified', 'reports/latest/difficulty_degenerate_frame_seed.dat' using 1:4 with linespoints lw 2 title 'seed max error', 'reports/latest/difficulty_degenerate_frame_seed.dat' using 1:3 axes x1y2 with lines dt 2 title 'seed misclassified', 'reports/latest/difficulty_degenerate_frame_seed32.dat' using 1:4 with linespoints lw 2 title 'seed32 max error', 'reports/latest/difficulty_degenerate_frame_seed32.dat' using 1:3 axes x1y2 with lines dt 2 title 'seed32 misclassified', 'reports/latest/difficulty_degenerate_frame_stable.dat' using 1:4 with linespoints lw 2 title 'stable max error', 'reports/latest/difficulty_degenerate_frame_stable.dat' using 1:3 axes x1y2 with lines dt 2 title 'stable misclassified', 'reports/latest/difficulty_degenerate_frame_stable32.dat' using 1:4 with linespoints lw 2 title 'stable32 max error', 'reports/latest/difficulty_degenerate_frame_stable32.dat' using 1:3 axes x1y2 with lines dt 2 title 'stable32 misclassified'
set terminal pngcairo size 800,500 noenhanced font 'sans,10'
set output 'reports/latest/difficulty_degenerate_frame.png'
replot
unset output
set terminal svg size 800,500 dynamic noenhanced font 'sans,11'
set output 'reports/latest/difficulty_extent_edge.svg'
set title 'extent_edge: error and misclassification against k'
set xlabel 'k (difficulty 2^-k)'
set ylabel '1 + max t error (ulps)'
set logscale y
set y2label 'fraction of cases misclassified'
set y2range [0:1]
set y2tics
set ytics nomirror
set grid
set key outside right
plot 'reports/latest/difficulty_extent_edge_batch.dat' using 1:4 with linespoints lw 2 title 'batch max error', 'reports/latest/difficulty_extent_edge_batch.dat' using 1:3 axes x1y2 with lines dt 2 title 'batch misclassified', 'reports/latest/difficulty_extent_edge_certified.dat' using 1:4 with linespoints lw 2 title 'certified max error', 'reports/latest/difficulty_extent_edge_certified.dat' using 1:3 axes x1y2 with lines dt 2 title 'certified misclassified', 'reports/latest/difficulty_extent_edge_correct.dat' using 1:4 with linespoints lw 2 title 'correct max error', 'reports/latest/difficulty_extent_edge_correct.dat' using 1:3 axes x1y2 with lines dt 2 title 'correct misclassified', 'reports/latest/difficulty_extent_edge_correct32.dat' using 1:4 with linespoints lw 2 title 'correct32 max error', 'reports/latest/difficulty_extent_edge_correct32.dat' using 1:3 axes x1y2 with lines dt 2 title 'correct32 misclassified', 'reports/latest/difficulty_extent_edge_seed.dat' using 1:4 with linespoints lw 2 title 'seed max error', 'reports/latest/difficulty_extent_edge_seed.dat' using 1:3 axes x1y2 with lines dt 2 title 'seed misclassified', 'reports/latest/difficulty_extent_edge_seed32.dat' using 1:4 with linespoints lw 2 title 'seed32 max error', 'reports/latest/difficulty_extent_edge_seed32.dat' using 1:3 axes x1y2 with lines dt 2 title 'seed32 misclassified', 'reports/latest/difficulty_extent_edge_stable.dat' using 1:4 with linespoints lw 2 title 'stable max error', 'reports/latest/difficulty_extent_edge_stable.dat' using 1:3 axes x1y2 with lines dt 2 title 'stable misclassified', 'reports/latest/difficulty_extent_edge_stable32.dat' using 1:4 with linespoints lw 2 title 'stable32 max error', 'reports/latest/difficulty_extent_edge_stable32.dat' using 1:3 axes x1y2 with lines dt 2 title 'stable32 misclassified'
set terminal pngcairo size 800,500 noenhanced font 'sans,10'
set output 'reports/latest/difficulty_extent_edge.png'
replot
unset output
set terminal svg size 800,500 dynamic noenhanced font 'sans,11'
set output 'reports/latest/difficulty_generator.svg'
set title 'generator: error and misclassification against k'
set xlabel 'k (difficulty 2^-k)'
set ylabel '1 + max t error (ulps)'
set logscale y
set y2label 'fraction of cases misclassified'
set y2range [0:1]
set y2tics
set ytics nomirror
set grid
set key outside right
plot 'reports/latest/difficulty_generator_batch.dat' using 1:4 with linespoints lw 2 title 'batch max error', 'reports/latest/difficulty_generator_batch.dat' using 1:3 axes x1y2 with lines dt 2 title 'batch misclassified', 'reports/latest/difficulty_generator_certified.dat' using 1:4 with linespoints lw 2 title 'certified max error', 'reports/latest/difficulty_generator_certified.dat' using 1:3 axes x1y2 with lines dt 2 title 'certified misclassified', 'reports/latest/difficulty_generator_correct.dat' using 1:4 with linespoints lw 2 title 'correct max error', 'reports/latest/difficulty_generator_correct.dat' using 1:3 axes x1y2 with lines dt 2 title 'correct misclassified', 'reports/latest/difficulty_generator_correct32.dat' using 1:4 with linespoints lw 2 title 'correct32 max error', 'reports/latest/difficulty_generator_correct32.dat' using 1:3 axes x1y2 with lines dt 2 title 'correct32 misclassified', 'reports/latest/difficulty_generator_seed.dat' using 1:4 with linespoints lw 2 title 'seed max error', 'reports/latest/difficulty_generator_seed.dat' using 1:3 axes x1y2 with lines dt 2 title 'seed misclassified', 'reports/latest/difficulty_generator_seed32.dat' using 1:4 with linespoints lw 2 title 'seed32 max error', 'reports/latest/difficulty_generator_seed32.dat' using 1:3 axes x1y2 with lines dt 2 title 'seed32 misclassified', 'reports/latest/difficulty_generator_stable.dat' using 1:4 with linespoints lw 2 title 'stable max error', 'reports/latest/difficulty_generator_stable.dat' using 1:3 axes x1y2 with lines dt 2 title 'stable misclassified', 'reports/latest/difficulty_generator_stable32.dat' using 1:4 with linespoints lw 2 title 'stable32 max error', 'reports/latest/difficulty_generator_stable32.dat' using 1:3 axes x1y2 with lines dt 2 title 'stable32 misclassified'
set terminal pngcairo size 800,500 noenhanced font 'sans,10'
set output 'reports/latest/difficulty_generator.png'
replot
unset output
set terminal svg size 800,500 dynamic noenhanced font 'sans,11'
set output 'reports/latest/difficulty_inside_start.svg'
set title 'inside_start: error and misclassification against k'
set xlabel 'k (difficulty 2^-k)'
set ylabel '1 + max t error (ulps)'
set logscale y
set y2label 'fraction of cases misclassified'
set y2range [0:1]
set y2tics
set ytics nomirror
set grid
set key outside right
plot 'reports/latest/difficulty_inside_start_batch.dat' using 1:4 with linespoints lw 2 title 'batch max error', 'reports/latest/difficulty_inside_start_batch.dat' using 1:3 axes x1y2 with lines dt 2 title 'batch misclassified', 'reports/latest/difficulty_inside_start_certified.dat' using 1:4 with linespoints lw 2 title 'certified max error', 'reports/latest/difficulty_inside_start_certified.dat' using 1:3 axes x1y2 with lines dt 2 title 'certified misclassified', 'reports/latest/difficulty_inside_start_correct.dat' using 1:4 with linespoints lw 2 title 'correct max error', 'reports/latest/difficulty_inside_start_correct.dat' using 1:3 axes x1y2 with lines dt 2 title 'correct misclassified', 'reports/latest/difficulty_inside_start_correct32.dat' using 1:4 with linespoints lw 2 title 'correct32 max error', 'reports/latest/difficulty_inside_start_correct32.dat' using 1:3 axes x1y2 with lines dt 2 title 'correct32 misclassified', 'reports/latest/difficulty_inside_start_seed.dat' using 1:4 with linespoints lw 2 title 'seed max error', 'reports/latest/difficulty_inside_start_seed.dat' using 1:3 axes x1y2 with lines dt 2 title 'seed misclassified', 'reports/latest/difficulty_inside_start_seed32.dat' using 1:4 with linespoints lw 2 title 'seed32 max error', 'reports/latest/difficulty_inside_start_seed32.dat' using 1:3 axes x1y2 with lines dt 2 title 'seed32 misclassified', 'reports/latest/difficulty_inside_start_stable.dat' using 1:4 with linespoints lw 2 title 'stable max error', 'reports/latest/difficulty_inside_start_stable.dat' using 1:3 axes x1y2 with lines dt 2 title 'stable misclassified', 'reports/latest/difficulty_inside_start_stable32.dat' using 1:4 with linespoints lw 2 title 'stable32 max error', 'reports/latest/difficulty_inside_start_stable32.dat' using 1:3 axes x1y2 with lines dt 2 title 'stable32 misclassified'
set terminal pngcairo size 800,500 noenhanced font 'sans,10'
set output 'reports/latest/difficulty_inside_start.png'
replot
unset output
set terminal svg size 800,500 dynamic noenhanced font 'sans,11'
set output 'reports/latest/difficulty_near_tangent.svg'
set title 'near_tangent: error and misclassification against k'
set xlabel 'k (difficulty 2^-k)'
set ylabel '1 + max t error (ulps)'
set logscale y
set y2label 'fraction of cases misclassified'
set y2range [0:1]
set y2tics
set ytics nomirror
set grid
set key outside right
plot 'reports/latest/difficulty_near_tangent_batch.dat' using 1:4 with linespoints lw 2 title 'batch max error', 'reports/latest/difficulty_near_tangent_batch.dat' using 1:3 axes x1y2 with lines dt 2 title 'batch misclassified', 'reports/latest/difficulty_near_tangent_certified.dat' using 1:4 with linespoints lw 2 title 'certified max error', 'reports/latest/difficulty_near_tangent_certified.dat' using 1:3 axes x1y2 with lines dt 2 title 'certified misclassified', 'reports/latest/difficulty_near_tangent_correct.dat' using 1:4 with linespoints lw 2 title 'correct max error', 'reports/latest/difficulty_near_tangent_correct.dat' using 1:3 axes x1y2 with lines dt 2 title 'correct misclassified', 'reports/latest/difficulty_near_tangent_correct32.dat' using 1:4 with linespoints lw 2 title 'correct32 max error', 'reports/latest/difficulty_near_tangent_correct32.dat' using 1:3 axes x1y2 with lines dt 2 title 'correct32 misclassified', 'reports/latest/difficulty_near_tangent_seed.dat' using 1:4 with linespoints lw 2 title 'seed max error', 'reports/latest/difficulty_near_tangent_seed.dat' using 1:3 axes x1y2 with lines dt 2 title 'seed misclassified', 'reports/latest/difficulty_near_tangent_seed32.dat' using 1:4 with linespoints lw 2 title 'seed32 max error', 'reports/latest/difficulty_near_tangent_seed32.dat' using 1:3 axes x1y2 with lines dt 2 title 'seed32 misclassified', 'reports/latest/difficulty_near_tangent_stable.dat' using 1:4 with linespoints lw 2 title 'stable max error', 'reports/latest/difficulty_near_tangent_stable.dat' using 1:3 axes x1y2 with lines dt 2 title 'stable misclassified', 'reports/latest/difficulty_near_tangent_stable32.dat' using 1:4 with linespoints lw 2 title 'stable32 max error', 'reports/latest/difficulty_near_tangent_stable32.dat' using 1:3 axes x1y2 with lines dt 2 title 'stable32 misclassified'
set terminal pngcairo size 800,500 noenhanced font 'sans,10'
set output 'reports/latest/difficulty_near_tangent.png'
replot
unset output
set terminal svg size 800,500 dynamic noenhanced font 'sans,11'
set output 'reports/latest/difficulty_rim.svg'
set title 'rim: error and misclassification against k'
set xlabel 'k (difficulty 2^-k)'
set ylabel '1 + max t error (ulps)'
set logscale y
set y2label 'fraction of cases misclassified'
set y2range [0:1]
set y2tics
set ytics nomirror
set grid
set key outside right
plot 'reports/latest/difficulty_rim_batch.dat' using 1:4 with linespoints lw 2 title 'batch max error', 'reports/latest/difficulty_rim_batch.dat' using 1:3 axes x1y2 with lines dt 2 title 'batch misclassified', 'reports/latest/difficulty_rim_certified.dat' using 1:4 with linespoints lw 2 title 'certified max error', 'reports/latest/difficulty_rim_certified.dat' using 1:3 axes x1y2 with lines dt 2 title 'certified misclassified', 'reports/latest/difficulty_rim_correct.dat' using 1:4 with linespoints lw 2 title 'correct max error', 'reports/latest/difficulty_rim_correct.dat' using 1:3 axes x1y2 with lines dt 2 title 'correct misclassified', 'reports/latest/difficulty_rim_correct32.dat' using 1:4 with linespoints lw 2 title 'correct32 max error', 'reports/latest/difficulty_rim_correct32.dat' using 1:3 axes x1y2 with lines dt 2 title 'correct32 misclassified', 'reports/latest/difficulty_rim_seed.dat' using 1:4 with linespoints lw 2 title 'seed max error', 'reports/latest/difficulty_rim_seed.dat' using 1:3 axes x1y2 with lines dt 2 title 'seed misclassified', 'reports/latest/difficulty_rim_seed32.dat' using 1:4 with linespoints lw 2 title 'seed32 max error', 'reports/latest/difficulty_rim_seed32.dat' using 1:3 axes x1y2 with lines dt 2 title 'seed32 misclassified', 'reports/latest/difficulty_rim_stable.dat' using 1:4 with linespoints lw 2 title 'stable max error', 'reports/latest/difficulty_rim_stable.dat' using 1:3 axes x1y2 with lines dt 2 title 'stable misclassified', 'reports/latest/difficulty_rim_stable32.dat' using 1:4 with linespoints lw 2 title 'stable32 max error', 'reports/latest/difficulty_rim_stable32.dat' using 1:3 axes x1y2 with lines dt 2 title 'stable32 misclassified'
set terminal pngcairo size 800,500 noenhanced font 'sans,10'
set output 'reports/latest/difficulty_rim.png'
replot
unset output
set terminal svg size 800,500 dynamic noenhanced font 'sans,11'
set output 'reports/latest/difficulty_scale.svg'
set title 'scale: error and misclassification against k'
set xlabel 'k (difficulty 2^-k)'
set ylabel '1 + max t error (ulps)'
set logscale y
set y2label 'fraction of cases misclassified'
set y2range [0:1]
set y2tics
set ytics nomirror
set grid
set key outside right
plot 'reports/latest/difficulty_scale_batch.dat' using 1:4 with linespoints lw 2 title 'batch max error', 'reports/latest/difficulty_scale_batch.dat' using 1:3 axes x1y2 with lines dt 2 title 'batch misclassified', 'reports/latest/difficulty_scale_certified.dat' using 1:4 with linespoints lw 2 title 'certified max error', 'reports/latest/difficulty_scale_certified.dat' using 1:3 axes x1y2 with lines dt 2 title 'certified misclassified', 'reports/latest/difficulty_scale_correct.dat' using 1:4 with linespoints lw 2 title 'correct max error', 'reports/latest/difficulty_scale_correct.dat' using 1:3 axes x1y2 with lines dt 2 title 'correct misclassified', 'reports/latest/difficulty_scale_correct32.dat' using 1:4 with linespoints lw 2 title 'correct32 max error', 'reports/latest/difficulty_scale_correct32.dat' using 1:3 axes x1y2 with lines dt 2 title 'correct32 misclassified', 'reports/latest/difficulty_scale_seed.dat' using 1:4 with linespoints lw 2 title 'seed max error', 'reports/latest/difficulty_scale_seed.dat' using 1:3 axes x1y2 with lines dt 2 title 'seed misclassified', 'reports/latest/difficulty_scale_seed32.dat' using 1:4 with linespoints lw 2 title 'seed32 max error', 'reports/latest/difficulty_scale_seed32.dat' using 1:3 axes x1y2 with lines dt 2 title 'seed32 misclassified', 'reports/latest/difficulty_scale_stable.dat' using 1:4 with linespoints lw 2 title 'stable max error', 'reports/latest/difficulty_scale_stable.dat' using 1:3 axes x1y2 with lines dt 2 title 'stable misclassified', 'reports/latest/difficulty_scale_stable32.dat' using 1:4 with linespoints lw 2 title 'stable32 max error', 'reports/latest/difficulty_scale_stable32.dat' using 1:3 axes x1y2 with lines dt 2 title 'stable32 misclassified'
set terminal pngcairo size 800,500 noenhanced font 'sans,10'
set output 'reports/latest/difficulty_scale.png'
replot
unset output
set terminal svg size 800,500 dynamic noenhanced font 'sans,11'
set output 'reports/latest/difficulty_two_nappes.svg'
set title 'two_nappes: error and misclassification against k'
set xlabel 'k (difficulty 2^-k)'
set ylabel '1 + max t error (ulps)'
set logscale y
set y2label 'fraction of cases misclassified'
set y2range [0:1]
set y2tics
set ytics nomirror
set grid
set key outside right
plot 'reports/latest/difficulty_two_nappes_batch.dat' using 1:4 with linespoints lw 2 title 'batch max error', 'reports/latest/difficulty_two_nappes_batch.dat' using 1:3 axes x1y2 with lines dt 2 title 'batch misclassified', 'reports/latest/difficulty_two_nappes_certified.dat' using 1:4 with linespoints lw 2 title 'certified max error', 'reports/latest/difficulty_two_nappes_certified.dat' using 1:3 axes x1y2 with lines dt 2 title 'certified misclassified', 'reports/latest/difficulty_two_nappes_correct.dat' using 1:4 with linespoints lw 2 title 'correct max error', 'reports/latest/difficulty_two_nappes_correct.dat' using 1:3 axes x1y2 with lines dt 2 title 'correct misclassified', 'reports/latest/difficulty_two_nappes_correct32.dat' using 1:4 with linespoints lw 2 title 'correct32 max error', 'reports/latest/difficulty_two_nappes_correct32.dat' using 1:3 axes x1y2 with lines dt 2 title 'correct32 misclassified', 'reports/latest/difficulty_two_nappes_seed.dat' using 1:4 with linespoints lw 2 title 'seed max error', 'reports/latest/difficulty_two_nappes_seed.dat' using 1:3 axes x1y2 with lines dt 2 title 'seed misclassified', 'reports/latest/difficulty_two_nappes_seed32.dat' using 1:4 with linespoints lw 2 title 'seed32 max error', 'reports/latest/difficulty_two_nappes_seed32.dat' using 1:3 axes x1y2 with lines dt 2 title 'seed32 misclassified', 'reports/latest/difficulty_two_nappes_stable.dat' using 1:4 with linespoints lw 2 title 'stable max error', 'reports/latest/difficulty_two_nappes_stable.dat' using 1:3 axes x1y2 with lines dt 2 title 'stable misclassified', 'reports/latest/difficulty_two_nappes_stable32.dat' using 1:4 with linespoints lw 2 title 'stable32 max error', 'reports/latest/difficulty_two_nappes_stable32.dat' using 1:3 axes x1y2 with lines dt 2 title 'stable32 misclassified'
set terminal pngcairo size 800,500 noenhanced font 'sans,10'
set output 'reports/latest/difficulty_two_nappes.png'
replot
unset output
