"""`seasynth.generate` from Python beside the same work through the Rust library
(`examples/synthesis_time.rs`), in turn, at each size: the default hybrid sea, median of
R runs each, the ratio per pair of runs.

    cargo build --release --example synthesis_time
    python python/examples/overhead.py [SIZES] [R] [PAIRS] [keep]   # e.g. 1024,4096 15 5

`keep`: both keep freed memory for reuse (`seasynth.keep_freed_memory()`); without it
both return it to the system, glibc's default.
"""

import pathlib
import statistics
import subprocess
import sys
import time

import seasynth

REPO = pathlib.Path(__file__).resolve().parents[2]
RUST = REPO / "target" / "release" / "examples" / "synthesis_time"


def python_ms(n: int, runs: int) -> float:
    p = seasynth.Params(size=n)
    times = []
    for _ in range(runs):
        t = time.perf_counter()
        f = seasynth.generate(p)
        times.append((time.perf_counter() - t) * 1e3)
        del f
    return statistics.median(times)


KEEP = len(sys.argv) > 4 and sys.argv[4] == "keep"


def rust_ms(n: int, runs: int) -> float:
    args = [str(RUST), str(n), str(runs)] + (["keep"] if KEEP else [])
    out = subprocess.run(args, capture_output=True, text=True, check=True)
    return float(out.stdout.strip())


def main() -> None:
    sizes = [int(s) for s in (sys.argv[1] if len(sys.argv) > 1 else "1024,4096").split(",")]
    runs = int(sys.argv[2]) if len(sys.argv) > 2 else 15
    pairs = int(sys.argv[3]) if len(sys.argv) > 3 else 5
    if KEEP:
        seasynth.keep_freed_memory()
    print("| grid | Python `generate` (ms) | Rust `synthesize_checked` (ms) | Python ÷ Rust (median of pairs) |")
    print("|---|---|---|---|")
    for n in sizes:
        py, rs, ratio = [], [], []
        for _ in range(pairs):
            r = rust_ms(n, runs)
            p = python_ms(n, runs)
            rs.append(r)
            py.append(p)
            ratio.append(p / r)
        print(f"| {n}² | {statistics.median(py):.1f} | {statistics.median(rs):.1f} | "
              f"{statistics.median(ratio):.3f} ({min(ratio):.3f}–{max(ratio):.3f}) |")


if __name__ == "__main__":
    main()
