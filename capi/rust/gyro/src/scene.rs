//! Scenes: models (spheres, boxes, planes, instanced meshes) placed by transforms and
//! parents, under a BVH or an octree.
use core::ptr::{self, NonNull};

use crate::{check, count, sys, Camera, Error, Frustum, Mesh, Rays, Result, Status, Vec3};

pub type ModelDef = sys::gyro_model_def;
pub type ModelId = sys::gyro_model_id;
pub type Transform = sys::gyro_transform;

/// The acceleration structure of a scene.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum SceneAccel {
    Bvh,
    Octree,
}

/// Whether a scene's ray batches (either structure) prefetch each next visit's cache lines (speed
/// only, never a result): `Auto` (the default) when the tree exceeds 8 MiB.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum RayPrefetch {
    Auto,
    Always,
    Never,
}

/// Per-ray scene results: t, the model hit (null id for a miss) and its primitive (the
/// triangle of a mesh model, 0 for other shapes, -1 for a miss, GYRO_RAY_INVALID), and
/// optionally the normal and the barycentrics. Each slice is at least as long as the rays.
pub struct SceneHits<'a> {
    pub t: &'a mut [f32],
    pub model: &'a mut [ModelId],
    pub primitive: Option<&'a mut [i32]>,
    pub normal: Option<[&'a mut [f32]; 3]>,
    pub uv: Option<[&'a mut [f32]; 2]>,
}

impl<'a> SceneHits<'a> {
    pub fn new(t: &'a mut [f32], model: &'a mut [ModelId]) -> Self {
        SceneHits { t, model, primitive: None, normal: None, uv: None }
    }

    fn raw(&mut self, rays: usize) -> Result<sys::gyro_scene_hit_soa> {
        let mut lens = vec![self.t.len(), self.model.len()];
        lens.extend(self.primitive.iter().map(|s| s.len()));
        lens.extend(self.normal.iter().flat_map(|n| n.iter().map(|s| s.len())));
        lens.extend(self.uv.iter().flat_map(|n| n.iter().map(|s| s.len())));
        if lens.iter().any(|&l| l < rays) {
            return Err(Error::local(Status::InvalidCount, format!("scene hits: {lens:?} elements for {rays} rays")));
        }
        let primitive = self.primitive.as_mut().map_or(ptr::null_mut(), |s| s.as_mut_ptr());
        let (nx, ny, nz) = match &mut self.normal {
            Some([x, y, z]) => (x.as_mut_ptr(), y.as_mut_ptr(), z.as_mut_ptr()),
            None => (ptr::null_mut(), ptr::null_mut(), ptr::null_mut()),
        };
        let (u, v) = match &mut self.uv {
            Some([u, v]) => (u.as_mut_ptr(), v.as_mut_ptr()),
            None => (ptr::null_mut(), ptr::null_mut()),
        };
        Ok(sys::gyro_scene_hit_soa { t: self.t.as_mut_ptr(), model: self.model.as_mut_ptr(), primitive, nx, ny, nz, u, v })
    }
}

/// A set of models; destroyed on drop (mesh models keep their meshes alive in the scene).
pub struct Scene {
    raw: NonNull<sys::gyro_scene>,
}

unsafe impl Send for Scene {}

impl Drop for Scene {
    fn drop(&mut self) {
        unsafe { sys::gyro_scene_destroy(self.raw.as_ptr()) }
    }
}

impl Scene {
    pub fn new(accel: SceneAccel) -> Result<Scene> {
        let a = match accel {
            SceneAccel::Bvh => sys::GYRO_SCENE_BVH,
            SceneAccel::Octree => sys::GYRO_SCENE_OCTREE,
        };
        let mut raw = ptr::null_mut();
        check(unsafe { sys::gyro_scene_create(a, &mut raw) })?;
        Ok(Scene { raw: NonNull::new(raw).expect("gyro_scene_create returned GYRO_OK and NULL") })
    }

    /// Sets whether ray batches prefetch each next visit's cache lines.
    pub fn set_ray_prefetch(&mut self, mode: RayPrefetch) -> Result<()> {
        let m = match mode {
            RayPrefetch::Auto => sys::GYRO_RAY_PREFETCH_AUTO,
            RayPrefetch::Always => sys::GYRO_RAY_PREFETCH_ALWAYS,
            RayPrefetch::Never => sys::GYRO_RAY_PREFETCH_NEVER,
        };
        check(unsafe { sys::gyro_scene_set_ray_prefetch(self.raw.as_ptr(), m) })
    }

    /// Sets whether moves alone refit the BVH instead of rebuilding it (the default: true).
    /// Hits are the same either way, except which model an any hit names.
    pub fn set_refit(&mut self, enabled: bool) -> Result<()> {
        check(unsafe { sys::gyro_scene_set_refit(self.raw.as_ptr(), u32::from(enabled)) })
    }

    /// A unit sphere at the origin, identity transform, no parent.
    pub fn model_def() -> ModelDef {
        unsafe { sys::gyro_model_def_default() }
    }

    pub fn as_ptr(&self) -> *const sys::gyro_scene {
        self.raw.as_ptr()
    }

    /// Adds a model; `mesh` is the mesh of a GYRO_MODEL_MESH model (the scene keeps its own
    /// reference) and replaces def.mesh.
    pub fn add_model(&mut self, def: &ModelDef, mesh: Option<&Mesh>) -> Result<ModelId> {
        let mut d = *def;
        d.mesh = mesh.map_or(ptr::null(), |m| m.as_ptr());
        let mut id = ModelId { index: 0, generation: 0 };
        check(unsafe { sys::gyro_scene_add_model(self.raw.as_ptr(), &d, &mut id) })?;
        Ok(id)
    }

    pub fn remove_model(&mut self, id: ModelId) -> Result<()> {
        check(unsafe { sys::gyro_scene_remove_model(self.raw.as_ptr(), id) })
    }

    /// The model's transform relative to its parent.
    pub fn set_transform(&mut self, id: ModelId, local: &Transform) -> Result<()> {
        check(unsafe { sys::gyro_scene_set_transform(self.raw.as_ptr(), id, local) })
    }

    /// A null parent detaches the model.
    pub fn set_parent(&mut self, id: ModelId, parent: ModelId) -> Result<()> {
        check(unsafe { sys::gyro_scene_set_parent(self.raw.as_ptr(), id, parent) })
    }

    /// The layers the model is in (all 32 to start with): the masked raycasts, queries and
    /// picks see it only through a shared bit; 0 hides it from all of them.
    pub fn set_layers(&mut self, id: ModelId, layers: u32) -> Result<()> {
        check(unsafe { sys::gyro_scene_set_layers(self.raw.as_ptr(), id, layers) })
    }

    pub fn model_count(&self) -> usize {
        unsafe { sys::gyro_scene_model_count(self.as_ptr()).max(0) as usize }
    }

    /// The closest hit of every ray (ties to the lower model index).
    pub fn raycast_closest(&self, rays: &Rays, hits: &mut SceneHits) -> Result<()> {
        let n = rays.len()?;
        let h = hits.raw(n)?;
        let r = rays.raw();
        check(unsafe { sys::gyro_scene_raycast_closest(self.as_ptr(), &r, count(n, "rays")?, &h) })
    }

    /// Any hit (occlusion, line of sight).
    pub fn raycast_any(&self, rays: &Rays, hits: &mut SceneHits) -> Result<()> {
        let n = rays.len()?;
        let h = hits.raw(n)?;
        let r = rays.raw();
        check(unsafe { sys::gyro_scene_raycast_any(self.as_ptr(), &r, count(n, "rays")?, &h) })
    }

    /// The closest hit of every ray among the models whose layers share a bit with the
    /// ray's `masks[i]` (at least as many masks as rays).
    pub fn raycast_closest_masked(&self, rays: &Rays, masks: &[u32], hits: &mut SceneHits) -> Result<()> {
        let (r, h, n) = self.masked(rays, masks, hits)?;
        check(unsafe { sys::gyro_scene_raycast_closest_masked(self.as_ptr(), &r, masks.as_ptr(), n, &h) })
    }

    /// Any hit, with layers as `raycast_closest_masked`.
    pub fn raycast_any_masked(&self, rays: &Rays, masks: &[u32], hits: &mut SceneHits) -> Result<()> {
        let (r, h, n) = self.masked(rays, masks, hits)?;
        check(unsafe { sys::gyro_scene_raycast_any_masked(self.as_ptr(), &r, masks.as_ptr(), n, &h) })
    }

    fn masked(&self, rays: &Rays, masks: &[u32], hits: &mut SceneHits) -> Result<(sys::gyro_ray_soa, sys::gyro_scene_hit_soa, i32)> {
        let n = rays.len()?;
        if masks.len() < n {
            return Err(Error::local(Status::InvalidCount, format!("ray masks: {} for {n} rays", masks.len())));
        }
        let h = hits.raw(n)?;
        Ok((rays.raw(), h, count(n, "rays")?))
    }

    /// The models overlapping a sphere, in ascending id order.
    pub fn query_sphere(&self, center: Vec3, radius: f32) -> Result<Vec<ModelId>> {
        self.query_sphere_masked(center, radius, u32::MAX)
    }

    /// The models overlapping a sphere whose layers share a bit with `mask`, ascending.
    pub fn query_sphere_masked(&self, center: Vec3, radius: f32, mask: u32) -> Result<Vec<ModelId>> {
        let v = [[center.x], [center.y], [center.z], [radius]];
        let [cx, cy, cz, r] = columns(&v);
        self.query_shape(sys::GYRO_SHAPE_SPHERE, sys::gyro_shape_soa_as { sphere: sys::gyro_sphere_soa { cx, cy, cz, r } }, mask)
    }

    /// The models overlapping an axis-aligned box (centre, half extents), ascending.
    pub fn query_aabb(&self, center: Vec3, half_extents: Vec3) -> Result<Vec<ModelId>> {
        self.query_aabb_masked(center, half_extents, u32::MAX)
    }

    /// `query_aabb` among the models whose layers share a bit with `mask`.
    pub fn query_aabb_masked(&self, center: Vec3, half_extents: Vec3, mask: u32) -> Result<Vec<ModelId>> {
        let (c, e) = (center, half_extents);
        let v = [[c.x], [c.y], [c.z], [e.x], [e.y], [e.z]];
        let [cx, cy, cz, ex, ey, ez] = columns(&v);
        self.query_shape(sys::GYRO_SHAPE_AABB, sys::gyro_shape_soa_as { aabb: sys::gyro_aabb_soa { cx, cy, cz, ex, ey, ez } }, mask)
    }

    /// The models overlapping an oriented box: centre, half extents and its unit axes (the
    /// rows of its orientation: world = local * orientation + centre), ascending.
    pub fn query_obb(&self, center: Vec3, half_extents: Vec3, axes: [Vec3; 3]) -> Result<Vec<ModelId>> {
        self.query_obb_masked(center, half_extents, axes, u32::MAX)
    }

    /// `query_obb` among the models whose layers share a bit with `mask`.
    pub fn query_obb_masked(&self, center: Vec3, half_extents: Vec3, axes: [Vec3; 3], mask: u32) -> Result<Vec<ModelId>> {
        let (c, e, [u0, u1, u2]) = (center, half_extents, axes);
        let v = [
            [c.x], [c.y], [c.z], [e.x], [e.y], [e.z],
            [u0.x], [u0.y], [u0.z], [u1.x], [u1.y], [u1.z], [u2.x], [u2.y], [u2.z],
        ];
        let [cx, cy, cz, ex, ey, ez, u0x, u0y, u0z, u1x, u1y, u1z, u2x, u2y, u2z] = columns(&v);
        let obb = sys::gyro_obb_soa { cx, cy, cz, ex, ey, ez, u0x, u0y, u0z, u1x, u1y, u1z, u2x, u2y, u2z };
        self.query_shape(sys::GYRO_SHAPE_OBB, sys::gyro_shape_soa_as { obb }, mask)
    }

    /// The models whose bounds intersect the frustum (never one that is visible left out),
    /// ascending.
    pub fn query_frustum(&self, frustum: &Frustum) -> Result<Vec<ModelId>> {
        self.query_frustum_masked(frustum, u32::MAX)
    }

    /// `query_frustum` among the models whose layers share a bit with `mask`.
    pub fn query_frustum_masked(&self, frustum: &Frustum, mask: u32) -> Result<Vec<ModelId>> {
        collect_ids(|out, capacity, n| unsafe {
            sys::gyro_scene_query_frustum_masked(self.as_ptr(), &frustum.0, mask, out, capacity, n)
        })
    }

    /// The closest model under a screen point (pixels from the top-left, y down) of a
    /// viewport of `viewport` = (width, height) pixels; None when the picking ray hits none.
    pub fn pick(&self, camera: &Camera, screen: (f32, f32), viewport: (f32, f32)) -> Result<Option<PickHit>> {
        self.pick_masked(camera, screen, viewport, u32::MAX)
    }

    /// `pick` among the models whose layers share a bit with `mask`.
    pub fn pick_masked(&self, camera: &Camera, screen: (f32, f32), viewport: (f32, f32), mask: u32) -> Result<Option<PickHit>> {
        let mut h = sys::gyro_scene_hit {
            hit: 0,
            t: 0.0,
            point: [0.0; 3],
            normal: [0.0; 3],
            model: ModelId { index: 0, generation: 0 },
            primitive: 0,
            u: 0.0,
            v: 0.0,
        };
        check(unsafe {
            sys::gyro_scene_pick_masked(self.as_ptr(), &camera.0, screen.0, screen.1, viewport.0, viewport.1, mask, &mut h)
        })?;
        Ok((h.hit != 0).then_some(h))
    }

    fn query_shape(&self, kind: sys::gyro_shape_type, shape: sys::gyro_shape_soa_as, mask: u32) -> Result<Vec<ModelId>> {
        let shape = sys::gyro_shape_soa { r#type: kind, reserved: 0, r#as: shape };
        collect_ids(|out, capacity, n| unsafe { sys::gyro_scene_query_masked(self.as_ptr(), &shape, mask, out, capacity, n) })
    }
}

/// A pick's answer: t along the picking ray, the point, the normal, the model, and for a
/// mesh model the triangle and its barycentrics.
pub type PickHit = sys::gyro_scene_hit;

/// Shape 0 of a structure-of-arrays view: a pointer to each one-element column of
/// `values`, valid while `values` lives.
fn columns<const N: usize>(values: &[[f32; 1]; N]) -> [*const f32; N] {
    core::array::from_fn(|k| values[k].as_ptr())
}

/// The ids a counting query gives: asked once for the count, then into a buffer that size
/// (the scene does not change between the calls: queries take it shared).
fn collect_ids(query: impl Fn(*mut ModelId, i32, &mut i32) -> sys::gyro_status) -> Result<Vec<ModelId>> {
    let mut n = 0;
    check(query(ptr::null_mut(), 0, &mut n))?;
    let mut out = vec![ModelId { index: 0, generation: 0 }; n.max(0) as usize];
    let mut got = 0;
    check(query(out.as_mut_ptr(), n, &mut got))?;
    out.truncate(got.clamp(0, n) as usize);
    Ok(out)
}
