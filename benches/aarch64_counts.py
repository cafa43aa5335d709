#!/usr/bin/env python3
"""Instruction counts of each kernel on aarch64, NEON lanes against the
portable code (BENCHMARKS.md, "aarch64 (NEON)").

Builds the `kernel_asm` bench binary of the benches package (release) for
aarch64-unknown-linux-gnu twice, with the NEON lanes and with
`--cfg rayhit_portable`, each in its own target directory. For each kernel
function it counts the instructions of its body in `objdump -d` (every
path; out-of-line helpers, the kernels' rare slow paths, not included),
and the instructions executed by the binary's one call, helpers included,
from qemu's trace of every instruction (`-singlestep -d exec,nochain`).
Prints a Markdown table. Needs what `.ci/aarch64` installs; run from the
repository root: `python3 benches/aarch64_counts.py`.
"""

import json
import os
import re
import subprocess
import tempfile

TARGET = "aarch64-unknown-linux-gnu"
SYSROOT = "/usr/aarch64-linux-gnu"
KERNELS = [
    ("box_prepared", "`Aabb::clip`, `PreparedRay` (4 lanes)"),
    ("triangle_prepared", "`Triangle::hit`, `PreparedRay` (4 lanes)"),
    ("box_batch_8", "`AabbBatch::clip`, 8 boxes"),
    ("box_batch_16", "`AabbBatch::clip`, 16 boxes"),
    ("triangle_batch_8", "`TriangleBatch::hit`, 8 triangles"),
    ("triangle_batch_16", "`TriangleBatch::hit`, 16 triangles"),
    ("quantized_children", "`QuantizedChildren::clip` (8 children)"),
]
# Where qemu-user loads a position-independent aarch64 executable.
LOAD_BASE = 0x55_0000_0000


def build(name, rustflags):
    """The bench binary built into target/aarch64-<name>; its path."""
    env = dict(os.environ)
    env["CARGO_TARGET_DIR"] = f"target/aarch64-{name}"
    env["CARGO_TARGET_AARCH64_UNKNOWN_LINUX_GNU_LINKER"] = "aarch64-linux-gnu-gcc"
    env["RUSTFLAGS"] = rustflags
    out = subprocess.run(
        ["cargo", "bench", "-q", "--no-run", "-p", "rayhit-benches",
         "--bench", "kernel_asm", "--target", TARGET,
         "--message-format=json"],
        check=True, env=env, capture_output=True, text=True).stdout
    for line in out.splitlines():
        msg = json.loads(line)
        if msg.get("reason") == "compiler-artifact" and msg.get("executable") \
                and msg["target"]["name"] == "kernel_asm":
            return msg["executable"]
    raise SystemExit("cargo built no kernel_asm binary")


def symbols(binary):
    """Function name -> (start, size), for the binary's own functions."""
    out = subprocess.run(["aarch64-linux-gnu-nm", "-S", "-C", binary],
                         check=True, capture_output=True, text=True).stdout
    found = {}
    for line in out.splitlines():
        m = re.match(r"([0-9a-f]+) ([0-9a-f]+) [tT] kernel_asm::(\w+)$", line)
        if m:
            found[m.group(3)] = (int(m.group(1), 16), int(m.group(2), 16))
    return found


def static_counts(binary):
    """Function name -> instructions in its body."""
    out = subprocess.run(
        ["aarch64-linux-gnu-objdump", "-d", "-C", "--no-show-raw-insn", binary],
        check=True, capture_output=True, text=True).stdout
    counts, name = {}, None
    for line in out.splitlines():
        m = re.match(r"[0-9a-f]+ <kernel_asm::(\w+)>:$", line)
        if m:
            name = m.group(1)
            counts[name] = 0
        elif re.match(r"[0-9a-f]+ <", line):
            name = None
        elif name and re.match(r"\s+[0-9a-f]+:\t", line):
            counts[name] += 1
    return counts


def executed_counts(binary, syms):
    """Function name -> instructions executed from its entry until control
    is back in `main`, for the one call `main` makes."""
    with tempfile.NamedTemporaryFile(suffix=".log") as log:
        subprocess.run(
            ["qemu-aarch64", "-L", SYSROOT, "-singlestep", "-d", "exec,nochain",
             "-D", log.name, binary],
            check=True, capture_output=True)
        trace = open(log.name).read()
    pcs = [int(m, 16) - LOAD_BASE
           for m in re.findall(r"^Trace \d+: \S+ \[[0-9a-f]+/([0-9a-f]+)/", trace, re.M)]
    main_start, main_size = syms["main"]
    entries = {syms[k][0]: k for k, _ in KERNELS}
    counts, current = {}, None
    for pc in pcs:
        if current is None:
            current = entries.get(pc)
            if current is not None:
                counts[current] = 1
        elif main_start <= pc < main_start + main_size:
            current = None
        else:
            counts[current] += 1
    return counts


def main():
    rows = {}
    for name, flags in [("neon", ""), ("portable", "--cfg rayhit_portable")]:
        binary = build(name, flags)
        syms = symbols(binary)
        rows[name] = (static_counts(binary), executed_counts(binary, syms))
    print("| kernel | body, NEON | body, portable | NEON / portable "
          "| executed, NEON | executed, portable | NEON / portable |")
    print("| --- | ---: | ---: | ---: | ---: | ---: | ---: |")
    for key, label in KERNELS:
        (sn, en), (sp, ep) = rows["neon"], rows["portable"]
        s_n, s_p, e_n, e_p = sn[key], sp[key], en[key], ep[key]
        print(f"| {label} | {s_n} | {s_p} | {s_n / s_p:.2f} "
              f"| {e_n} | {e_p} | {e_n / e_p:.2f} |")


if __name__ == "__main__":
    main()
