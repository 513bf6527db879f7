//! The scene: camera, objects, materials, textures, lights and render settings, with
//! ray queries over its objects.
//!
//! A scene is edited freely (objects, textures, camera), then [`Scene::commit`]ted:
//! commit validates every number, gathers the lights, rebuilds the object hierarchy
//! and inspects the scene to choose its [`Plan`]. Rendering an uncommitted scene is an
//! error. Commit reuses its buffers, so a task that moves objects per evaluation
//! commits without allocating.

use super::bvh::Bvh;
use super::camera::Camera;
use super::error::RenderError;
use super::light::{Emitter, Light, PointLight};
use super::material::{Albedo, Material};
use super::math::{Aabb, Ray, Rgb, Vec3};
use super::plan::Plan;
use super::sampler::Sequence;
use super::shape::{Hit, Quad, Shape, Sphere};
use super::texture::Texture;

/// One shape with its material and optional area emission.
#[derive(Clone, Debug)]
pub struct Object {
    /// Geometry.
    pub shape: Shape,
    /// Index into the scene's materials.
    pub material: u32,
    /// Area emission (quads and spheres only).
    pub emitter: Option<Emitter>,
}

impl Object {
    /// A non-emitting object.
    pub fn new(shape: Shape, material: u32) -> Object {
        Object {
            shape,
            material,
            emitter: None,
        }
    }

    /// The same object, emitting.
    pub fn with_emitter(mut self, emitter: Emitter) -> Object {
        self.emitter = Some(emitter);
        self
    }
}

/// Path-length settings of a scene.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Depth {
    /// Maximum path depth, counted as in Mitsuba 3: 1 = emitters seen directly, 2 = direct
    /// lighting, 3 = one indirect bounce, …; `None` = unbounded (Russian roulette ends
    /// paths). Default: `Some(5)`.
    pub max: Option<u32>,
    /// Russian roulette starts at paths of this depth (Mitsuba's `rr_depth`). Default: 5.
    pub roulette: u32,
}

impl Default for Depth {
    fn default() -> Self {
        Depth {
            max: Some(5),
            roulette: 5,
        }
    }
}

/// Objects in the scene above which closest-hit queries go through a BVH over object
/// boxes instead of a list. Below it, testing every (analytic) shape directly is about
/// as cheap as testing their boxes, and skips the traversal; the task scenes (3 to 8
/// objects) all use the list.
pub const LIST_MAX_OBJECTS: usize = 8;

/// The object index that matches no object (for the `skip` arguments of ray queries).
pub const NO_OBJECT: u32 = u32::MAX;

/// A renderable scene.
#[derive(Clone, Debug)]
pub struct Scene {
    camera: Camera,
    objects: Vec<Object>,
    materials: Vec<Material>,
    textures: Vec<Texture>,
    point_lights: Vec<PointLight>,
    depth: Depth,
    sequence: Sequence,
    // Derived by `commit`.
    lights: Vec<Light>,
    areas: Vec<f32>,
    boxes: Vec<Aabb>,
    /// The sphere about the box of every specular object, if any (`commit`).
    specular: Option<(Vec3, f32)>,
    top: Bvh,
    /// List mode: the quads, the spheres, and the other objects, each with its object
    /// index, so that the common analytic shapes are tested in tight, inlined loops.
    quads: Vec<(Quad, u32)>,
    spheres: Vec<(Sphere, u32)>,
    others: Vec<u32>,
    plan: Plan,
    committed: bool,
}

impl Scene {
    /// An empty scene seen by `camera`.
    pub fn new(camera: Camera) -> Scene {
        Scene {
            camera,
            objects: Vec::new(),
            materials: Vec::new(),
            textures: Vec::new(),
            point_lights: Vec::new(),
            depth: Depth::default(),
            sequence: Sequence::default(),
            lights: Vec::new(),
            areas: Vec::new(),
            boxes: Vec::new(),
            specular: None,
            top: Bvh::new(),
            quads: Vec::new(),
            spheres: Vec::new(),
            others: Vec::new(),
            plan: Plan::general(),
            committed: false,
        }
    }

    /// Adds a material; returns its index.
    pub fn add_material(&mut self, material: Material) -> u32 {
        self.committed = false;
        self.materials.push(material);
        (self.materials.len() - 1) as u32
    }

    /// Adds a texture; returns its index (for [`Albedo::Texture`]).
    pub fn add_texture(&mut self, texture: Texture) -> usize {
        self.committed = false;
        self.textures.push(texture);
        self.textures.len() - 1
    }

    /// Adds an object; returns its index.
    pub fn add_object(&mut self, object: Object) -> u32 {
        self.committed = false;
        self.objects.push(object);
        (self.objects.len() - 1) as u32
    }

    /// Adds a point light.
    pub fn add_point_light(&mut self, light: PointLight) {
        self.committed = false;
        self.point_lights.push(light);
    }

    /// Sets the path-length settings.
    pub fn set_depth(&mut self, depth: Depth) {
        self.committed = false;
        self.depth = depth;
    }

    /// Sets the sample sequence (default [`Sequence::PaddedSobol`]).
    pub fn set_sequence(&mut self, sequence: Sequence) {
        self.sequence = sequence;
    }

    /// Replaces the camera.
    pub fn set_camera(&mut self, camera: Camera) {
        self.camera = camera;
    }

    /// Object `index`, for editing (the scene must be committed again).
    ///
    /// # Panics
    /// If `index` is out of range.
    pub fn object_mut(&mut self, index: u32) -> &mut Object {
        self.committed = false;
        &mut self.objects[index as usize]
    }

    /// Texture `index`, for editing (the scene must be committed again).
    ///
    /// # Panics
    /// If `index` is out of range.
    pub fn texture_mut(&mut self, index: usize) -> &mut Texture {
        self.committed = false;
        &mut self.textures[index]
    }

    /// The camera.
    pub fn camera(&self) -> &Camera {
        &self.camera
    }

    /// The objects.
    pub fn objects(&self) -> &[Object] {
        &self.objects
    }

    /// The materials.
    pub fn materials(&self) -> &[Material] {
        &self.materials
    }

    /// The textures.
    pub fn textures(&self) -> &[Texture] {
        &self.textures
    }

    /// The lights gathered by the last commit (area emitters first, then point lights).
    pub fn lights(&self) -> &[Light] {
        &self.lights
    }

    /// Path-length settings.
    pub fn depth(&self) -> Depth {
        self.depth
    }

    /// The sample sequence.
    pub fn sequence(&self) -> Sequence {
        self.sequence
    }

    /// The plan chosen by the last commit.
    pub fn plan(&self) -> Plan {
        self.plan
    }

    /// True when the scene has not changed since the last successful commit.
    pub fn is_committed(&self) -> bool {
        self.committed
    }

    /// The reflectance ρ of `albedo` at texture coordinates `uv`.
    #[inline]
    pub fn albedo(&self, albedo: Albedo, uv: (f32, f32)) -> Rgb {
        match albedo {
            Albedo::Constant(c) => c,
            Albedo::Texture(k) => self.textures[k].lookup(uv.0, uv.1),
        }
    }

    /// The area of object `index` if it is an area emitter (else 0).
    #[inline]
    pub fn emitter_area(&self, index: u32) -> f32 {
        self.areas[index as usize]
    }

    /// The sphere (centre, radius) about the bounding box of every object with a
    /// specular material (mirror or dielectric), as of the last commit; `None` when
    /// there is none. Every caustic path's first specular vertex lies within it.
    pub fn specular_bound(&self) -> Option<(Vec3, f32)> {
        self.specular
    }

    /// Validates the scene and derives lights, the object hierarchy and the plan.
    ///
    /// # Errors
    /// The first invalid shape, material, texture or light found; the scene then stays
    /// uncommitted.
    pub fn commit(&mut self) -> Result<(), RenderError> {
        self.committed = false;
        for texture in &self.textures {
            texture.validate()?;
        }
        for material in &self.materials {
            material.validate(self.textures.len())?;
        }
        self.lights.clear();
        self.areas.clear();
        self.boxes.clear();
        self.quads.clear();
        self.spheres.clear();
        self.others.clear();
        let mut specular = Aabb::EMPTY;
        for (index, object) in self.objects.iter().enumerate() {
            object.shape.validate()?;
            if object.material as usize >= self.materials.len() {
                return Err(RenderError::InvalidMaterial(
                    "object refers to a missing material",
                ));
            }
            let mut area = 0.0;
            if let Some(emitter) = &object.emitter {
                let r = emitter.radiance;
                if !(r.is_finite() && r.x >= 0.0 && r.y >= 0.0 && r.z >= 0.0) {
                    return Err(RenderError::InvalidMaterial(
                        "emitted radiance must be finite and ≥ 0",
                    ));
                }
                area = match &object.shape {
                    Shape::Quad(q) => q.area(),
                    Shape::Sphere(s) => s.area(),
                    Shape::Cuboid(_) | Shape::Mesh(_) => {
                        return Err(RenderError::UnsupportedEmitter);
                    }
                };
                if !r.is_black() {
                    self.lights.push(Light::Area {
                        object: index as u32,
                        area,
                    });
                }
            }
            self.areas.push(area);
            let bounds = object.shape.bounds();
            if self.materials[object.material as usize].is_specular() {
                specular = specular.union(bounds);
            }
            self.boxes.push(bounds);
            match &object.shape {
                Shape::Quad(q) => self.quads.push((*q, index as u32)),
                Shape::Sphere(s) => self.spheres.push((*s, index as u32)),
                Shape::Cuboid(_) | Shape::Mesh(_) => self.others.push(index as u32),
            }
        }
        for light in &self.point_lights {
            let i = light.intensity;
            if !(light.position.is_finite()
                && i.is_finite()
                && i.x >= 0.0
                && i.y >= 0.0
                && i.z >= 0.0)
            {
                return Err(RenderError::InvalidGeometry(
                    "point light needs finite position and intensity ≥ 0",
                ));
            }
            if !i.is_black() {
                self.lights.push(Light::Point(*light));
            }
        }
        if let Some(0) = self.depth.max {
            return Err(RenderError::InvalidGeometry("maximum depth must be ≥ 1"));
        }
        self.specular = (specular.min.x <= specular.max.x).then(|| {
            let centre = specular.centroid();
            (centre, (specular.max - centre).length())
        });
        self.top.build(&self.boxes);
        self.plan = Plan::inspect(self);
        self.committed = true;
        Ok(())
    }

    /// True when some diffuse material in use reads a texture.
    pub(super) fn uses_textures(&self) -> bool {
        self.objects.iter().any(|o| {
            matches!(
                self.materials[o.material as usize],
                Material::Diffuse(Albedo::Texture(_))
            )
        })
    }

    /// Closest hit in (0, `t_max`) on any object but `skip` (pass [`NO_OBJECT`] to test
    /// all): through the object BVH when `bvh`, else by testing every object.
    #[inline]
    pub fn intersect(&self, ray: &Ray, t_max: f32, skip: u32, bvh: bool) -> Option<Hit> {
        let mut best: Option<Hit> = None;
        if bvh {
            self.top.closest(ray.origin, ray.dir, t_max, |k, t_max| {
                if k == skip {
                    return None;
                }
                let hit = self.objects[k as usize].shape.intersect(ray, t_max, k)?;
                best = Some(hit);
                Some(hit.t)
            });
        } else {
            let (mut t_max, mut object) = (t_max, NO_OBJECT);
            for (q, k) in &self.quads {
                if *k != skip
                    && let Some(t) = q.hit(ray, t_max)
                {
                    (t_max, object) = (t, *k);
                }
            }
            for (s, k) in &self.spheres {
                if *k != skip
                    && let Some(t) = s.hit(ray, t_max)
                {
                    (t_max, object) = (t, *k);
                }
            }
            if object != NO_OBJECT {
                best = Some(Hit {
                    t: t_max,
                    object,
                    prim: 0,
                    u: 0.0,
                    v: 0.0,
                });
            }
            for &k in &self.others {
                if k == skip {
                    continue;
                }
                if let Some(hit) = self.objects[k as usize].shape.intersect(ray, t_max, k) {
                    t_max = hit.t;
                    best = Some(hit);
                }
            }
        }
        best
    }

    /// True if an object other than `skip.0` and `skip.1` blocks the ray within
    /// (0, `t_max`).
    #[inline]
    pub fn occluded(&self, ray: &Ray, t_max: f32, skip: (u32, u32), bvh: bool) -> bool {
        let tested = |k: u32| k != skip.0 && k != skip.1;
        if bvh {
            self.top.any(ray.origin, ray.dir, t_max, |k| {
                tested(k) && self.objects[k as usize].shape.occluded(ray, t_max)
            })
        } else {
            self.quads
                .iter()
                .any(|(q, k)| tested(*k) && q.hit(ray, t_max).is_some())
                || self
                    .spheres
                    .iter()
                    .any(|(s, k)| tested(*k) && s.hit(ray, t_max).is_some())
                || self
                    .others
                    .iter()
                    .any(|&k| tested(k) && self.objects[k as usize].shape.occluded(ray, t_max))
        }
    }
}
