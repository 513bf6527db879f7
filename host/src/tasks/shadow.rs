//! SHADOW: find a sphere that the camera cannot see from its shadow (docs/design.md §3, exact).

use hodr_core::optim::preset::Hyper;

use super::{ParametricScene, Task3d, TaskSettings, check_params, start_uniform};
use crate::render::{
    Camera, Depth, Emitter, Material, Object, Quad, RenderError, Rgb, Scene, Shape, Sphere, Vec3,
};

/// SHADOW, exactly as docs/design.md §3 defines it (z up), so other renderers can render the
/// identical scene:
///
/// * ground: Lambertian square [−2, 2]² at z = 0, albedo 0.5;
/// * sphere: Lambertian, albedo 0.5, radius 0.5, centre (θ₀, θ₁, 3);
/// * light: a 1×1 square centred at (0, 0, 12) facing down (−z), radiance 400 in every
///   channel, black (non-reflecting) itself;
/// * camera: pinhole at (0, 0, 2) looking at (0, 0, 0), up +y (image right = +x), 80° field
///   of view, box pixel filter;
/// * path tracing with maximum depth 3 (direct light plus one indirect bounce).
///
/// The sphere (z ∈ [2.5, 3.5]) is behind the camera for every θ: only its shadow and a
/// faint one-bounce reflection reach the image. Unshadowed ground radiance at the image
/// centre ≈ 400·0.5/(π·144) ≈ 0.442.
///
/// * θ = (x, y), θ* = (−0.55, −0.55).
/// * Start: (0.55, 0.55) + U[−0.1, 0.1]² — the start's shadow (radius ≈ 0.85 with
///   penumbra, centred at 4/3·(x, y)) shares no ground point with the target's.
/// * Objective: 64×64, 4 spp; target 256 spp; images 128×128.
/// * The paper's hyper-parameters: 1 pair, σ 0.5 → 0.01, Δ = 3, 10 line-search steps,
///   recompute 5, Adam η = 0.02; σ₀ = 0.5. Budget: 1500 evaluations (quick: 100).
///
/// **Landscape.** A shadow that leaves the image removes its whole cost, so the loss
/// is lower with the sphere out of view than at the start, which sits on a mesa whose
/// smoothed Hessian is negative definite, while θ* is a narrow well about 1.5 away:
/// descent from the start tends to push the sphere out of view, and what converges
/// finds the well by a sample and keeps it. The measured landscape and convergence
/// figures are in docs/notes/2026-11-23-benchmarks-before-auto.md ("Measurements
/// moved out of doc comments"); `cargo test -p hodr-tests --test render_convergence
/// shadow` reproduces the landscape.
#[derive(Clone, Copy, Debug, Default)]
pub struct Shadow;

struct ShadowScene {
    scene: Scene,
    sphere: u32,
}

impl ParametricScene for ShadowScene {
    fn scene(&self) -> &Scene {
        &self.scene
    }

    fn set_params(&mut self, theta: &[f64]) -> Result<(), RenderError> {
        check_params(theta, 2)?;
        self.scene.object_mut(self.sphere).shape = Shape::Sphere(Sphere {
            center: Vec3::new(theta[0] as f32, theta[1] as f32, 3.0),
            radius: 0.5,
        });
        self.scene.commit()
    }
}

impl Task3d for Shadow {
    fn name(&self) -> &'static str {
        "SHADOW"
    }

    fn description(&self) -> &'static str {
        "(x, y) of a sphere behind the camera, seen only through its shadow on the ground"
    }

    fn dimension(&self) -> usize {
        2
    }

    fn true_params(&self) -> Vec<f64> {
        vec![-0.55, -0.55]
    }

    fn start(&self, seed: u64) -> Vec<f64> {
        (0..2)
            .map(|k| 0.55 + 0.2 * (start_uniform(seed, k) - 0.5))
            .collect()
    }

    /// The sphere's (x, y) over the ground square [−2, 2]²: beyond it the shadow leaves
    /// the ground and the image no longer changes.
    fn bounds(&self) -> Option<(Vec<f64>, Vec<f64>)> {
        Some((vec![-2.0; 2], vec![2.0; 2]))
    }

    fn settings(&self) -> TaskSettings {
        TaskSettings::STANDARD
    }

    fn hyper(&self) -> Hyper<f64> {
        Hyper {
            pairs: 1,
            sigma_start: 0.5,
            sigma_end: 0.01,
            trust_radius: 3.0,
            line_search_iterations: 10,
            recompute: 5,
            learning_rate: 0.02,
            ..Hyper::default()
        }
    }

    fn budget(&self, quick: bool) -> usize {
        if quick { 100 } else { 1500 }
    }

    fn scene(&self) -> Result<Box<dyn ParametricScene>, RenderError> {
        let x = Vec3::new(1.0, 0.0, 0.0);
        let y = Vec3::new(0.0, 1.0, 0.0);
        let camera = Camera::look_at(Vec3::new(0.0, 0.0, 2.0), Vec3::ZERO, y, 80.0)?;
        let mut scene = Scene::new(camera);
        let grey = scene.add_material(Material::diffuse(Rgb::splat(0.5)));
        let black = scene.add_material(Material::Black);
        scene.add_object(Object::new(
            Shape::Quad(Quad::centered(Vec3::ZERO, x, y, (4.0, 4.0))?),
            grey,
        ));
        let sphere = scene.add_object(Object::new(
            Shape::Sphere(Sphere {
                center: Vec3::new(-0.55, -0.55, 3.0),
                radius: 0.5,
            }),
            grey,
        ));
        // x × (−y) = −z: the light faces the ground.
        let light = Quad::centered(Vec3::new(0.0, 0.0, 12.0), x, -y, (1.0, 1.0))?;
        scene.add_object(
            Object::new(Shape::Quad(light), black).with_emitter(Emitter::new(Rgb::splat(400.0))),
        );
        scene.set_depth(Depth {
            max: Some(3),
            roulette: 5,
        });
        let mut s = ShadowScene { scene, sphere };
        s.set_params(&self.true_params())?;
        Ok(Box::new(s))
    }
}
