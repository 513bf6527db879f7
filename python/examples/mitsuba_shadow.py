"""hodr with Mitsuba 3 as the black-box renderer, on the project's SHADOW scene
(docs/design.md §3): a sphere behind the camera, seen only through its shadow on the
ground, starts where its shadow shares no pixel with the target's.

hodr's Auto gets only the problem statement (x0, sigma0 = 0.5, the ground's bounds and
a budget) and renders through `mi.render` with the noise seed it hands out: the renders
it compares (an iteration's samples, θ and its trial step) share one seed, so they see
the same Monte Carlo noise. Beside it, Mitsuba's own
answer: Adam on its automatic-differentiation gradients with a projective integrator,
which differentiates the shadow's edge.

    pip install ./python mitsuba
    # Mitsuba's LLVM variants need libLLVM >= 16 (Debian 12: apt-get install libllvm19)
    export DRJIT_LIBLLVM_PATH=/usr/lib/x86_64-linux-gnu/libLLVM.so.19.1
    python python/examples/mitsuba_shadow.py [--seeds 5] [--size 128] [--budget 600]

Prints, per seed and method, the final parameter error and whether it fell to 1 % of
the start's (a 99 % reduction), the evaluations (renders) and the wall time.
"""

import argparse
import time

import numpy as np

import hodr

TRUTH = np.array([-0.55, -0.55])

# The projective integrator's discontinuity sampling, cut to what SHADOW has: no primary
# silhouettes (the sphere is never in view), the shadow's edge an indirect one; no
# guiding structure (rebuilt every iteration otherwise).
INTEGRATOR_OPTIONS = {"prb_projective": {"sppp": 0, "sppi": 16, "guiding": "none"}}


def scene_dict(mi, size, integrator):
    """SHADOW: ground [-2, 2]² at z = 0, sphere r = 0.5 at (x, y, 3), both albedo 0.5; a
    1×1 emitter at height 12 facing down, radiance 400; a pinhole camera at (0, 0, 2)
    looking down (up +y, 80° field of view, box filter); path depth at most 3."""
    t = mi.ScalarTransform4f
    grey = {"type": "diffuse", "reflectance": {"type": "rgb", "value": 0.5}}
    return {
        "type": "scene",
        "integrator": dict({"type": integrator, "max_depth": 3}, **INTEGRATOR_OPTIONS.get(integrator, {})),
        "sensor": {
            "type": "perspective",
            "fov": 80,
            "to_world": t().look_at(origin=[0, 0, 2], target=[0, 0, 0], up=[0, 1, 0]),
            "sampler": {"type": "independent"},
            "film": {"type": "hdrfilm", "width": size, "height": size, "sample_border": True,
                     "rfilter": {"type": "box"}, "pixel_format": "rgb"},
        },
        "ground": {"type": "rectangle", "to_world": t().scale([2, 2, 1]), "bsdf": grey},
        "sphere": {"type": "sphere", "to_world": t().translate([TRUTH[0], TRUTH[1], 3.0]).scale(0.5),
                   "bsdf": grey},
        "light": {
            "type": "rectangle",
            "to_world": t().translate([0, 0, 12]) @ t().rotate([1, 0, 0], 180) @ t().scale([0.5, 0.5, 1]),
            "emitter": {"type": "area", "radiance": {"type": "rgb", "value": 400}},
        },
    }


def start(seed):
    """The plateau start: (0.55, 0.55) + U[-0.1, 0.1]², fixed by the seed."""
    return np.array([0.55, 0.55]) + np.random.default_rng(seed).uniform(-0.1, 0.1, 2)


class Shadow:
    """The scene in Mitsuba, its target image and the image loss of a sphere position."""

    def __init__(self, mi, size, spp=4, target_spp=256, integrator="path"):
        self.mi, self.spp = mi, spp
        self.scene = mi.load_dict(scene_dict(mi, size, integrator))
        self.params = mi.traverse(self.scene)
        self.target = mi.render(self.scene, spp=target_spp, seed=2**31 - 1)
        self.renders = 0

    def place(self, x, y):
        mi = self.mi
        self.params["sphere.to_world"] = mi.Transform4f().translate(mi.Point3f(x, y, 3.0)).scale(0.5)
        self.params.update()

    def loss(self, theta, seed):
        """Mean squared image error at θ, rendered with noise seed `seed`."""
        self.place(float(theta[0]), float(theta[1]))
        self.renders += 1
        image = self.mi.render(self.scene, self.params, spp=self.spp, seed=int(seed) % 2**32)
        return float(np.mean((np.asarray(image) - np.asarray(self.target)) ** 2))


def run_hodr(shadow, seed, budget):
    shadow.renders = 0
    res = hodr.minimize(shadow.loss, start(seed), 0.5, bounds=(-2.0, 2.0), budget=budget,
                        seed=seed, noisy=True)
    return res.x, shadow.renders


def run_mitsuba_adam(mi, dr, shadow, seed, iterations, lr=0.02):
    """Adam on Mitsuba's AD gradients of the same loss (one render per iteration)."""
    opt = mi.ad.Adam(lr=lr)
    x0, y0 = (float(v) for v in start(seed))
    opt["xy"] = mi.Point2f(x0, y0)
    for i in range(iterations):
        xy = opt["xy"]
        shadow.params["sphere.to_world"] = mi.Transform4f().translate(
            mi.Point3f(xy.x, xy.y, 3.0)).scale(0.5)
        shadow.params.update()
        # An opaque seed keeps Dr.Jit from compiling a new kernel for every value.
        image = mi.render(shadow.scene, shadow.params, spp=shadow.spp, seed=dr.opaque(mi.UInt32, i))
        loss = dr.mean(dr.square(image - shadow.target), axis=None)
        dr.backward(loss)
        opt.step()
        opt["xy"] = dr.clip(opt["xy"], -2.0, 2.0)
    return np.array([opt["xy"].x[0], opt["xy"].y[0]]), iterations


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--seeds", type=int, default=5)
    parser.add_argument("--size", type=int, default=128)
    parser.add_argument("--budget", type=int, default=600, help="hodr's renders per seed")
    parser.add_argument("--iterations", type=int, default=300, help="Mitsuba Adam steps per seed")
    parser.add_argument("--threads", type=int, default=0, help="Dr.Jit threads (0: all)")
    parser.add_argument("--variant", default="llvm_ad_rgb",
                        help="Mitsuba variant; Mitsuba's own Adam needs an _ad_ one")
    args = parser.parse_args()

    import drjit as dr
    import mitsuba as mi

    mi.set_variant(args.variant)
    if args.threads:
        dr.set_thread_count(args.threads)
    shadow = Shadow(mi, args.size)
    projective = Shadow(mi, args.size, integrator="prb_projective")
    print("| method | seed | final parameter error | 99 % reduction | renders | wall time |")
    print("|---|---|---|---|---|---|")
    for seed in range(args.seeds):
        for name, run in (
            ("hodr Auto", lambda: run_hodr(shadow, seed, args.budget)),
            ("Mitsuba Adam (AD, prb_projective)",
             lambda: run_mitsuba_adam(mi, dr, projective, seed, args.iterations)),
        ):
            clock = time.perf_counter()
            theta, renders = run()
            elapsed = time.perf_counter() - clock
            error = np.linalg.norm(theta - TRUTH)
            solved = error <= 0.01 * np.linalg.norm(start(seed) - TRUTH)
            print(f"| {name} | {seed} | {error:.4f} | {'yes' if solved else 'no'} | {renders} | "
                  f"{elapsed:.1f} s |", flush=True)


if __name__ == "__main__":
    main()
