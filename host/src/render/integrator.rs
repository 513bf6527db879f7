//! The path tracer: unidirectional path tracing with next-event estimation (NEE),
//! multiple importance sampling (MIS, power heuristic), Russian roulette and a maximum
//! depth; parallel over image rows with rayon.
//!
//! For a path x₀ (camera) → x₁ → x₂ …, the estimator adds at each vertex xₖ
//! * emission seen by the BSDF-sampled ray: β·Le·w_bsdf, with w_bsdf = 1 after the
//!   camera or a specular bounce, else p_bsdf²/(p_bsdf² + p_light²);
//! * at diffuse vertices, NEE: one light picked uniformly, a point y on it,
//!   β·f·Le·cos θ·w_light/p_light if the segment xₖ → y is unblocked;
//!
//! and continues with β ← β·f·cos θ/p (ρ for Lambert). Path depth counts segments as in
//! Mitsuba 3 (see [`super::Depth`]). From depth `roulette` on, a path survives with
//! probability q = min(max channel of β, 0.95) and β is divided by q.
//!
//! With the plan's `light_paths`, a path whose first vertex is diffuse and which then
//! meets only specular vertices before an emitter adds nothing: the light pass
//! ([`super::light_tracer`]) traces those caustic paths from the lights and adds them
//! after the camera pass.
//!
//! **Determinism.** Sample n of pixel p in a frame with seed s uses the numbers
//! [`PixelSampler::new`]`(s, p, spp).sample(n)`; dimensions 0–1 jitter the pixel (box
//! filter) and each vertex k ≥ 1 owns dimensions b … b + 5, b = 2 + 6(k − 1): the light
//! point (b, b + 1), the BSDF direction (b + 2, b + 3), the light choice (b + 4) and
//! roulette (b + 5). The 2-D integrands start at even dimensions, so at the first vertex
//! each is one of the padded sequences' 2-D point sets. Pixels are independent, so the
//! image is bit-identical at any thread count.
//!
//! **Self-intersection.** Rays start 1e-4·(1 + max |coordinate|) off the surface along
//! the geometric normal, and a ray leaving a plane (or a convex solid outwards) does not
//! test that object at all ([`Shape::cannot_rehit`]), which also saves the test.
//!
//! **Robustness.** A sample whose radiance is not finite is dropped (counted as black)
//! and pixel values are clamped to the finite `f32` range: no pixel is NaN or infinite.
//!
//! **Allocation.** Rendering writes into the caller's [`Film`]; the integrator itself
//! allocates nothing (rayon's scheduler manages its own job queues).

use std::f32::consts::FRAC_1_PI;

use rayon::prelude::*;

use super::error::RenderError;
use super::film::Film;
use super::light::{Light, power_heuristic, sample_area};
use super::light_tracer::{CHUNKS, add_caustics};
use super::material::{Albedo, Material, reflect, sample_cosine, sample_dielectric};
use super::math::{Ray, Rgb, Vec3};
use super::plan::Plan;
use super::sampler::{PixelSampler, SampleStream};
use super::scene::{NO_OBJECT, Scene};
use super::shape::Shape;

/// Dimensions each path vertex owns in the sample stream, and their offsets.
const DIMS_PER_VERTEX: usize = 6;
const DIM_LIGHT_POINT: usize = 0;
const DIM_BSDF: usize = 2;
const DIM_LIGHT_CHOICE: usize = 4;
const DIM_ROULETTE: usize = 5;
/// Survival probability cap for Russian roulette (camera and light paths).
pub(super) const MAX_SURVIVAL: f32 = 0.95;

/// Renders `scene` into `film` with `spp` samples per pixel and frame seed `seed`, using
/// the scene's own [`Plan`].
///
/// # Errors
/// [`RenderError::ZeroSamples`], [`RenderError::NotCommitted`].
pub fn render(scene: &Scene, film: &mut Film, spp: u32, seed: u64) -> Result<(), RenderError> {
    render_with_plan(scene, &scene.plan(), film, spp, seed)
}

/// As [`render`], with an explicit plan (e.g. [`Plan::general`] to measure what
/// specialisation saves). A plan that switches off a stage the scene needs gives a
/// wrong image, not an error.
///
/// # Errors
/// [`RenderError::ZeroSamples`], [`RenderError::NotCommitted`].
pub fn render_with_plan(
    scene: &Scene,
    plan: &Plan,
    film: &mut Film,
    spp: u32,
    seed: u64,
) -> Result<(), RenderError> {
    if spp == 0 {
        return Err(RenderError::ZeroSamples);
    }
    if !scene.is_committed() {
        return Err(RenderError::NotCommitted);
    }
    if scene.lights().is_empty() {
        film.data_mut().fill(0.0);
        return Ok(());
    }
    match (plan.next_event, plan.emission, plan.direct_last) {
        (true, true, true) => run::<true, true, true>(scene, plan, film, spp, seed),
        (true, true, false) => run::<true, true, false>(scene, plan, film, spp, seed),
        (true, false, true) => run::<true, false, true>(scene, plan, film, spp, seed),
        (true, false, false) => run::<true, false, false>(scene, plan, film, spp, seed),
        (false, true, true) => run::<false, true, true>(scene, plan, film, spp, seed),
        (false, true, false) => run::<false, true, false>(scene, plan, film, spp, seed),
        (false, false, _) => film.data_mut().fill(0.0),
    }
    if plan.light_paths {
        let (width, height) = (film.width(), film.height());
        let paths = u64::from(spp) * u64::from(width) * u64::from(height);
        let len = 3 * width as usize * height as usize;
        let (image, scratch) = film.data_and_scratch(CHUNKS * len);
        add_caustics(scene, plan, image, scratch, (width, height), paths, seed);
        for v in image.iter_mut() {
            *v = v.clamp(-f32::MAX, f32::MAX);
        }
    }
    Ok(())
}

fn run<const NEE: bool, const EMIT: bool, const DIRECT_LAST: bool>(
    scene: &Scene,
    plan: &Plan,
    film: &mut Film,
    spp: u32,
    seed: u64,
) {
    let (width, height) = (film.width(), film.height());
    let inv_spp = 1.0 / spp as f32;
    let sequence = scene.sequence();
    film.data_mut()
        .par_chunks_mut(3 * width as usize)
        .enumerate()
        .for_each(|(y, row)| {
            for (x, out) in row.chunks_exact_mut(3).enumerate() {
                let pixel = y as u64 * u64::from(width) + x as u64;
                let sampler = PixelSampler::new(sequence, seed, pixel, spp);
                let mut sum = Rgb::ZERO;
                for n in 0..spp {
                    let stream = sampler.sample(n);
                    let (jx, jy) = stream.get2(0);
                    let ray = scene
                        .camera()
                        .ray(x as f32 + jx, y as f32 + jy, width, height);
                    let l = trace::<NEE, EMIT, DIRECT_LAST>(scene, plan, ray, &stream);
                    if l.is_finite() {
                        sum += l;
                    }
                }
                let v = sum * inv_spp;
                out[0] = v.x.clamp(-f32::MAX, f32::MAX);
                out[1] = v.y.clamp(-f32::MAX, f32::MAX);
                out[2] = v.z.clamp(-f32::MAX, f32::MAX);
            }
        });
}

/// Offset for spawning rays: 1e-4 of the larger of 1 and the point's largest coordinate.
#[inline]
pub(super) fn spawn(p: Vec3, n: Vec3) -> Vec3 {
    p + n * (1e-4 * (1.0 + p.max_abs_component()))
}

/// The radiance carried back along `ray` by one path.
#[inline]
fn trace<const NEE: bool, const EMIT: bool, const DIRECT_LAST: bool>(
    scene: &Scene,
    plan: &Plan,
    mut ray: Ray,
    stream: &SampleStream,
) -> Rgb {
    let max_depth = scene.depth().max.unwrap_or(u32::MAX);
    let roulette = scene.depth().roulette;
    let mut radiance = Rgb::ZERO;
    let mut beta = Rgb::ONE;
    // The camera counts as a specular "bounce": emitters seen directly get full weight.
    let mut specular = true;
    let mut bsdf_pdf = 0.0f32;
    let mut depth = 1u32;
    // The path left the first vertex, diffuse, and met only specular vertices since: an
    // emitter it reaches closes a caustic path, the light pass's when the plan has one.
    let mut caustic = false;
    // The object the current ray leaves, when it cannot hit it again.
    let mut skip = NO_OBJECT;
    while let Some(hit) = scene.intersect(&ray, f32::INFINITY, skip, plan.bvh) {
        let object = &scene.objects()[hit.object as usize];
        let material = scene.materials()[object.material as usize];
        let want_uv = plan.textures && matches!(material, Material::Diffuse(Albedo::Texture(_)));
        let surface = object.shape.surface(&ray, &hit, want_uv);
        let wo = -ray.dir;

        if EMIT
            && let Some(emitter) = &object.emitter
            && !(specular && caustic)
        {
            let le = emitter.radiance_towards(surface.ng, wo);
            if !le.is_black() {
                let weight = if specular || !NEE {
                    1.0
                } else {
                    // Ray directions are unit, so t is the distance.
                    let cos_l = surface.ng.dot(wo).abs();
                    let pick = 1.0 / scene.lights().len() as f32;
                    let light_pdf = pick * hit.t * hit.t / (cos_l * scene.emitter_area(hit.object));
                    power_heuristic(bsdf_pdf, light_pdf)
                };
                radiance += beta * le * weight;
            }
        }
        if depth >= max_depth {
            break;
        }
        let base = 2 + DIMS_PER_VERTEX * (depth as usize - 1);
        // Normals on the side of the outgoing direction.
        let flip = surface.ng.dot(wo) < 0.0;
        let (ng, ns) = if flip {
            (-surface.ng, -surface.ns)
        } else {
            (surface.ng, surface.ns)
        };

        match material {
            Material::Black => break,
            Material::Diffuse(albedo) => {
                let rho = scene.albedo(albedo, surface.uv);
                let last = DIRECT_LAST && depth + 1 >= max_depth;
                if NEE {
                    // Shadow rays leave on the `ng` side.
                    let own = if object.shape.cannot_rehit(surface.ng, ng) {
                        hit.object
                    } else {
                        NO_OBJECT
                    };
                    let at = Vertex {
                        p: surface.p,
                        ng,
                        ns,
                        own,
                    };
                    radiance += beta * rho * direct(scene, plan, &at, stream, base, last);
                }
                if last {
                    break;
                }
                let (u1, u2) = stream.get2(base + DIM_BSDF);
                let (wi, pdf) = sample_cosine(ns, u1, u2);
                if wi.dot(ng) <= 0.0 || pdf <= 0.0 {
                    break;
                }
                beta *= rho;
                specular = false;
                caustic = plan.light_paths && depth == 1;
                bsdf_pdf = pdf;
                ray = Ray::new(spawn(surface.p, ng), wi);
            }
            Material::Mirror(reflectance) => {
                let wi = reflect(wo, ns);
                if wi.dot(ng) <= 0.0 {
                    break;
                }
                beta *= reflectance;
                specular = true;
                ray = Ray::new(spawn(surface.p, ng), wi);
            }
            Material::Dielectric { ior } => {
                let s = sample_dielectric(wo, surface.ns, ior, stream.get(base + DIM_BSDF));
                beta *= s.weight;
                specular = true;
                let side = if s.wi.dot(surface.ng) >= 0.0 {
                    surface.ng
                } else {
                    -surface.ng
                };
                ray = Ray::new(spawn(surface.p, side), s.wi);
            }
        }
        skip = if object.shape.cannot_rehit(surface.ng, ray.dir) {
            hit.object
        } else {
            NO_OBJECT
        };
        if depth >= roulette {
            let q = beta.max_component().min(MAX_SURVIVAL);
            // q is never NaN: β is finite (non-finite samples are dropped later anyway).
            if stream.get(base + DIM_ROULETTE) >= q {
                break;
            }
            beta *= 1.0 / q;
        }
        depth += 1;
    }
    radiance
}

/// A diffuse path vertex, as NEE needs it.
struct Vertex {
    /// Position.
    p: Vec3,
    /// Geometric normal on the side of the outgoing direction.
    ng: Vec3,
    /// Shading normal on the same side.
    ns: Vec3,
    /// The vertex's object if shadow rays cannot hit it again, else [`NO_OBJECT`].
    own: u32,
}

/// The unit direction from `origin` to `target`, the distance and its square; `None`
/// when the points coincide.
#[inline(always)]
pub(super) fn towards(origin: Vec3, target: Vec3) -> Option<(Vec3, f32, f32)> {
    let d = target - origin;
    let dist2 = d.length_squared();
    if dist2 <= 0.0 {
        return None;
    }
    let dist = dist2.sqrt();
    Some((d / dist, dist, dist2))
}

/// NEE at a diffuse vertex: Le·cos θ·w/(π·p_light) for one sampled light, or 0 if it is
/// blocked or behind. The caller multiplies by β·ρ.
#[inline]
fn direct(
    scene: &Scene,
    plan: &Plan,
    at: &Vertex,
    stream: &SampleStream,
    base: usize,
    full_weight: bool,
) -> Rgb {
    let Vertex { p, ng, ns, own } = *at;
    let lights = scene.lights();
    let count = lights.len();
    if count == 0 {
        return Rgb::ZERO;
    }
    let light = if count == 1 {
        lights[0]
    } else {
        lights[((stream.get(base + DIM_LIGHT_CHOICE) * count as f32) as usize).min(count - 1)]
    };
    let pick = 1.0 / count as f32;
    let origin = spawn(p, ng);
    match light {
        Light::Area { object, area } => {
            let emitter_object = &scene.objects()[object as usize];
            let (u1, u2) = stream.get2(base + DIM_LIGHT_POINT);
            let (y, ny) = sample_area(&emitter_object.shape, u1, u2);
            let Some((wi, dist, dist2)) = towards(origin, y) else {
                return Rgb::ZERO;
            };
            let cos_s = ns.dot(wi);
            let cos_l = ny.dot(wi).abs();
            if cos_s <= 0.0 || ng.dot(wi) <= 0.0 || cos_l <= 0.0 {
                return Rgb::ZERO;
            }
            let Some(emitter) = emitter_object.emitter else {
                return Rgb::ZERO;
            };
            let le = emitter.radiance_towards(ny, -wi);
            if le.is_black() {
                return Rgb::ZERO;
            }
            // A planar emitter cannot block a segment that ends on it.
            let target = if matches!(emitter_object.shape, Shape::Quad(_)) {
                object
            } else {
                NO_OBJECT
            };
            let shadow = Ray::new(origin, wi);
            if scene.occluded(&shadow, dist * (1.0 - 1e-4), (own, target), plan.bvh) {
                return Rgb::ZERO;
            }
            let light_pdf = pick * dist2 / (cos_l * area);
            let weight = if full_weight {
                1.0
            } else {
                power_heuristic(light_pdf, cos_s * FRAC_1_PI)
            };
            le * (cos_s * FRAC_1_PI * weight / light_pdf)
        }
        Light::Point(point) => {
            let Some((wi, dist, dist2)) = towards(origin, point.position) else {
                return Rgb::ZERO;
            };
            let cos_s = ns.dot(wi);
            if cos_s <= 0.0 || ng.dot(wi) <= 0.0 {
                return Rgb::ZERO;
            }
            let shadow = Ray::new(origin, wi);
            if scene.occluded(&shadow, dist * (1.0 - 1e-4), (own, NO_OBJECT), plan.bvh) {
                return Rgb::ZERO;
            }
            point.intensity * (cos_s * FRAC_1_PI / (dist2 * pick))
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::tasks;

    /// The same frame seed gives bit-identical images on 1 and 2 threads (and a
    /// different seed a different image), for an analytic scene and a mesh scene.
    #[test]
    fn deterministic_across_thread_counts() {
        for name in ["SHADOW", "CAUSTIC"] {
            let task = tasks::by_name(name).unwrap();
            let scene = task.scene().unwrap();
            let frames: Vec<Film> = [1usize, 2, 2]
                .iter()
                .enumerate()
                .map(|(k, &threads)| {
                    let pool = rayon::ThreadPoolBuilder::new()
                        .num_threads(threads)
                        .build()
                        .unwrap();
                    let mut film = Film::new(12, 10).unwrap();
                    let seed = if k == 2 { 8 } else { 7 };
                    pool.install(|| render(scene.scene(), &mut film, 3, seed))
                        .unwrap();
                    film
                })
                .collect();
            assert_eq!(frames[0].data(), frames[1].data(), "{name}");
            assert_ne!(frames[1].data(), frames[2].data(), "{name}");
        }
    }

    #[test]
    fn zero_spp_and_uncommitted_scenes_are_errors() {
        let task = tasks::by_name("SHADOW").unwrap();
        let scene = task.scene().unwrap();
        let mut film = Film::new(2, 2).unwrap();
        assert!(matches!(
            render(scene.scene(), &mut film, 0, 0),
            Err(RenderError::ZeroSamples)
        ));
        let mut edited = scene.scene().clone();
        edited.set_depth(crate::render::Depth::default());
        assert!(matches!(
            render(&edited, &mut film, 1, 0),
            Err(RenderError::NotCommitted)
        ));
    }
}
