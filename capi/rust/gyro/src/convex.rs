//! Convex hulls and GJK/EPA queries on arrays of shape pairs (ABI 1.4).
use core::marker::PhantomData;
use core::ptr::{self, NonNull};

use crate::{check, count, same_len, sys, Quat, Result, Vec3};

pub type ConvexHullInfo = sys::gyro_convex_hull_info;
pub type ConvexPlane = sys::gyro_convex_plane;
pub type ConvexEdge = sys::gyro_convex_edge;
pub type ConvexMass = sys::gyro_convex_mass;
pub type ConvexPose = sys::gyro_convex_pose;
pub type ConvexResult = sys::gyro_convex_result;

/// A convex polyhedron built by quickhull. Immutable: may be queried from many threads.
pub struct ConvexHull {
    raw: NonNull<sys::gyro_convex_hull>,
}

unsafe impl Send for ConvexHull {}
unsafe impl Sync for ConvexHull {}

impl Drop for ConvexHull {
    fn drop(&mut self) {
        unsafe { sys::gyro_convex_hull_destroy(self.raw.as_ptr()) }
    }
}

/// Calls one of the hull's copy-out getters twice: for the count, then for the elements.
fn copy_out<T: Copy>(
    hull: &ConvexHull,
    get: unsafe extern "C" fn(*const sys::gyro_convex_hull, *mut T, i32, *mut i32) -> sys::gyro_status,
) -> Result<Vec<T>> {
    let mut n = 0;
    check(unsafe { get(hull.as_ptr(), ptr::null_mut(), 0, &mut n) })?;
    let mut out = Vec::with_capacity(n.max(0) as usize);
    let mut got = 0;
    check(unsafe { get(hull.as_ptr(), out.as_mut_ptr(), n, &mut got) })?;
    unsafe { out.set_len(got.clamp(0, n) as usize) };
    Ok(out)
}

impl ConvexHull {
    /// The convex hull of at least 4 points with volume (copied; near-duplicates welded).
    pub fn new(points: &[Vec3]) -> Result<ConvexHull> {
        let mut raw = ptr::null_mut();
        check(unsafe { sys::gyro_convex_hull_create(points.as_ptr(), count(points.len(), "hull points")?, &mut raw) })?;
        Ok(ConvexHull { raw: NonNull::new(raw).expect("gyro_convex_hull_create returned GYRO_OK and NULL") })
    }

    pub fn as_ptr(&self) -> *const sys::gyro_convex_hull {
        self.raw.as_ptr()
    }

    pub fn info(&self) -> Result<ConvexHullInfo> {
        let mut i = ConvexHullInfo { vertex_count: 0, face_count: 0, edge_count: 0, face_vertex_count: 0 };
        check(unsafe { sys::gyro_convex_hull_get_info(self.as_ptr(), &mut i) })?;
        Ok(i)
    }

    pub fn vertices(&self) -> Result<Vec<Vec3>> {
        copy_out(self, sys::gyro_convex_hull_get_vertices)
    }

    /// One outward plane per face.
    pub fn planes(&self) -> Result<Vec<ConvexPlane>> {
        copy_out(self, sys::gyro_convex_hull_get_planes)
    }

    /// face_count + 1 offsets into face_vertices.
    pub fn face_starts(&self) -> Result<Vec<u32>> {
        copy_out(self, sys::gyro_convex_hull_get_face_starts)
    }

    /// Every face's vertex indices, counter-clockwise seen from outside.
    pub fn face_vertices(&self) -> Result<Vec<u32>> {
        copy_out(self, sys::gyro_convex_hull_get_face_vertices)
    }

    pub fn edges(&self) -> Result<Vec<ConvexEdge>> {
        copy_out(self, sys::gyro_convex_hull_get_edges)
    }

    /// Volume, centroid and inertia at density 1.
    pub fn mass(&self) -> Result<ConvexMass> {
        let mut m: ConvexMass = unsafe { core::mem::zeroed() };
        check(unsafe { sys::gyro_convex_hull_mass(self.as_ptr(), &mut m) })?;
        Ok(m)
    }
}

/// A convex shape in its local frame, as the pair queries take it. Built by the
/// constructors, so a hull shape always points at a live [`ConvexHull`] (borrowed for 'h).
#[repr(transparent)]
#[derive(Clone, Copy)]
pub struct ConvexShape<'h> {
    raw: sys::gyro_convex_shape,
    _hull: PhantomData<&'h ConvexHull>,
}

impl<'h> ConvexShape<'h> {
    fn of(kind: sys::gyro_convex_type) -> Self {
        let mut raw: sys::gyro_convex_shape = unsafe { core::mem::zeroed() };
        raw.r#type = kind;
        raw.hull = ptr::null();
        ConvexShape { raw, _hull: PhantomData }
    }

    pub fn sphere(radius: f32) -> Self {
        let mut s = Self::of(sys::GYRO_CONVEX_SPHERE);
        s.raw.radius = radius;
        s
    }

    /// A box of the given half extents around the origin.
    pub fn cuboid(half_extents: Vec3) -> Self {
        let mut s = Self::of(sys::GYRO_CONVEX_BOX);
        s.raw.half_extents = half_extents;
        s
    }

    /// The segment (0, +-half_height, 0) plus radius.
    pub fn capsule(radius: f32, half_height: f32) -> Self {
        let mut s = Self::of(sys::GYRO_CONVEX_CAPSULE);
        s.raw.radius = radius;
        s.raw.half_height = half_height;
        s
    }

    pub fn cylinder(radius: f32, half_height: f32) -> Self {
        let mut s = Self::of(sys::GYRO_CONVEX_CYLINDER);
        s.raw.radius = radius;
        s.raw.half_height = half_height;
        s
    }

    pub fn triangle(a: Vec3, b: Vec3, c: Vec3) -> Self {
        let mut s = Self::of(sys::GYRO_CONVEX_TRIANGLE);
        s.raw.triangle = [a, b, c];
        s
    }

    pub fn hull(hull: &'h ConvexHull) -> Self {
        let mut s = Self::of(sys::GYRO_CONVEX_HULL);
        s.raw.hull = hull.as_ptr();
        s
    }

    pub fn raw(&self) -> &sys::gyro_convex_shape {
        &self.raw
    }
}

/// The pose of a position and a rotation quaternion (normalised). Errors: NON_FINITE,
/// INVALID_ARGUMENT (a zero quaternion).
pub fn convex_pose(position: Vec3, orientation: Quat) -> Result<ConvexPose> {
    let mut p: ConvexPose = unsafe { core::mem::zeroed() };
    check(unsafe { sys::gyro_convex_pose_from_quat(position, orientation, &mut p) })?;
    Ok(p)
}

/// A pose without rotation.
pub fn convex_pose_at(position: Vec3) -> ConvexPose {
    let e = |x, y, z| Vec3 { x, y, z };
    ConvexPose { position, rotation: [e(1.0, 0.0, 0.0), e(0.0, 1.0, 0.0), e(0.0, 0.0, 1.0)] }
}

type PairFn = unsafe extern "C" fn(
    *const sys::gyro_convex_shape,
    *const ConvexPose,
    *const sys::gyro_convex_shape,
    *const ConvexPose,
    i32,
    *mut ConvexResult,
) -> sys::gyro_status;

fn pairs(f: PairFn, a: &[ConvexShape], pa: &[ConvexPose], b: &[ConvexShape], pb: &[ConvexPose], out: &mut [ConvexResult]) -> Result<()> {
    let n = same_len("convex pairs", &[a.len(), pa.len(), b.len(), pb.len(), out.len()])?;
    let n = count(n, "convex pairs")?;
    // ConvexShape is repr(transparent) over gyro_convex_shape
    check(unsafe { f(a.as_ptr().cast(), pa.as_ptr(), b.as_ptr().cast(), pb.as_ptr(), n, out.as_mut_ptr()) })
}

/// out[i] = the boolean verdict of GJK on (a[i] at pa[i], b[i] at pb[i]). All slices have the
/// same length; a pair that cannot be answered gets GYRO_CONVEX_INVALID_INPUT.
pub fn convex_intersect_pairs(a: &[ConvexShape], pa: &[ConvexPose], b: &[ConvexShape], pb: &[ConvexPose], out: &mut [ConvexResult]) -> Result<()> {
    pairs(sys::gyro_convex_intersect_pairs, a, pa, b, pb, out)
}

/// Distance and closest points by GJK; intersecting pairs report 0.
pub fn convex_distance_pairs(a: &[ConvexShape], pa: &[ConvexPose], b: &[ConvexShape], pb: &[ConvexPose], out: &mut [ConvexResult]) -> Result<()> {
    pairs(sys::gyro_convex_distance_pairs, a, pa, b, pb, out)
}

/// Distance of separated pairs, penetration depth (distance = -depth) by EPA otherwise.
pub fn convex_penetration_pairs(a: &[ConvexShape], pa: &[ConvexPose], b: &[ConvexShape], pb: &[ConvexPose], out: &mut [ConvexResult]) -> Result<()> {
    pairs(sys::gyro_convex_penetration_pairs, a, pa, b, pb, out)
}

/// Contact generation's query (ABI 1.6): convex_penetration_pairs' answer for overlapping
/// pairs; separated pairs stop at the first separating axis (GYRO_CONVEX_SEPARATED, the
/// distance an upper bound of the gap).
pub fn convex_contact_pairs(a: &[ConvexShape], pa: &[ConvexPose], b: &[ConvexShape], pb: &[ConvexPose], out: &mut [ConvexResult]) -> Result<()> {
    pairs(sys::gyro_convex_contact_pairs, a, pa, b, pb, out)
}
