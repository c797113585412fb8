//! Springs, cloth and soft bodies owned by a world (ABI 1.3).
use crate::{check, count, same_len, sys, view_slice, Error, Result, Status, Vec3, World};

pub type SoftBodyId = sys::gyro_soft_body_id;
pub type ClothDef = sys::gyro_cloth_def;
pub type SoftCubeDef = sys::gyro_soft_cube_def;
pub type SoftMeshDef = sys::gyro_soft_mesh_def;
pub type SoftSettings = sys::gyro_soft_settings;
pub type SoftBodyStats = sys::gyro_soft_body_stats;
pub type SpringConstants = sys::gyro_spring_constants;
pub type SpringFamily = sys::gyro_spring_family;

/// gyro::ClothDef's defaults: 32 x 32 particles over 10 x 10 m at the origin, 1 kg each.
pub fn cloth_def() -> ClothDef {
    unsafe { sys::gyro_cloth_def_default() }
}

pub fn soft_cube_def() -> SoftCubeDef {
    unsafe { sys::gyro_soft_cube_def_default() }
}

/// The constants of a soft mesh; the vertex and index arrays are given to
/// [`World::create_soft_mesh`].
pub fn soft_mesh_def() -> SoftMeshDef {
    unsafe { sys::gyro_soft_mesh_def_default() }
}

/// gyro::SoftSettings' defaults: XPBD, 16 sub-steps, gravity (0, -9.81, 0).
pub fn soft_settings() -> SoftSettings {
    unsafe { sys::gyro_soft_settings_default() }
}

/// Zero-copy view of one soft body's particles and triangles, borrowed from the world.
pub struct SoftBodyView<'w> {
    raw: sys::gyro_soft_body_view,
    _world: core::marker::PhantomData<&'w World>,
}

macro_rules! soft_columns {
    ($($name:ident),*) => {
        $(pub fn $name(&self) -> &'w [f32] {
            unsafe { view_slice(self.raw.$name, self.raw.count) }
        })*
    };
}

impl<'w> SoftBodyView<'w> {
    /// Particles.
    pub fn len(&self) -> usize {
        self.raw.count as usize
    }
    pub fn is_empty(&self) -> bool {
        self.raw.count == 0
    }
    soft_columns!(px, py, pz, vx, vy, vz, inverse_mass);
    /// Three particle indices per triangle.
    pub fn triangles(&self) -> &'w [u32] {
        let n = self.raw.triangle_count.saturating_mul(3);
        unsafe { view_slice(self.raw.triangles, n) }
    }
}

impl World {
    /// A grid cloth on the x-z plane (def.nx * def.nz particles).
    pub fn create_cloth(&mut self, def: &ClothDef) -> Result<SoftBodyId> {
        let mut id = SoftBodyId { index: 0, generation: 0 };
        check(unsafe { sys::gyro_world_create_cloth(self.mut_ptr(), def, &mut id) })?;
        Ok(id)
    }

    /// The appendix's soft cube: 8 particles, 28 springs.
    pub fn create_soft_cube(&mut self, def: &SoftCubeDef) -> Result<SoftBodyId> {
        let mut id = SoftBodyId { index: 0, generation: 0 };
        check(unsafe { sys::gyro_world_create_soft_cube(self.mut_ptr(), def, &mut id) })?;
        Ok(id)
    }

    /// A soft body from a closed triangle mesh: vertex positions as x, y, z slices (copied)
    /// and three indices per triangle; the rest of `def` gives masses and springs.
    pub fn create_soft_mesh(
        &mut self,
        def: &SoftMeshDef,
        x: &[f32],
        y: &[f32],
        z: &[f32],
        indices: &[u32],
    ) -> Result<SoftBodyId> {
        let n = same_len("create_soft_mesh vertices", &[x.len(), y.len(), z.len()])?;
        if indices.len() % 3 != 0 {
            return Err(Error::local(Status::InvalidCount, "create_soft_mesh: indices.len() is not a multiple of 3"));
        }
        let mut d = *def;
        d.vertex_count = count(n, "create_soft_mesh vertices")?;
        d.x = x.as_ptr();
        d.y = y.as_ptr();
        d.z = z.as_ptr();
        d.indices = indices.as_ptr();
        d.triangle_count = count(indices.len() / 3, "create_soft_mesh triangles")?;
        let mut id = SoftBodyId { index: 0, generation: 0 };
        check(unsafe { sys::gyro_world_create_soft_mesh(self.mut_ptr(), &d, &mut id) })?;
        Ok(id)
    }

    /// The id becomes stale.
    pub fn destroy_soft_body(&mut self, id: SoftBodyId) -> Result<()> {
        check(unsafe { sys::gyro_world_destroy_soft_body(self.mut_ptr(), id) })
    }

    pub fn soft_body_is_valid(&self, id: SoftBodyId) -> bool {
        unsafe { sys::gyro_soft_body_is_valid(self.ptr(), id) != 0 }
    }

    pub fn soft_body_count(&self) -> Result<usize> {
        let mut n = 0;
        check(unsafe { sys::gyro_world_soft_body_count(self.ptr(), &mut n) })?;
        Ok(n as usize)
    }

    pub fn soft_settings(&self, id: SoftBodyId) -> Result<SoftSettings> {
        let mut s = soft_settings();
        check(unsafe { sys::gyro_soft_body_get_settings(self.ptr(), id, &mut s) })?;
        Ok(s)
    }

    pub fn set_soft_settings(&mut self, id: SoftBodyId, settings: &SoftSettings) -> Result<()> {
        check(unsafe { sys::gyro_soft_body_set_settings(self.mut_ptr(), id, settings) })
    }

    /// Constants of every spring of one family (GYRO_SPRING_*).
    pub fn set_spring_family(&mut self, id: SoftBodyId, family: SpringFamily, c: SpringConstants) -> Result<()> {
        check(unsafe { sys::gyro_soft_body_set_family(self.mut_ptr(), id, family, &c) })
    }

    pub fn spring_family(&self, id: SoftBodyId, family: SpringFamily) -> Result<SpringConstants> {
        let mut c = SpringConstants { stiffness: 0.0, damping: 0.0 };
        check(unsafe { sys::gyro_soft_body_get_family(self.ptr(), id, family, &mut c) })?;
        Ok(c)
    }

    /// Pinned particles have inverse mass 0 and move only when set_particle_position moves them.
    pub fn pin(&mut self, id: SoftBodyId, particle: u32) -> Result<()> {
        check(unsafe { sys::gyro_soft_body_pin(self.mut_ptr(), id, particle) })
    }

    pub fn unpin(&mut self, id: SoftBodyId, particle: u32) -> Result<()> {
        check(unsafe { sys::gyro_soft_body_unpin(self.mut_ptr(), id, particle) })
    }

    pub fn is_pinned(&self, id: SoftBodyId, particle: u32) -> Result<bool> {
        let mut p = 0;
        check(unsafe { sys::gyro_soft_body_is_pinned(self.ptr(), id, particle, &mut p) })?;
        Ok(p != 0)
    }

    pub fn particle_position(&self, id: SoftBodyId, particle: u32) -> Result<Vec3> {
        let mut p = crate::vec3(0.0, 0.0, 0.0);
        check(unsafe { sys::gyro_soft_body_get_position(self.ptr(), id, particle, &mut p) })?;
        Ok(p)
    }

    /// Teleports the particle (how a pinned particle is moved); its velocity is kept.
    pub fn set_particle_position(&mut self, id: SoftBodyId, particle: u32, position: Vec3) -> Result<()> {
        check(unsafe { sys::gyro_soft_body_set_position(self.mut_ptr(), id, particle, position) })
    }

    pub fn particle_velocity(&self, id: SoftBodyId, particle: u32) -> Result<Vec3> {
        let mut v = crate::vec3(0.0, 0.0, 0.0);
        check(unsafe { sys::gyro_soft_body_get_velocity(self.ptr(), id, particle, &mut v) })?;
        Ok(v)
    }

    pub fn set_particle_velocity(&mut self, id: SoftBodyId, particle: u32, velocity: Vec3) -> Result<()> {
        check(unsafe { sys::gyro_soft_body_set_velocity(self.mut_ptr(), id, particle, velocity) })
    }

    /// A cloth's particle at grid column ix (< nx) and row iz (< nz).
    pub fn cloth_index(&self, id: SoftBodyId, ix: u32, iz: u32) -> Result<u32> {
        let mut i = 0;
        check(unsafe { sys::gyro_soft_body_cloth_index(self.ptr(), id, ix, iz, &mut i) })?;
        Ok(i)
    }

    /// Keeps particles a and b rest_length apart (negative: their current distance);
    /// returns the joint's number among the body's joints.
    pub fn add_distance_joint(&mut self, id: SoftBodyId, a: u32, b: u32, rest_length: f32) -> Result<u32> {
        let mut j = 0;
        check(unsafe { sys::gyro_soft_body_add_distance_joint(self.mut_ptr(), id, a, b, rest_length, &mut j) })?;
        Ok(j)
    }

    pub fn soft_view(&self, id: SoftBodyId) -> Result<SoftBodyView<'_>> {
        let mut raw: sys::gyro_soft_body_view = unsafe { core::mem::zeroed() };
        check(unsafe { sys::gyro_soft_body_get_view(self.ptr(), id, &mut raw) })?;
        Ok(SoftBodyView { raw, _world: core::marker::PhantomData })
    }

    /// Strain and energies of the current state.
    pub fn soft_stats(&self, id: SoftBodyId) -> Result<SoftBodyStats> {
        let mut s: SoftBodyStats = unsafe { core::mem::zeroed() };
        check(unsafe { sys::gyro_soft_body_get_stats(self.ptr(), id, &mut s) })?;
        Ok(s)
    }

    /// The 64-bit witness of one soft body.
    pub fn soft_hash(&self, id: SoftBodyId) -> Result<u64> {
        let mut h = 0;
        check(unsafe { sys::gyro_soft_body_hash(self.ptr(), id, &mut h) })?;
        Ok(h)
    }
}
