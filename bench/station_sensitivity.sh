#!/bin/sh
# The reference study's Table 6 sensitivity study with chutelab's DEM, at V3-41 of the LIGGGHTS rig (3 m/s,
# 41 t/h, as the reference study): contact law, time step, shear modulus, particle size. Prints the mean plate
# normal force, its standard error and the fluctuation (sd of the 3 ms samples in the steady window).
set -eu
B=${B:-build/app/chutelab}
OUT=${OUT:-/tmp/chutelab-bench-sensitivity}
mkdir -p "$OUT"
run() {
  name=$1
  shift
  $B simulate --dataset datasets/liggghts-rig --condition V3-41 --no-cache --out "$OUT/$name" "$@" >"$OUT/$name.txt" 2>/dev/null
  start=$(awk -F' = ' '$1=="window_start_s"{print $2}' "$OUT/$name/run.txt")
  awk -F, -v s="$start" -v n="$name" -v args="$*" 'NR>1 && $1>s {k++; x+=$2; xx+=$2*$2}
    END {m=x/k; printf "%-26s %-48s R_n %7.3f N  sd of 3 ms samples %6.3f N\n", n, args, m, sqrt(xx/k-m*m)}' \
    "$OUT/$name/timeseries.csv"
  grep -E "normal force|impact point|wall \(" "$OUT/$name.txt" | sed 's/^/    /'
}
run base-13.6mm-E          --diameter-mm 13.6 --shear-modulus-scale 1
run lsd                    --diameter-mm 13.6 --shear-modulus-scale 1 --contact lsd
run dt-1-20                --diameter-mm 13.6 --shear-modulus-scale 1 --dt-fraction 0.05
run G-x10                  --diameter-mm 13.6 --shear-modulus-scale 10
run G-div10                --diameter-mm 13.6 --shear-modulus-scale 0.1
run d-9mm                  --diameter-mm 9 --shear-modulus-scale 1
