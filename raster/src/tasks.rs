//! The 2D tasks of docs/design.md §3: TRI1D, BOX2, BOX10 and SHAPES, fully defined here.
//!
//! Every task lives on an `size` × `size` image (default [`DEFAULT_SIZE`] = 64) with the
//! length unit **u = size / 8 pixels**: θ's position coordinates are in u, so the image
//! spans [0, 8] whatever its size, and σ values are comparable across sizes.
//!
//! | task | n | scene | θ | true θ | start |
//! |---|---|---|---|---|---|
//! | `tri1d` | 1 | white triangle, apex (x, a), base (x ± h, a + h), a = round(3.25u) + ½, h = round(1.25u) px, on black, AA off | x / u | 2 | x ~ U[5, 6.5) |
//! | `box2` | 2 | orange (1, 0.6, 0.2) square of side 1.5u on black, AA off | centre / u | (2.5, 2.5) | each ~ U[4.5, 6) |
//! | `box10` | 10 | five squares of side u, colours (1, ½, ½), (½, 1, ½), (½, ½, 1), (0, ½, ½), (½, 0, ½), on grey ½, AA off | centres / u | (1.5,1.5) (6.5,1.5) (4,4) (1.5,6.5) (6.5,6.5) | see below |
//! | `shapes` | 18 | three circles on grey 0.5, AA on | per circle: centre / u, radius / (u/2), RGB | see below | see below |
//!
//! **BOX10 start**: each square is displaced from its target by (±dx, ±dy), dx, dy ~
//! U[1.1, 1.6) u, each sign random but flipped when the square would leave [0.75, 7.25].
//! Since |dx| > 1 = the side, no square overlaps its own target. The colours differ
//! from the grey background along one channel each, in pairwise orthogonal or opposite
//! directions, so covering another square's target never lowers the loss: with
//! black and saturated colours (yellow over red, say) it would, and squares settle on
//! the wrong targets.
//!
//! **SHAPES truth**: circle 0 at (2, 2), radius u, colour (0.9, 0.2, 0.2); circle 1 at
//! (5.75, 2.5), radius 1.25u, (0.2, 0.7, 0.3); circle 2 at (3.5, 5.75), radius 1.1u,
//! (0.2, 0.3, 0.9) — or any ordering of the three: they do not overlap, so every
//! ordering renders the target, and the parameter error is to the nearest one. **Start**: radius r₀ ~ U[0.6, 0.9) u, each colour channel ~
//! U[0.3, 0.7), centre at distance d ~ U[r* + r₀ + 0.25, r* + r₀ + 1) u from the target
//! centre in a uniformly random direction, redrawn (up to 64 times, then the first
//! direction of 32 evenly spaced ones that fits) until the circle lies inside the image:
//! no circle overlaps its own target.
//!
//! Positions are clamped so that every shape stays inside the image (the squares and
//! the triangle wholly, the circles' centres), as the paper's BOX2 clamps its
//! position: otherwise moving a shape out of view, which removes its own error, would
//! be a spurious minimum. Starts are a pure function of (task, seed). The loss is the MSE over RGB in [0, 1]
//! against the target rendered at the true θ; on a start, each shape's own region
//! contributes a constant, so the loss is exactly flat (a plateau) until a shape
//! touches its target. [`Settings`] carries the paper's hyper-parameters for BOX2,
//! adapted ones for BOX10 (see its constant) and ours for TRI1D and SHAPES.

use hodr_core::optim::preset::Hyper;
use rand_xoshiro::Xoshiro256PlusPlus;
use rand_xoshiro::rand_core::{Rng, SeedableRng};

use crate::color::Rgba;
use crate::error::Error;
use crate::objective::{Caching, Problem, RasterObjective};
use crate::params::{Attribute, Binding, ParamMap};
use crate::scene::Scene;
use crate::shape::{Geometry, Point, Shape};
use crate::target::Target;

/// The default image side in pixels.
pub const DEFAULT_SIZE: u32 = 64;

/// The task names [`by_name`] accepts.
pub const NAMES: [&str; 4] = ["tri1d", "box2", "box10", "shapes"];

/// Optimiser hyper-parameters for a task (docs/design.md §3's columns).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Settings {
    /// Antithetic pairs per estimate.
    pub pairs: usize,
    /// σ at the first iteration, θ units.
    pub sigma_start: f64,
    /// σ at the last iteration (linear schedule), θ units.
    pub sigma_end: f64,
    /// Trust radius (in units of σ for the HVP variants), θ units.
    pub trust_radius: f64,
    /// Newton–Raphson line-search iterations of NCG.
    pub line_search_iterations: usize,
    /// NCG restarts the direction every this many iterations.
    pub recompute: usize,
    /// Adam's learning rate for the first-order methods.
    pub adam_learning_rate: f64,
}

impl Settings {
    /// The same settings as hodr-core's preset hyper-parameters, [`Hyper::default`] for
    /// the rest (line-search tolerance 1e-3, the paper's independent draws for its HVP
    /// presets).
    pub fn hyper(&self) -> Hyper<f64> {
        Hyper {
            pairs: self.pairs,
            sigma_start: self.sigma_start,
            sigma_end: self.sigma_end,
            trust_radius: self.trust_radius,
            line_search_iterations: self.line_search_iterations,
            recompute: self.recompute,
            learning_rate: self.adam_learning_rate,
            ..Hyper::default()
        }
    }
}

/// One fully defined task: the truth, the parameter map, the starts and the settings.
#[derive(Clone, Debug)]
pub struct Task {
    name: &'static str,
    size: u32,
    truth: Scene,
    map: ParamMap,
    theta_true: Vec<f64>,
    settings: Settings,
    /// Parameters per shape where the shapes are interchangeable (every ordering of
    /// them renders θ*'s image), `None` where order matters.
    interchangeable: Option<usize>,
}

/// The task `name` (one of [`NAMES`], case-insensitive) at the default size.
///
/// # Errors
/// [`Error::UnknownTask`].
pub fn by_name(name: &str) -> Result<Task, Error> {
    Task::new(name, DEFAULT_SIZE)
}

/// Every task at the default size, in [`NAMES`] order.
pub fn all() -> Vec<Task> {
    NAMES.iter().filter_map(|name| by_name(name).ok()).collect()
}

impl Task {
    /// The task `name` on a `size` × `size` image.
    ///
    /// # Errors
    /// [`Error::UnknownTask`]; [`Error::InvalidSize`] unless 8 ≤ size ≤ [`crate::MAX_SIDE`].
    pub fn new(name: &str, size: u32) -> Result<Task, Error> {
        if !(8..=crate::MAX_SIDE).contains(&size) {
            return Err(Error::InvalidSize {
                width: size,
                height: size,
            });
        }
        let u = size as f32 / 8.0;
        // SHAPES's circles share one binding layout and do not overlap at θ*, so any
        // ordering of them renders the target; BOX10's squares keep their colours.
        let (name, truth, bindings, settings, interchangeable) =
            match name.to_ascii_lowercase().as_str() {
                "tri1d" => ("tri1d", tri1d(size, u)?, tri1d_map(u), TRI1D, None),
                "box2" => ("box2", box2(size, u)?, box_map(1, u, 1.5), BOX2, None),
                "box10" => ("box10", box10(size, u)?, box_map(5, u, 1.0), BOX10, None),
                "shapes" => (
                    "shapes",
                    shapes(size, u)?,
                    shapes_map(u),
                    SHAPES,
                    Some(SHAPES_PARAMETERS),
                ),
                _ => return Err(Error::UnknownTask(name.to_string())),
            };
        let map = ParamMap::new(bindings, &truth)?;
        let theta_true = map.read(&truth);
        Ok(Task {
            name,
            size,
            truth,
            map,
            theta_true,
            settings,
            interchangeable,
        })
    }

    /// The task's name, as in [`NAMES`].
    pub fn name(&self) -> &'static str {
        self.name
    }

    /// Image side in pixels.
    pub fn size(&self) -> u32 {
        self.size
    }

    /// n, the dimension of θ.
    pub fn dim(&self) -> usize {
        self.map.dim()
    }

    /// θ*, the parameters of the target.
    pub fn theta_true(&self) -> &[f64] {
        &self.theta_true
    }

    /// The hyper-parameters.
    pub fn settings(&self) -> Settings {
        self.settings
    }

    /// The parameter map.
    pub fn map(&self) -> &ParamMap {
        &self.map
    }

    /// The scene at θ*.
    pub fn truth(&self) -> &Scene {
        &self.truth
    }

    /// The target image: the scene at θ*.
    pub fn target(&self) -> Target {
        Target::from_scene(&self.truth)
    }

    /// The inverse problem (MSE loss) with the given caching.
    pub fn problem(&self, caching: Caching) -> Problem {
        // The map was checked against this very scene and the target is its render,
        // so construction cannot fail.
        Problem::new(self.truth.clone(), self.map.clone(), self.target())
            .unwrap_or_else(|_| unreachable!("task problems are consistent by construction"))
            .with_caching(caching)
    }

    /// The objective with caching on and one renderer per rayon thread.
    ///
    /// # Errors
    /// As [`RasterObjective::new`].
    pub fn objective(&self) -> Result<RasterObjective, Error> {
        RasterObjective::new(self.problem(Caching::On))
    }

    /// A start θ₀ drawn from the task's start distribution with `seed`.
    pub fn start(&self, seed: u64) -> Vec<f64> {
        let mut rng = Xoshiro256PlusPlus::seed_from_u64(seed ^ name_hash(self.name));
        let mut uniform = |lo: f64, hi: f64| lo + (hi - lo) * unit(&mut rng);
        match self.name {
            "tri1d" => vec![uniform(5.0, 6.5)],
            "box2" => vec![uniform(4.5, 6.0), uniform(4.5, 6.0)],
            "box10" => {
                let mut theta = self.theta_true.clone();
                for t in &mut theta {
                    let d = uniform(1.1, 1.6);
                    let sign = if uniform(0.0, 1.0) < 0.5 { -1.0 } else { 1.0 };
                    let moved = *t + sign * d;
                    *t = if (0.75..=7.25).contains(&moved) {
                        moved
                    } else {
                        *t - sign * d
                    };
                }
                theta
            }
            _ => shapes_start(&self.theta_true, &mut uniform),
        }
    }

    /// Euclidean distance of θ to θ*, in θ units. Where the task's shapes are
    /// interchangeable (SHAPES), to the nearest of θ*'s orderings — all of which render
    /// the target — minimised over the k! assignments of θ's k shapes to the target's.
    pub fn parameter_distance(&self, theta: &[f64]) -> f64 {
        let block = self.interchangeable.unwrap_or(self.theta_true.len()).max(1);
        let shapes = self.theta_true.len() / block;
        nearest_assignment(theta, &self.theta_true, block, 0, &mut vec![false; shapes]).sqrt()
    }

    /// Root-mean-square distance of θ to θ*, in θ units: [`Task::parameter_distance`]
    /// over √n.
    pub fn parameter_error(&self, theta: &[f64]) -> f64 {
        self.parameter_distance(theta) / (self.theta_true.len().max(1) as f64).sqrt()
    }
}

/// The least Σ of squared differences between θ's shapes from `shape` on (blocks of
/// `block` parameters) and the target's shapes not yet `taken`, each used once.
fn nearest_assignment(
    theta: &[f64],
    truth: &[f64],
    block: usize,
    shape: usize,
    taken: &mut [bool],
) -> f64 {
    let Some(own) = theta
        .chunks(block)
        .nth(shape)
        .filter(|_| shape < taken.len())
    else {
        return 0.0;
    };
    let mut best = f64::INFINITY;
    for (target, params) in truth.chunks(block).enumerate() {
        if taken[target] {
            continue;
        }
        let here: f64 = own.iter().zip(params).map(|(a, b)| (a - b).powi(2)).sum();
        taken[target] = true;
        let rest = nearest_assignment(theta, truth, block, shape + 1, taken);
        taken[target] = false;
        best = best.min(here + rest);
    }
    best
}

const TRI1D: Settings = Settings {
    pairs: 4,
    sigma_start: 1.0,
    sigma_end: 0.01,
    trust_radius: 2.0,
    line_search_iterations: 3,
    recompute: 10,
    adam_learning_rate: 0.3,
};

const BOX2: Settings = Settings {
    pairs: 6,
    sigma_start: 1.5,
    sigma_end: 0.01,
    trust_radius: 2.0,
    line_search_iterations: 3,
    recompute: 10,
    adam_learning_rate: 0.3,
};

/// The paper's σ start (0.6), recompute and line search; more pairs (16, not 6), a
/// smaller trust radius (σ, not 10σ) and a lower final σ (0.05, not 0.1): with the
/// paper's values in our units every NCG step on the plateau moves each square by up
/// to 6 of the image's 8 units and the squares scatter.
const BOX10: Settings = Settings {
    pairs: 16,
    sigma_start: 0.6,
    sigma_end: 0.05,
    trust_radius: 1.0,
    line_search_iterations: 3,
    recompute: 30,
    adam_learning_rate: 0.05,
};

const SHAPES: Settings = Settings {
    pairs: 6,
    sigma_start: 0.5,
    sigma_end: 0.02,
    trust_radius: 5.0,
    line_search_iterations: 3,
    recompute: 20,
    adam_learning_rate: 0.05,
};

const BLACK: Rgba = Rgba::rgb(0.0, 0.0, 0.0);

fn square(centre: (f32, f32), side: f32, fill: Rgba) -> Shape {
    Shape::new(
        Geometry::Rect {
            center: Point::new(centre.0, centre.1),
            width: side,
            height: side,
            rotation: 0.0,
        },
        fill,
    )
    .with_anti_alias(false)
}

fn tri1d(size: u32, u: f32) -> Result<Scene, Error> {
    // A right-angled apex with its tip on a pixel-centre row: every row's covered width
    // is then an integer number of pixels, so with anti-aliasing off the covered pixel
    // count does not change under horizontal translation and the plateau is exactly flat.
    let (apex, half) = tri1d_geometry(u);
    let x = 2.0 * u;
    let tri = Geometry::Triangle([
        Point::new(x, apex),
        Point::new(x - half, apex + half),
        Point::new(x + half, apex + half),
    ]);
    Scene::new(size, size, BLACK)?
        .with(Shape::new(tri, Rgba::rgb(1.0, 1.0, 1.0)).with_anti_alias(false))
}

/// TRI1D's apex y (a pixel-centre row) and half base (= height, whole pixels).
fn tri1d_geometry(u: f32) -> (f32, f32) {
    ((3.25 * u).round() + 0.5, (1.25 * u).round().max(1.0))
}

fn tri1d_map(u: f32) -> Vec<Binding> {
    // The scene holds the triangle at x = 2u (θ* = 2); θ translates it by u·(θ − 2).
    // Clamped so the whole triangle stays in the image.
    let (u, h) = (f64::from(u), f64::from(tri1d_geometry(u).1));
    vec![
        Binding::new(0, Attribute::X, u)
            .with_offset(-2.0 * u)
            .with_clamp(h - 2.0 * u, 6.0 * u - h),
    ]
}

fn box2(size: u32, u: f32) -> Result<Scene, Error> {
    Scene::new(size, size, BLACK)?.with(square(
        (2.5 * u, 2.5 * u),
        1.5 * u,
        Rgba::rgb(1.0, 0.6, 0.2),
    ))
}

const BOX10_CENTRES: [(f32, f32); 5] = [(1.5, 1.5), (6.5, 1.5), (4.0, 4.0), (1.5, 6.5), (6.5, 6.5)];

fn box10(size: u32, u: f32) -> Result<Scene, Error> {
    let mut scene = Scene::new(size, size, Rgba::rgb(0.5, 0.5, 0.5))?;
    for (&(x, y), fill) in BOX10_CENTRES.iter().zip(BOX10_COLOURS) {
        scene.push(square((x * u, y * u), u, fill))?;
    }
    Ok(scene)
}

/// Grey ± ½ along one channel each: the offsets from the background are pairwise
/// orthogonal or opposite, so no square lowers the loss by sitting on another's target
/// (the overlap changes the error by −2·(a − g)·(b − g) ≥ 0 for colours a, b on grey g).
const BOX10_COLOURS: [Rgba; 5] = [
    Rgba::rgb(1.0, 0.5, 0.5),
    Rgba::rgb(0.5, 1.0, 0.5),
    Rgba::rgb(0.5, 0.5, 1.0),
    Rgba::rgb(0.0, 0.5, 0.5),
    Rgba::rgb(0.5, 0.0, 0.5),
];

/// Centre bindings of `squares` squares of side `side`·u, clamped inside the image.
fn box_map(squares: usize, u: f32, side: f64) -> Vec<Binding> {
    let u = f64::from(u);
    let (lo, hi) = (side / 2.0 * u, (8.0 - side / 2.0) * u);
    (0..squares)
        .flat_map(|i| {
            [
                Binding::new(i, Attribute::X, u).with_clamp(lo, hi),
                Binding::new(i, Attribute::Y, u).with_clamp(lo, hi),
            ]
        })
        .collect()
}

/// Parameters per SHAPES circle: centre x, y, 2r (all in u) and R, G, B.
const SHAPES_PARAMETERS: usize = 6;

/// (centre x, centre y, radius) in u, and colour, of the SHAPES circles.
const CIRCLES: [(f32, f32, f32, Rgba); 3] = [
    (2.0, 2.0, 1.0, Rgba::rgb(0.9, 0.2, 0.2)),
    (5.75, 2.5, 1.25, Rgba::rgb(0.2, 0.7, 0.3)),
    (3.5, 5.75, 1.1, Rgba::rgb(0.2, 0.3, 0.9)),
];

fn shapes(size: u32, u: f32) -> Result<Scene, Error> {
    let mut scene = Scene::new(size, size, Rgba::rgb(0.5, 0.5, 0.5))?;
    for &(x, y, r, fill) in &CIRCLES {
        scene.push(Shape::new(
            Geometry::Circle {
                center: Point::new(x * u, y * u),
                radius: r * u,
            },
            fill,
        ))?;
    }
    Ok(scene)
}

fn shapes_map(u: f32) -> Vec<Binding> {
    let u = f64::from(u);
    (0..CIRCLES.len())
        .flat_map(|i| {
            [
                Binding::new(i, Attribute::X, u).with_clamp(0.0, 8.0 * u),
                Binding::new(i, Attribute::Y, u).with_clamp(0.0, 8.0 * u),
                Binding::new(i, Attribute::Radius, u / 2.0).with_clamp(0.0, 4.0 * u),
                Binding::new(i, Attribute::Red, 1.0),
                Binding::new(i, Attribute::Green, 1.0),
                Binding::new(i, Attribute::Blue, 1.0),
            ]
        })
        .collect()
}

/// SHAPES start: θ is (x, y, 2r, R, G, B) per circle, positions and radii in u.
fn shapes_start(truth: &[f64], uniform: &mut impl FnMut(f64, f64) -> f64) -> Vec<f64> {
    let mut theta = truth.to_vec();
    let chunks = truth.chunks_exact(SHAPES_PARAMETERS);
    for (c, t) in chunks.zip(theta.chunks_exact_mut(SHAPES_PARAMETERS)) {
        let (x, y, r_true) = (c[0], c[1], c[2] / 2.0);
        let r = uniform(0.6, 0.9);
        let d = uniform(r_true + r + 0.25, r_true + r + 1.0);
        let inside = |px: f64, py: f64| (r..=8.0 - r).contains(&px) && (r..=8.0 - r).contains(&py);
        let mut centre = None;
        for _ in 0..64 {
            let phi = uniform(0.0, std::f64::consts::TAU);
            let (px, py) = (x + d * phi.cos(), y + d * phi.sin());
            if inside(px, py) {
                centre = Some((px, py));
                break;
            }
        }
        let (px, py) = centre.unwrap_or_else(|| {
            (0..32)
                .map(|k| f64::from(k) * std::f64::consts::TAU / 32.0)
                .map(|phi| (x + d * phi.cos(), y + d * phi.sin()))
                .find(|&(px, py)| inside(px, py))
                .unwrap_or((4.0, 4.0))
        });
        t[0] = px;
        t[1] = py;
        t[2] = 2.0 * r;
        for v in &mut t[3..6] {
            *v = uniform(0.3, 0.7);
        }
    }
    theta
}

/// A uniform number in [0, 1) from the top 53 bits.
fn unit(rng: &mut Xoshiro256PlusPlus) -> f64 {
    (rng.next_u64() >> 11) as f64 * (1.0 / (1u64 << 53) as f64)
}

/// FNV-1a of the name, so that equal seeds give unrelated starts across tasks.
fn name_hash(name: &str) -> u64 {
    name.bytes().fold(0xcbf2_9ce4_8422_2325, |h, b| {
        (h ^ u64::from(b)).wrapping_mul(0x0100_0000_01b3)
    })
}
