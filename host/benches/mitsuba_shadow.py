"""Mitsuba 3 on hodr's SHADOW scene (docs/design.md §3), for the yardstick rows of BENCHMARKS.md.

Renders SHADOW at θ* (sphere centre (-0.55, -0.55, 3)) at 128×128 with Mitsuba's
`path` integrator (max depth 3, box filter) and reports, per spp in 4, 16, 64: the
fastest and median wall time of a frame, samples per second from the fastest, and the
RMSE over all renders against a 1024-spp independent-sampler reference (linear RGB),
as `cargo bench -p hodr-host --bench render_rmse` does for hodr.

Set-up (not part of CI; Mitsuba is not a dependency of hodr):

    python3 -m venv /tmp/mi && /tmp/mi/bin/pip install mitsuba numpy
    # drjit's LLVM backend needs libLLVM >= 16 (Debian 12: apt-get install libllvm19)
    export DRJIT_LIBLLVM_PATH=/usr/lib/x86_64-linux-gnu/libLLVM-19.so
    /tmp/mi/bin/python host/benches/mitsuba_shadow.py --threads 2 --sampler independent

`--reference-png F` also writes the reference as 8-bit sRGB PNG (needs pillow), to
compare with `hodr render --task shadow --spp 1024 --out G.png`.
"""

import argparse
import time

import drjit as dr
import mitsuba as mi
import numpy as np

SIZE = 128
REFERENCE_SPP = 1024
MIN_RENDERS = 5
MIN_SECONDS = 2.0


def scene_dict(sampler):
    t = mi.ScalarTransform4f
    grey = {"type": "diffuse", "reflectance": {"type": "rgb", "value": 0.5}}
    return {
        "type": "scene",
        "integrator": {"type": "path", "max_depth": 3},
        "sensor": {
            "type": "perspective",
            "fov": 80,
            "to_world": t().look_at(origin=[0, 0, 2], target=[0, 0, 0], up=[0, 1, 0]),
            "sampler": {"type": sampler},
            "film": {
                "type": "hdrfilm",
                "width": SIZE,
                "height": SIZE,
                "rfilter": {"type": "box"},
                "pixel_format": "rgb",
            },
        },
        # Mitsuba's rectangle is [-1, 1]² in z = 0 facing +z.
        "ground": {"type": "rectangle", "to_world": t().scale([2, 2, 1]), "bsdf": grey},
        "sphere": {"type": "sphere", "center": [-0.55, -0.55, 3.0], "radius": 0.5, "bsdf": grey},
        "light": {
            "type": "rectangle",
            "to_world": t().translate([0, 0, 12])
            @ t().rotate([1, 0, 0], 180)
            @ t().scale([0.5, 0.5, 1]),
            "emitter": {"type": "area", "radiance": {"type": "rgb", "value": 400}},
        },
    }


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("--variant", default="llvm_ad_rgb")
    parser.add_argument("--threads", type=int, default=2)
    parser.add_argument("--sampler", default="independent")
    parser.add_argument("--reference-png")
    args = parser.parse_args()
    mi.set_variant(args.variant)
    dr.set_thread_count(args.threads)

    def render(scene, spp, seed):
        return np.array(mi.render(scene, spp=spp, seed=seed))

    reference = render(mi.load_dict(scene_dict("independent")), REFERENCE_SPP, 999)
    print(f"reference mean {reference.mean():.4f}, centre {reference[63:65, 63:65].mean():.4f}")
    if args.reference_png:
        from PIL import Image

        x = np.clip(reference, 0.0, 1.0)
        srgb = np.where(x <= 0.0031308, 12.92 * x, 1.055 * x ** (1 / 2.4) - 0.055)
        Image.fromarray(np.round(srgb * 255).astype(np.uint8)).save(args.reference_png)

    scene = mi.load_dict(scene_dict(args.sampler))
    print("| sampler | threads | spp | fastest ms | median ms | M samples/s | RMSE |")
    print("|---|---|---|---|---|---|---|")
    for spp in (4, 16, 64):
        render(scene, spp, 0)  # compiles the kernel for this spp
        times, errors, seed = [], [], 1
        end = time.perf_counter() + MIN_SECONDS
        while time.perf_counter() < end or len(times) < MIN_RENDERS:
            start = time.perf_counter()
            image = render(scene, spp, seed)
            times.append(time.perf_counter() - start)
            errors.append(np.sqrt(((image - reference) ** 2).mean()))
            seed += 1
        fastest = min(times)
        print(
            f"| {args.sampler} | {args.threads} | {spp} | {fastest * 1e3:.2f} | "
            f"{np.median(times) * 1e3:.2f} | {SIZE * SIZE * spp / fastest / 1e6:.2f} | "
            f"{np.mean(errors):.4f} |"
        )


if __name__ == "__main__":
    main()
