set terminal svg size 800,500 dynamic noenhanced font 'sans,11'
set output 'reports/peers/pareto.svg'
set title 'run time against error (every family)'
set xlabel 'ns per solve, median, generic cases'
set ylabel '1 + t error in ulps of its precision (the *32 solvers: float)'
set logscale y
set grid
set key outside bottom center horizontal
set offsets graph 0.15, graph 0.15, graph 0.1, graph 0.1
plot 'reports/peers/pareto.dat' using 2:3:1 with labels offset 0,1 notitle, '' using 2:3 with points pt 7 ps 1.5 title 'max', '' using 2:4 with points pt 5 ps 1.5 title 'p99'
set terminal pngcairo size 800,500 noenhanced font 'sans,10'
set output 'reports/peers/pareto.png'
replot
unset output
set terminal svg size 800,500 dynamic noenhanced font 'sans,11'
set output 'reports/peers/difficulty_apex.svg'
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
plot 'reports/peers/difficulty_apex_bullet.dat' using 1:4 with linespoints lw 2 title 'bullet max error', 'reports/peers/difficulty_apex_bullet.dat' using 1:3 axes x1y2 with lines dt 2 title 'bullet misclassified', 'reports/peers/difficulty_apex_correct.dat' using 1:4 with linespoints lw 2 title 'correct max error', 'reports/peers/difficulty_apex_correct.dat' using 1:3 axes x1y2 with lines dt 2 title 'correct misclassified', 'reports/peers/difficulty_apex_embree.dat' using 1:4 with linespoints lw 2 title 'embree max error', 'reports/peers/difficulty_apex_embree.dat' using 1:3 axes x1y2 with lines dt 2 title 'embree misclassified', 'reports/peers/difficulty_apex_occt.dat' using 1:4 with linespoints lw 2 title 'occt max error', 'reports/peers/difficulty_apex_occt.dat' using 1:3 axes x1y2 with lines dt 2 title 'occt misclassified'
set terminal pngcairo size 800,500 noenhanced font 'sans,10'
set output 'reports/peers/difficulty_apex.png'
replot
unset output
set terminal svg size 800,500 dynamic noenhanced font 'sans,11'
set output 'reports/peers/difficulty_axis_parallel.svg'
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
plot 'reports/peers/difficulty_axis_parallel_bullet.dat' using 1:4 with linespoints lw 2 title 'bullet max error', 'reports/peers/difficulty_axis_parallel_bullet.dat' using 1:3 axes x1y2 with lines dt 2 title 'bullet misclassified', 'reports/peers/difficulty_axis_parallel_correct.dat' using 1:4 with linespoints lw 2 title 'correct max error', 'reports/peers/difficulty_axis_parallel_correct.dat' using 1:3 axes x1y2 with lines dt 2 title 'correct misclassified', 'reports/peers/difficulty_axis_parallel_embree.dat' using 1:4 with linespoints lw 2 title 'embree max error', 'reports/peers/difficulty_axis_parallel_embree.dat' using 1:3 axes x1y2 with lines dt 2 title 'embree misclassified', 'reports/peers/difficulty_axis_parallel_occt.dat' using 1:4 with linespoints lw 2 title 'occt max error', 'reports/peers/difficulty_axis_parallel_occt.dat' using 1:3 axes x1y2 with lines dt 2 title 'occt misclassified', 'reports/peers/difficulty_axis_parallel_ode.dat' using 1:4 with linespoints lw 2 title 'ode max error', 'reports/peers/difficulty_axis_parallel_ode.dat' using 1:3 axes x1y2 with lines dt 2 title 'ode misclassified'
set terminal pngcairo size 800,500 noenhanced font 'sans,10'
set output 'reports/peers/difficulty_axis_parallel.png'
replot
unset output
set terminal svg size 800,500 dynamic noenhanced font 'sans,11'
set output 'reports/peers/difficulty_cap_axis.svg'
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
plot 'reports/peers/difficulty_cap_axis_bullet.dat' using 1:4 with linespoints lw 2 title 'bullet max error', 'reports/peers/difficulty_cap_axis_bullet.dat' using 1:3 axes x1y2 with lines dt 2 title 'bullet misclassified', 'reports/peers/difficulty_cap_axis_correct.dat' using 1:4 with linespoints lw 2 title 'correct max error', 'reports/peers/difficulty_cap_axis_correct.dat' using 1:3 axes x1y2 with lines dt 2 title 'correct misclassified', 'reports/peers/difficulty_cap_axis_embree.dat' using 1:4 with linespoints lw 2 title 'embree max error', 'reports/peers/difficulty_cap_axis_embree.dat' using 1:3 axes x1y2 with lines dt 2 title 'embree misclassified', 'reports/peers/difficulty_cap_axis_occt.dat' using 1:4 with linespoints lw 2 title 'occt max error', 'reports/peers/difficulty_cap_axis_occt.dat' using 1:3 axes x1y2 with lines dt 2 title 'occt misclassified', 'reports/peers/difficulty_cap_axis_ode.dat' using 1:4 with linespoints lw 2 title 'ode max error', 'reports/peers/difficulty_cap_axis_ode.dat' using 1:3 axes x1y2 with lines dt 2 title 'ode misclassified'
set terminal pngcairo size 800,500 noenhanced font 'sans,10'
set output 'reports/peers/difficulty_cap_axis.png'
replot
unset output
set terminal svg size 800,500 dynamic noenhanced font 'sans,11'
set output 'reports/peers/difficulty_cap_plane.svg'
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
plot 'reports/peers/difficulty_cap_plane_bullet.dat' using 1:4 with linespoints lw 2 title 'bullet max error', 'reports/peers/difficulty_cap_plane_bullet.dat' using 1:3 axes x1y2 with lines dt 2 title 'bullet misclassified', 'reports/peers/difficulty_cap_plane_correct.dat' using 1:4 with linespoints lw 2 title 'correct max error', 'reports/peers/difficulty_cap_plane_correct.dat' using 1:3 axes x1y2 with lines dt 2 title 'correct misclassified', 'reports/peers/difficulty_cap_plane_embree.dat' using 1:4 with linespoints lw 2 title 'embree max error', 'reports/peers/difficulty_cap_plane_embree.dat' using 1:3 axes x1y2 with lines dt 2 title 'embree misclassified', 'reports/peers/difficulty_cap_plane_occt.dat' using 1:4 with linespoints lw 2 title 'occt max error', 'reports/peers/difficulty_cap_plane_occt.dat' using 1:3 axes x1y2 with lines dt 2 title 'occt misclassified', 'reports/peers/difficulty_cap_plane_ode.dat' using 1:4 with linespoints lw 2 title 'ode max error', 'reports/peers/difficulty_cap_plane_ode.dat' using 1:3 axes x1y2 with lines dt 2 title 'ode misclassified'
set terminal pngcairo size 800,500 noenhanced font 'sans,10'
set output 'reports/peers/difficulty_cap_plane.png'
replot
unset output
set terminal svg size 800,500 dynamic noenhanced font 'sans,11'
set output 'reports/peers/difficulty_degenerate_frame.svg'
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
plot 'reports/peers/difficulty_degenerate_frame_bullet.dat' using 1:4 with linespoints lw 2 title 'bullet max error', 'reports/peers/difficulty_degenerate_frame_bullet.dat' using 1:3 axes x1y2 with lines dt 2 title 'bullet misclassified', 'reports/peers/difficulty_degenerate_frame_correct.dat' using 1:4 with linespoints lw 2 title 'correct max error', 'reports/peers/difficulty_degenerate_frame_correct.dat' using 1:3 axes x1y2 with lines dt 2 title 'correct misclassified', 'reports/peers/difficulty_degenerate_frame_embree.dat' using 1:4 with linespoints lw 2 title 'embree max error', 'reports/peers/difficulty_degenerate_frame_embree.dat' using 1:3 axes x1y2 with lines dt 2 title 'embree misclassified', 'reports/peers/difficulty_degenerate_frame_occt.dat' using 1:4 with linespoints lw 2 title 'occt max error', 'reports/peers/difficulty_degenerate_frame_occt.dat' using 1:3 axes x1y2 with lines dt 2 title 'occt misclassified', 'reports/peers/difficulty_degenerate_frame_ode.dat' using 1:4 with linespoints lw 2 title 'ode max error', 'reports/peers/difficulty_degenerate_frame_ode.dat' using 1:3 axes x1y2 with lines dt 2 title 'ode misclassified'
set terminal pngcairo size 800,500 noenhanced font 'sans,10'
set output 'reports/peers/difficulty_degenerate_frame.png'
replot
unset output
set terminal svg size 800,500 dynamic noenhanced font 'sans,11'
set output 'reports/peers/difficulty_extent_edge.svg'
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
plot 'reports/peers/difficulty_extent_edge_bullet.dat' using 1:4 with linespoints lw 2 title 'bullet max error', 'reports/peers/difficulty_extent_edge_bullet.dat' using 1:3 axes x1y2 with lines dt 2 title 'bullet misclassified', 'reports/peers/difficulty_extent_edge_correct.dat' using 1:4 with linespoints lw 2 title 'correct max error', 'reports/peers/difficulty_extent_edge_correct.dat' using 1:3 axes x1y2 with lines dt 2 title 'correct misclassified', 'reports/peers/difficulty_extent_edge_embree.dat' using 1:4 with linespoints lw 2 title 'embree max error', 'reports/peers/difficulty_extent_edge_embree.dat' using 1:3 axes x1y2 with lines dt 2 title 'embree misclassified', 'reports/peers/difficulty_extent_edge_occt.dat' using 1:4 with linespoints lw 2 title 'occt max error', 'reports/peers/difficulty_extent_edge_occt.dat' using 1:3 axes x1y2 with lines dt 2 title 'occt misclassified', 'reports/peers/difficulty_extent_edge_ode.dat' using 1:4 with linespoints lw 2 title 'ode max error', 'reports/peers/difficulty_extent_edge_ode.dat' using 1:3 axes x1y2 with lines dt 2 title 'ode misclassified'
set terminal pngcairo size 800,500 noenhanced font 'sans,10'
set output 'reports/peers/difficulty_extent_edge.png'
replot
unset output
set terminal svg size 800,500 dynamic noenhanced font 'sans,11'
set output 'reports/peers/difficulty_generator.svg'
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
plot 'reports/peers/difficulty_generator_bullet.dat' using 1:4 with linespoints lw 2 title 'bullet max error', 'reports/peers/difficulty_generator_bullet.dat' using 1:3 axes x1y2 with lines dt 2 title 'bullet misclassified', 'reports/peers/difficulty_generator_correct.dat' using 1:4 with linespoints lw 2 title 'correct max error', 'reports/peers/difficulty_generator_correct.dat' using 1:3 axes x1y2 with lines dt 2 title 'correct misclassified', 'reports/peers/difficulty_generator_embree.dat' using 1:4 with linespoints lw 2 title 'embree max error', 'reports/peers/difficulty_generator_embree.dat' using 1:3 axes x1y2 with lines dt 2 title 'embree misclassified', 'reports/peers/difficulty_generator_occt.dat' using 1:4 with linespoints lw 2 title 'occt max error', 'reports/peers/difficulty_generator_occt.dat' using 1:3 axes x1y2 with lines dt 2 title 'occt misclassified'
set terminal pngcairo size 800,500 noenhanced font 'sans,10'
set output 'reports/peers/difficulty_generator.png'
replot
unset output
set terminal svg size 800,500 dynamic noenhanced font 'sans,11'
set output 'reports/peers/difficulty_inside_start.svg'
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
plot 'reports/peers/difficulty_inside_start_bullet.dat' using 1:4 with linespoints lw 2 title 'bullet max error', 'reports/peers/difficulty_inside_start_bullet.dat' using 1:3 axes x1y2 with lines dt 2 title 'bullet misclassified', 'reports/peers/difficulty_inside_start_correct.dat' using 1:4 with linespoints lw 2 title 'correct max error', 'reports/peers/difficulty_inside_start_correct.dat' using 1:3 axes x1y2 with lines dt 2 title 'correct misclassified', 'reports/peers/difficulty_inside_start_embree.dat' using 1:4 with linespoints lw 2 title 'embree max error', 'reports/peers/difficulty_inside_start_embree.dat' using 1:3 axes x1y2 with lines dt 2 title 'embree misclassified', 'reports/peers/difficulty_inside_start_occt.dat' using 1:4 with linespoints lw 2 title 'occt max error', 'reports/peers/difficulty_inside_start_occt.dat' using 1:3 axes x1y2 with lines dt 2 title 'occt misclassified', 'reports/peers/difficulty_inside_start_ode.dat' using 1:4 with linespoints lw 2 title 'ode max error', 'reports/peers/difficulty_inside_start_ode.dat' using 1:3 axes x1y2 with lines dt 2 title 'ode misclassified'
set terminal pngcairo size 800,500 noenhanced font 'sans,10'
set output 'reports/peers/difficulty_inside_start.png'
replot
unset output
set terminal svg size 800,500 dynamic noenhanced font 'sans,11'
set output 'reports/peers/difficulty_near_tangent.svg'
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
plot 'reports/peers/difficulty_near_tangent_bullet.dat' using 1:4 with linespoints lw 2 title 'bullet max error', 'reports/peers/difficulty_near_tangent_bullet.dat' using 1:3 axes x1y2 with lines dt 2 title 'bullet misclassified', 'reports/peers/difficulty_near_tangent_correct.dat' using 1:4 with linespoints lw 2 title 'correct max error', 'reports/peers/difficulty_near_tangent_correct.dat' using 1:3 axes x1y2 with lines dt 2 title 'correct misclassified', 'reports/peers/difficulty_near_tangent_embree.dat' using 1:4 with linespoints lw 2 title 'embree max error', 'reports/peers/difficulty_near_tangent_embree.dat' using 1:3 axes x1y2 with lines dt 2 title 'embree misclassified', 'reports/peers/difficulty_near_tangent_occt.dat' using 1:4 with linespoints lw 2 title 'occt max error', 'reports/peers/difficulty_near_tangent_occt.dat' using 1:3 axes x1y2 with lines dt 2 title 'occt misclassified', 'reports/peers/difficulty_near_tangent_ode.dat' using 1:4 with linespoints lw 2 title 'ode max error', 'reports/peers/difficulty_near_tangent_ode.dat' using 1:3 axes x1y2 with lines dt 2 title 'ode misclassified'
set terminal pngcairo size 800,500 noenhanced font 'sans,10'
set output 'reports/peers/difficulty_near_tangent.png'
replot
unset output
set terminal svg size 800,500 dynamic noenhanced font 'sans,11'
set output 'reports/peers/difficulty_rim.svg'
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
plot 'reports/peers/difficulty_rim_bullet.dat' using 1:4 with linespoints lw 2 title 'bullet max error', 'reports/peers/difficulty_rim_bullet.dat' using 1:3 axes x1y2 with lines dt 2 title 'bullet misclassified', 'reports/peers/difficulty_rim_correct.dat' using 1:4 with linespoints lw 2 title 'correct max error', 'reports/peers/difficulty_rim_correct.dat' using 1:3 axes x1y2 with lines dt 2 title 'correct misclassified', 'reports/peers/difficulty_rim_embree.dat' using 1:4 with linespoints lw 2 title 'embree max error', 'reports/peers/difficulty_rim_embree.dat' using 1:3 axes x1y2 with lines dt 2 title 'embree misclassified', 'reports/peers/difficulty_rim_occt.dat' using 1:4 with linespoints lw 2 title 'occt max error', 'reports/peers/difficulty_rim_occt.dat' using 1:3 axes x1y2 with lines dt 2 title 'occt misclassified', 'reports/peers/difficulty_rim_ode.dat' using 1:4 with linespoints lw 2 title 'ode max error', 'reports/peers/difficulty_rim_ode.dat' using 1:3 axes x1y2 with lines dt 2 title 'ode misclassified'
set terminal pngcairo size 800,500 noenhanced font 'sans,10'
set output 'reports/peers/difficulty_rim.png'
replot
unset output
set terminal svg size 800,500 dynamic noenhanced font 'sans,11'
set output 'reports/peers/difficulty_scale.svg'
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
plot 'reports/peers/difficulty_scale_bullet.dat' using 1:4 with linespoints lw 2 title 'bullet max error', 'reports/peers/difficulty_scale_bullet.dat' using 1:3 axes x1y2 with lines dt 2 title 'bullet misclassified', 'reports/peers/difficulty_scale_correct.dat' using 1:4 with linespoints lw 2 title 'correct max error', 'reports/peers/difficulty_scale_correct.dat' using 1:3 axes x1y2 with lines dt 2 title 'correct misclassified', 'reports/peers/difficulty_scale_embree.dat' using 1:4 with linespoints lw 2 title 'embree max error', 'reports/peers/difficulty_scale_embree.dat' using 1:3 axes x1y2 with lines dt 2 title 'embree misclassified', 'reports/peers/difficulty_scale_occt.dat' using 1:4 with linespoints lw 2 title 'occt max error', 'reports/peers/difficulty_scale_occt.dat' using 1:3 axes x1y2 with lines dt 2 title 'occt misclassified', 'reports/peers/difficulty_scale_ode.dat' using 1:4 with linespoints lw 2 title 'ode max error', 'reports/peers/difficulty_scale_ode.dat' using 1:3 axes x1y2 with lines dt 2 title 'ode misclassified'
set terminal pngcairo size 800,500 noenhanced font 'sans,10'
set output 'reports/peers/difficulty_scale.png'
replot
unset output
set terminal svg size 800,500 dynamic noenhanced font 'sans,11'
set output 'reports/peers/difficulty_two_nappes.svg'
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
plot 'reports/peers/difficulty_two_nappes_correct.dat' using 1:4 with linespoints lw 2 title 'correct max error', 'reports/peers/difficulty_two_nappes_correct.dat' using 1:3 axes x1y2 with lines dt 2 title 'correct misclassified', 'reports/peers/difficulty_two_nappes_occt.dat' using 1:4 with linespoints lw 2 title 'occt max error', 'reports/peers/difficulty_two_nappes_occt.dat' using 1:3 axes x1y2 with lines dt 2 title 'occt misclassified'
set terminal pngcairo size 800,500 noenhanced font 'sans,10'
set output 'reports/peers/difficulty_two_nappes.png'
replot
unset output
