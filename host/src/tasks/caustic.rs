//! CAUSTIC: the heights of a glass slab whose caustic must match a target.

use hodr_core::optim::preset::Hyper;

use super::{ParametricScene, Task3d, TaskSettings, TextureTask, check_params, start_uniform};
use crate::render::procedural::HeightField;
use crate::render::{
    Camera, Depth, Emitter, Material, MeshInstance, Object, Quad, RenderError, Rgb, Scene, Shape,
    Transform, Vec3,
};

/// Control heights per side.
pub const CONTROLS: usize = 16;

/// The slab of CAUSTIC.
const FIELD: HeightField = HeightField {
    cols: CONTROLS,
    rows: CONTROLS,
    center: (0.0, 0.0),
    size: (1.6, 1.6),
    bottom: 1.0,
    top: 1.15,
    max_height: 0.3,
};

/// CAUSTIC (z up):
///
/// * floor: Lambertian 4×4 square at z = 0, albedo 0.8;
/// * slab: glass (index of refraction 1.5) over [−0.8, 0.8]², flat bottom at z = 1, top
///   at z = 1.15 + h(i, j) over 16×16 control points (θ[16·j + i] = h at x = −0.8 +
///   1.6·i/15, y = −0.8 + 1.6·j/15), heights clamped to [−0.075, 0.3], shaded with
///   smooth normals ([`HeightField`]);
/// * light: a 1.2×1.2 square centred at (0, 0, 3.5) facing down, radiance 30;
/// * camera: pinhole at (0, −3.5, 1.8) looking at (0, 0, 0), up +z, 45° field of view:
///   it sees the floor under the slab from the front, below the slab;
/// * maximum depth 5, Russian roulette from depth 5. Light reaches the floor under the
///   slab only through the glass (shadow rays are blocked by it): the renderer traces
///   that caustic from the light ([`crate::render::Plan`]'s `light_paths`). Five
///   segments hold every path of the caustic the camera sees on the floor (light →
///   slab → slab → floor → camera is four) and of the slab seen with the floor or the
///   light through it; they leave out the caustic seen through the slab (camera → slab
///   → slab → floor → slab → slab → light, six), which neither camera nor light paths
///   sample but by chance: with it, its fireflies outweighed, on one noise seed, the
///   change of the loss between nearby θ.
///
/// * θ* = two smooth domes, h = 0.12·exp(−‖p − (−0.35, 0.2)‖²/(2·0.22²))
///   + 0.08·exp(−‖p − (0.35, −0.25)‖²/(2·0.18²)), each focusing a bright spot.
/// * Start: a flat slab with iid U[−0.01, 0.01] heights.
/// * Objective: 64×64, 16 spp; target 1024 spp; images 128×128.
/// * Bounds: the heights the slab renders, [−0.075, 0.3]; σ₀ = 0.05.
/// * Hyper-parameters: the paper has none for CAUSTIC; the paper's methods borrow
///   [`TextureTask`]'s (the other task with hundreds of parameters). Budget: 4000 evaluations
///   (quick: 60, the most expensive evaluations of the path-traced tasks:
///   BSDF-sampled caustic paths).
#[derive(Clone, Copy, Debug, Default)]
pub struct Caustic;

struct CausticScene {
    scene: Scene,
    slab: u32,
    heights: Vec<f32>,
    positions: Vec<Vec3>,
    normals: Vec<Vec3>,
}

impl ParametricScene for CausticScene {
    fn scene(&self) -> &Scene {
        &self.scene
    }

    fn set_params(&mut self, theta: &[f64]) -> Result<(), RenderError> {
        check_params(theta, CONTROLS * CONTROLS)?;
        for (h, &t) in self.heights.iter_mut().zip(theta) {
            *h = t as f32;
        }
        FIELD.vertices(&self.heights, &mut self.positions, &mut self.normals)?;
        if let Shape::Mesh(instance) = &mut self.scene.object_mut(self.slab).shape {
            instance.mesh.update(&self.positions, Some(&self.normals))?;
        }
        self.scene.commit()
    }
}

impl Task3d for Caustic {
    fn name(&self) -> &'static str {
        "CAUSTIC"
    }

    fn description(&self) -> &'static str {
        "16×16 control heights of a glass slab whose caustic on the floor must match"
    }

    fn dimension(&self) -> usize {
        CONTROLS * CONTROLS
    }

    fn true_params(&self) -> Vec<f64> {
        let mut theta = Vec::with_capacity(CONTROLS * CONTROLS);
        let dome = |x: f64, y: f64, cx: f64, cy: f64, s: f64| {
            (-((x - cx).powi(2) + (y - cy).powi(2)) / (2.0 * s * s)).exp()
        };
        for j in 0..CONTROLS {
            for i in 0..CONTROLS {
                let x = -0.8 + 1.6 * i as f64 / (CONTROLS - 1) as f64;
                let y = -0.8 + 1.6 * j as f64 / (CONTROLS - 1) as f64;
                theta.push(
                    0.12 * dome(x, y, -0.35, 0.2, 0.22) + 0.08 * dome(x, y, 0.35, -0.25, 0.18),
                );
            }
        }
        theta
    }

    fn start(&self, seed: u64) -> Vec<f64> {
        (0..(CONTROLS * CONTROLS) as u64)
            .map(|k| 0.02 * (start_uniform(seed, k) - 0.5))
            .collect()
    }

    /// The heights the slab renders: [−(top − bottom)/2, max_height] (it clamps there).
    fn bounds(&self) -> Option<(Vec<f64>, Vec<f64>)> {
        let lo = -0.5 * f64::from(FIELD.top - FIELD.bottom);
        let hi = f64::from(FIELD.max_height);
        Some((vec![lo; CONTROLS * CONTROLS], vec![hi; CONTROLS * CONTROLS]))
    }

    /// 0.05: the domes of θ* are 0.08 and 0.12 high, the box 0.375 tall.
    fn scale(&self) -> f64 {
        0.05
    }

    fn settings(&self) -> TaskSettings {
        TaskSettings {
            objective_spp: 16,
            target_spp: 1024,
            ..TaskSettings::STANDARD
        }
    }

    fn hyper(&self) -> Hyper<f64> {
        TextureTask.hyper()
    }

    fn budget(&self, quick: bool) -> usize {
        if quick { 60 } else { 4000 }
    }

    fn scene(&self) -> Result<Box<dyn ParametricScene>, RenderError> {
        let x = Vec3::new(1.0, 0.0, 0.0);
        let y = Vec3::new(0.0, 1.0, 0.0);
        let z = Vec3::new(0.0, 0.0, 1.0);
        let camera = Camera::look_at(Vec3::new(0.0, -3.5, 1.8), Vec3::ZERO, z, 45.0)?;
        let mut scene = Scene::new(camera);
        let floor = scene.add_material(Material::diffuse(Rgb::splat(0.8)));
        let glass = scene.add_material(Material::Dielectric { ior: 1.5 });
        let black = scene.add_material(Material::Black);
        scene.add_object(Object::new(
            Shape::Quad(Quad::centered(Vec3::ZERO, x, y, (4.0, 4.0))?),
            floor,
        ));
        let heights = vec![0.0f32; CONTROLS * CONTROLS];
        let slab = scene.add_object(Object::new(
            Shape::Mesh(Box::new(MeshInstance {
                mesh: FIELD.mesh(&heights)?,
                transform: Transform::IDENTITY,
            })),
            glass,
        ));
        let light = Quad::centered(Vec3::new(0.0, 0.0, 3.5), x, -y, (1.2, 1.2))?;
        scene.add_object(
            Object::new(Shape::Quad(light), black).with_emitter(Emitter::new(Rgb::splat(30.0))),
        );
        scene.set_depth(Depth {
            max: Some(5),
            roulette: 5,
        });
        let mut s = CausticScene {
            scene,
            slab,
            heights,
            positions: Vec::new(),
            normals: Vec::new(),
        };
        s.set_params(&self.true_params())?;
        Ok(Box::new(s))
    }
}
