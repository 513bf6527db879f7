//! A CPU path tracer, the backend of the 3D tasks.
//!
//! The renderer is a point-sampled black box for hodr: θ → scene → image. It is written
//! for that use: deterministic per (frame seed, pixel, sample, dimension) so that both
//! halves of an antithetic pair see the same noise; allocation-free per render; and
//! specialised per scene so that the simple task scenes cost little per sample.
//!
//! ## Layout (one concept per file)
//! * [`math`]: vectors, rays, frames, boxes; [`transform`]: affine transforms;
//! * [`shape`]: spheres, quads, boxes, mesh instances; [`mesh`]: triangle meshes;
//!   [`bvh`]: the SAH hierarchy; [`procedural`]: lathe, torus, mug, height field;
//! * [`material`]: Lambert, mirror, dielectric; [`texture`]: image textures;
//!   [`light`]: area emitters, point lights, light sampling;
//! * [`camera`]: the pinhole camera; [`film`]: linear RGB images, PNG output;
//! * [`sampler`]: counter-based uniform numbers ([`sobol`]: scrambled Sobol pairs);
//!   [`scene`]: the scene and ray queries;
//!   [`plan`]: scene specialisation; [`integrator`]: the path tracer;
//!   [`light_tracer`]: caustics traced from the lights.
//!
//! Units: lengths are scene units, angles radians unless a name says degrees, radiance
//! in arbitrary linear units per RGB channel. Coordinates are right-handed; the tasks
//! use z up.
//!
//! ## Designs rejected
//! * A global BVH over every triangle of every object: θ moves whole objects (the MUG,
//!   the CBOX box), which would force a rebuild per evaluation; instanced meshes keep
//!   their object-space BVH and move by a transform.
//! * `f64` radiance: no accuracy gain visible at the sample counts used, at twice the
//!   memory traffic; losses are summed in `f64` instead.
//! * Per-thread RNG state: results would depend on scheduling.
//!
//! ```
//! use hodr_host::render::{Camera, Emitter, Film, Material, Object, Quad, Rgb, Scene, Shape, Vec3, render};
//!
//! let camera = Camera::look_at(Vec3::new(0.0, 0.0, 2.0), Vec3::ZERO, Vec3::new(0.0, 1.0, 0.0), 60.0)?;
//! let mut scene = Scene::new(camera);
//! let grey = scene.add_material(Material::diffuse(Rgb::splat(0.5)));
//! let black = scene.add_material(Material::Black);
//! let x = Vec3::new(1.0, 0.0, 0.0);
//! let y = Vec3::new(0.0, 1.0, 0.0);
//! scene.add_object(Object::new(Shape::Quad(Quad::centered(Vec3::ZERO, x, y, (4.0, 4.0))?), grey));
//! // The light faces down: u × v = x × (−y) = −z.
//! let light = Quad::centered(Vec3::new(0.0, 0.0, 5.0), x, -y, (1.0, 1.0))?;
//! scene.add_object(Object::new(Shape::Quad(light), black).with_emitter(Emitter::new(Rgb::splat(20.0))));
//! scene.commit()?;
//! let mut film = Film::new(16, 16)?;
//! render(&scene, &mut film, 4, 0)?;
//! assert!(film.pixel(8, 8)[0] > 0.0);
//! # Ok::<(), hodr_host::render::RenderError>(())
//! ```

pub mod bvh;
pub mod camera;
pub mod error;
pub mod film;
pub mod integrator;
pub mod light;
pub mod light_tracer;
pub mod material;
pub mod math;
pub mod mesh;
pub mod plan;
pub mod procedural;
pub mod sampler;
pub mod scene;
pub mod shape;
pub mod sobol;
pub mod texture;
pub mod transform;

pub use camera::Camera;
pub use error::RenderError;
pub use film::Film;
pub use integrator::{render, render_with_plan};
pub use light::{Emitter, Light, PointLight};
pub use material::{Albedo, Material};
pub use math::{Aabb, Ray, Rgb, Vec3};
pub use mesh::Mesh;
pub use plan::Plan;
pub use sampler::Sequence;
pub use scene::{Depth, Object, Scene};
pub use shape::{Cuboid, MeshInstance, Quad, Shape, Sphere};
pub use texture::Texture;
pub use transform::Transform;
