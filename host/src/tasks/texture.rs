//! TEXTURE: the 32×32 texels of a plane seen by the camera.

use hodr_core::optim::preset::Hyper;

use super::{ParametricScene, Task3d, TaskSettings, check_params, start_uniform};
use crate::render::{
    Albedo, Camera, Depth, Emitter, Material, Object, Quad, RenderError, Rgb, Scene, Shape,
    Texture, Vec3,
};

/// Texels per side.
pub const TEXELS: usize = 32;

/// TEXTURE (z up):
///
/// * plane: a 2×2 square at z = 0 facing +z, Lambertian with a 32×32 grey texture
///   (nearest-texel lookup); texel (i, j), parameter θ[32·j + i], covers the square's
///   column i from −x and row j from +y (row 0 at the top of the image);
/// * light: a 1×1 square centred at (0, 0, 4) facing down, radiance 40;
/// * camera: pinhole at (0, 0, 2) looking down, up +y, 55° field of view (the plane
///   fills the view with a thin black border; at 64×64 each texel covers about 1.9×1.9
///   pixels);
/// * maximum depth 2 (direct lighting only), so each pixel is linear in the texels it
///   sees and the loss is a convex quadratic in θ.
///
/// Texel values are used as albedos unclamped (a value outside [0, 1] is unphysical but
/// renders finitely, and keeps the loss quadratic).
///
/// * θ* = a pattern of 8-texel checks (0.25 / 0.75) with a bright disc (0.9) of radius 7
///   texels centred at texel (21, 11).
/// * Start: every texel iid U[0, 1].
/// * Objective: 64×64, 4 spp; target 256 spp; images 128×128.
/// * The paper's hyper-parameters: 4 pairs, σ 0.5 → 0.1, Δ = 10, 5 line-search steps,
///   recompute 30, Adam η = 0.05; σ₀ = 0.5. Budget: 10 000 evaluations (about ten per
///   parameter; quick: 200, the cheapest evaluations of the path-traced tasks).
#[derive(Clone, Copy, Debug, Default)]
pub struct TextureTask;

struct TextureScene {
    scene: Scene,
    texture: usize,
}

impl ParametricScene for TextureScene {
    fn scene(&self) -> &Scene {
        &self.scene
    }

    fn set_params(&mut self, theta: &[f64]) -> Result<(), RenderError> {
        check_params(theta, TEXELS * TEXELS)?;
        for (texel, &v) in self
            .scene
            .texture_mut(self.texture)
            .texels_mut()
            .iter_mut()
            .zip(theta)
        {
            *texel = Rgb::splat(v as f32);
        }
        self.scene.commit()
    }
}

impl Task3d for TextureTask {
    fn name(&self) -> &'static str {
        "TEXTURE"
    }

    fn description(&self) -> &'static str {
        "the 32×32 grey texels of a lit plane (1024 parameters, quadratic loss)"
    }

    fn dimension(&self) -> usize {
        TEXELS * TEXELS
    }

    fn true_params(&self) -> Vec<f64> {
        let mut theta = Vec::with_capacity(TEXELS * TEXELS);
        for j in 0..TEXELS {
            for i in 0..TEXELS {
                let (di, dj) = (i as f64 - 21.0, j as f64 - 11.0);
                theta.push(if di * di + dj * dj <= 49.0 {
                    0.9
                } else if (i / 8 + j / 8) % 2 == 0 {
                    0.25
                } else {
                    0.75
                });
            }
        }
        theta
    }

    fn start(&self, seed: u64) -> Vec<f64> {
        (0..(TEXELS * TEXELS) as u64)
            .map(|k| start_uniform(seed, k))
            .collect()
    }

    /// Texel albedos in [0, 1].
    fn bounds(&self) -> Option<(Vec<f64>, Vec<f64>)> {
        Some((vec![0.0; TEXELS * TEXELS], vec![1.0; TEXELS * TEXELS]))
    }

    fn settings(&self) -> TaskSettings {
        TaskSettings::STANDARD
    }

    fn hyper(&self) -> Hyper<f64> {
        Hyper {
            pairs: 4,
            sigma_start: 0.5,
            sigma_end: 0.1,
            trust_radius: 10.0,
            line_search_iterations: 5,
            recompute: 30,
            learning_rate: 0.05,
            ..Hyper::default()
        }
    }

    fn budget(&self, quick: bool) -> usize {
        if quick { 200 } else { 10_000 }
    }

    fn scene(&self) -> Result<Box<dyn ParametricScene>, RenderError> {
        let x = Vec3::new(1.0, 0.0, 0.0);
        let y = Vec3::new(0.0, 1.0, 0.0);
        let camera = Camera::look_at(Vec3::new(0.0, 0.0, 2.0), Vec3::ZERO, y, 55.0)?;
        let mut scene = Scene::new(camera);
        let texture = scene.add_texture(Texture::new(
            TEXELS as u32,
            TEXELS as u32,
            vec![Rgb::splat(0.5); TEXELS * TEXELS],
        )?);
        let plane = scene.add_material(Material::Diffuse(Albedo::Texture(texture)));
        let black = scene.add_material(Material::Black);
        scene.add_object(Object::new(
            Shape::Quad(Quad::centered(Vec3::ZERO, x, y, (2.0, 2.0))?),
            plane,
        ));
        let light = Quad::centered(Vec3::new(0.0, 0.0, 4.0), x, -y, (1.0, 1.0))?;
        scene.add_object(
            Object::new(Shape::Quad(light), black).with_emitter(Emitter::new(Rgb::splat(40.0))),
        );
        scene.set_depth(Depth {
            max: Some(2),
            roulette: 5,
        });
        let mut s = TextureScene { scene, texture };
        s.set_params(&self.true_params())?;
        Ok(Box::new(s))
    }
}
