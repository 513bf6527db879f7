"""`hodr fit2d` against primitive (Michael Fogleman's Go program), for BENCHMARKS.md.

For each target image, shape kind and count N: primitive's wall time and RMSE with N
shapes, `hodr fit2d`'s with N shapes, and hodr's RMSE when it may place shapes for as
long as primitive took (`--time`). Every image is first scaled to 128×128 (Lanczos) and
both programs fit and write at that size; the RMSE is over RGB in [0, 1] against that
128×128 target, computed here for both outputs alike. primitive runs with its alpha 128
(hodr's α = 0.5) and two workers (both cores); kinds map to its modes triangle 1,
rect 2 (axis-aligned, as hodr's), ellipse 3 (axis-aligned; hodr's ellipses rotate).

Set-up (not part of CI; primitive is not a dependency of hodr; Debian packages its Go
dependencies, so it builds without a module proxy):

    apt-get install golang-go golang-github-fogleman-gg-dev golang-github-nfnt-resize-dev \
        golang-golang-x-image-dev golang-github-golang-freetype-dev
    # a clone of github.com/fogleman/primitive under $GOPATH/src/github.com/fogleman/
    GOPATH=/tmp/gopath:/usr/share/gocode GO111MODULE=off go build -o /tmp/primitive .
    python3 -m venv /tmp/venv && /tmp/venv/bin/pip install pillow numpy
    cargo build --release -p hodr-host
    cargo run --release -p hodr-raster --example landscape -- /tmp/landscape.png 128
    /tmp/venv/bin/python host/benches/primitive_fit.py --primitive /tmp/primitive \
        /tmp/landscape.png $PRIMITIVE_CLONE/examples/*.png

Prints one Markdown table row per (image, kind, N).
"""

import argparse
import pathlib
import re
import subprocess
import tempfile
import time

import numpy as np
from PIL import Image

SIZE = 128
MODES = {"triangle": 1, "rect": 2, "ellipse": 3}


def rgb(path):
    """The image at `path` as float RGB in [0, 1]."""
    return np.asarray(Image.open(path).convert("RGB"), dtype=np.float64) / 255.0


def rmse(a, b):
    x, y = rgb(a), rgb(b)
    assert x.shape == y.shape, (a, x.shape, b, y.shape)
    return float(np.sqrt(((x - y) ** 2).mean()))


def timed(command):
    """Wall time of `command`, which must succeed."""
    start = time.perf_counter()
    subprocess.run(command, check=True, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    return time.perf_counter() - start


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("images", nargs="+", type=pathlib.Path)
    parser.add_argument("--primitive", required=True, help="the primitive binary")
    parser.add_argument("--hodr", default="target/release/hodr", help="the hodr binary")
    parser.add_argument("--kinds", default="triangle,rect,ellipse")
    parser.add_argument("--shapes", default="16,64")
    args = parser.parse_args()
    work = pathlib.Path(tempfile.mkdtemp(prefix="primitive-fit-"))
    print("| image | kind | N | primitive time | primitive RMSE | hodr time | hodr RMSE "
          "| hodr at primitive's time: shapes, RMSE |")
    print("|---|---|---|---|---|---|---|---|")
    for image in args.images:
        target = work / f"{image.stem}.png"
        Image.open(image).convert("RGB").resize((SIZE, SIZE), Image.LANCZOS).save(target)
        for kind in args.kinds.split(","):
            for n in args.shapes.split(","):
                ours, theirs, timed_out = (work / f"{image.stem}-{kind}-{n}-{w}.png"
                                           for w in ("hodr", "primitive", "time"))
                t_p = timed([args.primitive, "-i", target, "-o", theirs, "-n", n,
                             "-m", str(MODES[kind]), "-r", str(SIZE), "-s", str(SIZE),
                             "-j", "2", "-a", "128"])
                t_h = timed([args.hodr, "fit2d", "--target", target, "--shapes", n,
                             "--kind", kind, "--out", ours, "--seed", "0"])
                log = subprocess.run(
                    [args.hodr, "fit2d", "--target", target, "--shapes", "100000",
                     "--kind", kind, "--out", timed_out, "--seed", "0",
                     "--time", f"{t_p:.3f}"],
                    check=True, capture_output=True, text=True).stdout
                placed = re.search(r"(\d+) shapes, RMSE", log).group(1)
                print(f"| {image.stem} | {kind} | {n} | {t_p:.2f} s | {rmse(target, theirs):.4f} "
                      f"| {t_h:.2f} s | {rmse(target, ours):.4f} "
                      f"| {placed}, {rmse(target, timed_out):.4f} |", flush=True)


if __name__ == "__main__":
    main()
