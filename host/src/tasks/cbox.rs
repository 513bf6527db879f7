//! CBOX: the position of the small box in a Cornell box.

use hodr_core::optim::preset::Hyper;

use super::{ParametricScene, Shadow, Task3d, TaskSettings, check_params, start_uniform};
use crate::render::{
    Camera, Cuboid, Depth, Emitter, Material, Object, Quad, RenderError, Rgb, Scene, Shape,
    Transform, Vec3,
};

/// Floor coordinates of the small box's centre are clamped to ±this, which keeps the
/// box inside the room.
const LIMIT: f64 = 0.65;
/// Rotation of the small box about +z (radians).
const SMALL_BOX_TURN: f32 = -0.3;
/// Half size of the small box.
const SMALL_BOX_HALF: f32 = 0.3;

/// CBOX, a Cornell box in z-up coordinates (the classic y-up box's x, z are our x, y):
///
/// * room: x, y ∈ [−1, 1], z ∈ [0, 2], open towards −y; floor, ceiling and back wall
///   (y = 1) white (albedo 0.73), left wall (x = −1) red (0.63, 0.065, 0.05), right wall
///   (x = 1) green (0.14, 0.45, 0.091), all Lambertian;
/// * light: 0.5×0.4 rectangle at z = 1.98 centred on the ceiling, facing down, radiance
///   (17, 12, 4);
/// * tall box: half extents (0.3, 0.3, 0.6), turned 0.3 rad, centre (−0.35, 0.35, 0.6);
/// * small box: half extents 0.3, turned −0.3 rad, centre (θ₀, θ₁, 0.3), each coordinate
///   clamped to [−0.65, 0.65];
/// * camera: pinhole at (0, −3.9, 1) looking at (0, 0, 1), up +z, 40° field of view;
/// * maximum depth 6, Russian roulette from depth 4 — global illumination (colour
///   bleeding, the box's indirect shadow) matters.
///
/// * θ = (x, y) of the small box, θ* = (0.35, −0.3).
/// * Start: U[−0.6, 0.6] × U[−0.6, 0.0]; bounds [−0.65, 0.65]².
/// * Objective: 64×64, 4 spp; target 256 spp; images 128×128.
/// * Hyper-parameters: the paper has none for CBOX; it borrows [`Shadow`]'s (the other
///   task that moves an object over a floor), σ₀ = 0.5. Budget: 1500 evaluations
///   (quick: 100).
#[derive(Clone, Copy, Debug, Default)]
pub struct Cbox;

struct CboxScene {
    scene: Scene,
    small_box: u32,
}

impl ParametricScene for CboxScene {
    fn scene(&self) -> &Scene {
        &self.scene
    }

    fn set_params(&mut self, theta: &[f64]) -> Result<(), RenderError> {
        check_params(theta, 2)?;
        let (x, y) = (
            theta[0].clamp(-LIMIT, LIMIT) as f32,
            theta[1].clamp(-LIMIT, LIMIT) as f32,
        );
        self.scene.object_mut(self.small_box).shape = Shape::Cuboid(Cuboid {
            half: Vec3::splat(SMALL_BOX_HALF),
            transform: Transform::rotation_z(SMALL_BOX_TURN)
                .then(&Transform::translation(Vec3::new(x, y, SMALL_BOX_HALF))),
        });
        self.scene.commit()
    }
}

impl Task3d for Cbox {
    fn name(&self) -> &'static str {
        "CBOX"
    }

    fn description(&self) -> &'static str {
        "floor position of the small box in a Cornell box (global illumination)"
    }

    fn dimension(&self) -> usize {
        2
    }

    fn true_params(&self) -> Vec<f64> {
        vec![0.35, -0.3]
    }

    fn start(&self, seed: u64) -> Vec<f64> {
        vec![
            1.2 * (start_uniform(seed, 0) - 0.5),
            -0.6 * start_uniform(seed, 1),
        ]
    }

    /// The small box's floor position, [−0.65, 0.65]² (see `LIMIT`): beyond it the scene
    /// clamps θ, so the image no longer changes.
    fn bounds(&self) -> Option<(Vec<f64>, Vec<f64>)> {
        Some((vec![-LIMIT; 2], vec![LIMIT; 2]))
    }

    fn settings(&self) -> TaskSettings {
        TaskSettings::STANDARD
    }

    fn hyper(&self) -> Hyper<f64> {
        Shadow.hyper()
    }

    fn budget(&self, quick: bool) -> usize {
        if quick { 100 } else { 1500 }
    }

    fn scene(&self) -> Result<Box<dyn ParametricScene>, RenderError> {
        let x = Vec3::new(1.0, 0.0, 0.0);
        let y = Vec3::new(0.0, 1.0, 0.0);
        let z = Vec3::new(0.0, 0.0, 1.0);
        let camera = Camera::look_at(Vec3::new(0.0, -3.9, 1.0), Vec3::new(0.0, 0.0, 1.0), z, 40.0)?;
        let mut scene = Scene::new(camera);
        let white = scene.add_material(Material::diffuse(Rgb::splat(0.73)));
        let red = scene.add_material(Material::diffuse(Rgb::new(0.63, 0.065, 0.05)));
        let green = scene.add_material(Material::diffuse(Rgb::new(0.14, 0.45, 0.091)));
        let black = scene.add_material(Material::Black);
        // Walls, each facing into the room (normal = u × v).
        let walls = [
            (Vec3::new(0.0, 0.0, 0.0), x, y, white),  // floor, +z
            (Vec3::new(0.0, 0.0, 2.0), x, -y, white), // ceiling, −z
            (Vec3::new(0.0, 1.0, 1.0), x, z, white),  // back, −y
            (Vec3::new(-1.0, 0.0, 1.0), y, z, red),   // left, +x
            (Vec3::new(1.0, 0.0, 1.0), z, y, green),  // right, −x
        ];
        for (center, u, v, material) in walls {
            scene.add_object(Object::new(
                Shape::Quad(Quad::centered(center, u, v, (2.0, 2.0))?),
                material,
            ));
        }
        let light = Quad::centered(Vec3::new(0.0, 0.0, 1.98), x, -y, (0.5, 0.4))?;
        scene.add_object(
            Object::new(Shape::Quad(light), black)
                .with_emitter(Emitter::new(Rgb::new(17.0, 12.0, 4.0))),
        );
        scene.add_object(Object::new(
            Shape::Cuboid(Cuboid {
                half: Vec3::new(0.3, 0.3, 0.6),
                transform: Transform::rotation_z(0.3)
                    .then(&Transform::translation(Vec3::new(-0.35, 0.35, 0.6))),
            }),
            white,
        ));
        let small_box = scene.add_object(Object::new(
            Shape::Cuboid(Cuboid {
                half: Vec3::splat(SMALL_BOX_HALF),
                transform: Transform::IDENTITY,
            }),
            white,
        ));
        scene.set_depth(Depth {
            max: Some(6),
            roulette: 4,
        });
        let mut s = CboxScene { scene, small_box };
        s.set_params(&self.true_params())?;
        Ok(Box::new(s))
    }
}
