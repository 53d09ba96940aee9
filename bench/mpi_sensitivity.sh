#!/usr/bin/env bash
# `chutelab sensitivity` (quick, the full default study) once as one process and once under
# `mpirun -n 2`, niced, with the load average sampled every 30 s; compares sensitivity.csv (and
# .md/.html) byte for byte. Usage: bench/mpi_sensitivity.sh [chutelab binary] [output folder]
set -euo pipefail
bin=${1:-build/app/chutelab}
out=${2:-/tmp/chutelab-mpi-sensitivity}
rm -rf "$out" && mkdir -p "$out"
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
sample() { while true; do echo "$(date -u +%T) $(cut -d' ' -f1-3 /proc/loadavg)"; sleep 30; done; }
sample >"$out/load.log" & sampler=$!
trap 'kill $sampler' EXIT
echo "serial start $(date -u +%T)" >>"$out/times.log"
/usr/bin/time -f "serial wall %e s user %U s" -a -o "$out/times.log" \
  nice "$bin" sensitivity --out "$out/serial" >"$out/serial.log" 2>&1
echo "mpi start $(date -u +%T)" >>"$out/times.log"
/usr/bin/time -f "mpirun -n 2 wall %e s user %U s" -a -o "$out/times.log" \
  nice mpirun -n 2 --oversubscribe "$bin" sensitivity --out "$out/mpi" >"$out/mpi.log" 2>&1
echo "end $(date -u +%T)" >>"$out/times.log"
for f in sensitivity.csv sensitivity.md sensitivity.html; do
  if cmp -s "$out/serial/$f" "$out/mpi/$f"; then echo "$f identical" >>"$out/times.log"; else echo "$f DIFFERS" >>"$out/times.log"; fi
done
cat "$out/times.log"
