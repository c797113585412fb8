// gyro for C#: the safe layer over Gyro.Native.cs.
//
// - World, Mesh, Scene and ConvexHull own their C object through a SafeHandle and release
//   it on Dispose (or, as a last resort, on finalisation).
// - Every failing call throws GyroException, which carries the Status and the text of
//   gyro_last_error() read right after the call. No status is ever ignored.
// - The first use of any of these classes checks the library's ABI version against the
//   binding's (same major, library minor >= binding minor) and throws
//   GyroVersionException otherwise; DllNotFoundException says where libgyro is looked for.
// - Batch calls take arrays or spans in structure-of-arrays form, as the C ABI does; their
//   lengths are checked here, because the C side cannot see them.
// - Plain-data values are the C structs themselves (Gyro.Native.Vec3, BodyDef, ...);
//   definitions start from Defaults.*, which are the library's own defaults.
using System;
using System.Runtime.InteropServices;
using Gyro.Native;
using N = Gyro.Native.NativeMethods;

namespace Gyro
{
    /// <summary>A gyro call failed: Status is the C status, Detail gyro_last_error()'s text.</summary>
    public class GyroException : Exception
    {
        public Status Status { get; }
        public string Function { get; }
        public string Detail { get; }

        public GyroException(Status status, string function, string detail)
            : this(status, function, detail, function + " failed: " + StatusName(status) + (detail.Length > 0 ? " (" + detail + ")" : "")) { }

        protected GyroException(Status status, string function, string detail, string message) : base(message)
        {
            Status = status;
            Function = function;
            Detail = detail;
        }

        static string StatusName(Status s)
        {
            try { return N.Utf8(N.gyro_status_name(s)); }
            catch (Exception) { return s.ToString(); }
        }
    }

    /// <summary>The loaded libgyro implements another ABI than this binding was written for.</summary>
    public sealed class GyroVersionException : GyroException
    {
        public uint LibraryAbi { get; }
        public uint BindingAbi { get; }

        public GyroVersionException(uint library, uint binding, string why)
            : base(Status.Unsupported, "gyro_abi_version", why,
                   "libgyro ABI " + (library >> 16) + "." + (library & 0xffff) + " cannot serve this binding (written for ABI " +
                   (binding >> 16) + "." + (binding & 0xffff) + "): " + why)
        {
            LibraryAbi = library;
            BindingAbi = binding;
        }
    }

    /// <summary>The library: version, features, SIMD level and threads.</summary>
    public static class GyroLibrary
    {
        /// <summary>The ABI this binding was written against.</summary>
        public const uint BindingAbi = Constants.GYRO_ABI_VERSION;
        public const int BindingAbiMajor = (int)(BindingAbi >> 16);
        public const int BindingAbiMinor = (int)(BindingAbi & 0xffff);

        static readonly object gate = new object();
        static volatile bool compatible;

        /// <summary>Checks once that libgyro loads and that its ABI serves this binding.
        /// Every class of this layer calls it before its first native call.</summary>
        public static void EnsureCompatible()
        {
            if (compatible) return;
            lock (gate)
            {
                if (compatible) return;
                uint v;
                try
                {
                    v = N.gyro_abi_version();
                }
                catch (DllNotFoundException e)
                {
                    throw new DllNotFoundException(
                        "gyro: cannot load the native library \"" + N.Library + "\" (libgyro.so on Linux, libgyro.dylib on macOS, gyro.dll on Windows); " +
                        "put it next to the program or on LD_LIBRARY_PATH / DYLD_LIBRARY_PATH / PATH", e);
                }
                CheckAbi(v);
                compatible = true;
            }
        }

        /// <summary>Throws GyroVersionException unless a library of ABI libraryAbi
        /// ((major &lt;&lt; 16) | minor) can serve this binding: the same major, and a minor at least
        /// the binding's (a newer library keeps every older minor's calls and layouts).</summary>
        public static void CheckAbi(uint libraryAbi)
        {
            uint major = libraryAbi >> 16, minor = libraryAbi & 0xffff;
            if (major != BindingAbiMajor)
                throw new GyroVersionException(libraryAbi, BindingAbi, "the major versions differ (" + major + " != " + BindingAbiMajor + "): layouts or calls changed incompatibly");
            if (minor < BindingAbiMinor)
                throw new GyroVersionException(libraryAbi, BindingAbi, "the library is older (minor " + minor + " < " + BindingAbiMinor + ") and lacks calls or fields this binding uses");
        }

        public static uint AbiVersion { get { EnsureCompatible(); return N.gyro_abi_version(); } }
        public static string Version { get { EnsureCompatible(); return N.Utf8(N.gyro_version_string()); } }
        public static Features Features { get { EnsureCompatible(); return N.gyro_features(); } }
        public static bool Has(Features f) { return (Features & f) == f; }

        /// <summary>The detail of this thread's last failed call ("" if none).</summary>
        public static string LastError { get { EnsureCompatible(); return N.Utf8(N.gyro_last_error()); } }
        public static string StatusName(Status s) { EnsureCompatible(); return N.Utf8(N.gyro_status_name(s)); }

        /// <summary>The level kernels run at; setting a level the build or CPU lacks throws
        /// (Status.Unsupported); SimdLevel.Auto returns to the default.</summary>
        public static SimdLevel SimdLevel
        {
            get { EnsureCompatible(); return N.gyro_get_simd_level(); }
            set { EnsureCompatible(); Check.Ok(N.gyro_set_simd_level(value), "gyro_set_simd_level"); }
        }
        public static bool IsSimdLevelAvailable(SimdLevel level) { EnsureCompatible(); return N.gyro_simd_level_available(level) != 0; }
        public static string SimdLevelName(SimdLevel level) { EnsureCompatible(); return N.Utf8(N.gyro_simd_level_name(level)); }

        /// <summary>Threads batch calls may use; 0 returns to the default. Results never depend on it.</summary>
        public static uint ThreadCount
        {
            get { EnsureCompatible(); return N.gyro_get_thread_count(); }
            set { EnsureCompatible(); Check.Ok(N.gyro_set_thread_count(value), "gyro_set_thread_count"); }
        }
    }

    internal static class Check
    {
        public static void Ok(Status s, string function)
        {
            if (s != Status.Ok) throw new GyroException(s, function, N.Utf8(N.gyro_last_error()));
        }

        public static void Length(int have, int need, string name)
        {
            if (have < need) throw new ArgumentException(name + " has " + have + " elements, the call needs " + need, name);
        }

        public static void NotNull(object o, string name)
        {
            if (o == null) throw new ArgumentNullException(name);
        }

        public static bool Bool(uint v) { return v != 0; }
    }

    /// <summary>The library's default definitions (gyro_*_def_default).</summary>
    public static class Defaults
    {
        public static WorldDef World() { GyroLibrary.EnsureCompatible(); return N.gyro_world_def_default(); }
        /// <summary>A dynamic unit box (half extents 0.5, 1 kg) at the origin, awake.</summary>
        public static BodyDef Body() { GyroLibrary.EnsureCompatible(); return N.gyro_body_def_default(); }
        public static MeshDef Mesh() { GyroLibrary.EnsureCompatible(); return N.gyro_mesh_def_default(); }
        public static ModelDef Model() { GyroLibrary.EnsureCompatible(); return N.gyro_model_def_default(); }
        public static SoftSettings SoftSettings() { GyroLibrary.EnsureCompatible(); return N.gyro_soft_settings_default(); }
        public static ClothDef Cloth() { GyroLibrary.EnsureCompatible(); return N.gyro_cloth_def_default(); }
        public static SoftCubeDef SoftCube() { GyroLibrary.EnsureCompatible(); return N.gyro_soft_cube_def_default(); }
        public static SoftMeshDef SoftMesh() { GyroLibrary.EnsureCompatible(); return N.gyro_soft_mesh_def_default(); }
    }

    /// <summary>Holds a SafeHandle's reference count up while its raw pointer is used (for the
    /// opaque pointers stored inside definition structs).</summary>
    internal struct HandleLease : IDisposable
    {
        readonly SafeHandle h;
        readonly bool added;
        public readonly IntPtr Pointer;

        public HandleLease(SafeHandle handle)
        {
            h = handle;
            added = false;
            Pointer = IntPtr.Zero;
            if (handle == null) return;
            handle.DangerousAddRef(ref added);
            Pointer = handle.DangerousGetHandle();
        }

        public void Dispose() { if (added) h.DangerousRelease(); }
    }

    // ------------------------------------------------------------------ batches (structure of arrays)

    /// <summary>Rays o + t d, t in [tmin, tmax], as arrays of Capacity elements; calls use the
    /// first Count. Tmin and Tmax are optional (null: 0 and +infinity); Set creates them on the
    /// first ray that needs them.</summary>
    public sealed class RayBatch
    {
        public readonly float[] Ox, Oy, Oz, Dx, Dy, Dz;
        public float[] Tmin, Tmax;
        int count;

        public RayBatch(int capacity, bool withRange = false)
        {
            if (capacity < 0) throw new ArgumentOutOfRangeException(nameof(capacity));
            Ox = new float[capacity]; Oy = new float[capacity]; Oz = new float[capacity];
            Dx = new float[capacity]; Dy = new float[capacity]; Dz = new float[capacity];
            if (withRange) { Tmin = new float[capacity]; Tmax = Filled(capacity, float.PositiveInfinity); }
            count = capacity;
        }

        public int Capacity => Ox.Length;
        public int Count
        {
            get { return count; }
            set { if (value < 0 || value > Capacity) throw new ArgumentOutOfRangeException(nameof(Count)); count = value; }
        }

        public void Set(int i, Vec3 origin, Vec3 direction, float tmin = 0, float tmax = float.PositiveInfinity)
        {
            Ox[i] = origin.X; Oy[i] = origin.Y; Oz[i] = origin.Z;
            Dx[i] = direction.X; Dy[i] = direction.Y; Dz[i] = direction.Z;
            if (Tmin == null && tmin != 0) Tmin = new float[Capacity];
            if (Tmax == null && !float.IsPositiveInfinity(tmax)) Tmax = Filled(Capacity, float.PositiveInfinity);
            if (Tmin != null) Tmin[i] = tmin;
            if (Tmax != null) Tmax[i] = tmax;
        }

        internal static float[] Filled(int n, float v)
        {
            float[] a = new float[n];
            for (int i = 0; i < n; ++i) a[i] = v;
            return a;
        }

        internal void CheckArrays()
        {
            if (Tmin != null) Check.Length(Tmin.Length, count, "Tmin");
            if (Tmax != null) Check.Length(Tmax.Length, count, "Tmax");
        }
    }

    /// <summary>Per-ray results: T and Primitive always; the normal and the barycentrics when
    /// asked for (null arrays are skipped by the call).</summary>
    public sealed class HitBatch
    {
        public readonly float[] T;
        public readonly int[] Primitive;
        public readonly float[] Nx, Ny, Nz, U, V;

        public HitBatch(int capacity, bool normals = true, bool barycentrics = false)
        {
            T = new float[capacity];
            Primitive = new int[capacity];
            if (normals) { Nx = new float[capacity]; Ny = new float[capacity]; Nz = new float[capacity]; }
            if (barycentrics) { U = new float[capacity]; V = new float[capacity]; }
        }

        public int Capacity => T.Length;
        public Vec3 Normal(int i) { return Nx == null ? Vec3.Zero : new Vec3(Nx[i], Ny[i], Nz[i]); }
    }

    /// <summary>Per-ray scene results: T and Model always, Primitive, the normal and the
    /// barycentrics when asked for.</summary>
    public sealed class SceneHitBatch
    {
        public readonly float[] T;
        public readonly ModelId[] Model;
        public readonly int[] Primitive;
        public readonly float[] Nx, Ny, Nz, U, V;

        public SceneHitBatch(int capacity, bool normals = true, bool barycentrics = false)
        {
            T = new float[capacity];
            Model = new ModelId[capacity];
            Primitive = new int[capacity];
            if (normals) { Nx = new float[capacity]; Ny = new float[capacity]; Nz = new float[capacity]; }
            if (barycentrics) { U = new float[capacity]; V = new float[capacity]; }
        }

        public int Capacity => T.Length;
        public Vec3 Normal(int i) { return Nx == null ? Vec3.Zero : new Vec3(Nx[i], Ny[i], Nz[i]); }
    }

    /// <summary>Spheres as arrays: centres and radii.</summary>
    public sealed class SphereBatch
    {
        public readonly float[] Cx, Cy, Cz, R;

        public SphereBatch(int capacity)
        {
            Cx = new float[capacity]; Cy = new float[capacity]; Cz = new float[capacity]; R = new float[capacity];
        }

        public int Count => Cx.Length;
        public void Set(int i, Vec3 c, float r) { Cx[i] = c.X; Cy[i] = c.Y; Cz[i] = c.Z; R[i] = r; }
    }

    internal static unsafe class Soa
    {
        public static RaySoa Rays(float* ox, float* oy, float* oz, float* dx, float* dy, float* dz, float* tmin, float* tmax)
        {
            RaySoa r;
            r.Ox = ox; r.Oy = oy; r.Oz = oz; r.Dx = dx; r.Dy = dy; r.Dz = dz; r.Tmin = tmin; r.Tmax = tmax;
            return r;
        }
    }

    // ------------------------------------------------------------------ free functions: rays, frustum, camera

    /// <summary>Brute-force batch queries on arrays of shapes.</summary>
    public static unsafe class Geometry
    {
        /// <summary>Closest hit of every ray against every sphere (ties to the lower index).</summary>
        public static void RaycastSpheresClosest(RayBatch rays, SphereBatch spheres, HitBatch hits)
        {
            Check.NotNull(rays, nameof(rays)); Check.NotNull(spheres, nameof(spheres)); Check.NotNull(hits, nameof(hits));
            GyroLibrary.EnsureCompatible();
            rays.CheckArrays();
            Check.Length(hits.Capacity, rays.Count, nameof(hits));
            fixed (float* ox = rays.Ox, oy = rays.Oy, oz = rays.Oz, dx = rays.Dx, dy = rays.Dy, dz = rays.Dz, tmin = rays.Tmin, tmax = rays.Tmax)
            fixed (float* cx = spheres.Cx, cy = spheres.Cy, cz = spheres.Cz, r = spheres.R)
            fixed (float* t = hits.T, nx = hits.Nx, ny = hits.Ny, nz = hits.Nz, u = hits.U, v = hits.V)
            fixed (int* prim = hits.Primitive)
            {
                RaySoa rs = Soa.Rays(ox, oy, oz, dx, dy, dz, tmin, tmax);
                SphereSoa ss; ss.Cx = cx; ss.Cy = cy; ss.Cz = cz; ss.R = r;
                HitSoa hs; hs.T = t; hs.Primitive = prim; hs.Nx = nx; hs.Ny = ny; hs.Nz = nz; hs.U = u; hs.V = v;
                Check.Ok(N.gyro_raycast_spheres_closest(&rs, rays.Count, &ss, spheres.Count, &hs), "gyro_raycast_spheres_closest");
            }
        }

        /// <summary>visible[i] = whether sphere i may be visible (never culls a visible one).</summary>
        public static void CullSpheres(Frustum frustum, SphereBatch spheres, uint[] visible)
        {
            Check.NotNull(spheres, nameof(spheres)); Check.NotNull(visible, nameof(visible));
            GyroLibrary.EnsureCompatible();
            Check.Length(visible.Length, spheres.Count, nameof(visible));
            fixed (float* cx = spheres.Cx, cy = spheres.Cy, cz = spheres.Cz, r = spheres.R)
            fixed (uint* vis = visible)
            {
                ShapeSoa s = default(ShapeSoa);
                s.Type = ShapeType.Sphere;
                s.As.Sphere.Cx = cx; s.As.Sphere.Cy = cy; s.As.Sphere.Cz = cz; s.As.Sphere.R = r;
                Check.Ok(N.gyro_frustum_cull(&frustum, &s, spheres.Count, vis), "gyro_frustum_cull");
            }
        }
    }

    /// <summary>Cameras (row vectors, depth in [0, 1]) and their frusta.</summary>
    public static unsafe class Cameras
    {
        public static Camera Perspective(float fovY, float aspect, float zNear, float zFar)
        {
            GyroLibrary.EnsureCompatible();
            return N.gyro_camera_perspective(fovY, aspect, zNear, zFar);
        }

        public static void LookAt(ref Camera camera, Vec3 eye, Vec3 target, Vec3 up)
        {
            GyroLibrary.EnsureCompatible();
            fixed (Camera* c = &camera)
                Check.Ok(N.gyro_camera_look_at(c, &eye.X, &target.X, &up.X), "gyro_camera_look_at");
        }

        /// <summary>The row-major view-projection matrix (clip = world * M), 16 floats.</summary>
        public static float[] ViewProjection(Camera camera)
        {
            GyroLibrary.EnsureCompatible();
            float[] m = new float[16];
            fixed (float* p = m) Check.Ok(N.gyro_camera_view_projection(&camera, p), "gyro_camera_view_projection");
            return m;
        }

        /// <summary>The ray through a screen point (pixels, origin top-left, y down).</summary>
        public static void PickingRay(Camera camera, float screenX, float screenY, float viewportWidth, float viewportHeight,
                                      out Vec3 origin, out Vec3 direction)
        {
            GyroLibrary.EnsureCompatible();
            Vec3 o = default(Vec3), d = default(Vec3);
            Check.Ok(N.gyro_camera_picking_ray(&camera, screenX, screenY, viewportWidth, viewportHeight, &o.X, &d.X), "gyro_camera_picking_ray");
            origin = o;
            direction = d;
        }

        public static Frustum Frustum(Camera camera)
        {
            GyroLibrary.EnsureCompatible();
            Frustum f;
            Check.Ok(N.gyro_camera_frustum(&camera, &f), "gyro_camera_frustum");
            return f;
        }

        public static Frustum FrustumFromMatrix(ReadOnlySpan<float> viewProjection)
        {
            GyroLibrary.EnsureCompatible();
            Check.Length(viewProjection.Length, 16, nameof(viewProjection));
            Frustum f;
            fixed (float* m = &MemoryMarshal.GetReference(viewProjection))
                Check.Ok(N.gyro_frustum_from_matrix(m, &f), "gyro_frustum_from_matrix");
            return f;
        }
    }

    // ------------------------------------------------------------------ meshes

    /// <summary>An immutable triangle mesh with its BVH; may be queried from many threads.</summary>
    public sealed unsafe class Mesh : IDisposable
    {
        public MeshHandle Handle { get; }

        Mesh(MeshHandle h) { Handle = h; }

        /// <summary>Copies the vertices (SoA) and 3 indices per triangle, and builds the BVH.</summary>
        public static Mesh Create(ReadOnlySpan<float> x, ReadOnlySpan<float> y, ReadOnlySpan<float> z, ReadOnlySpan<uint> indices)
        {
            GyroLibrary.EnsureCompatible();
            if (y.Length != x.Length || z.Length != x.Length) throw new ArgumentException("x, y and z must have the same length");
            if (indices.Length % 3 != 0) throw new ArgumentException("indices: 3 per triangle", nameof(indices));
            MeshDef def = N.gyro_mesh_def_default();
            MeshHandle h;
            fixed (float* px = &MemoryMarshal.GetReference(x), py = &MemoryMarshal.GetReference(y), pz = &MemoryMarshal.GetReference(z))
            fixed (uint* pi = &MemoryMarshal.GetReference(indices))
            {
                def.VertexCount = x.Length;
                def.X = px; def.Y = py; def.Z = pz;
                def.Indices = pi;
                def.TriangleCount = indices.Length / 3;
                Status s = N.gyro_mesh_create(&def, out h);
                if (s != Status.Ok) { h.Dispose(); Check.Ok(s, "gyro_mesh_create"); }
            }
            return new Mesh(h);
        }

        /// <summary>Reads a Wavefront OBJ file (v and f lines).</summary>
        public static Mesh LoadObj(string path)
        {
            Check.NotNull(path, nameof(path));
            GyroLibrary.EnsureCompatible();
            MeshHandle h;
            fixed (byte* p = N.ToUtf8z(path))
            {
                Status s = N.gyro_mesh_load_obj(p, out h);
                if (s != Status.Ok) { h.Dispose(); Check.Ok(s, "gyro_mesh_load_obj"); }
            }
            return new Mesh(h);
        }

        public MeshInfo Info
        {
            get { MeshInfo i; Check.Ok(N.gyro_mesh_get_info(Handle, &i), "gyro_mesh_get_info"); return i; }
        }

        /// <summary>Closest hit of every ray; Primitive is the triangle, -1 for a miss,
        /// Constants.GYRO_RAY_INVALID for a ray that cannot be answered.</summary>
        public void RaycastClosest(RayBatch rays, HitBatch hits) { Cast(rays, hits, false); }
        /// <summary>Any hit (occlusion).</summary>
        public void RaycastAny(RayBatch rays, HitBatch hits) { Cast(rays, hits, true); }

        void Cast(RayBatch rays, HitBatch hits, bool any)
        {
            Check.NotNull(rays, nameof(rays)); Check.NotNull(hits, nameof(hits));
            rays.CheckArrays();
            Check.Length(hits.Capacity, rays.Count, nameof(hits));
            fixed (float* ox = rays.Ox, oy = rays.Oy, oz = rays.Oz, dx = rays.Dx, dy = rays.Dy, dz = rays.Dz, tmin = rays.Tmin, tmax = rays.Tmax)
            fixed (float* t = hits.T, nx = hits.Nx, ny = hits.Ny, nz = hits.Nz, u = hits.U, v = hits.V)
            fixed (int* prim = hits.Primitive)
            {
                RaySoa rs = Soa.Rays(ox, oy, oz, dx, dy, dz, tmin, tmax);
                HitSoa hs; hs.T = t; hs.Primitive = prim; hs.Nx = nx; hs.Ny = ny; hs.Nz = nz; hs.U = u; hs.V = v;
                if (any) Check.Ok(N.gyro_mesh_raycast_any(Handle, &rs, rays.Count, &hs), "gyro_mesh_raycast_any");
                else Check.Ok(N.gyro_mesh_raycast_closest(Handle, &rs, rays.Count, &hs), "gyro_mesh_raycast_closest");
            }
        }

        public void Dispose() { Handle.Dispose(); }
    }

    // ------------------------------------------------------------------ scenes

    /// <summary>Models (spheres, boxes, planes, instanced meshes) under a BVH or an octree.</summary>
    public sealed unsafe class Scene : IDisposable
    {
        public SceneHandle Handle { get; }

        public Scene(SceneAccel accel = SceneAccel.Bvh)
        {
            GyroLibrary.EnsureCompatible();
            SceneHandle h;
            Status s = N.gyro_scene_create(accel, out h);
            if (s != Status.Ok) { h.Dispose(); Check.Ok(s, "gyro_scene_create"); }
            Handle = h;
        }

        /// <summary>Whether ray batches prefetch each next visit's cache lines (speed only, never a result).</summary>
        public void SetRayPrefetch(RayPrefetch mode)
        {
            Check.Ok(N.gyro_scene_set_ray_prefetch(Handle, mode), "gyro_scene_set_ray_prefetch");
        }

        /// <summary>Whether moves alone refit the BVH instead of rebuilding it (the default: true). Hits are
        /// the same either way, except which model an any hit names.</summary>
        public void SetRefit(bool enabled)
        {
            Check.Ok(N.gyro_scene_set_refit(Handle, enabled ? 1u : 0u), "gyro_scene_set_refit");
        }

        /// <summary>Adds a model; def.Mesh must be IntPtr.Zero (use AddMesh for meshes).</summary>
        public ModelId AddModel(ModelDef def)
        {
            if (def.Mesh != IntPtr.Zero) throw new ArgumentException("use AddMesh to place a mesh", nameof(def));
            ModelId id;
            Check.Ok(N.gyro_scene_add_model(Handle, &def, &id), "gyro_scene_add_model");
            return id;
        }

        public ModelId AddSphere(Vec3 center, float radius, ModelId parent = default(ModelId))
        {
            ModelDef d = N.gyro_model_def_default();
            d.Shape = ModelShape.Sphere;
            d.Radius = radius;
            d.Transform = Transform.At(center);
            d.Parent = parent;
            return AddModel(d);
        }

        public ModelId AddBox(Vec3 center, Vec3 halfExtents, ModelId parent = default(ModelId))
        {
            ModelDef d = N.gyro_model_def_default();
            d.Shape = ModelShape.Box;
            d.HalfExtents[0] = halfExtents.X; d.HalfExtents[1] = halfExtents.Y; d.HalfExtents[2] = halfExtents.Z;
            d.Transform = Transform.At(center);
            d.Parent = parent;
            return AddModel(d);
        }

        /// <summary>The plane dot(normal, p) = d (normal of unit length).</summary>
        public ModelId AddPlane(Vec3 normal, float d)
        {
            ModelDef m = N.gyro_model_def_default();
            m.Shape = ModelShape.Plane;
            m.Plane[0] = normal.X; m.Plane[1] = normal.Y; m.Plane[2] = normal.Z; m.Plane[3] = d;
            return AddModel(m);
        }

        /// <summary>An instance of mesh (the scene keeps its own reference).</summary>
        public ModelId AddMesh(Mesh mesh, Transform transform, ModelId parent = default(ModelId))
        {
            Check.NotNull(mesh, nameof(mesh));
            ModelDef d = N.gyro_model_def_default();
            d.Shape = ModelShape.Mesh;
            d.Transform = transform;
            d.Parent = parent;
            ModelId id;
            using (HandleLease lease = new HandleLease(mesh.Handle))
            {
                d.Mesh = lease.Pointer;
                Check.Ok(N.gyro_scene_add_model(Handle, &d, &id), "gyro_scene_add_model");
            }
            return id;
        }

        public void RemoveModel(ModelId id) { Check.Ok(N.gyro_scene_remove_model(Handle, id), "gyro_scene_remove_model"); }
        public void SetTransform(ModelId id, Transform local) { Check.Ok(N.gyro_scene_set_transform(Handle, id, &local), "gyro_scene_set_transform"); }
        public void SetParent(ModelId id, ModelId parent) { Check.Ok(N.gyro_scene_set_parent(Handle, id, parent), "gyro_scene_set_parent"); }
        /// <summary>The layers the model is in (all 32 to start with): masked rays, queries and picks see it only through a shared bit.</summary>
        public void SetLayers(ModelId id, uint layers) { Check.Ok(N.gyro_scene_set_layers(Handle, id, layers), "gyro_scene_set_layers"); }
        public int ModelCount => N.gyro_scene_model_count(Handle);

        /// <summary>Closest hit of every ray (the brute-force answer over every model). With masks, ray i sees only the models whose ray mask shares a bit with masks[i].</summary>
        public void RaycastClosest(RayBatch rays, SceneHitBatch hits, uint[] masks = null) { Cast(rays, hits, false, masks); }
        /// <summary>Any hit (occlusion, line of sight); masks as RaycastClosest.</summary>
        public void RaycastAny(RayBatch rays, SceneHitBatch hits, uint[] masks = null) { Cast(rays, hits, true, masks); }

        void Cast(RayBatch rays, SceneHitBatch hits, bool any, uint[] masks)
        {
            Check.NotNull(rays, nameof(rays)); Check.NotNull(hits, nameof(hits));
            rays.CheckArrays();
            Check.Length(hits.Capacity, rays.Count, nameof(hits));
            if (masks != null) Check.Length(masks.Length, rays.Count, nameof(masks));
            fixed (float* ox = rays.Ox, oy = rays.Oy, oz = rays.Oz, dx = rays.Dx, dy = rays.Dy, dz = rays.Dz, tmin = rays.Tmin, tmax = rays.Tmax)
            fixed (float* t = hits.T, nx = hits.Nx, ny = hits.Ny, nz = hits.Nz, u = hits.U, v = hits.V)
            fixed (ModelId* model = hits.Model)
            fixed (int* prim = hits.Primitive)
            {
                RaySoa rs = Soa.Rays(ox, oy, oz, dx, dy, dz, tmin, tmax);
                SceneHitSoa hs;
                hs.T = t; hs.Model = model; hs.Primitive = prim; hs.Nx = nx; hs.Ny = ny; hs.Nz = nz; hs.U = u; hs.V = v;
                fixed (uint* m = masks)
                {
                    if (any) Check.Ok(N.gyro_scene_raycast_any_masked(Handle, &rs, m, rays.Count, &hs), "gyro_scene_raycast_any_masked");
                    else Check.Ok(N.gyro_scene_raycast_closest_masked(Handle, &rs, m, rays.Count, &hs), "gyro_scene_raycast_closest_masked");
                }
            }
        }

        /// <summary>Models overlapping a sphere, ascending ids; only those whose layers share a bit with mask (as every query).</summary>
        public ModelId[] QuerySphere(Vec3 center, float radius, uint mask = 0xFFFFFFFFu)
        {
            float cx = center.X, cy = center.Y, cz = center.Z, r = radius;
            ShapeSoa s = default(ShapeSoa);
            s.Type = ShapeType.Sphere;
            s.As.Sphere.Cx = &cx; s.As.Sphere.Cy = &cy; s.As.Sphere.Cz = &cz; s.As.Sphere.R = &r;
            return Query(&s, null, mask);
        }

        /// <summary>Models overlapping an axis-aligned box, ascending ids.</summary>
        public ModelId[] QueryAabb(Vec3 center, Vec3 halfExtents, uint mask = 0xFFFFFFFFu)
        {
            float cx = center.X, cy = center.Y, cz = center.Z, ex = halfExtents.X, ey = halfExtents.Y, ez = halfExtents.Z;
            ShapeSoa s = default(ShapeSoa);
            s.Type = ShapeType.Aabb;
            s.As.Aabb.Cx = &cx; s.As.Aabb.Cy = &cy; s.As.Aabb.Cz = &cz; s.As.Aabb.Ex = &ex; s.As.Aabb.Ey = &ey; s.As.Aabb.Ez = &ez;
            return Query(&s, null, mask);
        }

        /// <summary>Models overlapping an oriented box (centre, half extents, unit axes: the rows of its orientation), ascending ids.</summary>
        public ModelId[] QueryObb(Vec3 center, Vec3 halfExtents, Vec3 axis0, Vec3 axis1, Vec3 axis2, uint mask = 0xFFFFFFFFu)
        {
            float cx = center.X, cy = center.Y, cz = center.Z, ex = halfExtents.X, ey = halfExtents.Y, ez = halfExtents.Z;
            float u0x = axis0.X, u0y = axis0.Y, u0z = axis0.Z, u1x = axis1.X, u1y = axis1.Y, u1z = axis1.Z;
            float u2x = axis2.X, u2y = axis2.Y, u2z = axis2.Z;
            ShapeSoa s = default(ShapeSoa);
            s.Type = ShapeType.Obb;
            s.As.Obb.Cx = &cx; s.As.Obb.Cy = &cy; s.As.Obb.Cz = &cz; s.As.Obb.Ex = &ex; s.As.Obb.Ey = &ey; s.As.Obb.Ez = &ez;
            s.As.Obb.U0x = &u0x; s.As.Obb.U0y = &u0y; s.As.Obb.U0z = &u0z;
            s.As.Obb.U1x = &u1x; s.As.Obb.U1y = &u1y; s.As.Obb.U1z = &u1z;
            s.As.Obb.U2x = &u2x; s.As.Obb.U2y = &u2y; s.As.Obb.U2z = &u2z;
            return Query(&s, null, mask);
        }

        /// <summary>Models whose bounding volume intersects the frustum, ascending ids.</summary>
        public ModelId[] QueryFrustum(Frustum frustum, uint mask = 0xFFFFFFFFu) { return Query(null, &frustum, mask); }

        ModelId[] Query(ShapeSoa* shape, Frustum* frustum, uint mask)
        {
            // Ask for the count, then fetch; a scene cannot change in between (one thread per scene).
            int count = 0;
            if (shape != null) Check.Ok(N.gyro_scene_query_masked(Handle, shape, mask, null, 0, &count), "gyro_scene_query_masked");
            else Check.Ok(N.gyro_scene_query_frustum_masked(Handle, frustum, mask, null, 0, &count), "gyro_scene_query_frustum_masked");
            ModelId[] ids = new ModelId[count];
            if (count == 0) return ids;
            fixed (ModelId* p = ids)
            {
                if (shape != null) Check.Ok(N.gyro_scene_query_masked(Handle, shape, mask, p, count, &count), "gyro_scene_query_masked");
                else Check.Ok(N.gyro_scene_query_frustum_masked(Handle, frustum, mask, p, count, &count), "gyro_scene_query_frustum_masked");
            }
            return ids;
        }

        /// <summary>The closest model under a screen point among those whose layers share a bit with mask; Hit == 0 when there is none.</summary>
        public SceneHit Pick(Camera camera, float screenX, float screenY, float viewportWidth, float viewportHeight, uint mask = 0xFFFFFFFFu)
        {
            SceneHit h;
            Check.Ok(N.gyro_scene_pick_masked(Handle, &camera, screenX, screenY, viewportWidth, viewportHeight, mask, &h), "gyro_scene_pick_masked");
            return h;
        }

        public void Dispose() { Handle.Dispose(); }
    }

    // ------------------------------------------------------------------ convex hulls and pair queries

    /// <summary>An immutable convex polyhedron (quickhull).</summary>
    public sealed unsafe class ConvexHull : IDisposable
    {
        public ConvexHullHandle Handle { get; }

        public ConvexHull(ReadOnlySpan<Vec3> points)
        {
            GyroLibrary.EnsureCompatible();
            ConvexHullHandle h;
            fixed (Vec3* p = &MemoryMarshal.GetReference(points))
            {
                Status s = N.gyro_convex_hull_create(p, points.Length, out h);
                if (s != Status.Ok) { h.Dispose(); Check.Ok(s, "gyro_convex_hull_create"); }
            }
            Handle = h;
        }

        public ConvexHullInfo Info
        {
            get { ConvexHullInfo i; Check.Ok(N.gyro_convex_hull_get_info(Handle, &i), "gyro_convex_hull_get_info"); return i; }
        }

        public Vec3[] Vertices()
        {
            int n = 0;
            Check.Ok(N.gyro_convex_hull_get_vertices(Handle, null, 0, &n), "gyro_convex_hull_get_vertices");
            Vec3[] a = new Vec3[n];
            fixed (Vec3* p = a) Check.Ok(N.gyro_convex_hull_get_vertices(Handle, p, n, &n), "gyro_convex_hull_get_vertices");
            return a;
        }

        public ConvexPlane[] Planes()
        {
            int n = 0;
            Check.Ok(N.gyro_convex_hull_get_planes(Handle, null, 0, &n), "gyro_convex_hull_get_planes");
            ConvexPlane[] a = new ConvexPlane[n];
            fixed (ConvexPlane* p = a) Check.Ok(N.gyro_convex_hull_get_planes(Handle, p, n, &n), "gyro_convex_hull_get_planes");
            return a;
        }

        /// <summary>face_count + 1 offsets into FaceVertices().</summary>
        public uint[] FaceStarts()
        {
            int n = 0;
            Check.Ok(N.gyro_convex_hull_get_face_starts(Handle, null, 0, &n), "gyro_convex_hull_get_face_starts");
            uint[] a = new uint[n];
            fixed (uint* p = a) Check.Ok(N.gyro_convex_hull_get_face_starts(Handle, p, n, &n), "gyro_convex_hull_get_face_starts");
            return a;
        }

        public uint[] FaceVertices()
        {
            int n = 0;
            Check.Ok(N.gyro_convex_hull_get_face_vertices(Handle, null, 0, &n), "gyro_convex_hull_get_face_vertices");
            uint[] a = new uint[n];
            fixed (uint* p = a) Check.Ok(N.gyro_convex_hull_get_face_vertices(Handle, p, n, &n), "gyro_convex_hull_get_face_vertices");
            return a;
        }

        public ConvexEdge[] Edges()
        {
            int n = 0;
            Check.Ok(N.gyro_convex_hull_get_edges(Handle, null, 0, &n), "gyro_convex_hull_get_edges");
            ConvexEdge[] a = new ConvexEdge[n];
            fixed (ConvexEdge* p = a) Check.Ok(N.gyro_convex_hull_get_edges(Handle, p, n, &n), "gyro_convex_hull_get_edges");
            return a;
        }

        /// <summary>Volume, centroid and inertia at density 1, in the hull's frame.</summary>
        public ConvexMass Mass()
        {
            ConvexMass m;
            Check.Ok(N.gyro_convex_hull_mass(Handle, &m), "gyro_convex_hull_mass");
            return m;
        }

        /// <summary>This hull as a shape for the Convex pair queries. The shape holds the raw
        /// pointer: keep this ConvexHull alive (undisposed) while the shape is used.</summary>
        public ConvexShape AsShape()
        {
            ConvexShape s = default(ConvexShape);
            s.Type = ConvexType.Hull;
            s.Hull = Handle.DangerousGetHandle();
            return s;
        }

        public void Dispose() { Handle.Dispose(); }
    }

    /// <summary>GJK/EPA queries on arrays of pairs (a[i] at pa[i], b[i] at pb[i]).</summary>
    public static unsafe class Convex
    {
        public static ConvexPose PoseFromQuat(Vec3 position, Quat orientation)
        {
            GyroLibrary.EnsureCompatible();
            ConvexPose p;
            Check.Ok(N.gyro_convex_pose_from_quat(position, orientation, &p), "gyro_convex_pose_from_quat");
            return p;
        }

        public static void IntersectPairs(ReadOnlySpan<ConvexShape> a, ReadOnlySpan<ConvexPose> pa, ReadOnlySpan<ConvexShape> b,
                                          ReadOnlySpan<ConvexPose> pb, Span<ConvexResult> results)
        { Pairs(0, a, pa, b, pb, results); }

        public static void DistancePairs(ReadOnlySpan<ConvexShape> a, ReadOnlySpan<ConvexPose> pa, ReadOnlySpan<ConvexShape> b,
                                         ReadOnlySpan<ConvexPose> pb, Span<ConvexResult> results)
        { Pairs(1, a, pa, b, pb, results); }

        public static void PenetrationPairs(ReadOnlySpan<ConvexShape> a, ReadOnlySpan<ConvexPose> pa, ReadOnlySpan<ConvexShape> b,
                                            ReadOnlySpan<ConvexPose> pb, Span<ConvexResult> results)
        { Pairs(2, a, pa, b, pb, results); }

        /// <summary>Contact generation's query (ABI 1.6): PenetrationPairs' answer for overlapping
        /// pairs; separated pairs stop at the first separating axis (Separated, distance an upper bound).</summary>
        public static void ContactPairs(ReadOnlySpan<ConvexShape> a, ReadOnlySpan<ConvexPose> pa, ReadOnlySpan<ConvexShape> b,
                                        ReadOnlySpan<ConvexPose> pb, Span<ConvexResult> results)
        { Pairs(3, a, pa, b, pb, results); }

        static void Pairs(int which, ReadOnlySpan<ConvexShape> a, ReadOnlySpan<ConvexPose> pa, ReadOnlySpan<ConvexShape> b,
                          ReadOnlySpan<ConvexPose> pb, Span<ConvexResult> results)
        {
            GyroLibrary.EnsureCompatible();
            int n = a.Length;
            if (pa.Length != n || b.Length != n || pb.Length != n)
                throw new ArgumentException("a, pa, b and pb must have the same length");
            Check.Length(results.Length, n, nameof(results));
            fixed (ConvexShape* sa = &MemoryMarshal.GetReference(a), sb = &MemoryMarshal.GetReference(b))
            fixed (ConvexPose* qa = &MemoryMarshal.GetReference(pa), qb = &MemoryMarshal.GetReference(pb))
            fixed (ConvexResult* r = &MemoryMarshal.GetReference(results))
            {
                if (which == 0) Check.Ok(N.gyro_convex_intersect_pairs(sa, qa, sb, qb, n, r), "gyro_convex_intersect_pairs");
                else if (which == 1) Check.Ok(N.gyro_convex_distance_pairs(sa, qa, sb, qb, n, r), "gyro_convex_distance_pairs");
                else if (which == 2) Check.Ok(N.gyro_convex_penetration_pairs(sa, qa, sb, qb, n, r), "gyro_convex_penetration_pairs");
                else Check.Ok(N.gyro_convex_contact_pairs(sa, qa, sb, qb, n, r), "gyro_convex_contact_pairs");
            }
        }
    }

    // ------------------------------------------------------------------ world

    /// <summary>Zero-copy read view of the bodies' state (dense slots 0..Count-1, Ids[i] names
    /// slot i). Valid until the next body creation or destruction, step, or Dispose.</summary>
    public unsafe struct BodyStateView
    {
        readonly BodyView v;
        internal BodyStateView(BodyView view) { v = view; }

        public int Count => v.Count;
        public ReadOnlySpan<BodyId> Ids => new ReadOnlySpan<BodyId>(v.Ids, v.Count);
        public ReadOnlySpan<float> Px => new ReadOnlySpan<float>(v.Px, v.Count);
        public ReadOnlySpan<float> Py => new ReadOnlySpan<float>(v.Py, v.Count);
        public ReadOnlySpan<float> Pz => new ReadOnlySpan<float>(v.Pz, v.Count);
        public ReadOnlySpan<float> Qx => new ReadOnlySpan<float>(v.Qx, v.Count);
        public ReadOnlySpan<float> Qy => new ReadOnlySpan<float>(v.Qy, v.Count);
        public ReadOnlySpan<float> Qz => new ReadOnlySpan<float>(v.Qz, v.Count);
        public ReadOnlySpan<float> Qw => new ReadOnlySpan<float>(v.Qw, v.Count);
        public ReadOnlySpan<float> Vx => new ReadOnlySpan<float>(v.Vx, v.Count);
        public ReadOnlySpan<float> Vy => new ReadOnlySpan<float>(v.Vy, v.Count);
        public ReadOnlySpan<float> Vz => new ReadOnlySpan<float>(v.Vz, v.Count);
        public ReadOnlySpan<float> Wx => new ReadOnlySpan<float>(v.Wx, v.Count);
        public ReadOnlySpan<float> Wy => new ReadOnlySpan<float>(v.Wy, v.Count);
        public ReadOnlySpan<float> Wz => new ReadOnlySpan<float>(v.Wz, v.Count);
        public Vec3 Position(int slot) { Bounds(slot); return new Vec3(v.Px[slot], v.Py[slot], v.Pz[slot]); }
        public Quat Orientation(int slot) { Bounds(slot); return new Quat(v.Qx[slot], v.Qy[slot], v.Qz[slot], v.Qw[slot]); }
        void Bounds(int slot) { if ((uint)slot >= (uint)v.Count) throw new ArgumentOutOfRangeException(nameof(slot)); }
    }

    /// <summary>Zero-copy read view of one soft body's particles and triangles. Valid until
    /// the next step, change of the body, soft body creation or destruction, or Dispose.</summary>
    public unsafe struct SoftBodyStateView
    {
        readonly SoftBodyView v;
        internal SoftBodyStateView(SoftBodyView view) { v = view; }

        public int Count => v.Count;
        public int TriangleCount => v.TriangleCount;
        public ReadOnlySpan<float> Px => new ReadOnlySpan<float>(v.Px, v.Count);
        public ReadOnlySpan<float> Py => new ReadOnlySpan<float>(v.Py, v.Count);
        public ReadOnlySpan<float> Pz => new ReadOnlySpan<float>(v.Pz, v.Count);
        public ReadOnlySpan<float> Vx => new ReadOnlySpan<float>(v.Vx, v.Count);
        public ReadOnlySpan<float> Vy => new ReadOnlySpan<float>(v.Vy, v.Count);
        public ReadOnlySpan<float> Vz => new ReadOnlySpan<float>(v.Vz, v.Count);
        public ReadOnlySpan<float> InverseMass => new ReadOnlySpan<float>(v.InverseMass, v.Count);
        /// <summary>Three particle indices per triangle.</summary>
        public ReadOnlySpan<uint> Triangles => new ReadOnlySpan<uint>(v.Triangles, v.TriangleCount * 3);
    }

    /// <summary>The last step's contact events, sorted by (a, b). Valid until the next step.</summary>
    public unsafe struct ContactEventsView
    {
        readonly ContactEvents e;
        internal ContactEventsView(ContactEvents events) { e = events; }
        public ReadOnlySpan<ContactEvent> Begin => new ReadOnlySpan<ContactEvent>(e.Begin, e.BeginCount);
        public ReadOnlySpan<ContactEvent> End => new ReadOnlySpan<ContactEvent>(e.End, e.EndCount);
    }

    /// <summary>A dynamics world: rigid bodies, contacts, soft bodies. One thread at a time;
    /// separate worlds may step in parallel.</summary>
    public sealed unsafe class World : IDisposable
    {
        public WorldHandle Handle { get; }

        World(WorldHandle h) { Handle = h; }

        /// <summary>A world with the library's default settings.</summary>
        public World() : this(Defaults.World()) { }

        public World(WorldDef def)
        {
            GyroLibrary.EnsureCompatible();
            WorldHandle h;
            Status s = N.gyro_world_create(&def, out h);
            if (s != Status.Ok) { h.Dispose(); Check.Ok(s, "gyro_world_create"); }
            Handle = h;
        }

        /// <summary>A new world holding a snapshot's state.</summary>
        public static World FromSnapshot(ReadOnlySpan<byte> snapshot)
        {
            GyroLibrary.EnsureCompatible();
            WorldHandle h;
            fixed (byte* p = &MemoryMarshal.GetReference(snapshot))
            {
                Status s = N.gyro_world_create_from_snapshot(p, (ulong)snapshot.Length, out h);
                if (s != Status.Ok) { h.Dispose(); Check.Ok(s, "gyro_world_create_from_snapshot"); }
            }
            return new World(h);
        }

        public void Dispose() { Handle.Dispose(); }

        /// <summary>Advances by dt seconds. A NaN, infinite or non-positive dt throws and changes nothing.</summary>
        public void Step(float dt) { Check.Ok(N.gyro_world_step(Handle, dt), "gyro_world_step"); }

        /// <summary>The 64-bit witness of the whole state.</summary>
        public ulong Hash
        {
            get { ulong h; Check.Ok(N.gyro_world_hash(Handle, &h), "gyro_world_hash"); return h; }
        }

        public int BodyCount
        {
            get { int n; Check.Ok(N.gyro_world_body_count(Handle, &n), "gyro_world_body_count"); return n; }
        }

        // -------------------------------------------------------------- bodies

        /// <summary>Creates a body; def.Mesh and def.Hull must be IntPtr.Zero (use the overloads).</summary>
        public BodyId CreateBody(BodyDef def)
        {
            if (def.Mesh != IntPtr.Zero || def.Hull != IntPtr.Zero)
                throw new ArgumentException("use CreateBody(def, Mesh) or CreateBody(def, ConvexHull)", nameof(def));
            BodyId id;
            Check.Ok(N.gyro_body_create(Handle, &def, &id), "gyro_body_create");
            return id;
        }

        /// <summary>A static mesh body (the world keeps its own reference to the mesh).</summary>
        public BodyId CreateBody(BodyDef def, Mesh mesh)
        {
            Check.NotNull(mesh, nameof(mesh));
            BodyId id;
            using (HandleLease lease = new HandleLease(mesh.Handle))
            {
                def.Shape = BodyShape.Mesh;
                def.Mesh = lease.Pointer;
                def.Hull = IntPtr.Zero;
                Check.Ok(N.gyro_body_create(Handle, &def, &id), "gyro_body_create");
            }
            return id;
        }

        /// <summary>A hull body (the world copies the hull).</summary>
        public BodyId CreateBody(BodyDef def, ConvexHull hull)
        {
            Check.NotNull(hull, nameof(hull));
            BodyId id;
            using (HandleLease lease = new HandleLease(hull.Handle))
            {
                def.Shape = BodyShape.Hull;
                def.Hull = lease.Pointer;
                def.Mesh = IntPtr.Zero;
                Check.Ok(N.gyro_body_create(Handle, &def, &id), "gyro_body_create");
            }
            return id;
        }

        public BodyId CreateBox(Vec3 position, Vec3 halfExtents, BodyType type = BodyType.Dynamic)
        {
            BodyDef d = N.gyro_body_def_default();
            d.Type = type; d.Shape = BodyShape.Box; d.HalfExtents = halfExtents; d.Position = position;
            return CreateBody(d);
        }

        public BodyId CreateSphere(Vec3 position, float radius, BodyType type = BodyType.Dynamic)
        {
            BodyDef d = N.gyro_body_def_default();
            d.Type = type; d.Shape = BodyShape.Sphere; d.Radius = radius; d.Position = position;
            return CreateBody(d);
        }

        /// <summary>A static ground plane y = height, normal +y.</summary>
        public BodyId CreateGround(float height = 0)
        {
            BodyDef d = N.gyro_body_def_default();
            d.Type = BodyType.Static; d.Shape = BodyShape.Plane; d.Position = new Vec3(0, height, 0);
            return CreateBody(d);
        }

        public void DestroyBody(BodyId id) { Check.Ok(N.gyro_body_destroy(Handle, id), "gyro_body_destroy"); }
        public bool IsValid(BodyId id) { return N.gyro_body_is_valid(Handle, id) != 0; }

        public void GetTransform(BodyId id, out Vec3 position, out Quat orientation)
        {
            Vec3 p; Quat q;
            Check.Ok(N.gyro_body_get_transform(Handle, id, &p, &q), "gyro_body_get_transform");
            position = p; orientation = q;
        }

        public Vec3 GetPosition(BodyId id)
        {
            Vec3 p;
            Check.Ok(N.gyro_body_get_transform(Handle, id, &p, null), "gyro_body_get_transform");
            return p;
        }

        public Quat GetOrientation(BodyId id)
        {
            Quat q;
            Check.Ok(N.gyro_body_get_transform(Handle, id, null, &q), "gyro_body_get_transform");
            return q;
        }

        /// <summary>Where the shape's own frame sits in the body frame (hull bodies: the mass frame).</summary>
        public void GetShapeFrame(BodyId id, out Vec3 offset, out Quat rotation)
        {
            Vec3 o; Quat r;
            Check.Ok(N.gyro_body_get_shape_frame(Handle, id, &o, &r), "gyro_body_get_shape_frame");
            offset = o; rotation = r;
        }

        /// <summary>Teleports the body and wakes it.</summary>
        public void SetTransform(BodyId id, Vec3 position, Quat orientation)
        {
            Check.Ok(N.gyro_body_set_transform(Handle, id, position, orientation), "gyro_body_set_transform");
        }

        public void GetVelocity(BodyId id, out Vec3 linear, out Vec3 angular)
        {
            Vec3 l, a;
            Check.Ok(N.gyro_body_get_velocity(Handle, id, &l, &a), "gyro_body_get_velocity");
            linear = l; angular = a;
        }

        public Vec3 GetLinearVelocity(BodyId id)
        {
            Vec3 l;
            Check.Ok(N.gyro_body_get_velocity(Handle, id, &l, null), "gyro_body_get_velocity");
            return l;
        }

        public Vec3 GetAngularVelocity(BodyId id)
        {
            Vec3 a;
            Check.Ok(N.gyro_body_get_velocity(Handle, id, null, &a), "gyro_body_get_velocity");
            return a;
        }

        public void SetVelocity(BodyId id, Vec3 linear, Vec3 angular)
        {
            Check.Ok(N.gyro_body_set_velocity(Handle, id, linear, angular), "gyro_body_set_velocity");
        }

        /// <summary>0 for static and kinematic bodies.</summary>
        public float GetMass(BodyId id) { float m; Check.Ok(N.gyro_body_get_mass(Handle, id, &m), "gyro_body_get_mass"); return m; }
        public BodyType GetBodyType(BodyId id) { BodyType t; Check.Ok(N.gyro_body_get_type(Handle, id, &t), "gyro_body_get_type"); return t; }
        public ulong GetUserData(BodyId id) { ulong u; Check.Ok(N.gyro_body_get_user_data(Handle, id, &u), "gyro_body_get_user_data"); return u; }

        /// <summary>Forces and torques act during the next step only.</summary>
        public void ApplyForce(BodyId id, Vec3 force, Vec3 worldPoint) { Check.Ok(N.gyro_body_apply_force(Handle, id, force, worldPoint), "gyro_body_apply_force"); }
        public void ApplyForceAtCenter(BodyId id, Vec3 force) { Check.Ok(N.gyro_body_apply_force_at_center(Handle, id, force), "gyro_body_apply_force_at_center"); }
        public void ApplyTorque(BodyId id, Vec3 torque) { Check.Ok(N.gyro_body_apply_torque(Handle, id, torque), "gyro_body_apply_torque"); }
        /// <summary>Impulses change the velocity at once.</summary>
        public void ApplyLinearImpulse(BodyId id, Vec3 impulse, Vec3 worldPoint) { Check.Ok(N.gyro_body_apply_linear_impulse(Handle, id, impulse, worldPoint), "gyro_body_apply_linear_impulse"); }
        public void ApplyAngularImpulse(BodyId id, Vec3 impulse) { Check.Ok(N.gyro_body_apply_angular_impulse(Handle, id, impulse), "gyro_body_apply_angular_impulse"); }

        public void SetAwake(BodyId id, bool awake) { Check.Ok(N.gyro_body_set_awake(Handle, id, awake ? 1u : 0u), "gyro_body_set_awake"); }
        public bool IsAwake(BodyId id) { uint a; Check.Ok(N.gyro_body_is_awake(Handle, id, &a), "gyro_body_is_awake"); return a != 0; }

        public BodyStateView GetBodyView()
        {
            BodyView v;
            Check.Ok(N.gyro_world_get_body_view(Handle, &v), "gyro_world_get_body_view");
            return new BodyStateView(v);
        }

        public StepTimings Timings
        {
            get { StepTimings t; Check.Ok(N.gyro_world_get_timings(Handle, &t), "gyro_world_get_timings"); return t; }
        }

        public StepStats Stats
        {
            get { StepStats s; Check.Ok(N.gyro_world_get_stats(Handle, &s), "gyro_world_get_stats"); return s; }
        }

        /// <summary>Milliseconds the last step spent in one stage.</summary>
        public double StageTime(StepStage stage)
        {
            double ms;
            Check.Ok(N.gyro_world_get_stage_time(Handle, stage, &ms), "gyro_world_get_stage_time");
            return ms;
        }

        public ContactEventsView ContactEvents
        {
            get { ContactEvents e; Check.Ok(N.gyro_world_get_contact_events(Handle, &e), "gyro_world_get_contact_events"); return new ContactEventsView(e); }
        }

        // -------------------------------------------------------------- soft bodies

        public SoftBodyId CreateCloth(ClothDef def)
        {
            SoftBodyId id;
            Check.Ok(N.gyro_world_create_cloth(Handle, &def, &id), "gyro_world_create_cloth");
            return id;
        }

        public SoftBodyId CreateSoftCube(SoftCubeDef def)
        {
            SoftBodyId id;
            Check.Ok(N.gyro_world_create_soft_cube(Handle, &def, &id), "gyro_world_create_soft_cube");
            return id;
        }

        /// <summary>A soft body from a closed triangle mesh; the pointer fields of def are set
        /// from the spans (the other fields are taken from def: start from Defaults.SoftMesh()).</summary>
        public SoftBodyId CreateSoftMesh(SoftMeshDef def, ReadOnlySpan<float> x, ReadOnlySpan<float> y, ReadOnlySpan<float> z, ReadOnlySpan<uint> indices)
        {
            if (y.Length != x.Length || z.Length != x.Length) throw new ArgumentException("x, y and z must have the same length");
            if (indices.Length % 3 != 0) throw new ArgumentException("indices: 3 per triangle", nameof(indices));
            SoftBodyId id;
            fixed (float* px = &MemoryMarshal.GetReference(x), py = &MemoryMarshal.GetReference(y), pz = &MemoryMarshal.GetReference(z))
            fixed (uint* pi = &MemoryMarshal.GetReference(indices))
            {
                def.VertexCount = x.Length;
                def.X = px; def.Y = py; def.Z = pz;
                def.Indices = pi;
                def.TriangleCount = indices.Length / 3;
                Check.Ok(N.gyro_world_create_soft_mesh(Handle, &def, &id), "gyro_world_create_soft_mesh");
            }
            return id;
        }

        public void DestroySoftBody(SoftBodyId id) { Check.Ok(N.gyro_world_destroy_soft_body(Handle, id), "gyro_world_destroy_soft_body"); }
        public bool IsValid(SoftBodyId id) { return N.gyro_soft_body_is_valid(Handle, id) != 0; }

        public int SoftBodyCount
        {
            get { int n; Check.Ok(N.gyro_world_soft_body_count(Handle, &n), "gyro_world_soft_body_count"); return n; }
        }

        public void SetSoftSettings(SoftBodyId id, SoftSettings settings)
        {
            Check.Ok(N.gyro_soft_body_set_settings(Handle, id, &settings), "gyro_soft_body_set_settings");
        }

        public SoftSettings GetSoftSettings(SoftBodyId id)
        {
            SoftSettings s = N.gyro_soft_settings_default();
            Check.Ok(N.gyro_soft_body_get_settings(Handle, id, &s), "gyro_soft_body_get_settings");
            return s;
        }

        public void SetSpringFamily(SoftBodyId id, SpringFamily family, SpringConstants constants)
        {
            Check.Ok(N.gyro_soft_body_set_family(Handle, id, family, &constants), "gyro_soft_body_set_family");
        }

        public SpringConstants GetSpringFamily(SoftBodyId id, SpringFamily family)
        {
            SpringConstants c;
            Check.Ok(N.gyro_soft_body_get_family(Handle, id, family, &c), "gyro_soft_body_get_family");
            return c;
        }

        public void SetSoftMass(SoftBodyId id, float mass) { Check.Ok(N.gyro_soft_body_set_mass(Handle, id, mass), "gyro_soft_body_set_mass"); }
        public void SetParticleMass(SoftBodyId id, uint particle, float mass) { Check.Ok(N.gyro_soft_body_set_particle_mass(Handle, id, particle, mass), "gyro_soft_body_set_particle_mass"); }
        public void Pin(SoftBodyId id, uint particle) { Check.Ok(N.gyro_soft_body_pin(Handle, id, particle), "gyro_soft_body_pin"); }
        public void Unpin(SoftBodyId id, uint particle) { Check.Ok(N.gyro_soft_body_unpin(Handle, id, particle), "gyro_soft_body_unpin"); }

        public bool IsPinned(SoftBodyId id, uint particle)
        {
            uint p;
            Check.Ok(N.gyro_soft_body_is_pinned(Handle, id, particle, &p), "gyro_soft_body_is_pinned");
            return p != 0;
        }

        public Vec3 GetParticlePosition(SoftBodyId id, uint particle)
        {
            Vec3 p;
            Check.Ok(N.gyro_soft_body_get_position(Handle, id, particle, &p), "gyro_soft_body_get_position");
            return p;
        }

        public void SetParticlePosition(SoftBodyId id, uint particle, Vec3 position)
        {
            Check.Ok(N.gyro_soft_body_set_position(Handle, id, particle, position), "gyro_soft_body_set_position");
        }

        public Vec3 GetParticleVelocity(SoftBodyId id, uint particle)
        {
            Vec3 v;
            Check.Ok(N.gyro_soft_body_get_velocity(Handle, id, particle, &v), "gyro_soft_body_get_velocity");
            return v;
        }

        public void SetParticleVelocity(SoftBodyId id, uint particle, Vec3 velocity)
        {
            Check.Ok(N.gyro_soft_body_set_velocity(Handle, id, particle, velocity), "gyro_soft_body_set_velocity");
        }

        /// <summary>A cloth's particle at grid column ix (along x) and row iz (along z).</summary>
        public uint ClothIndex(SoftBodyId id, uint ix, uint iz)
        {
            uint i;
            Check.Ok(N.gyro_soft_body_cloth_index(Handle, id, ix, iz, &i), "gyro_soft_body_cloth_index");
            return i;
        }

        /// <summary>Keeps particles a and b restLength apart (negative: their current distance);
        /// returns the joint's number among the body's joints.</summary>
        public uint AddDistanceJoint(SoftBodyId id, uint a, uint b, float restLength)
        {
            uint j;
            Check.Ok(N.gyro_soft_body_add_distance_joint(Handle, id, a, b, restLength, &j), "gyro_soft_body_add_distance_joint");
            return j;
        }

        public void AddBallJoint(SoftBodyId id, uint a, uint b) { Check.Ok(N.gyro_soft_body_add_ball_joint(Handle, id, a, b), "gyro_soft_body_add_ball_joint"); }

        public void AddHingeJoint(SoftBodyId id, uint a0, uint b0, uint a1, uint b1)
        {
            Check.Ok(N.gyro_soft_body_add_hinge_joint(Handle, id, a0, b0, a1, b1), "gyro_soft_body_add_hinge_joint");
        }

        public SoftBodyStateView GetSoftBodyView(SoftBodyId id)
        {
            SoftBodyView v;
            Check.Ok(N.gyro_soft_body_get_view(Handle, id, &v), "gyro_soft_body_get_view");
            return new SoftBodyStateView(v);
        }

        public SoftBodyStats GetSoftBodyStats(SoftBodyId id)
        {
            SoftBodyStats s;
            Check.Ok(N.gyro_soft_body_get_stats(Handle, id, &s), "gyro_soft_body_get_stats");
            return s;
        }

        public ulong SoftBodyHash(SoftBodyId id)
        {
            ulong h;
            Check.Ok(N.gyro_soft_body_hash(Handle, id, &h), "gyro_soft_body_hash");
            return h;
        }

        // -------------------------------------------------------------- snapshot and restore

        /// <summary>Bytes a snapshot of the world as it is now takes.</summary>
        public long SnapshotSize
        {
            get { ulong n; Check.Ok(N.gyro_world_snapshot_size(Handle, &n), "gyro_world_snapshot_size"); return checked((long)n); }
        }

        /// <summary>The world's whole state as bytes.</summary>
        public byte[] Snapshot()
        {
            byte[] b = new byte[checked((int)SnapshotSize)];
            int n = Snapshot(b);
            if (n != b.Length) Array.Resize(ref b, n);
            return b;
        }

        /// <summary>Writes a snapshot into buffer and returns its size in bytes (throws
        /// GyroException with Status.InvalidCount when buffer is too small).</summary>
        public int Snapshot(Span<byte> buffer)
        {
            ulong n;
            fixed (byte* p = &MemoryMarshal.GetReference(buffer))
                Check.Ok(N.gyro_world_snapshot(Handle, p, (ulong)buffer.Length, &n), "gyro_world_snapshot");
            return checked((int)n);
        }

        /// <summary>Replaces the world's whole state with a snapshot's (unchanged on failure).</summary>
        public void Restore(ReadOnlySpan<byte> snapshot)
        {
            fixed (byte* p = &MemoryMarshal.GetReference(snapshot))
                Check.Ok(N.gyro_world_restore(Handle, p, (ulong)snapshot.Length), "gyro_world_restore");
        }

        // -------------------------------------------------------------- record and replay

        public void RecordBegin() { Check.Ok(N.gyro_world_record_begin(Handle), "gyro_world_record_begin"); }
        public void RecordEnd() { Check.Ok(N.gyro_world_record_end(Handle), "gyro_world_record_end"); }

        /// <summary>The recording so far.</summary>
        public byte[] RecordCopy()
        {
            ulong size;
            Check.Ok(N.gyro_world_record_size(Handle, &size), "gyro_world_record_size");
            byte[] b = new byte[checked((int)size)];
            ulong n;
            fixed (byte* p = b) Check.Ok(N.gyro_world_record_copy(Handle, p, (ulong)b.Length, &n), "gyro_world_record_copy");
            if (n != (ulong)b.Length) Array.Resize(ref b, checked((int)n));
            return b;
        }

        public void RecordSave(string path)
        {
            Check.NotNull(path, nameof(path));
            fixed (byte* p = N.ToUtf8z(path)) Check.Ok(N.gyro_world_record_save(Handle, p), "gyro_world_record_save");
        }
    }

    /// <summary>Replays recordings (World.RecordBegin ... RecordCopy / RecordSave).</summary>
    public static unsafe class Replay
    {
        /// <summary>A divergence is a result (Diverged = 1), not an exception.</summary>
        public static ReplayReport Run(ReadOnlySpan<byte> recording)
        {
            GyroLibrary.EnsureCompatible();
            ReplayReport r = default(ReplayReport);
            r.StructSize = (uint)Marshal.SizeOf(typeof(ReplayReport));
            fixed (byte* p = &MemoryMarshal.GetReference(recording))
                Check.Ok(N.gyro_replay(p, (ulong)recording.Length, &r), "gyro_replay");
            return r;
        }

        public static ReplayReport RunFile(string path)
        {
            Check.NotNull(path, nameof(path));
            GyroLibrary.EnsureCompatible();
            ReplayReport r = default(ReplayReport);
            r.StructSize = (uint)Marshal.SizeOf(typeof(ReplayReport));
            fixed (byte* p = N.ToUtf8z(path)) Check.Ok(N.gyro_replay_file(p, &r), "gyro_replay_file");
            return r;
        }
    }
}
