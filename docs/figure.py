"""Builds docs/li-tian.png from seasynth's TIFF outputs (needs numpy and pillow).

    cargo build --release && python3 docs/figure.py
"""
import subprocess

import numpy as np
from PIL import Image

BIN = "target/release/seasynth"
PANELS = [
    ["--preset", "li-tian-perlin"],
    ["--preset", "li-tian-fft"],
    ["--preset", "li-tian"],
    ["--preset", "li-tian", "--set", "blend.beta=matched"],
]
SIDE = 256
GAP = 4

tiles = []
for i, args in enumerate(PANELS):
    out = f"out/figure-{i}.tif"
    subprocess.run([BIN, "generate", *args, "-o", out, "-q"], check=True)
    h = np.array(Image.open(out), dtype=np.float32)
    lo, hi = h.min(), h.max()
    g = ((h - lo) / (hi - lo) * 255).round().astype(np.uint8)
    tiles.append(Image.fromarray(g).resize((SIDE, SIDE), Image.LANCZOS))

sheet = Image.new("L", (len(tiles) * SIDE + (len(tiles) - 1) * GAP, SIDE), 255)
for i, t in enumerate(tiles):
    sheet.paste(t, (i * (SIDE + GAP), 0))
sheet.save("docs/li-tian.png", optimize=True)
