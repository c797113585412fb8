//! Safe Rust API over gyro's C ABI (`capi/gyro.h`, through the generated `gyro-sys`).
//!
//! - Handles own their C object and release it on drop: [`World`], [`Mesh`], [`Scene`],
//!   [`ConvexHull`].
//! - Every fallible call returns [`Result`]; an [`Error`] carries the [`Status`] and the
//!   text of `gyro_last_error()` read right after the failing call.
//! - Plain-data values are the C structs themselves ([`Vec3`], [`BodyDef`], ...), so every
//!   field of the ABI is reachable; definitions start from the C defaults ([`world_def`],
//!   [`body_def`], ...). Pointers inside definitions (meshes, hulls, vertex arrays) are set
//!   by the safe calls from borrowed Rust values, never taken from the caller.
//! - Batch calls take slices (structure of arrays, as the ABI does) and check their lengths.
use core::ffi::CStr;
use core::fmt;

pub use gyro_sys as sys;

mod camera;
mod convex;
mod mesh;
mod scene;
mod soft;
mod world;

pub use camera::{Camera, Frustum};
pub use convex::{
    convex_contact_pairs, convex_distance_pairs, convex_intersect_pairs, convex_penetration_pairs, convex_pose, convex_pose_at, ConvexEdge, ConvexHull, ConvexHullInfo,
    ConvexMass, ConvexPlane, ConvexPose, ConvexResult, ConvexShape,
};
pub use mesh::{raycast_spheres_closest, Hits, Mesh, MeshInfo, Rays, Spheres};
pub use scene::{ModelDef, ModelId, PickHit, RayPrefetch, Scene, SceneAccel, SceneHits, Transform};
pub use soft::{
    cloth_def, soft_cube_def, soft_mesh_def, soft_settings, ClothDef, SoftBodyId, SoftBodyStats, SoftBodyView,
    SoftCubeDef, SoftMeshDef, SoftSettings, SpringConstants, SpringFamily,
};
pub use world::{
    body_def, replay, replay_file, world_def, BodyDef, BodyId, BodyShape, BodyType, BodyView, ContactEvent, ContactEvents, ReplayReport, StepStats,
    StepTimings, World, WorldDef,
};

pub type Vec3 = sys::gyro_vec3;
pub type Quat = sys::gyro_quat;

/// A vector.
pub const fn vec3(x: f32, y: f32, z: f32) -> Vec3 {
    Vec3 { x, y, z }
}

/// The identity rotation (x, y, z, w) = (0, 0, 0, 1).
pub const QUAT_IDENTITY: Quat = Quat { x: 0.0, y: 0.0, z: 0.0, w: 1.0 };

/// Why a call failed: the `gyro_status` codes other than `GYRO_OK`.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Status {
    NullArgument,
    InvalidCount,
    NonFinite,
    InvalidArgument,
    Unsupported,
    OutOfMemory,
    StaleId,
    Internal,
    CorruptData,
    /// A code this crate does not know (a newer library).
    Other(i32),
}

impl Status {
    pub fn from_code(code: sys::gyro_status) -> Status {
        match code {
            sys::GYRO_STATUS_NULL_ARGUMENT => Status::NullArgument,
            sys::GYRO_STATUS_INVALID_COUNT => Status::InvalidCount,
            sys::GYRO_STATUS_NON_FINITE => Status::NonFinite,
            sys::GYRO_STATUS_INVALID_ARGUMENT => Status::InvalidArgument,
            sys::GYRO_STATUS_UNSUPPORTED => Status::Unsupported,
            sys::GYRO_STATUS_OUT_OF_MEMORY => Status::OutOfMemory,
            sys::GYRO_STATUS_STALE_ID => Status::StaleId,
            sys::GYRO_STATUS_INTERNAL => Status::Internal,
            sys::GYRO_STATUS_CORRUPT_DATA => Status::CorruptData,
            other => Status::Other(other),
        }
    }

    pub fn code(self) -> sys::gyro_status {
        match self {
            Status::NullArgument => sys::GYRO_STATUS_NULL_ARGUMENT,
            Status::InvalidCount => sys::GYRO_STATUS_INVALID_COUNT,
            Status::NonFinite => sys::GYRO_STATUS_NON_FINITE,
            Status::InvalidArgument => sys::GYRO_STATUS_INVALID_ARGUMENT,
            Status::Unsupported => sys::GYRO_STATUS_UNSUPPORTED,
            Status::OutOfMemory => sys::GYRO_STATUS_OUT_OF_MEMORY,
            Status::StaleId => sys::GYRO_STATUS_STALE_ID,
            Status::Internal => sys::GYRO_STATUS_INTERNAL,
            Status::CorruptData => sys::GYRO_STATUS_CORRUPT_DATA,
            Status::Other(c) => c,
        }
    }

    /// The library's name of the status ("null_argument", ...).
    pub fn name(self) -> String {
        unsafe { c_string(sys::gyro_status_name(self.code())) }
    }
}

/// A failed call: its status and the detail gyro_last_error() gave.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Error {
    status: Status,
    message: String,
}

impl Error {
    /// The error of the call that just returned `code` on this thread.
    fn last(code: sys::gyro_status) -> Error {
        let message = unsafe { c_string(sys::gyro_last_error()) };
        Error { status: Status::from_code(code), message }
    }

    /// An error found on the Rust side before calling the library (slice lengths).
    fn local(status: Status, message: impl Into<String>) -> Error {
        Error { status, message: message.into() }
    }

    pub fn status(&self) -> Status {
        self.status
    }

    pub fn message(&self) -> &str {
        &self.message
    }
}

impl fmt::Display for Error {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{}: {}", self.status.name(), self.message)
    }
}

impl std::error::Error for Error {}

pub type Result<T> = core::result::Result<T, Error>;

/// Ok for GYRO_OK, else the status with gyro_last_error().
fn check(code: sys::gyro_status) -> Result<()> {
    if code == sys::GYRO_OK {
        Ok(())
    } else {
        Err(Error::last(code))
    }
}

/// A slice length as the ABI's int32_t count.
fn count(len: usize, what: &str) -> Result<i32> {
    i32::try_from(len).map_err(|_| Error::local(Status::InvalidCount, format!("{what}: {len} elements is too many")))
}

/// The common length of several slices.
fn same_len(what: &str, lens: &[usize]) -> Result<usize> {
    let n = lens.first().copied().unwrap_or(0);
    if lens.iter().any(|&l| l != n) {
        return Err(Error::local(Status::InvalidCount, format!("{what}: slices of different lengths {lens:?}")));
    }
    Ok(n)
}

unsafe fn c_string(p: *const core::ffi::c_char) -> String {
    if p.is_null() {
        String::new()
    } else {
        CStr::from_ptr(p).to_string_lossy().into_owned()
    }
}

/// A read-only slice from a view's pointer (NULL is fine when n is 0).
unsafe fn view_slice<'a, T>(p: *const T, n: i32) -> &'a [T] {
    if p.is_null() || n <= 0 {
        &[]
    } else {
        core::slice::from_raw_parts(p, n as usize)
    }
}

/// The ABI version of the linked library: (major << 16) | minor.
pub fn abi_version() -> u32 {
    unsafe { sys::gyro_abi_version() }
}

/// True when the linked library can serve these bindings: the same major version and a
/// minor version at least the one the bindings were generated from.
pub fn abi_compatible() -> bool {
    let lib = abi_version();
    lib >> 16 == sys::GYRO_ABI_VERSION >> 16 && (lib & 0xFFFF) >= (sys::GYRO_ABI_VERSION & 0xFFFF)
}

/// The library version, e.g. "0.1.0".
pub fn version() -> String {
    unsafe { c_string(sys::gyro_version_string()) }
}

/// The GYRO_FEATURE_* bits of the linked library.
pub fn features() -> u32 {
    unsafe { sys::gyro_features() }
}

/// Threads batch calls may use; 0 returns to the default. Results do not depend on it.
pub fn set_thread_count(threads: u32) -> Result<()> {
    check(unsafe { sys::gyro_set_thread_count(threads) })
}
