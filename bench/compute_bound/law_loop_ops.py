#!/usr/bin/env python3
"""The vectorised contact-law loop of a compiled dem_bench, counted instruction by instruction: the
loop (a backward branch) with the most packed-double operations inside the run_chunk of the bench's
model, its operations by mnemonic, and the floating-point operations per contact (each packed op
covers as many contacts as its register holds doubles). Usage: law_loop_ops.py BINARY"""
import collections, re, subprocess, sys

binary = sys.argv[1]
model = "ContactModel<chutelab::dem::HertzMindlin, chutelab::dem::CoulombHistorySpring, " \
        "chutelab::dem::RollingConstantTorque, chutelab::dem::NoCohesion>"
nm = subprocess.run(["nm", "-C", "-S", binary], capture_output=True, text=True, check=True).stdout
start = size = None
for line in nm.splitlines():
    if "run_chunk<chutelab::dem::" + model + " >(chutelab::dem::pair_loop::ContactChunk&" in line:
        start, size = int(line.split()[0], 16), int(line.split()[1], 16)
if start is None:
    sys.exit("no ContactChunk run_chunk of the bench's model in " + binary)
asm = subprocess.run(["objdump", "-d", "--no-show-raw-insn", f"--start-address={start}",
                      f"--stop-address={start + size}", binary], capture_output=True, text=True, check=True).stdout
ins = []
for line in asm.splitlines():
    m = re.match(r"\s+([0-9a-f]+):\s+(\S+)\s*(.*)", line)
    if m:
        ins.append((int(m.group(1), 16), m.group(2), m.group(3)))
packed = lambda op, arg: re.match(r"v.*pd$", op) and re.search(r"[xyz]mm", arg)
best = None
for addr, op, arg in ins:
    m = re.match(r"([0-9a-f]+)", arg) if op.startswith("j") else None
    if m and int(m.group(1), 16) < addr:
        lo = int(m.group(1), 16)
        body = [x for x in ins if lo <= x[0] <= addr]
        n = sum(1 for x in body if packed(x[1], x[2]))
        # the innermost loop with the most packed operations per instruction
        key = (n / len(body), n)
        if n and (best is None or key > best[0]):
            best = (key, lo, addr, body)
_, lo, hi, body = best
lanes = 8 if any("zmm" in x[2] for x in body) else 4 if any("ymm" in x[2] for x in body) else 2
count = collections.Counter(x[1] for x in body)
print(f"law loop {lo:#x}-{hi:#x}: {len(body)} instructions, {lanes} contacts per iteration")
for op, n in count.most_common():
    print(f"  {n:4d} {op}")
add = sum(n for op, n in count.items() if re.match(r"v(add|sub)pd$", op))
mul = count["vmulpd"]
fma = sum(n for op, n in count.items() if op.startswith("vfm") or op.startswith("vfnm"))
div, sqrt = count["vdivpd"], count["vsqrtpd"]
print(f"per contact: {mul} mul, {add} add/sub, {fma} fma, {div} div, {sqrt} sqrt; "
      f"{mul + add + 2 * fma + div + sqrt} flops (div and sqrt counted as one each)")
