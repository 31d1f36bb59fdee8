#!/usr/bin/env python3
"""Where a `perf record` profile's time goes, through inlined functions.

raylab's lane code is `#[inline(always)]` all the way down (it must compile inside the dispatched
AVX2 function), so `perf report` puts ~95% of a path-traced render in one symbol,
`renderer::simd::avx2::run_avx2`, and `perf report --sort srcline` names only the innermost
intrinsic (`avx.rs:283`) and takes minutes. This script asks the debug info (`addr2line -i`,
once for every distinct sampled address) for each sample's chain of inlined calls, then prints

  * the inclusive share of each function (a sample counts once for every function on its chain),
  * the innermost function and line of the samples,
  * with --lines FN: the share of each line of FN, the calls inlined there included (which step
    of `PathGroup::step` costs what),
  * with --chains FN: the callers of FN, four frames deep.

    perf record -o /tmp/p.data target/release/raylab render assets/reference/spheres.xml \\
        --integrator path --sampler sobol --spp 64 --output /tmp/s.exr
    scripts/perf_inlined.py /tmp/p.data target/release/raylab --lines step

Release builds keep their debug info (the workspace's `[profile.release] debug`), so any release
binary works. Needs `perf` and binutils (`addr2line`, `nm`).
"""
import argparse
import collections
import re
import subprocess


def symbol_addresses(binary):
    """Each (mangled) symbol's address in the binary."""
    out = subprocess.run(["nm", binary], capture_output=True, text=True, check=True).stdout
    table = {}
    for line in out.splitlines():
        parts = line.split()
        if len(parts) == 3:
            table[parts[2]] = int(parts[0], 16)
    return table


def sample_counts(perf_data, symbols):
    """Samples per address in the binary (as `nm` numbers it), and the total sample count."""
    out = subprocess.run(
        ["perf", "script", "-i", perf_data, "-F", "ip,sym,symoff,dso", "-G", "--no-demangle"],
        capture_output=True,
        text=True,
        check=True,
    ).stdout
    counts, total = collections.Counter(), 0
    for line in out.splitlines():
        line = line.strip()
        if not line:
            continue
        total += 1
        match = re.match(r"\S+ (\S+)\+0x([0-9a-f]+) \(", line)
        if match and match.group(1) in symbols:
            counts[symbols[match.group(1)] + int(match.group(2), 16)] += 1
    return counts, total


def inline_chains(binary, addresses):
    """Per address, its chain of (function, location), innermost first (`addr2line -i`)."""
    out = subprocess.run(
        ["addr2line", "-a", "-i", "-f", "-C", "-e", binary] + [hex(a) for a in addresses],
        capture_output=True,
        text=True,
        check=True,
    ).stdout.splitlines()
    chains, current, i = {}, None, 0
    while i < len(out):
        if out[i].startswith("0x"):
            current = int(out[i], 16)
            chains[current] = []
            i += 1
            continue
        location = out[i + 1] if i + 1 < len(out) else "?"
        chains[current].append((short_name(out[i]), location.split("/")[-1].split(" ")[0]))
        i += 2
    return chains


def short_name(function):
    """The function's name without generic arguments and paths into std."""
    for _ in range(4):
        function = re.sub(r"<[^<>]*>", "", function)
    return function[:110]


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("perf_data", help="the perf.data file")
    parser.add_argument("binary", help="the binary that was profiled")
    parser.add_argument("--top", type=int, default=40, help="functions to list (default 40)")
    parser.add_argument("--lines", metavar="FN", help="the share of each line of function FN")
    parser.add_argument("--chains", metavar="FN", help="the callers of function FN")
    args = parser.parse_args()

    counts, total = sample_counts(args.perf_data, symbol_addresses(args.binary))
    chains = inline_chains(args.binary, sorted(counts))
    share = lambda n: f"{100 * n / max(total, 1):6.2f}%"
    print(f"{total} samples, {sum(counts.values())} in {args.binary}")

    inclusive, innermost = collections.Counter(), collections.Counter()
    for address, n in counts.items():
        chain = chains.get(address, [])
        for function in {f for f, _ in chain}:
            inclusive[function] += n
        if chain:
            innermost[f"{chain[0][0]}  @{chain[0][1]}"] += n
    print("\ninclusive (the calls inlined into a function counted with it):")
    for function, n in inclusive.most_common(args.top):
        print(f"{share(n)}  {function}")
    print("\ninnermost function and line:")
    for where, n in innermost.most_common(20):
        print(f"{share(n)}  {where}")

    if args.lines:
        lines = collections.Counter()
        for address, n in counts.items():
            for function, location in chains.get(address, []):
                if function == args.lines:
                    lines[location] += n
                    break
        print(f"\nlines of {args.lines} (with what is inlined at each):")
        for location, n in lines.most_common(args.top):
            print(f"{share(n)}  {location}")

    if args.chains:
        callers = collections.Counter()
        for address, n in counts.items():
            chain = chains.get(address, [])
            for k, (function, _) in enumerate(chain):
                if function == args.chains:
                    callers[" < ".join(f"{f}@{l}" for f, l in chain[k : k + 4])] += n
                    break
        print(f"\ncallers of {args.chains}:")
        for path, n in callers.most_common(15):
            print(f"{share(n)}  {path}")


if __name__ == "__main__":
    main()
