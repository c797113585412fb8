//! Cameras (perspective, orthographic), their view-projection matrices, picking rays and
//! frustums, and frustum culling of spheres. Conventions of gyro/camera.hpp: row vectors
//! (clip = world * M), depth in [0, 1], screen pixels from the top-left corner, y down.
use crate::{check, count, same_len, sys, Result, Spheres, Vec3};

/// A camera: the C struct itself (eye, axes, projection), every field reachable.
#[derive(Clone, Copy, Debug)]
pub struct Camera(pub sys::gyro_camera);

/// Six planes (left, right, bottom, top, near, far) `[nx, ny, nz, d]` with unit normals
/// pointing in: a point p is inside where dot(n, p) >= d for all six.
#[derive(Clone, Copy, Debug)]
pub struct Frustum(pub sys::gyro_frustum);

fn xyz(v: Vec3) -> [f32; 3] {
    [v.x, v.y, v.z]
}

impl Camera {
    /// A perspective camera at the origin looking down +z (fov_y in radians).
    pub fn perspective(fov_y: f32, aspect: f32, z_near: f32, z_far: f32) -> Camera {
        Camera(unsafe { sys::gyro_camera_perspective(fov_y, aspect, z_near, z_far) })
    }

    /// The same camera with an orthographic view volume of `width` x `height` world units.
    pub fn orthographic(width: f32, height: f32, z_near: f32, z_far: f32) -> Camera {
        let mut c = Camera::perspective(1.0, width / height, z_near, z_far);
        c.0.mode = sys::GYRO_PROJECTION_ORTHOGRAPHIC;
        c.0.width = width;
        c.0.height = height;
        c
    }

    /// Points the camera from `eye` at `target`, `up` the world's up direction. An error
    /// (the camera unchanged) for non-finite input, eye = target or up along the view.
    pub fn look_at(&mut self, eye: Vec3, target: Vec3, up: Vec3) -> Result<()> {
        let (e, t, u) = (xyz(eye), xyz(target), xyz(up));
        check(unsafe { sys::gyro_camera_look_at(&mut self.0, e.as_ptr(), t.as_ptr(), u.as_ptr()) })
    }

    /// The view-projection matrix, row-major, row vectors: clip = world * M.
    pub fn view_projection(&self) -> Result<[f32; 16]> {
        let mut m = [0.0f32; 16];
        check(unsafe { sys::gyro_camera_view_projection(&self.0, m.as_mut_ptr()) })?;
        Ok(m)
    }

    /// The ray (origin on the near plane, unit direction) through a screen point of a
    /// viewport of `viewport` = (width, height) pixels.
    pub fn picking_ray(&self, screen: (f32, f32), viewport: (f32, f32)) -> Result<(Vec3, Vec3)> {
        let (mut o, mut d) = ([0.0f32; 3], [0.0f32; 3]);
        check(unsafe {
            sys::gyro_camera_picking_ray(&self.0, screen.0, screen.1, viewport.0, viewport.1, o.as_mut_ptr(), d.as_mut_ptr())
        })?;
        Ok((Vec3 { x: o[0], y: o[1], z: o[2] }, Vec3 { x: d[0], y: d[1], z: d[2] }))
    }

    /// The camera's frustum.
    pub fn frustum(&self) -> Result<Frustum> {
        let mut f = sys::gyro_frustum { planes: [[0.0; 4]; 6] };
        check(unsafe { sys::gyro_camera_frustum(&self.0, &mut f) })?;
        Ok(Frustum(f))
    }
}

impl Frustum {
    /// The frustum of a view-projection matrix (row-major, row vectors).
    pub fn from_matrix(view_projection: &[f32; 16]) -> Result<Frustum> {
        let mut f = sys::gyro_frustum { planes: [[0.0; 4]; 6] };
        check(unsafe { sys::gyro_frustum_from_matrix(view_projection.as_ptr(), &mut f) })?;
        Ok(Frustum(f))
    }

    /// Whether each sphere may be visible: `true` for every sphere that is (never one
    /// culled that is visible), `false` for those certainly outside, a few invisible ones
    /// near the frustum's corners kept. `visible` is at least as long as the spheres.
    pub fn cull_spheres(&self, spheres: &Spheres, visible: &mut [bool]) -> Result<()> {
        let n = same_len("spheres", &[spheres.center[0].len(), spheres.center[1].len(), spheres.center[2].len(), spheres.radius.len()])?;
        if visible.len() < n {
            return Err(crate::Error::local(crate::Status::InvalidCount, format!("visible: {} for {n} spheres", visible.len())));
        }
        let shape = sys::gyro_shape_soa {
            r#type: sys::GYRO_SHAPE_SPHERE,
            reserved: 0,
            r#as: sys::gyro_shape_soa_as {
                sphere: sys::gyro_sphere_soa {
                    cx: spheres.center[0].as_ptr(),
                    cy: spheres.center[1].as_ptr(),
                    cz: spheres.center[2].as_ptr(),
                    r: spheres.radius.as_ptr(),
                },
            },
        };
        let mut flags = vec![0u32; n];
        check(unsafe { sys::gyro_frustum_cull(&self.0, &shape, count(n, "spheres")?, flags.as_mut_ptr()) })?;
        for (v, f) in visible.iter_mut().zip(&flags) {
            *v = *f != 0;
        }
        Ok(())
    }
}
