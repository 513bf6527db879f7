//! Scene specialisation: which integrator stages a scene needs.
//!
//! [`Plan::inspect`] looks at a committed scene once and switches off every stage it
//! cannot use. The integrator is instantiated (monomorphised) per combination of the
//! three `const` switches, so a switched-off stage costs nothing — not even a branch —
//! in the per-sample loop; the other two are plain branches that predict perfectly.
//!
//! | stage | kept when | saves |
//! |---|---|---|
//! | `next_event` (light sampling, shadow rays) | the scene has a light | the shadow ray and light sample per vertex |
//! | `emission` (emitter lookup and MIS on hit) | the scene has an area emitter | the emitter test per hit |
//! | `direct_last` (NEE only, no BSDF ray, at the last vertex) | always valid | one ray cast per path |
//! | `textures` (texture coordinates and fetches) | a material reads a texture | uv computation per hit |
//! | `bvh` (object hierarchy instead of a list) | more than [`LIST_MAX_OBJECTS`] objects | box tests for small scenes |
//! | `light_paths` (caustics traced from the lights) | the scene has an area light and a specular object | the caustics' noise (below) |
//!
//! `direct_last`: at the last vertex that may scatter (depth = max − 1), a diffuse vertex
//! only lights by NEE with full weight and the path ends there; the general plan also
//! traces a BSDF ray to find emitters by MIS. Both are unbiased; with a max depth of 2
//! this is the classic direct-lighting integrator with one shadow ray.
//! `light_paths`: a diffuse surface the camera sees lit through glass or a mirror
//! (light → specular⁺ → diffuse → camera, a caustic) is lit only by camera paths whose
//! BSDF-sampled rays happen to leave through the specular chain towards the light, each
//! carrying that light's full radiance: fireflies. With `light_paths` such paths are
//! traced from the lights instead and splatted into the pixels about where they land
//! ([`super::light_tracer`]), and camera paths leave them out: the same image in
//! expectation but for the caustic's reconstruction filter (a tent of one pixel's
//! radius, not the pixel's box), with the caustic's noise spread evenly over its
//! pixels.
//!
//! [`Plan::general`] is the unspecialised integrator, kept for comparison (benchmarks):
//! a plain path tracer.
//!
//! A scene without any light renders black without tracing a ray.

use super::light::Light;
use super::scene::{LIST_MAX_OBJECTS, Scene};

/// The integrator stages a scene needs; see the module documentation.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub struct Plan {
    /// Sample lights at diffuse vertices (next-event estimation).
    pub next_event: bool,
    /// Look up area emission at hits (with MIS weights when `next_event`).
    pub emission: bool,
    /// NEE only at the last scattering vertex, without a BSDF ray.
    pub direct_last: bool,
    /// Compute texture coordinates and read textures.
    pub textures: bool,
    /// Traverse the object hierarchy rather than the object list.
    pub bvh: bool,
    /// Trace caustic paths (light → specular⁺ → diffuse → camera) from the lights.
    pub light_paths: bool,
}

impl Plan {
    /// The integrator as it would run without inspecting the scene: every stage of the
    /// path tracer on, no light paths.
    pub const fn general() -> Plan {
        Plan {
            next_event: true,
            emission: true,
            direct_last: false,
            textures: true,
            bvh: true,
            light_paths: false,
        }
    }

    /// The leanest plan that renders `scene` as [`Plan::general`] would (in expectation,
    /// caustics but for their filter; the per-sample noise differs where `direct_last`
    /// or `light_paths` applies).
    pub fn inspect(scene: &Scene) -> Plan {
        Plan {
            next_event: !scene.lights().is_empty(),
            emission: scene
                .objects()
                .iter()
                .any(|o| o.emitter.is_some_and(|e| !e.radiance.is_black())),
            direct_last: true,
            textures: scene.uses_textures(),
            bvh: scene.objects().len() > LIST_MAX_OBJECTS,
            light_paths: scene.specular_bound().is_some()
                && scene
                    .lights()
                    .iter()
                    .any(|light| matches!(light, Light::Area { .. })),
        }
    }
}
