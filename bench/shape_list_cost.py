#!/usr/bin/env python3
"""Compile time and binary size of one scene built with two shape lists.

Compiles tests/shape_list/spheres_and_planes.cpp twice with the same
compiler and flags: with ShapeList<SphereT, PlaneT> and with AllShapes
(-DSPOOK_ALL_SHAPES), then prints wall-clock compile time, stripped binary
size and the number of collider functions instantiated (nm).

    python3 bench/shape_list_cost.py [--cxx g++] [--flags "-O2"]
"""
import argparse
import shutil
import subprocess
import tempfile
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
SOURCE = ROOT / "tests" / "shape_list" / "spheres_and_planes.cpp"


def build(cxx, flags, defines, out):
    command = [cxx, "-std=c++20", *flags.split(), *defines, "-I", str(ROOT / "include"),
               "-isystem", "/usr/include/eigen3", str(SOURCE), "-o", str(out), "-lccd"]
    start = time.perf_counter()
    subprocess.run(command, check=True)
    seconds = time.perf_counter() - start
    subprocess.run(["strip", str(out)], check=True) if shutil.which("strip") else None
    return seconds


def colliders(binary_unstripped):
    text = subprocess.run(["nm", "-C", str(binary_unstripped)], capture_output=True, text=True).stdout
    return len({line.split(" ", 2)[-1] for line in text.splitlines() if "Collider<" in line and "::collide(" in line})


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("--cxx", default="g++")
    parser.add_argument("--flags", default="-O2")
    args = parser.parse_args()
    rows = []
    with tempfile.TemporaryDirectory() as tmp:
        for name, defines in (("ShapeList<SphereT, PlaneT>", []), ("AllShapes", ["-DSPOOK_ALL_SHAPES"])):
            symbols = Path(tmp) / "symbols"
            subprocess.run([args.cxx, "-std=c++20", *args.flags.split(), *defines, "-I", str(ROOT / "include"),
                            "-isystem", "/usr/include/eigen3", str(SOURCE), "-o", str(symbols), "-lccd"], check=True)
            count = colliders(symbols)
            binary = Path(tmp) / "binary"
            seconds = build(args.cxx, args.flags, defines, binary)
            rows.append((name, seconds, binary.stat().st_size, count))
    print(f"shape list cost ({args.cxx} {args.flags}, one scene, compile of one translation unit)\n")
    print("| shape list | compile time (s) | stripped binary (bytes) | collider functions |")
    print("|---|---|---|---|")
    for name, seconds, size, count in rows:
        print(f"| {name} | {seconds:.1f} | {size} | {count} |")


if __name__ == "__main__":
    main()
