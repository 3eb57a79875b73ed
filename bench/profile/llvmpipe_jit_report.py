#!/usr/bin/python3
"""The report of llvmpipe_jit.sh: from the disassembled JIT code and perf's sampled addresses, the
share of each JIT function, of llvmpipe's per-lane memory loops, and the hottest instructions.

usage: llvmpipe_jit_report.py JIT.asm SAMPLES.txt (one hexadecimal address a line: perf script -F ip)
"""
import bisect
import collections
import re
import sys

INSTRUCTION = re.compile(r"\s*([0-9a-f]+):\s+(?:[0-9a-f]{2} )+\s*(.*)")
# llvmpipe (Mesa 22.3) loads and stores a storage buffer one lane at a time: a masked broadcast of a
# dword into the lane, or a scalar store, indexed by the lane's offset
LANE_MEMORY = re.compile(r"vpbroadcastd \(%r\w+,%r\w+,4\),%[xy]mm\d+\{%k|mov\s+%e\w+,\(%r\w+,%r\w+,4\)")


def read_code(path):
    code = {}
    for line in open(path):
        m = INSTRUCTION.match(line)
        if m:
            code[int(m.group(1), 16)] = m.group(2).strip()
    return code


def main():
    if len(sys.argv) != 3:
        sys.exit(__doc__.split("\n\n")[1])
    code = read_code(sys.argv[1])
    addresses = sorted(code)
    starts = sorted(a for a, text in code.items() if re.match(r"push\s+%rbp$", text))
    lane_memory = sorted(a for a, text in code.items() if LANE_MEMORY.search(text))
    samples = collections.Counter(int(line.split()[0], 16) for line in open(sys.argv[2]) if line.strip())
    total = sum(samples.values())
    if not total or not addresses:
        sys.exit("llvmpipe_jit_report.py: no samples or no code")

    in_jit = {a: n for a, n in samples.items() if addresses[0] <= a <= addresses[-1] + 16}
    print(f"{total} samples, {100 * sum(in_jit.values()) / total:.1f} % in JIT code")
    print("\nJIT functions (from each 'push %rbp'; a fetch function llvmpipe calls counts with the one before it):")
    functions = collections.Counter()
    for a, n in in_jit.items():
        i = bisect.bisect_right(starts, a) - 1
        functions[starts[i] if i >= 0 else addresses[0]] += n
    for start, n in sorted(functions.items(), key=lambda kv: -kv[1]):
        if n / total >= 0.01:
            print(f"  {start:#x}  {100 * n / total:5.1f} %")

    # a sample lands on the instruction after the one that stalled: count those within a few
    # instructions of a per-lane load or store as the loop's
    near = 0
    for a, n in in_jit.items():
        i = bisect.bisect_right(lane_memory, a)
        if (i > 0 and a - lane_memory[i - 1] < 48) or (i < len(lane_memory) and lane_memory[i] - a < 48):
            near += n
    print(f"\nwithin 48 bytes of a per-lane storage load or store: {100 * near / total:.1f} % of the samples "
          "(a lower bound of the loops' share: a loop's lane bookkeeping lies further off)")

    print("\nhottest instructions (the sample lands after the one that waited):")
    for a, n in sorted(in_jit.items(), key=lambda kv: -kv[1])[:12]:
        i = bisect.bisect_left(addresses, a)
        print(f"  {100 * n / total:5.1f} %  {a:#x}")
        for b in addresses[max(0, i - 4):i + 1]:
            print(f"      {b:#x}  {code[b]}")


if __name__ == "__main__":
    main()
