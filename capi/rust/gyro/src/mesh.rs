//! Triangle meshes with their BVH, and the structure-of-arrays rays and hits of batch raycasts.
use core::ptr::{self, NonNull};
use std::ffi::CString;
use std::path::Path;

use crate::{check, count, same_len, sys, Error, Result, Status};

pub type MeshInfo = sys::gyro_mesh_info;

/// Rays o + t d, t in [tmin, tmax], as slices of equal length (nothing is copied). tmin and
/// tmax default to 0 and +infinity.
#[derive(Clone, Copy)]
pub struct Rays<'a> {
    pub origin: [&'a [f32]; 3],
    pub direction: [&'a [f32]; 3],
    pub tmin: Option<&'a [f32]>,
    pub tmax: Option<&'a [f32]>,
}

impl<'a> Rays<'a> {
    pub fn new(origin: [&'a [f32]; 3], direction: [&'a [f32]; 3]) -> Self {
        Rays { origin, direction, tmin: None, tmax: None }
    }

    /// The same rays limited to [tmin, tmax].
    pub fn with_range(self, tmin: &'a [f32], tmax: &'a [f32]) -> Self {
        Rays { tmin: Some(tmin), tmax: Some(tmax), ..self }
    }

    /// The number of rays; an error if the slices differ in length.
    pub fn len(&self) -> Result<usize> {
        let mut lens = vec![];
        lens.extend(self.origin.iter().chain(self.direction.iter()).map(|s| s.len()));
        lens.extend(self.tmin.iter().chain(self.tmax.iter()).map(|s| s.len()));
        same_len("rays", &lens)
    }

    /// True when there are no rays (or the slices differ in length).
    pub fn is_empty(&self) -> bool {
        self.len().map_or(true, |n| n == 0)
    }

    pub(crate) fn raw(&self) -> sys::gyro_ray_soa {
        sys::gyro_ray_soa {
            ox: self.origin[0].as_ptr(),
            oy: self.origin[1].as_ptr(),
            oz: self.origin[2].as_ptr(),
            dx: self.direction[0].as_ptr(),
            dy: self.direction[1].as_ptr(),
            dz: self.direction[2].as_ptr(),
            tmin: self.tmin.map_or(ptr::null(), |s| s.as_ptr()),
            tmax: self.tmax.map_or(ptr::null(), |s| s.as_ptr()),
        }
    }
}

/// Per-ray results written by the raycasts: t and the primitive (-1 for a miss,
/// GYRO_RAY_INVALID for a ray that cannot be answered), and optionally the unit normal and
/// the barycentric u, v of a triangle hit. Every slice is at least as long as the rays.
pub struct Hits<'a> {
    pub t: &'a mut [f32],
    pub primitive: &'a mut [i32],
    pub normal: Option<[&'a mut [f32]; 3]>,
    pub uv: Option<[&'a mut [f32]; 2]>,
}

impl<'a> Hits<'a> {
    pub fn new(t: &'a mut [f32], primitive: &'a mut [i32]) -> Self {
        Hits { t, primitive, normal: None, uv: None }
    }

    pub(crate) fn raw(&mut self, rays: usize) -> Result<sys::gyro_hit_soa> {
        let mut lens = vec![self.t.len(), self.primitive.len()];
        lens.extend(self.normal.iter().flat_map(|n| n.iter().map(|s| s.len())));
        lens.extend(self.uv.iter().flat_map(|n| n.iter().map(|s| s.len())));
        if lens.iter().any(|&l| l < rays) {
            return Err(Error::local(Status::InvalidCount, format!("hits: {lens:?} elements for {rays} rays")));
        }
        let (nx, ny, nz) = match &mut self.normal {
            Some([x, y, z]) => (x.as_mut_ptr(), y.as_mut_ptr(), z.as_mut_ptr()),
            None => (ptr::null_mut(), ptr::null_mut(), ptr::null_mut()),
        };
        let (u, v) = match &mut self.uv {
            Some([u, v]) => (u.as_mut_ptr(), v.as_mut_ptr()),
            None => (ptr::null_mut(), ptr::null_mut()),
        };
        Ok(sys::gyro_hit_soa { t: self.t.as_mut_ptr(), primitive: self.primitive.as_mut_ptr(), nx, ny, nz, u, v })
    }
}

/// Spheres as slices: centre and radius.
#[derive(Clone, Copy)]
pub struct Spheres<'a> {
    pub center: [&'a [f32]; 3],
    pub radius: &'a [f32],
}

/// The closest hit of every ray against every sphere (brute force): the primitive is the
/// sphere's index.
pub fn raycast_spheres_closest(rays: &Rays, spheres: &Spheres, hits: &mut Hits) -> Result<()> {
    let n = rays.len()?;
    let m = same_len("spheres", &[spheres.center[0].len(), spheres.center[1].len(), spheres.center[2].len(), spheres.radius.len()])?;
    let s = sys::gyro_sphere_soa {
        cx: spheres.center[0].as_ptr(),
        cy: spheres.center[1].as_ptr(),
        cz: spheres.center[2].as_ptr(),
        r: spheres.radius.as_ptr(),
    };
    let h = hits.raw(n)?;
    let r = rays.raw();
    check(unsafe { sys::gyro_raycast_spheres_closest(&r, count(n, "rays")?, &s, count(m, "spheres")?, &h) })
}

/// An immutable triangle mesh with its BVH; may be queried from many threads at once.
pub struct Mesh {
    raw: NonNull<sys::gyro_mesh>,
}

unsafe impl Send for Mesh {}
unsafe impl Sync for Mesh {}

impl Drop for Mesh {
    fn drop(&mut self) {
        unsafe { sys::gyro_mesh_destroy(self.raw.as_ptr()) }
    }
}

impl Mesh {
    /// A mesh from vertex positions and triangles (three vertex indices each); both copied.
    pub fn new(vertices: &[[f32; 3]], triangles: &[[u32; 3]]) -> Result<Mesh> {
        let x: Vec<f32> = vertices.iter().map(|v| v[0]).collect();
        let y: Vec<f32> = vertices.iter().map(|v| v[1]).collect();
        let z: Vec<f32> = vertices.iter().map(|v| v[2]).collect();
        let indices: Vec<u32> = triangles.iter().flatten().copied().collect();
        Mesh::from_soa(&x, &y, &z, &indices)
    }

    /// A mesh from structure-of-arrays positions and three indices per triangle.
    pub fn from_soa(x: &[f32], y: &[f32], z: &[f32], indices: &[u32]) -> Result<Mesh> {
        let n = same_len("mesh vertices", &[x.len(), y.len(), z.len()])?;
        if indices.len() % 3 != 0 {
            return Err(Error::local(Status::InvalidCount, "mesh: indices.len() is not a multiple of 3"));
        }
        let mut def = unsafe { sys::gyro_mesh_def_default() };
        def.vertex_count = count(n, "mesh vertices")?;
        def.x = x.as_ptr();
        def.y = y.as_ptr();
        def.z = z.as_ptr();
        def.indices = indices.as_ptr();
        def.triangle_count = count(indices.len() / 3, "mesh triangles")?;
        let mut raw = ptr::null_mut();
        check(unsafe { sys::gyro_mesh_create(&def, &mut raw) })?;
        Ok(Mesh { raw: NonNull::new(raw).expect("gyro_mesh_create returned GYRO_OK and NULL") })
    }

    /// Reads a Wavefront OBJ file (v and f lines).
    pub fn load_obj(path: &Path) -> Result<Mesh> {
        let c = CString::new(path.as_os_str().as_encoded_bytes())
            .map_err(|_| Error::local(Status::InvalidArgument, "load_obj: a NUL byte in the path"))?;
        let mut raw = ptr::null_mut();
        check(unsafe { sys::gyro_mesh_load_obj(c.as_ptr(), &mut raw) })?;
        Ok(Mesh { raw: NonNull::new(raw).expect("gyro_mesh_load_obj returned GYRO_OK and NULL") })
    }

    pub fn as_ptr(&self) -> *const sys::gyro_mesh {
        self.raw.as_ptr()
    }

    pub fn info(&self) -> Result<MeshInfo> {
        let mut info: MeshInfo = unsafe { core::mem::zeroed() };
        check(unsafe { sys::gyro_mesh_get_info(self.as_ptr(), &mut info) })?;
        Ok(info)
    }

    /// The closest hit of every ray: the primitive is the triangle index (ties to the lower).
    pub fn raycast_closest(&self, rays: &Rays, hits: &mut Hits) -> Result<()> {
        let n = rays.len()?;
        let h = hits.raw(n)?;
        let r = rays.raw();
        check(unsafe { sys::gyro_mesh_raycast_closest(self.as_ptr(), &r, count(n, "rays")?, &h) })
    }

    /// Any hit (occlusion): some triangle crossed in [tmin, tmax].
    pub fn raycast_any(&self, rays: &Rays, hits: &mut Hits) -> Result<()> {
        let n = rays.len()?;
        let h = hits.raw(n)?;
        let r = rays.raw();
        check(unsafe { sys::gyro_mesh_raycast_any(self.as_ptr(), &r, count(n, "rays")?, &h) })
    }
}
