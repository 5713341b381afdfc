#!/usr/bin/python3
"""The DEM's libraries contain no fused multiply-add instruction.

    no_fused_multiply_add.py LIBRARY.a ...      exit 1 naming each function that holds one

A fused multiply-add rounds once where the source rounds twice, so a DEM step compiled with one gives other last
bits, and a run other numbers, than the portable build (and than the stored golden numbers). The build asks for
none (-ffp-contract=off, and -mno-fma -mno-avx512f with DEMCAL_NATIVE, AVX-512 for the parallel bond's file
alone), but GCC's vectoriser has emitted vfmaddsub under -ffp-contract=off before (AVX-512's own fused forms in
the Hertz and JKR loops when they were tried with it); this reads the machine code itself (objdump, binutils).
"""
import re
import subprocess
import sys

# FMA3 and AVX-512 forms (vfmadd132sd, vfnmsub231pd, vfmaddsub213pd, ...) and AMD's FMA4 (vfmaddsd, ...).
FUSED = re.compile(r"\bvfn?m(add|sub)(sub|add)?(132|213|231)?[ps][sdh]\b")
FUNCTION = re.compile(r"^[0-9a-f]+ <(.+)>:$")


def fused_in(library):
    """(function, instruction) for every fused multiply-add in the library's machine code."""
    out = subprocess.run(["objdump", "-d", "--no-show-raw-insn", "-C", library], capture_output=True, text=True)
    if out.returncode != 0:
        sys.exit(f"no_fused_multiply_add: objdump could not read {library}: {out.stderr.strip()}")
    found, function = [], "?"
    for line in out.stdout.splitlines():
        m = FUNCTION.match(line)
        if m:
            function = m.group(1)
            continue
        f = FUSED.search(line)
        if f:
            found.append((function, f.group(0)))
    return found


def main(libraries):
    if not libraries:
        sys.exit("usage: no_fused_multiply_add.py LIBRARY.a ...")
    bad = 0
    for library in libraries:
        for function, instruction in fused_in(library):
            print(f"{library}: {function}: {instruction}")
            bad += 1
    if bad:
        print(f"{bad} fused multiply-add instruction(s): the DEM's numbers would depend on the build's instruction set")
        return 1
    print(f"no fused multiply-add in {len(libraries)} librar{'y' if len(libraries) == 1 else 'ies'}")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
