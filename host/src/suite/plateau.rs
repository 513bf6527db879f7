//! Plateau problems: where f is flat over most of the space, so only sampling at the
//! right scale finds the way.
//!
//! **Discs** ([`discs`]): k = n/2 discs of radius [`RADIUS`] px on a [`SIDE`]×[`SIDE`]
//! image; θ = (x₁, y₁, …, x_k, y_k) their centres in pixels. Pixel (c, r) is covered
//! when its centre (c + ½, r + ½) lies strictly inside some disc (point sampling, no
//! anti-aliasing), and f(θ) = (1/SIDE²)·#{pixels whose coverage differs from the
//! target's} — the mean squared difference of the binary images. Targets and starts
//! sit in distinct cells of a 4×4 grid of [`CELL`]-px cells, each centre jittered by at
//! most [`JITTER`] px from its cell's centre, so no two discs overlap and no start disc
//! overlaps a target: every start is on the plateau f = (|D| + |T|)/SIDE², where |T| is
//! fixed and the discs' covered pixel count |D| changes only as a pixel centre crosses a
//! disc's edge. The discs are interchangeable (the image is their union), so the
//! parameter error is taken over the best assignment of discs to targets. f* = 0 at the
//! targets; bounds [0, SIDE]ⁿ; σ₀ = [`DISC_SIGMA0`].
//!
//! Two kinds of local minimum are part of the problem, as they are of a scene whose
//! objects can overlap or leave the view: |D| falls where discs overlap one another (two
//! discs on one target leave another uncovered, f one disc's pixels over SIDE²), and
//! where a disc hangs over the image's edge — up to three quarters of it out of view with
//! its centre in a corner. Leaving either costs f a rise before the disc reaches a free
//! target.
//!
//! **Integer** ([`integer`]): f(x) = Σᵢ κ^((i−1)/(n−1))·(R(round(x) − x*))ᵢ² with
//! κ = [`INTEGER_CONDITION`], R a random rotation and x* an integer point in [−3, 3]ⁿ:
//! a rotated ellipsoid seen only at integer points, piecewise constant on unit cells.
//! f* = 0 exactly on the cell of x*, and the parameter error is ‖round(x) − x*‖;
//! bounds [−5, 5]ⁿ, starts uniform in [−4, 4]ⁿ, σ₀ = [`INTEGER_SIGMA0`].

use super::problem::{Bounds, Family, Measure, Observation, Problem, StartFn, uniform_start};
use super::random;

/// Image side, pixels.
pub const SIDE: usize = 64;

/// Disc radius, pixels.
pub const RADIUS: f64 = 6.0;

/// Grid cell side, pixels (SIDE / 4).
pub const CELL: usize = 16;

/// Largest offset of a disc centre from its cell's centre along each axis, pixels:
/// centres in different cells are then at least CELL − 2·JITTER = 13 > 2·RADIUS apart,
/// and every disc lies inside the image (CELL/2 − JITTER = 6.5 > RADIUS).
pub const JITTER: f64 = 1.5;

/// σ₀ of the disc problems, pixels: a disc diameter and a bit — the distance over which
/// a disc's position matters.
pub const DISC_SIGMA0: f64 = 10.0;

/// Condition number κ of the integer problems' ellipsoid.
pub const INTEGER_CONDITION: f64 = 100.0;

/// σ₀ of the integer problems.
pub const INTEGER_SIGMA0: f64 = 2.0;

/// The disc-plateau loss: k target discs, rendered once.
#[derive(Clone, Debug)]
pub struct Discs {
    target: Vec<bool>,
    target_pixels: usize,
}

impl Discs {
    /// The loss against discs centred at `centres` (x₁, y₁, x₂, y₂, …).
    pub fn new(centres: &[f64]) -> Discs {
        let mut target = vec![false; SIDE * SIDE];
        for (p, t) in target.iter_mut().enumerate() {
            let (px, py) = ((p % SIDE) as f64 + 0.5, (p / SIDE) as f64 + 0.5);
            *t = centres.chunks_exact(2).any(|c| inside(c[0], c[1], px, py));
        }
        let target_pixels = target.iter().filter(|&&t| t).count();
        Discs {
            target,
            target_pixels,
        }
    }

    /// f(θ): the fraction of pixels whose coverage differs from the target's.
    ///
    /// Only pixels in the discs' bounding boxes can be covered; each covered pixel is
    /// counted once, by the first disc covering it, adding 1 to the mismatch off the
    /// target and removing 1 on it (from the |T| every uncovered target pixel costs).
    pub fn value(&self, theta: &[f64]) -> f64 {
        let mut mismatch = self.target_pixels as i64;
        for (k, c) in theta.chunks_exact(2).enumerate() {
            let (cx, cy) = (c[0], c[1]);
            let (x0, x1) = (pixel_range(cx - RADIUS), pixel_range(cx + RADIUS));
            let (y0, y1) = (pixel_range(cy - RADIUS), pixel_range(cy + RADIUS));
            for row in y0..=y1 {
                for col in x0..=x1 {
                    let (px, py) = (col as f64 + 0.5, row as f64 + 0.5);
                    if !inside(cx, cy, px, py)
                        || theta[..2 * k]
                            .chunks_exact(2)
                            .any(|e| inside(e[0], e[1], px, py))
                    {
                        continue;
                    }
                    mismatch += if self.target[row * SIDE + col] { -1 } else { 1 };
                }
            }
        }
        mismatch as f64 / (SIDE * SIDE) as f64
    }
}

/// Whether the pixel centre (px, py) lies strictly inside the disc at (cx, cy).
pub(super) fn inside(cx: f64, cy: f64, px: f64, py: f64) -> bool {
    (px - cx).powi(2) + (py - cy).powi(2) < RADIUS * RADIUS
}

/// The pixel index containing coordinate v, clamped into the image (NaN → 0).
pub(super) fn pixel_range(v: f64) -> usize {
    (v.floor().max(0.0) as usize).min(SIDE - 1)
}

/// `k` centres in distinct cells of the 4×4 grid not in `taken`, chosen and jittered
/// from `seed`; returns the centres and the cells used.
fn place(k: usize, taken: &[usize], seed: u64) -> (Vec<f64>, Vec<usize>) {
    let per_row = SIDE / CELL;
    let mut free: Vec<usize> = (0..per_row * per_row)
        .filter(|c| !taken.contains(c))
        .collect();
    let jitter = random::uniform(2 * k, -JITTER, JITTER, random::seed_of("jitter", &[seed]));
    let picks = random::uniform(k, 0.0, 1.0, random::seed_of("cells", &[seed]));
    let mut centres = Vec::with_capacity(2 * k);
    let mut cells = Vec::with_capacity(k);
    for (j, u) in picks.iter().enumerate() {
        let cell = free.remove(((u * free.len() as f64) as usize).min(free.len() - 1));
        let half = CELL as f64 / 2.0;
        centres.push(((cell % per_row) * CELL) as f64 + half + jitter[2 * j]);
        centres.push(((cell / per_row) * CELL) as f64 + half + jitter[2 * j + 1]);
        cells.push(cell);
    }
    (centres, cells)
}

/// The disc-plateau problem with n/2 discs (n even, 2 ≤ n ≤ 16), instance `instance`.
///
/// # Panics
/// If n is odd or outside 2..=16 (the grid has 16 cells for targets and starts).
pub fn discs(n: usize, instance: u64, budget_per_dim: usize) -> Problem {
    assert!(
        n.is_multiple_of(2) && (2..=16).contains(&n),
        "discs need even n ≤ 16"
    );
    let k = n / 2;
    let (x_opt, target_cells) = place(k, &[], random::seed_of("discs", &[n as u64, instance]));
    let loss = Discs::new(&x_opt);
    let start: StartFn = Box::new(move |seed| place(k, &target_cells, seed).0);
    Problem {
        name: format!("discs-n{n:02}-i{instance}"),
        family: Family::Plateau,
        n,
        f: Box::new(move |x| loss.value(x)),
        observation: Observation::Exact,
        f_opt: 0.0,
        x_opt,
        measure: Measure::UnorderedPairs,
        start,
        sigma0: DISC_SIGMA0,
        bounds: Some(Bounds::cube(n, 0.0, SIDE as f64)),
        budget: budget_per_dim * n,
    }
}

/// The integer-plateau problem in n ≥ 2 dimensions, instance `instance`.
pub fn integer(n: usize, instance: u64, budget_per_dim: usize) -> Problem {
    let seed = |salt: &str| random::seed_of(salt, &[n as u64, instance]);
    let x_opt: Vec<f64> = random::uniform(n, -3.5, 3.5, seed("integer-xopt"))
        .into_iter()
        .map(f64::round)
        .collect();
    let r = random::rotation(n, seed("integer-r"));
    let weights: Vec<f64> = (0..n)
        .map(|i| INTEGER_CONDITION.powf(i as f64 / (n - 1).max(1) as f64))
        .collect();
    let centre = x_opt.clone();
    let f = move |x: &[f64]| {
        let d: Vec<f64> = x.iter().zip(&centre).map(|(a, b)| a.round() - b).collect();
        let mut z = vec![0.0; d.len()];
        random::mat_vec(&r, &d, &mut z);
        z.iter().zip(&weights).map(|(v, w)| w * v * v).sum()
    };
    Problem {
        name: format!("integer-n{n:02}-i{instance}"),
        family: Family::Integer,
        n,
        f: Box::new(f),
        observation: Observation::Exact,
        f_opt: 0.0,
        x_opt,
        measure: Measure::Rounded,
        start: uniform_start(n, -4.0, 4.0),
        sigma0: INTEGER_SIGMA0,
        bounds: Some(Bounds::cube(n, -5.0, 5.0)),
        budget: budget_per_dim * n,
    }
}
