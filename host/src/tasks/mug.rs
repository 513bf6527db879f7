//! MUG: the rotation of a mug about its vertical axis.

use std::f64::consts::{FRAC_PI_2, TAU};

use hodr_core::optim::preset::Hyper;

use super::{ParametricScene, Task3d, TaskSettings, check_params, start_uniform};
use crate::render::procedural::mug;
use crate::render::{
    Camera, Depth, Emitter, Material, MeshInstance, Object, Quad, RenderError, Rgb, Scene, Shape,
    Transform, Vec3,
};

/// MUG (z up):
///
/// * mug: [`crate::render::procedural::mug`] (outer radius 0.4, height 1, handle on +x at
///   θ = 0), Lambertian albedo (0.75, 0.25, 0.2), standing at the origin and rotated by
///   θ·[`Mug::RADIANS_PER_UNIT`] = 0.2·θ radians about +z (counter-clockwise from above);
/// * ground: Lambertian 6×6 square at z = 0, albedo 0.6;
/// * light: a 1.5×1.5 square centred at (0, −1, 4) facing down, radiance 15;
/// * camera: pinhole at (0, −3.2, 1.6) looking at (0, 0, 0.45), up +z, 40° field of view;
/// * maximum depth 3.
///
/// * θ = (angle in units of 0.2 rad), θ* = 3 (0.6 rad: handle to the right, turned
///   slightly away). The unit makes the paper's MUG schedule meaningful: σ = 3 → 0.01
///   smooths over 0.6 rad → 0.002 rad, where in radians σ = 3 would blur the whole turn
///   (the first Fourier mode of the loss would shrink by e^(−σ²/2) ≈ 0.01).
/// * Start: (π/2 ± 0.25 rad)/0.2 = U[6.60, 9.10]: the handle points away from the camera
///   and hides behind the body, where the loss is flat to within noise.
/// * The loss has period 2π/0.2 ≈ 31.4; [`Task3d::parameter_error`] is the angular
///   distance, in the same units.
/// * Objective: 64×64, 4 spp; target 256 spp; images 128×128.
/// * The paper's hyper-parameters: 1 pair, σ 3 → 0.01, Δ = 4, 1 line-search step,
///   recompute 5, Adam η = 0.1; σ₀ = 3. Budget: 1500 evaluations (quick: 100).
///
/// **Landscape.** A plateau over the starts, a narrow well at θ* about one unit wide,
/// a wall beyond it where the handle turns towards the camera. Smoothed at the paper's
/// σ, f̄'s minimum lies on the plateau among the starts and moves to the well only for
/// σ ≲ 1, so an exact optimiser of f̄ under the paper's schedule would stay on the
/// plateau; runs that converge reach the well by noise while σ is still large. The
/// measured profile is in docs/notes/2026-11-23-benchmarks-before-auto.md
/// ("Measurements moved out of doc comments").
#[derive(Clone, Copy, Debug, Default)]
pub struct Mug;

impl Mug {
    /// Radians of mug rotation per unit of θ.
    pub const RADIANS_PER_UNIT: f64 = 0.2;
}

struct MugScene {
    scene: Scene,
    mug: u32,
}

impl ParametricScene for MugScene {
    fn scene(&self) -> &Scene {
        &self.scene
    }

    fn set_params(&mut self, theta: &[f64]) -> Result<(), RenderError> {
        check_params(theta, 1)?;
        // Reduce the angle in f64 first, so a large θ keeps its precision.
        let angle = (theta[0] * Mug::RADIANS_PER_UNIT).rem_euclid(TAU) as f32;
        if let Shape::Mesh(instance) = &mut self.scene.object_mut(self.mug).shape {
            instance.transform = Transform::rotation_z(angle);
        }
        self.scene.commit()
    }
}

impl Task3d for Mug {
    fn name(&self) -> &'static str {
        "MUG"
    }

    fn description(&self) -> &'static str {
        "rotation of a mug about its vertical axis; the handle starts hidden behind it"
    }

    fn dimension(&self) -> usize {
        1
    }

    fn true_params(&self) -> Vec<f64> {
        vec![0.6 / Mug::RADIANS_PER_UNIT]
    }

    fn start(&self, seed: u64) -> Vec<f64> {
        vec![(FRAC_PI_2 + 0.5 * (start_uniform(seed, 0) - 0.5)) / Mug::RADIANS_PER_UNIT]
    }

    fn settings(&self) -> TaskSettings {
        TaskSettings::STANDARD
    }

    fn hyper(&self) -> Hyper<f64> {
        Hyper {
            pairs: 1,
            sigma_start: 3.0,
            sigma_end: 0.01,
            trust_radius: 4.0,
            line_search_iterations: 1,
            recompute: 5,
            learning_rate: 0.1,
            ..Hyper::default()
        }
    }

    fn budget(&self, quick: bool) -> usize {
        if quick { 100 } else { 1500 }
    }

    fn parameter_error(&self, theta: &[f64]) -> f64 {
        let period = TAU / Mug::RADIANS_PER_UNIT;
        let d = (theta[0] - self.true_params()[0]).rem_euclid(period);
        d.min(period - d)
    }

    fn scene(&self) -> Result<Box<dyn ParametricScene>, RenderError> {
        let x = Vec3::new(1.0, 0.0, 0.0);
        let y = Vec3::new(0.0, 1.0, 0.0);
        let up = Vec3::new(0.0, 0.0, 1.0);
        let camera = Camera::look_at(
            Vec3::new(0.0, -3.2, 1.6),
            Vec3::new(0.0, 0.0, 0.45),
            up,
            40.0,
        )?;
        let mut scene = Scene::new(camera);
        let ground = scene.add_material(Material::diffuse(Rgb::splat(0.6)));
        let glaze = scene.add_material(Material::diffuse(Rgb::new(0.75, 0.25, 0.2)));
        let black = scene.add_material(Material::Black);
        scene.add_object(Object::new(
            Shape::Quad(Quad::centered(Vec3::ZERO, x, y, (6.0, 6.0))?),
            ground,
        ));
        let mug = scene.add_object(Object::new(
            Shape::Mesh(Box::new(MeshInstance {
                mesh: mug()?,
                transform: Transform::IDENTITY,
            })),
            glaze,
        ));
        let light = Quad::centered(Vec3::new(0.0, -1.0, 4.0), x, -y, (1.5, 1.5))?;
        scene.add_object(
            Object::new(Shape::Quad(light), black).with_emitter(Emitter::new(Rgb::splat(15.0))),
        );
        scene.set_depth(Depth {
            max: Some(3),
            roulette: 5,
        });
        let mut s = MugScene { scene, mug };
        s.set_params(&self.true_params())?;
        Ok(Box::new(s))
    }
}
