# course-out/maxwell.png: gnuplot course-out/maxwell.gp remakes it (data inline)
# size 1200 500
set terminal pngcairo size 1200,500 enhanced font 'DejaVu Sans,11'
set output 'course-out/maxwell.png'
$h << EOD
0.0625 0.02 0.04 0.06 0.14 0.06 0.124513
0.1875 0.1 0.22 0.4 0.32 0.32 0.362045
0.3125 0.16 0.36 0.32 0.48 0.52 0.56685
0.4375 0.44 0.58 0.62 0.66 0.74 0.722572
0.5625 0.44 0.62 0.7 0.8 0.88 0.819859
0.6875 0.44 0.62 0.82 0.74 0.86 0.857098
0.8125 0.4 0.54 0.9 0.98 0.86 0.839752
0.9375 0.76 1.2 0.82 0.7 0.68 0.778569
1.0625 3.64 1.76 0.9 0.8 0.8 0.687197
1.1875 0.58 0.68 0.94 0.74 0.5 0.57975
1.3125 0.5 0.58 0.54 0.42 0.6 0.468802
1.4375 0.3 0.36 0.36 0.46 0.5 0.36409
1.5625 0.12 0.12 0.2 0.24 0.14 0.271995
1.6875 0.08 0.14 0.18 0.2 0.14 0.195683
1.8125 0.02 0.1 0.06 0.08 0.22 0.135701
1.9375 0 0.04 0.12 0.16 0.1 0.090776
2.0625 0 0.04 0.04 0.08 0 0.0586106
2.1875 0 0 0 0 0.02 0.0365436
2.3125 0 0 0.02 0 0 0.0220117
2.4375 0 0 0 0 0.02 0.0128131
2.5625 0 0 0 0 0.04 0.00721008
2.6875 0 0 0 0 0 0.003923
2.8125 0 0 0 0 0 0.00206436
2.9375 0 0 0 0 0 0.0010508
EOD
$k << EOD
0.5 0.310757
1 0.170013
2 0.0810794
3 0.0431245
10 0.0235894
EOD
set multiplot layout 1,2
set title 'Speed histograms, 100 disks x 4 runs'
set xlabel 'v / V_0'
set ylabel 'f(v) / V_0^{-1}'
set key top right
plot for [k=2:6] $h u 1:k w histeps lw 2 t sprintf('C/N = %s', word('0.5 1 2 3 10', k-1)), 2*x*exp(-x*x) w l lw 3 dt 2 lc 'black' t 'Maxwell'
set title 'Kolmogorov-Smirnov distance to Maxwell'
set xlabel 'collisions per disk C/N'
set ylabel 'KS distance D (dimensionless)'
set logscale xy
set key top right
plot $k w lp pt 7 lw 2 t 'measured', 0.0435 w l dt 2 lc 'black' t 'noise of 400 exact Maxwell samples'
unset multiplot
