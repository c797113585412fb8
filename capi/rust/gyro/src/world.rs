//! The dynamics world and its rigid bodies (ABI 1.2), snapshots (ABI 1.5).
use core::ptr::{self, NonNull};

use crate::{check, sys, view_slice, ConvexHull, Error, Mesh, Quat, Result, Status, Vec3};

pub type WorldDef = sys::gyro_world_def;
pub type BodyDef = sys::gyro_body_def;
pub type BodyId = sys::gyro_body_id;
pub type BodyType = sys::gyro_body_type;
pub type BodyShape = sys::gyro_body_shape;
pub type StepStats = sys::gyro_step_stats;
pub type StepTimings = sys::gyro_step_timings;
pub type ContactEvent = sys::gyro_contact_event;

/// gyro::WorldDef's defaults: the soft step with its sub-steps, sleeping on.
pub fn world_def() -> WorldDef {
    unsafe { sys::gyro_world_def_default() }
}

/// A dynamic unit box (1 kg) at the origin, at rest; no mesh, no hull.
pub fn body_def() -> BodyDef {
    unsafe { sys::gyro_body_def_default() }
}

/// A world of rigid bodies, particles and soft bodies. Destroyed on drop. It may move to
/// another thread (one thread at a time uses it: `&mut self` for every change).
pub struct World {
    raw: NonNull<sys::gyro_world>,
}

unsafe impl Send for World {}

impl Drop for World {
    fn drop(&mut self) {
        unsafe { sys::gyro_world_destroy(self.raw.as_ptr()) }
    }
}

/// Zero-copy view of the bodies' state (dense slots; `ids()[i]` names slot i). It borrows the
/// world, so no body can be created or destroyed and no step taken while it lives.
pub struct BodyView<'w> {
    raw: sys::gyro_body_view,
    _world: core::marker::PhantomData<&'w World>,
}

/// The last step's contact events (pairs that began or ended touching), borrowed from the world.
pub struct ContactEvents<'w> {
    pub begin: &'w [ContactEvent],
    pub end: &'w [ContactEvent],
}

macro_rules! view_columns {
    ($($name:ident),*) => {
        $(pub fn $name(&self) -> &'w [f32] {
            unsafe { view_slice(self.raw.$name, self.raw.count) }
        })*
    };
}

impl<'w> BodyView<'w> {
    pub fn len(&self) -> usize {
        self.raw.count as usize
    }
    pub fn is_empty(&self) -> bool {
        self.raw.count == 0
    }
    pub fn ids(&self) -> &'w [BodyId] {
        unsafe { view_slice(self.raw.ids, self.raw.count) }
    }
    view_columns!(px, py, pz, qx, qy, qz, qw, vx, vy, vz, wx, wy, wz);
}

impl World {
    /// A world with the given settings. Errors: NON_FINITE, INVALID_ARGUMENT (see gyro.h).
    pub fn new(def: &WorldDef) -> Result<World> {
        let mut raw = ptr::null_mut();
        check(unsafe { sys::gyro_world_create(def, &mut raw) })?;
        Ok(World { raw: NonNull::new(raw).expect("gyro_world_create returned GYRO_OK and NULL") })
    }

    /// A world with gyro's default settings.
    pub fn with_defaults() -> Result<World> {
        World::new(&world_def())
    }

    /// A new world holding a snapshot's state (see [`World::snapshot`]).
    pub fn from_snapshot(bytes: &[u8]) -> Result<World> {
        let mut raw = ptr::null_mut();
        check(unsafe { sys::gyro_world_create_from_snapshot(bytes.as_ptr().cast(), bytes.len() as u64, &mut raw) })?;
        Ok(World { raw: NonNull::new(raw).expect("gyro_world_create_from_snapshot returned GYRO_OK and NULL") })
    }

    /// The C handle, for calls this crate does not wrap.
    pub fn as_ptr(&self) -> *const sys::gyro_world {
        self.raw.as_ptr()
    }

    /// The C handle for mutating calls this crate does not wrap.
    pub fn as_mut_ptr(&mut self) -> *mut sys::gyro_world {
        self.raw.as_ptr()
    }

    pub(crate) fn ptr(&self) -> *const sys::gyro_world {
        self.raw.as_ptr()
    }

    pub(crate) fn mut_ptr(&mut self) -> *mut sys::gyro_world {
        self.raw.as_ptr()
    }

    /// Advances the world by dt seconds. Errors: NON_FINITE (NaN or infinite dt),
    /// INVALID_ARGUMENT (dt <= 0); the world is then unchanged.
    pub fn step(&mut self, dt: f32) -> Result<()> {
        check(unsafe { sys::gyro_world_step(self.mut_ptr(), dt) })
    }

    /// The 64-bit witness of the whole state: equal for equal call sequences.
    pub fn hash(&self) -> Result<u64> {
        let mut h = 0;
        check(unsafe { sys::gyro_world_hash(self.ptr(), &mut h) })?;
        Ok(h)
    }

    pub fn body_count(&self) -> Result<usize> {
        let mut n = 0;
        check(unsafe { sys::gyro_world_body_count(self.ptr(), &mut n) })?;
        Ok(n as usize)
    }

    /// Creates a body of any shape but mesh and hull (use [`World::create_mesh_body`] and
    /// [`World::create_hull_body`]); def.mesh and def.hull are ignored (taken as NULL).
    pub fn create_body(&mut self, def: &BodyDef) -> Result<BodyId> {
        let mut d = *def;
        d.mesh = ptr::null();
        d.hull = ptr::null();
        self.create_body_raw(&d)
    }

    /// A static body of shape GYRO_BODY_SHAPE_MESH; the world keeps its own reference.
    pub fn create_mesh_body(&mut self, def: &BodyDef, mesh: &Mesh) -> Result<BodyId> {
        let mut d = *def;
        d.shape = sys::GYRO_BODY_SHAPE_MESH;
        d.mesh = mesh.as_ptr();
        d.hull = ptr::null();
        self.create_body_raw(&d)
    }

    /// A body of shape GYRO_BODY_SHAPE_HULL; the world copies the hull. The body frame is
    /// the hull's mass frame (see gyro_body_get_shape_frame).
    pub fn create_hull_body(&mut self, def: &BodyDef, hull: &ConvexHull) -> Result<BodyId> {
        let mut d = *def;
        d.shape = sys::GYRO_BODY_SHAPE_HULL;
        d.mesh = ptr::null();
        d.hull = hull.as_ptr();
        self.create_body_raw(&d)
    }

    fn create_body_raw(&mut self, def: &BodyDef) -> Result<BodyId> {
        let mut id = BodyId { index: 0, generation: 0 };
        check(unsafe { sys::gyro_body_create(self.mut_ptr(), def, &mut id) })?;
        Ok(id)
    }

    /// The id becomes stale.
    pub fn destroy_body(&mut self, id: BodyId) -> Result<()> {
        check(unsafe { sys::gyro_body_destroy(self.mut_ptr(), id) })
    }

    /// True if id names a live body of this world.
    pub fn is_valid(&self, id: BodyId) -> bool {
        unsafe { sys::gyro_body_is_valid(self.ptr(), id) != 0 }
    }

    /// Position and orientation.
    pub fn transform(&self, id: BodyId) -> Result<(Vec3, Quat)> {
        let mut p = crate::vec3(0.0, 0.0, 0.0);
        let mut q = crate::QUAT_IDENTITY;
        check(unsafe { sys::gyro_body_get_transform(self.ptr(), id, &mut p, &mut q) })?;
        Ok((p, q))
    }

    pub fn position(&self, id: BodyId) -> Result<Vec3> {
        Ok(self.transform(id)?.0)
    }

    /// Teleports the body (and wakes it).
    pub fn set_transform(&mut self, id: BodyId, position: Vec3, orientation: Quat) -> Result<()> {
        check(unsafe { sys::gyro_body_set_transform(self.mut_ptr(), id, position, orientation) })
    }

    /// Linear and angular (world frame) velocity.
    pub fn velocity(&self, id: BodyId) -> Result<(Vec3, Vec3)> {
        let mut v = crate::vec3(0.0, 0.0, 0.0);
        let mut w = v;
        check(unsafe { sys::gyro_body_get_velocity(self.ptr(), id, &mut v, &mut w) })?;
        Ok((v, w))
    }

    pub fn set_velocity(&mut self, id: BodyId, linear: Vec3, angular: Vec3) -> Result<()> {
        check(unsafe { sys::gyro_body_set_velocity(self.mut_ptr(), id, linear, angular) })
    }

    /// kg; 0 for static and kinematic bodies.
    pub fn mass(&self, id: BodyId) -> Result<f32> {
        let mut m = 0.0;
        check(unsafe { sys::gyro_body_get_mass(self.ptr(), id, &mut m) })?;
        Ok(m)
    }

    pub fn body_type(&self, id: BodyId) -> Result<BodyType> {
        let mut t = 0;
        check(unsafe { sys::gyro_body_get_type(self.ptr(), id, &mut t) })?;
        Ok(t)
    }

    pub fn user_data(&self, id: BodyId) -> Result<u64> {
        let mut u = 0;
        check(unsafe { sys::gyro_body_get_user_data(self.ptr(), id, &mut u) })?;
        Ok(u)
    }

    /// A force at a world point, acting during the next step only.
    pub fn apply_force(&mut self, id: BodyId, force: Vec3, world_point: Vec3) -> Result<()> {
        check(unsafe { sys::gyro_body_apply_force(self.mut_ptr(), id, force, world_point) })
    }

    pub fn apply_force_at_center(&mut self, id: BodyId, force: Vec3) -> Result<()> {
        check(unsafe { sys::gyro_body_apply_force_at_center(self.mut_ptr(), id, force) })
    }

    pub fn apply_torque(&mut self, id: BodyId, torque: Vec3) -> Result<()> {
        check(unsafe { sys::gyro_body_apply_torque(self.mut_ptr(), id, torque) })
    }

    /// Changes the velocity at once.
    pub fn apply_linear_impulse(&mut self, id: BodyId, impulse: Vec3, world_point: Vec3) -> Result<()> {
        check(unsafe { sys::gyro_body_apply_linear_impulse(self.mut_ptr(), id, impulse, world_point) })
    }

    pub fn apply_angular_impulse(&mut self, id: BodyId, impulse: Vec3) -> Result<()> {
        check(unsafe { sys::gyro_body_apply_angular_impulse(self.mut_ptr(), id, impulse) })
    }

    pub fn set_awake(&mut self, id: BodyId, awake: bool) -> Result<()> {
        check(unsafe { sys::gyro_body_set_awake(self.mut_ptr(), id, awake as u32) })
    }

    pub fn is_awake(&self, id: BodyId) -> Result<bool> {
        let mut a = 0;
        check(unsafe { sys::gyro_body_is_awake(self.ptr(), id, &mut a) })?;
        Ok(a != 0)
    }

    /// The bodies' state as slices, without copying.
    pub fn body_view(&self) -> Result<BodyView<'_>> {
        let mut raw: sys::gyro_body_view = unsafe { core::mem::zeroed() };
        check(unsafe { sys::gyro_world_get_body_view(self.ptr(), &mut raw) })?;
        Ok(BodyView { raw, _world: core::marker::PhantomData })
    }

    pub fn stats(&self) -> Result<StepStats> {
        let mut s: StepStats = unsafe { core::mem::zeroed() };
        check(unsafe { sys::gyro_world_get_stats(self.ptr(), &mut s) })?;
        Ok(s)
    }

    /// Milliseconds per stage of the last step.
    pub fn timings(&self) -> Result<StepTimings> {
        let mut t: StepTimings = unsafe { core::mem::zeroed() };
        check(unsafe { sys::gyro_world_get_timings(self.ptr(), &mut t) })?;
        Ok(t)
    }

    pub fn contact_events(&self) -> Result<ContactEvents<'_>> {
        let mut e: sys::gyro_contact_events = unsafe { core::mem::zeroed() };
        check(unsafe { sys::gyro_world_get_contact_events(self.ptr(), &mut e) })?;
        unsafe { Ok(ContactEvents { begin: view_slice(e.begin, e.begin_count), end: view_slice(e.end, e.end_count) }) }
    }

    /// The whole state as bytes (self-contained, versioned, checksummed). A world restored
    /// from it steps on bit-identically.
    pub fn snapshot(&self) -> Result<Vec<u8>> {
        let mut size = 0u64;
        check(unsafe { sys::gyro_world_snapshot_size(self.ptr(), &mut size) })?;
        let len = usize::try_from(size)
            .map_err(|_| Error::local(Status::OutOfMemory, format!("a snapshot of {size} bytes")))?;
        let mut buf = vec![0u8; len];
        let mut written = 0u64;
        check(unsafe { sys::gyro_world_snapshot(self.ptr(), buf.as_mut_ptr().cast(), size, &mut written) })?;
        buf.truncate(written as usize);
        Ok(buf)
    }

    /// Replaces the whole state with a snapshot's. Errors (the world unchanged):
    /// CORRUPT_DATA (truncated, bad checksum, another format version), OUT_OF_MEMORY.
    pub fn restore(&mut self, bytes: &[u8]) -> Result<()> {
        check(unsafe { sys::gyro_world_restore(self.mut_ptr(), bytes.as_ptr().cast(), bytes.len() as u64) })
    }
}

pub type ReplayReport = sys::gyro_replay_report;

impl World {
    /// Starts recording this world's calls (ABI 1.5); the recording begins with a snapshot.
    pub fn record_begin(&mut self) -> Result<()> {
        check(unsafe { sys::gyro_world_record_begin(self.mut_ptr()) })
    }

    /// The recording so far.
    pub fn recording(&self) -> Result<Vec<u8>> {
        let mut size = 0u64;
        check(unsafe { sys::gyro_world_record_size(self.ptr(), &mut size) })?;
        let len = usize::try_from(size)
            .map_err(|_| Error::local(Status::OutOfMemory, format!("a recording of {size} bytes")))?;
        let mut buf = vec![0u8; len];
        let mut written = 0u64;
        check(unsafe { sys::gyro_world_record_copy(self.ptr(), buf.as_mut_ptr().cast(), size, &mut written) })?;
        buf.truncate(written as usize);
        Ok(buf)
    }

    /// Writes the recording so far to a file (see [`replay_file`]).
    pub fn save_recording(&self, path: &std::path::Path) -> Result<()> {
        let c = std::ffi::CString::new(path.as_os_str().as_encoded_bytes())
            .map_err(|_| Error::local(Status::InvalidArgument, "save_recording: a NUL byte in the path"))?;
        check(unsafe { sys::gyro_world_record_save(self.ptr(), c.as_ptr()) })
    }

    /// Stops recording and frees the recording.
    pub fn record_end(&mut self) -> Result<()> {
        check(unsafe { sys::gyro_world_record_end(self.mut_ptr()) })
    }
}

fn new_report() -> ReplayReport {
    let mut r: ReplayReport = unsafe { core::mem::zeroed() };
    r.struct_size = core::mem::size_of::<ReplayReport>() as u32;
    r
}

/// Replays a recording held in memory: a divergence is a result (`diverged == 1`), not an error.
pub fn replay(recording: &[u8]) -> Result<ReplayReport> {
    let mut r = new_report();
    check(unsafe { sys::gyro_replay(recording.as_ptr().cast(), recording.len() as u64, &mut r) })?;
    Ok(r)
}

/// Replays a recording file.
pub fn replay_file(path: &std::path::Path) -> Result<ReplayReport> {
    let c = std::ffi::CString::new(path.as_os_str().as_encoded_bytes())
        .map_err(|_| Error::local(Status::InvalidArgument, "replay_file: a NUL byte in the path"))?;
    let mut r = new_report();
    check(unsafe { sys::gyro_replay_file(c.as_ptr(), &mut r) })?;
    Ok(r)
}
