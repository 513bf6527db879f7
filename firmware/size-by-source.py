#!/usr/bin/env python3
"""Attributes the .text bytes of a firmware ELF to crates and source files.

Usage: size-by-source.py LLVM_OBJDUMP ELF [TOP_FILES]

Symbol sizes (llvm-nm --size-sort) hide inlined code: after LTO most of hodr-core is
inlined into a few large functions. This script instead charges every instruction to
the source line the debug line table gives for it (`llvm-objdump -d -l`), so inlined
code counts towards the crate it came from. Code from `core` inlined into hodr-core
(slice indexing, iterators, arithmetic) shows as `core`, not as hodr-core.
"""

import collections
import re
import subprocess
import sys

LOCAL = {"/core/src/": "hodr-core", "/embedded/src/": "hodr-embedded", "/firmware/src/": "hodr-firmware"}


def origin(path):
    """(crate, file) for a source path from the line table."""
    # The standard library's and registry crates' paths first: `library/core/src/` would
    # otherwise pass for hodr-core's `core/src/`.
    m = re.match(r"/rustc/[0-9a-f]+/library/(.+?)/src/(.*)", path)
    if m:
        return m.group(1).split("/")[-1], m.group(2)
    m = re.search(r"/registry/src/[^/]+/([^/]+)/(.*)", path)
    if m:
        return m.group(1), m.group(2)
    for marker, crate in LOCAL.items():
        if marker in path:
            return crate, path.split(marker, 1)[1]
    return "unknown", path


def main():
    objdump, elf = sys.argv[1], sys.argv[2]
    top = int(sys.argv[3]) if len(sys.argv) > 3 else 15
    listing = subprocess.run(
        [objdump, "-d", "-l", "--no-show-raw-insn", "-j", ".text", elf],
        capture_output=True, text=True, check=True,
    ).stdout
    source = ("unknown", "(no line information)")
    addresses = []
    for line in listing.splitlines():
        m = re.match(r"^; (/\S+):\d+", line)
        if m:
            source = origin(m.group(1))
            continue
        m = re.match(r"^\s*([0-9a-f]+):\s", line)
        if m:
            addresses.append((int(m.group(1), 16), source))
    by_file = collections.Counter()
    # An instruction's size is the gap to the next one; the last is left out.
    for (address, src), (following, _) in zip(addresses, addresses[1:]):
        by_file[src] += following - address
    by_crate = collections.Counter()
    for (crate, _), size in by_file.items():
        by_crate[crate] += size
    print("| crate | bytes |\n|---|---|")
    for crate, size in by_crate.most_common():
        print(f"| {crate} | {size} |")
    print("\n| crate | file | bytes |\n|---|---|---|")
    for (crate, path), size in by_file.most_common(top):
        print(f"| {crate} | {path} | {size} |")


if __name__ == "__main__":
    main()
