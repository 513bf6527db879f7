//! The cached static layer and the dirty-region evaluation.
//!
//! Shapes that θ does not move never change, so per problem we render once:
//!
//! * the **prefix layer**: background plus every shape below the lowest moving shape;
//! * the **static image**: background plus every shape that θ does not move, and its
//!   per-pixel error against the target as row-wise cumulative integer sums.
//!
//! An evaluation then builds the **dirty region**: the pixel bounds of the moving shapes
//! at θ, closed under "a static shape drawn above the lowest moving one touches it"
//! (such a shape must be redrawn, and it may paint outside the region so far). Outside
//! the region the frame equals the static image, whose error is known; inside, the
//! prefix layer is copied in, the shapes from the lowest moving one up that touch the
//! region are drawn, and the region is scored. Every shape drawn lies inside the
//! region, so nothing outside it is read or needs repairing afterwards: unlike a
//! "repaint the old and new bounding boxes" scheme, the frame's history never matters,
//! and each evaluation is a pure function of θ, bit for bit equal to a full render.

use tiny_skia::Pixmap;

use crate::objective::{Caching, Problem};
use crate::params::set;
use crate::region::{PixelRect, Region};
use crate::scene::new_pixmap;
use crate::shape::{PathScratch, Shape};

/// What every renderer of one problem shares, immutable after construction.
#[derive(Debug)]
pub(crate) struct Cache {
    /// Index of the lowest moving shape.
    first_moving: usize,
    /// Per shape: does θ drive it?
    moving: Vec<bool>,
    /// Background plus shapes below `first_moving`.
    prefix: Pixmap,
    /// Per row, `width + 1` cumulative error sums of the static image.
    static_rows: Vec<u64>,
    /// Error of the static image over all pixels.
    static_total: u64,
    /// Per shape, its pixel bounds in the scene as given (used for static shapes).
    static_rects: Vec<Option<PixelRect>>,
}

impl Cache {
    pub(crate) fn new(problem: &Problem) -> Self {
        let scene = problem.scene();
        let (width, height) = (scene.width(), scene.height());
        let shapes = scene.shapes();
        let mut moving = vec![false; shapes.len()];
        for b in problem.map().bindings() {
            moving[b.shape] = true;
        }
        let first_moving = moving.iter().position(|&m| m).unwrap_or(shapes.len());

        let mut scratch = PathScratch::default();
        let mut prefix = new_pixmap(width, height);
        prefix.fill(scene.background().to_skia());
        let mut still = prefix.clone();
        {
            let mut canvas = prefix.as_mut();
            for shape in &shapes[..first_moving] {
                shape.draw(&mut canvas, &mut scratch);
            }
            let mut canvas = still.as_mut();
            for (shape, _) in shapes.iter().zip(&moving).filter(|(_, m)| !**m) {
                shape.draw(&mut canvas, &mut scratch);
            }
        }

        let w = width as usize;
        let target = problem.target().rgb();
        let mut static_rows = Vec::with_capacity(height as usize * (w + 1));
        let mut static_total = 0;
        for y in 0..height as usize {
            let frame = &still.data()[y * w * 4..(y + 1) * w * 4];
            let truth = &target[y * w * 3..(y + 1) * w * 3];
            let mut sum = 0;
            static_rows.push(0);
            for x in 0..w {
                sum += problem
                    .loss()
                    .row_error(&frame[x * 4..x * 4 + 4], &truth[x * 3..x * 3 + 3]);
                static_rows.push(sum);
            }
            static_total += sum;
        }
        let static_rects = shapes.iter().map(|s| s.pixel_rect(width, height)).collect();
        Cache {
            first_moving,
            moving,
            prefix,
            static_rows,
            static_total,
            static_rects,
        }
    }
}

/// One thread's mutable state: the frame and the working copies of the shapes that
/// may be redrawn. Allocations happen here, once; evaluations reuse them.
#[derive(Debug)]
pub(crate) struct Renderer {
    frame: Pixmap,
    /// Working copies of `shapes[first_moving..]`.
    shapes: Vec<Shape>,
    /// Per working shape: static but inside the dirty region this evaluation.
    included: Vec<bool>,
    path: PathScratch,
    region: Region,
}

impl Renderer {
    pub(crate) fn new(problem: &Problem, cache: &Cache) -> Self {
        let shapes = problem.scene().shapes()[cache.first_moving..].to_vec();
        Renderer {
            frame: cache.prefix.clone(),
            included: vec![false; shapes.len()],
            shapes,
            path: PathScratch::default(),
            region: Region::default(),
        }
    }

    /// The integer error sum of the scene at θ (coordinate k read by `theta(k)`, which
    /// the caller has checked to be finite) against the target.
    pub(crate) fn error_sum(
        &mut self,
        problem: &Problem,
        cache: &Cache,
        theta: impl Fn(usize) -> f64,
    ) -> u64 {
        let first = cache.first_moving;
        let base = problem.scene().shapes();
        for (i, shape) in self.shapes.iter_mut().enumerate() {
            if cache.moving[first + i] {
                shape.copy_from(&base[first + i]);
            }
        }
        for (k, b) in problem.map().bindings().iter().enumerate() {
            set(
                b.attribute,
                &mut self.shapes[b.shape - first],
                b.value(theta(k)),
            );
        }
        match problem.caching() {
            Caching::Off => self.full(problem),
            Caching::On => self.dirty(problem, cache),
        }
    }

    /// Background and every shape, scored over the whole image.
    fn full(&mut self, problem: &Problem) -> u64 {
        let scene = problem.scene();
        self.frame.fill(scene.background().to_skia());
        let first = scene.shapes().len() - self.shapes.len();
        let mut canvas = self.frame.as_mut();
        for shape in scene.shapes()[..first].iter().chain(&self.shapes) {
            shape.draw(&mut canvas, &mut self.path);
        }
        problem
            .loss()
            .row_error(self.frame.data(), problem.target().rgb())
    }

    fn dirty(&mut self, problem: &Problem, cache: &Cache) -> u64 {
        let (width, height) = (problem.scene().width(), problem.scene().height());
        let first = cache.first_moving;
        self.region.clear();
        self.included.fill(false);
        for (i, shape) in self.shapes.iter().enumerate() {
            if cache.moving[first + i] {
                if let Some(rect) = shape.pixel_rect(width, height) {
                    self.region.push(rect);
                }
            }
        }
        // Close the region under the static shapes above `first` that touch it; each
        // pass adds at least one shape or stops, so at most `shapes` passes.
        loop {
            let mut grew = false;
            for (i, included) in self.included.iter_mut().enumerate() {
                let s = first + i;
                if cache.moving[s] || *included {
                    continue;
                }
                if let Some(rect) = cache.static_rects[s] {
                    if self.region.intersects(&rect) {
                        self.region.push(rect);
                        *included = true;
                        grew = true;
                    }
                }
            }
            if !grew {
                break;
            }
        }
        self.region.build_spans();

        let w = width as usize;
        let prefix = cache.prefix.data();
        {
            let frame = self.frame.data_mut();
            for span in self.region.spans() {
                let range = (span.y as usize * w + span.x0 as usize) * 4
                    ..(span.y as usize * w + span.x1 as usize) * 4;
                frame[range.clone()].copy_from_slice(&prefix[range]);
            }
        }
        let mut canvas = self.frame.as_mut();
        for (i, shape) in self.shapes.iter().enumerate() {
            if cache.moving[first + i] || self.included[i] {
                shape.draw(&mut canvas, &mut self.path);
            }
        }

        let frame = self.frame.data();
        let target = problem.target().rgb();
        let loss = problem.loss();
        let (mut removed, mut added) = (0, 0);
        for span in self.region.spans() {
            let (y, x0, x1) = (span.y as usize, span.x0 as usize, span.x1 as usize);
            let row = &cache.static_rows[y * (w + 1)..(y + 1) * (w + 1)];
            removed += row[x1] - row[x0];
            added += loss.row_error(
                &frame[(y * w + x0) * 4..(y * w + x1) * 4],
                &target[(y * w + x0) * 3..(y * w + x1) * 3],
            );
        }
        cache.static_total - removed + added
    }
}
