//! The light pass: caustic paths traced from the lights and splatted into the film.
//!
//! A caustic path runs light → one or more specular vertices (mirror, dielectric) → a
//! diffuse surface point x the camera sees directly → the camera. The light pass draws
//! P = spp·width·height such paths from the lights ([`super::Plan`]'s `light_paths`;
//! camera paths then leave these paths out, so each is counted once):
//!
//! * a light uniformly (probability 1/L for L lights; point lights send none: no camera
//!   path can reach them through a specular chain either), a point y on it uniformly by
//!   area A, and a direction ω uniformly within the cone from y about the sphere that
//!   bounds every specular object (solid angle Ω = 2π(1 − cos α), sin α = r/‖c − y‖;
//!   the whole sphere of directions, Ω = 4π, when y lies inside it): a path leaving
//!   outside the cone meets no specular object first. The path starts with the flux
//!   weight β = L·Le·|cos θ_y|·A·Ω, zero towards the side a one-sided emitter does not
//!   light;
//! * at a specular vertex the scattered direction is sampled as camera paths sample it
//!   (reflection with probability F), β unchanged but for a mirror's reflectance and
//!   the adjoint shading-normal factor |ωₒ·nₛ|·|ωᵢ·n_g|/(|ωₒ·n_g|·|ωᵢ·nₛ|) (ωₒ towards
//!   the light, ωᵢ onwards); flux crossing a dielectric is not rescaled by η², the
//!   factor radiance carries, whose product over a path from air to air is one;
//! * at the first diffuse point x after at least one specular vertex the path is joined
//!   to the camera if nothing blocks the segment, adding
//!   β·(ρ/π)·(ωₒ·nₛ)/(ωₒ·n_g)·|cos θₓ|·W/(P·d²) at the raster position it projects to
//!   (W the pixel's importance, [`super::Camera::raster`]; d and θₓ the distance and
//!   angle to the camera), and ends there. A path that meets a diffuse surface first
//!   ends without a contribution.
//! * The value is shared among the pixels whose centres lie within one pixel of that
//!   position along both axes, by the tent filter (1 − |Δx|)(1 − |Δy|), where camera
//!   paths average over their pixel (a box). A path's share then moves continuously as
//!   θ moves the point it lands on, so that on one noise seed the image, and a loss of
//!   it, changes continuously with θ where a box would make it jump as paths cross
//!   pixel borders; the price is a caustic blurred by the tent's one pixel. The image's
//!   sum is the box filter's but for paths landing within a pixel of its border.
//!
//! Path depth counts segments as camera paths do, the segment to the camera included,
//! and Russian roulette from depth `roulette` keeps a path with probability
//! q = min(max channel of β/β₀, 0.95).
//!
//! **Determinism.** The P paths are split into [`CHUNKS`] fixed chunks; path i of chunk
//! k draws its numbers from [`PixelSampler::new`]`(s′, k, count).sample(i)`, s′ the frame
//! seed mixed with a constant, and each chunk splats into its own image in the film's
//! scratch. The images are then summed in chunk order, so the film is bit-identical at
//! any thread count. Dimensions: the light point 0–1, the direction 2–3, the light
//! choice 4, and per specular vertex j ≥ 1 the reflection choice 5 + 2(j − 1) and
//! roulette 6 + 2(j − 1).

use std::f32::consts::{FRAC_1_PI, PI};

use rayon::prelude::*;

use super::integrator::{MAX_SURVIVAL, spawn, towards};
use super::light::{Light, sample_area, uniform_sphere};
use super::material::{Albedo, Material, reflect, sample_dielectric};
use super::math::{Frame, Ray, Rgb, Vec3};
use super::plan::Plan;
use super::sampler::{PixelSampler, SampleStream, mix64};
use super::scene::{NO_OBJECT, Scene};

/// Chunks the light pass's paths are split into (fixed, for determinism).
pub const CHUNKS: usize = 16;

/// Mixed into the frame seed so that the light pass's numbers are not the camera pass's.
const SEED_SALT: u64 = 0x4C49_4748_5450_4153;

const DIM_LIGHT_POINT: usize = 0;
const DIM_DIRECTION: usize = 2;
const DIM_LIGHT_CHOICE: usize = 4;
const DIM_FIRST_VERTEX: usize = 5;

/// Adds the light pass of `paths` paths, for frame seed `seed`, to `image` (the film's
/// `width` × `height` data, R, G, B per pixel), using `scratch` (at least
/// [`CHUNKS`]·3·width·height floats) for the chunks' images.
pub(super) fn add_caustics(
    scene: &Scene,
    plan: &Plan,
    image: &mut [f32],
    scratch: &mut [f32],
    (width, height): (u32, u32),
    paths: u64,
    seed: u64,
) {
    let Some(bound) = scene.specular_bound() else {
        return;
    };
    let len = image.len();
    let sequence = scene.sequence();
    let seed = mix64(seed ^ SEED_SALT);
    let scale = 1.0 / paths as f32;
    scratch[..CHUNKS * len]
        .par_chunks_mut(len)
        .enumerate()
        .for_each(|(chunk, splats)| {
            splats.fill(0.0);
            let first = paths * chunk as u64 / CHUNKS as u64;
            let count = (paths * (chunk as u64 + 1) / CHUNKS as u64 - first) as u32;
            let sampler = PixelSampler::new(sequence, seed, chunk as u64, count);
            for i in 0..count {
                let stream = sampler.sample(i);
                if let Some(((x, y), value)) = trace(scene, plan, bound, &stream, width, height) {
                    let value = value * scale;
                    if value.is_finite() {
                        splat(splats, width, height, x, y, value);
                    }
                }
            }
        });
    let scratch = &scratch[..CHUNKS * len];
    image
        .par_chunks_mut(3 * width as usize)
        .enumerate()
        .for_each(|(row, out)| {
            let (start, end) = (row * out.len(), (row + 1) * out.len());
            for chunk in scratch.chunks_exact(len) {
                for (o, &v) in out.iter_mut().zip(&chunk[start..end]) {
                    *o += v;
                }
            }
        });
}

/// Adds `value` at raster position (x, y) with the tent filter: to the (up to) four
/// pixels whose centres lie within one pixel of it along both axes, each with weight
/// (1 − |Δx|)(1 − |Δy|).
#[inline]
fn splat(image: &mut [f32], width: u32, height: u32, x: f32, y: f32, value: Rgb) {
    let (fx, fy) = (x - 0.5, y - 0.5);
    let (x0, y0) = (fx.floor(), fy.floor());
    let (tx, ty) = (fx - x0, fy - y0);
    for (dy, wy) in [(0, 1.0 - ty), (1, ty)] {
        let row = y0 as i64 + dy;
        if row < 0 || row >= i64::from(height) {
            continue;
        }
        for (dx, wx) in [(0, 1.0 - tx), (1, tx)] {
            let col = x0 as i64 + dx;
            if col < 0 || col >= i64::from(width) {
                continue;
            }
            let k = 3 * (row as usize * width as usize + col as usize);
            let v = value * (wx * wy);
            image[k] += v.x;
            image[k + 1] += v.y;
            image[k + 2] += v.z;
        }
    }
}

/// One light path: the raster position it lands at and the value it adds there (before
/// the 1/P), or `None`.
#[inline]
fn trace(
    scene: &Scene,
    plan: &Plan,
    (centre, radius): (Vec3, f32),
    stream: &SampleStream,
    width: u32,
    height: u32,
) -> Option<((f32, f32), Rgb)> {
    let lights = scene.lights();
    let count = lights.len();
    let choice = ((stream.get(DIM_LIGHT_CHOICE) * count as f32) as usize).min(count - 1);
    let Light::Area { object, area } = lights[choice] else {
        return None;
    };
    let emitter_object = &scene.objects()[object as usize];
    let emitter = emitter_object.emitter?;
    let (u1, u2) = stream.get2(DIM_LIGHT_POINT);
    let (y, ny) = sample_area(&emitter_object.shape, u1, u2);
    let (u1, u2) = stream.get2(DIM_DIRECTION);
    let (dir, solid_angle) = match towards(y, centre) {
        Some((axis, dist, _)) if dist > radius => {
            let cos_max = (1.0 - (radius / dist) * (radius / dist)).max(0.0).sqrt();
            let cos = 1.0 - u1 * (1.0 - cos_max);
            let sin = (1.0 - cos * cos).max(0.0).sqrt();
            let (s, c) = (2.0 * PI * u2).sin_cos();
            let local = Vec3::new(sin * c, sin * s, cos);
            (
                Frame::from_normal(axis).to_world(local),
                2.0 * PI * (1.0 - cos_max),
            )
        }
        _ => (uniform_sphere(u1, u2), 4.0 * PI),
    };
    let le = emitter.radiance_towards(ny, dir);
    let cos_y = ny.dot(dir).abs();
    if le.is_black() || cos_y <= 0.0 {
        return None;
    }
    let mut beta = le * (count as f32 * cos_y * area * solid_angle);
    let power = beta.max_component();
    let side = if ny.dot(dir) > 0.0 { ny } else { -ny };
    let mut ray = Ray::new(spawn(y, side), dir);
    let mut skip = if emitter_object.shape.cannot_rehit(side, dir) {
        object
    } else {
        NO_OBJECT
    };
    let max_depth = scene.depth().max.unwrap_or(u32::MAX);
    let roulette = scene.depth().roulette;
    // Segments traced so far, and specular vertices met.
    let mut segments = 0u32;
    let mut specular = 0usize;
    while let Some(hit) = scene.intersect(&ray, f32::INFINITY, skip, plan.bvh) {
        segments += 1;
        let object = &scene.objects()[hit.object as usize];
        let material = scene.materials()[object.material as usize];
        let want_uv = plan.textures && matches!(material, Material::Diffuse(Albedo::Texture(_)));
        let surface = object.shape.surface(&ray, &hit, want_uv);
        let wo = -ray.dir;
        let base = DIM_FIRST_VERTEX + 2 * specular;
        match material {
            Material::Black => return None,
            Material::Diffuse(albedo) => {
                if specular == 0 || segments + 1 > max_depth {
                    return None;
                }
                let rho = scene.albedo(albedo, surface.uv);
                return join_camera(
                    scene,
                    plan,
                    &surface_at(&surface, wo),
                    hit.object,
                    width,
                    height,
                )
                .map(|(at, factor)| (at, beta * rho * factor));
            }
            Material::Mirror(reflectance) => {
                let ns = oriented(surface.ns, wo);
                let ng = oriented(surface.ng, wo);
                let wi = reflect(wo, ns);
                if wi.dot(ng) <= 0.0 {
                    return None;
                }
                beta *= reflectance * adjoint_shading(wo, wi, ns, ng);
                ray = Ray::new(spawn(surface.p, ng), wi);
            }
            Material::Dielectric { ior } => {
                let s = sample_dielectric(wo, surface.ns, ior, stream.get(base));
                let ng = if s.wi.dot(surface.ng) >= 0.0 {
                    surface.ng
                } else {
                    -surface.ng
                };
                beta *= adjoint_shading(wo, s.wi, surface.ns, surface.ng);
                ray = Ray::new(spawn(surface.p, ng), s.wi);
            }
        }
        specular += 1;
        // The next vertex must still be able to join the camera.
        if segments + 2 > max_depth {
            return None;
        }
        skip = if object.shape.cannot_rehit(surface.ng, ray.dir) {
            hit.object
        } else {
            NO_OBJECT
        };
        if segments >= roulette {
            let q = (beta.max_component() / power).min(MAX_SURVIVAL);
            if stream.get(base + 1) >= q {
                return None;
            }
            beta *= 1.0 / q;
        }
    }
    None
}

/// `n` turned to the side of `w`.
#[inline(always)]
fn oriented(n: Vec3, w: Vec3) -> Vec3 {
    if n.dot(w) < 0.0 { -n } else { n }
}

/// The adjoint shading-normal factor |wo·ns|·|wi·ng| / (|wo·ng|·|wi·ns|) (1 where a
/// cosine vanishes).
#[inline(always)]
fn adjoint_shading(wo: Vec3, wi: Vec3, ns: Vec3, ng: Vec3) -> f32 {
    let num = wo.dot(ns).abs() * wi.dot(ng).abs();
    let den = wo.dot(ng).abs() * wi.dot(ns).abs();
    if num > 0.0 && den > 0.0 {
        num / den
    } else {
        1.0
    }
}

/// A diffuse point reached by a light path: position and both normals on the side the
/// light arrived from (`wo`), with `wo` itself.
struct Arrival {
    p: Vec3,
    ng: Vec3,
    ns: Vec3,
    wo: Vec3,
}

#[inline(always)]
fn surface_at(surface: &super::shape::Surface, wo: Vec3) -> Arrival {
    let flip = surface.ng.dot(wo) < 0.0;
    let (ng, ns) = if flip {
        (-surface.ng, -surface.ns)
    } else {
        (surface.ng, surface.ns)
    };
    Arrival {
        p: surface.p,
        ng,
        ns,
        wo,
    }
}

/// Joins a diffuse point to the camera: its pixel and (ωₒ·nₛ)/(ωₒ·n_g)·|cos θₓ|·W/(π·d²),
/// or `None` when the camera lies on the other side, off the image, or behind an object
/// (the conditions under which a camera path would have reached the point and left it
/// towards ωₒ).
#[inline]
fn join_camera(
    scene: &Scene,
    plan: &Plan,
    at: &Arrival,
    object: u32,
    width: u32,
    height: u32,
) -> Option<((f32, f32), f32)> {
    let camera = scene.camera();
    let (wc, dist, dist2) = towards(at.p, camera.origin())?;
    let cos_x = at.ng.dot(wc);
    let cos_in = at.ns.dot(at.wo);
    if cos_x <= 0.0 || cos_in <= 0.0 {
        return None;
    }
    let (x, y, importance) = camera.raster(-wc, width, height)?;
    // Off the image by more than the splat's reach (one pixel).
    if !(x > -1.0 && x < width as f32 + 1.0 && y > -1.0 && y < height as f32 + 1.0) {
        return None;
    }
    let own = if scene.objects()[object as usize]
        .shape
        .cannot_rehit(at.ng, wc)
    {
        object
    } else {
        NO_OBJECT
    };
    let shadow = Ray::new(spawn(at.p, at.ng), wc);
    if scene.occluded(&shadow, dist * (1.0 - 1e-4), (own, NO_OBJECT), plan.bvh) {
        return None;
    }
    let factor = cos_in / at.ng.dot(at.wo) * cos_x * importance * FRAC_1_PI / dist2;
    Some(((x, y), factor))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::render::{
        Camera, Depth, Emitter, Film, Object, Quad, Shape, Sphere, render_with_plan,
    };
    use crate::tasks;

    /// Per-frame image means of `frames` renders with `plan`: their mean and variance.
    fn frame_means(scene: &Scene, plan: &Plan, size: u32, spp: u32, frames: u64) -> (f64, f64) {
        let mut film = Film::new(size, size).unwrap();
        let means: Vec<f64> = (0..frames)
            .map(|seed| {
                render_with_plan(scene, plan, &mut film, spp, seed).unwrap();
                film.data().iter().map(|&v| f64::from(v)).sum::<f64>() / film.data().len() as f64
            })
            .collect();
        let mean = means.iter().sum::<f64>() / frames as f64;
        let var = means.iter().map(|m| (m - mean).powi(2)).sum::<f64>() / (frames - 1) as f64;
        (mean, var)
    }

    /// With the light pass the image's mean is the path tracer's in expectation (the
    /// means over `frames` frame seeds agree within 4 standard errors of their
    /// difference), and its variance over frame seeds is at least `gain` times lower.
    fn check_same_image(scene: &Scene, size: u32, spp: u32, frames: u64, gain: f64) {
        let plan = scene.plan();
        assert!(plan.light_paths);
        let (path, path_var) = frame_means(scene, &Plan::general(), size, spp, frames);
        let (light, light_var) = frame_means(scene, &plan, size, spp, frames);
        let se = ((path_var + light_var) / frames as f64).sqrt();
        assert!(
            (path - light).abs() < 4.0 * se,
            "path {path} ± {}, light {light} ± {}",
            (path_var / frames as f64).sqrt(),
            (light_var / frames as f64).sqrt()
        );
        assert!(light_var * gain < path_var, "{light_var} {path_var}");
    }

    #[test]
    fn glass_caustics_match_the_path_tracer() {
        let task = tasks::by_name("CAUSTIC").unwrap();
        let scene = task.scene().unwrap();
        check_same_image(scene.scene(), 16, 16, 200, 4.0);
    }

    /// A floor lit by a light above it, beside a mirror wall and under a glass ball.
    fn mirror_and_ball() -> Scene {
        let x = Vec3::new(1.0, 0.0, 0.0);
        let y = Vec3::new(0.0, 1.0, 0.0);
        let z = Vec3::new(0.0, 0.0, 1.0);
        let camera = Camera::look_at(Vec3::new(0.0, -4.0, 3.0), Vec3::ZERO, z, 50.0).unwrap();
        let mut scene = Scene::new(camera);
        let floor = scene.add_material(Material::diffuse(Rgb::new(0.8, 0.6, 0.4)));
        let mirror = scene.add_material(Material::Mirror(Rgb::splat(0.5)));
        let glass = scene.add_material(Material::Dielectric { ior: 1.5 });
        let black = scene.add_material(Material::Black);
        let quad = |centre, u, v, size| Shape::Quad(Quad::centered(centre, u, v, size).unwrap());
        scene.add_object(Object::new(quad(Vec3::ZERO, x, y, (4.0, 4.0)), floor));
        // The wall at x = 1.5 faces −x (y × z = x, so z × y).
        scene.add_object(Object::new(
            quad(Vec3::new(1.5, 0.0, 1.0), z, y, (2.0, 4.0)),
            mirror,
        ));
        scene.add_object(Object::new(
            Shape::Sphere(Sphere {
                center: Vec3::new(-0.7, 0.3, 0.8),
                radius: 0.4,
            }),
            glass,
        ));
        let light = quad(Vec3::new(0.8, 0.0, 2.0), x, -y, (0.6, 0.6));
        scene.add_object(Object::new(light, black).with_emitter(Emitter::new(Rgb::splat(20.0))));
        scene.set_depth(Depth {
            max: Some(5),
            roulette: 3,
        });
        scene.commit().unwrap();
        scene
    }

    #[test]
    fn mirror_and_ball_caustics_match_the_path_tracer() {
        check_same_image(&mirror_and_ball(), 16, 16, 200, 1.5);
    }

    /// Scenes without a specular object or without an area light have no light pass.
    #[test]
    fn only_scenes_with_caustics_get_a_light_pass() {
        for name in ["SHADOW", "MUG", "CBOX", "TEXTURE"] {
            let task = tasks::by_name(name).unwrap();
            assert!(!task.scene().unwrap().scene().plan().light_paths, "{name}");
        }
    }
}
