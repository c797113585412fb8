// gyro's C ABI (capi/gyro.h) for C#: the raw layer.
//
// - Every struct here is blittable, [StructLayout(LayoutKind.Sequential)], and names the C
//   struct it maps with [CStruct("gyro_...")]. Its fields are the C fields in C order, named
//   by the convention PascalCase(c_name) (struct_size -> StructSize, fov_y -> FovY). A C
//   array of a primitive type is a fixed buffer of the same length; a C array of structs
//   (gyro_vec3 inertia[3]) is one field per element, Inertia0 .. Inertia2.
// - Constants keep their C names (Constants.GYRO_OK); the enums below are built from them
//   and name the C typedef they stand for with [CEnum("gyro_...")].
// - NativeMethods holds one [DllImport("gyro")] per C function, under the C name. Opaque
//   objects are SafeHandles (WorldHandle, MeshHandle, SceneHandle, ConvexHullHandle); an
//   opaque pointer stored inside a struct is an IntPtr.
// - The test (tests/GyroTest.cs) checks all of this against <build>/capi/api/gyro_api.json:
//   sizes, offsets and types of every field, values of every constant, and every entry
//   point's return and parameter types.
//
// Everything here is unsafe and unchecked; Gyro.cs is the safe layer over it.
using System;
using System.Runtime.InteropServices;
using Microsoft.Win32.SafeHandles;

namespace Gyro.Native
{
    /// <summary>The C struct (or typedef'd struct) a C# struct maps.</summary>
    [AttributeUsage(AttributeTargets.Struct)]
    public sealed class CStructAttribute : Attribute
    {
        public readonly string Name;
        public CStructAttribute(string name) { Name = name; }
    }

    /// <summary>An anonymous C union: the struct that holds it and its field name there.</summary>
    [AttributeUsage(AttributeTargets.Struct)]
    public sealed class CUnionAttribute : Attribute
    {
        public readonly string Struct, Field;
        public CUnionAttribute(string structName, string field) { Struct = structName; Field = field; }
    }

    /// <summary>The C integer typedef an enum stands for (gyro_status, gyro_body_type, ...);
    /// null for an anonymous enum block (feature bits, overlap results, batch flags).</summary>
    [AttributeUsage(AttributeTargets.Enum)]
    public sealed class CEnumAttribute : Attribute
    {
        public readonly string Typedef;
        public CEnumAttribute(string typedefName) { Typedef = typedefName; }
    }

    /// <summary>The opaque C type a SafeHandle owns.</summary>
    [AttributeUsage(AttributeTargets.Class)]
    public sealed class COpaqueAttribute : Attribute
    {
        public readonly string Name;
        public COpaqueAttribute(string name) { Name = name; }
    }

    /// <summary>Every constant of gyro.h, under its C name.</summary>
    public static class Constants
    {
        /// <summary>The ABI this binding was written against: (major &lt;&lt; 16) | minor.</summary>
        public const uint GYRO_ABI_VERSION = (1u << 16) | 9u;

        public const uint GYRO_FEATURE_OPENMP = 1u << 0;
        public const uint GYRO_FEATURE_SIMD_SSE2 = 1u << 1;
        public const uint GYRO_FEATURE_SIMD_AVX2 = 1u << 2;
        public const uint GYRO_FEATURE_SIMD_AVX512 = 1u << 3;
        public const uint GYRO_FEATURE_SIMD_NEON = 1u << 4;
        public const uint GYRO_FEATURE_MATH = 1u << 8;
        public const uint GYRO_FEATURE_GEOMETRY = 1u << 9;
        public const uint GYRO_FEATURE_2D = 1u << 10;
        public const uint GYRO_FEATURE_SPATIAL = 1u << 11;
        public const uint GYRO_FEATURE_DYNAMICS = 1u << 12;
        public const uint GYRO_FEATURE_SOFT_BODIES = 1u << 13;
        public const uint GYRO_FEATURE_CONVEX = 1u << 14;
        public const uint GYRO_FEATURE_SNAPSHOT = 1u << 15;
        public const uint GYRO_FEATURE_REPLAY = 1u << 16;

        public const int GYRO_OK = 0;
        public const int GYRO_STATUS_NULL_ARGUMENT = 1;
        public const int GYRO_STATUS_INVALID_COUNT = 2;
        public const int GYRO_STATUS_NON_FINITE = 3;
        public const int GYRO_STATUS_INVALID_ARGUMENT = 4;
        public const int GYRO_STATUS_UNSUPPORTED = 5;
        public const int GYRO_STATUS_OUT_OF_MEMORY = 6;
        public const int GYRO_STATUS_STALE_ID = 7;
        public const int GYRO_STATUS_INTERNAL = 8;
        public const int GYRO_STATUS_CORRUPT_DATA = 9;

        public const uint GYRO_SIMD_AUTO = 0;
        public const uint GYRO_SIMD_SCALAR = 1;
        public const uint GYRO_SIMD_SSE2 = 2;
        public const uint GYRO_SIMD_AVX2 = 3;
        public const uint GYRO_SIMD_AVX512 = 4;
        public const uint GYRO_SIMD_NEON = 5;

        public const uint GYRO_SHAPE_SPHERE = 1;
        public const uint GYRO_SHAPE_AABB = 2;
        public const uint GYRO_SHAPE_OBB = 3;
        public const uint GYRO_SHAPE_PLANE = 4;
        public const uint GYRO_SHAPE_TRIANGLE = 5;

        public const uint GYRO_SEPARATED = 0;
        public const uint GYRO_OVERLAPPING = 1;
        public const uint GYRO_INVALID_INPUT = 2;

        public const uint GYRO_BATCH_STRICT = 1u << 0;

        public const int GYRO_RAY_INVALID = -2;

        public const uint GYRO_PROJECTION_PERSPECTIVE = 0;
        public const uint GYRO_PROJECTION_ORTHOGRAPHIC = 1;

        public const uint GYRO_MODEL_SPHERE = 0;
        public const uint GYRO_MODEL_BOX = 1;
        public const uint GYRO_MODEL_MESH = 2;
        public const uint GYRO_MODEL_PLANE = 3;

        public const uint GYRO_SCENE_BVH = 0;
        public const uint GYRO_SCENE_OCTREE = 1;
        public const uint GYRO_RAY_PREFETCH_AUTO = 0;
        public const uint GYRO_RAY_PREFETCH_ALWAYS = 1;
        public const uint GYRO_RAY_PREFETCH_NEVER = 2;

        public const uint GYRO_BODY_STATIC = 0;
        public const uint GYRO_BODY_KINEMATIC = 1;
        public const uint GYRO_BODY_DYNAMIC = 2;

        public const uint GYRO_BODY_SHAPE_SPHERE = 0;
        public const uint GYRO_BODY_SHAPE_BOX = 1;
        public const uint GYRO_BODY_SHAPE_PLANE = 2;
        public const uint GYRO_BODY_SHAPE_MESH = 3;
        public const uint GYRO_BODY_SHAPE_CAPSULE = 4;
        public const uint GYRO_BODY_SHAPE_HULL = 5;

        public const uint GYRO_CONTACT_SOFT_STEP = 0;
        public const uint GYRO_CONTACT_BAUMGARTE = 1;
        public const uint GYRO_CONTACT_LINEAR_PROJECTION = 2;

        public const uint GYRO_CONVEX_MANIFOLD_CLIPPING = 0;
        public const uint GYRO_CONVEX_MANIFOLD_INCREMENTAL = 1;

        public const uint GYRO_STAGE_FORCES = 0;
        public const uint GYRO_STAGE_BROADPHASE = 1;
        public const uint GYRO_STAGE_NARROWPHASE = 2;
        public const uint GYRO_STAGE_ISLANDS = 3;
        public const uint GYRO_STAGE_SOLVER = 4;
        public const uint GYRO_STAGE_PARTICLES = 5;
        public const uint GYRO_STAGE_TOTAL = 6;
        public const uint GYRO_STAGE_SOFT_BODIES = 7;

        public const uint GYRO_SOFT_MODEL_XPBD = 0;
        public const uint GYRO_SOFT_MODEL_SPRINGS = 1;

        public const uint GYRO_SPRING_STRUCTURAL = 0;
        public const uint GYRO_SPRING_SHEAR = 1;
        public const uint GYRO_SPRING_BEND = 2;
        public const uint GYRO_SPRING_RADIAL = 3;
        public const uint GYRO_SPRING_JOINT = 4;

        public const uint GYRO_COLLISION_PROJECTION = 0;
        public const uint GYRO_COLLISION_PENALTY = 1;

        public const uint GYRO_CONVEX_SPHERE = 0;
        public const uint GYRO_CONVEX_BOX = 1;
        public const uint GYRO_CONVEX_CAPSULE = 2;
        public const uint GYRO_CONVEX_CYLINDER = 3;
        public const uint GYRO_CONVEX_TRIANGLE = 4;
        public const uint GYRO_CONVEX_HULL = 5;

        public const uint GYRO_CONVEX_SEPARATED = 0;
        public const uint GYRO_CONVEX_TOUCHING = 1;
        public const uint GYRO_CONVEX_INTERSECTING = 2;
        public const uint GYRO_CONVEX_ITERATION_LIMIT = 3;
        public const uint GYRO_CONVEX_INVALID_INPUT = 4;
    }

    // ------------------------------------------------------------------ enums

    [Flags, CEnum(null)]
    public enum Features : uint
    {
        None = 0,
        OpenMP = Constants.GYRO_FEATURE_OPENMP,
        SimdSse2 = Constants.GYRO_FEATURE_SIMD_SSE2,
        SimdAvx2 = Constants.GYRO_FEATURE_SIMD_AVX2,
        SimdAvx512 = Constants.GYRO_FEATURE_SIMD_AVX512,
        SimdNeon = Constants.GYRO_FEATURE_SIMD_NEON,
        Math = Constants.GYRO_FEATURE_MATH,
        Geometry = Constants.GYRO_FEATURE_GEOMETRY,
        TwoD = Constants.GYRO_FEATURE_2D,
        Spatial = Constants.GYRO_FEATURE_SPATIAL,
        Dynamics = Constants.GYRO_FEATURE_DYNAMICS,
        SoftBodies = Constants.GYRO_FEATURE_SOFT_BODIES,
        Convex = Constants.GYRO_FEATURE_CONVEX,
        Snapshot = Constants.GYRO_FEATURE_SNAPSHOT,
        Replay = Constants.GYRO_FEATURE_REPLAY,
    }

    [CEnum("gyro_status")]
    public enum Status : int
    {
        Ok = Constants.GYRO_OK,
        NullArgument = Constants.GYRO_STATUS_NULL_ARGUMENT,
        InvalidCount = Constants.GYRO_STATUS_INVALID_COUNT,
        NonFinite = Constants.GYRO_STATUS_NON_FINITE,
        InvalidArgument = Constants.GYRO_STATUS_INVALID_ARGUMENT,
        Unsupported = Constants.GYRO_STATUS_UNSUPPORTED,
        OutOfMemory = Constants.GYRO_STATUS_OUT_OF_MEMORY,
        StaleId = Constants.GYRO_STATUS_STALE_ID,
        Internal = Constants.GYRO_STATUS_INTERNAL,
        CorruptData = Constants.GYRO_STATUS_CORRUPT_DATA,
    }

    [CEnum("gyro_simd_level")]
    public enum SimdLevel : uint
    {
        Auto = Constants.GYRO_SIMD_AUTO,
        Scalar = Constants.GYRO_SIMD_SCALAR,
        Sse2 = Constants.GYRO_SIMD_SSE2,
        Avx2 = Constants.GYRO_SIMD_AVX2,
        Avx512 = Constants.GYRO_SIMD_AVX512,
        Neon = Constants.GYRO_SIMD_NEON,
    }

    [CEnum("gyro_shape_type")]
    public enum ShapeType : uint
    {
        Sphere = Constants.GYRO_SHAPE_SPHERE,
        Aabb = Constants.GYRO_SHAPE_AABB,
        Obb = Constants.GYRO_SHAPE_OBB,
        Plane = Constants.GYRO_SHAPE_PLANE,
        Triangle = Constants.GYRO_SHAPE_TRIANGLE,
    }

    /// <summary>Per-pair results of the overlap calls (uint32_t out arrays).</summary>
    [CEnum(null)]
    public enum OverlapResult : uint
    {
        Separated = Constants.GYRO_SEPARATED,
        Overlapping = Constants.GYRO_OVERLAPPING,
        InvalidInput = Constants.GYRO_INVALID_INPUT,
    }

    [Flags, CEnum(null)]
    public enum BatchFlags : uint
    {
        None = 0,
        Strict = Constants.GYRO_BATCH_STRICT,
    }

    [CEnum("gyro_projection")]
    public enum Projection : uint
    {
        Perspective = Constants.GYRO_PROJECTION_PERSPECTIVE,
        Orthographic = Constants.GYRO_PROJECTION_ORTHOGRAPHIC,
    }

    [CEnum("gyro_model_shape")]
    public enum ModelShape : uint
    {
        Sphere = Constants.GYRO_MODEL_SPHERE,
        Box = Constants.GYRO_MODEL_BOX,
        Mesh = Constants.GYRO_MODEL_MESH,
        Plane = Constants.GYRO_MODEL_PLANE,
    }

    [CEnum("gyro_scene_accel")]
    public enum SceneAccel : uint
    {
        Bvh = Constants.GYRO_SCENE_BVH,
        Octree = Constants.GYRO_SCENE_OCTREE,
    }

    [CEnum("gyro_ray_prefetch")]
    public enum RayPrefetch : uint
    {
        Auto = Constants.GYRO_RAY_PREFETCH_AUTO,
        Always = Constants.GYRO_RAY_PREFETCH_ALWAYS,
        Never = Constants.GYRO_RAY_PREFETCH_NEVER,
    }

    [CEnum("gyro_body_type")]
    public enum BodyType : uint
    {
        Static = Constants.GYRO_BODY_STATIC,
        Kinematic = Constants.GYRO_BODY_KINEMATIC,
        Dynamic = Constants.GYRO_BODY_DYNAMIC,
    }

    [CEnum("gyro_body_shape")]
    public enum BodyShape : uint
    {
        Sphere = Constants.GYRO_BODY_SHAPE_SPHERE,
        Box = Constants.GYRO_BODY_SHAPE_BOX,
        Plane = Constants.GYRO_BODY_SHAPE_PLANE,
        Mesh = Constants.GYRO_BODY_SHAPE_MESH,
        Capsule = Constants.GYRO_BODY_SHAPE_CAPSULE,
        Hull = Constants.GYRO_BODY_SHAPE_HULL,
    }

    [CEnum("gyro_contact_model")]
    public enum ContactModel : uint
    {
        SoftStep = Constants.GYRO_CONTACT_SOFT_STEP,
        Baumgarte = Constants.GYRO_CONTACT_BAUMGARTE,
        LinearProjection = Constants.GYRO_CONTACT_LINEAR_PROJECTION,
    }

    [CEnum("gyro_convex_manifold")]
    public enum ConvexManifold : uint
    {
        Clipping = Constants.GYRO_CONVEX_MANIFOLD_CLIPPING,
        Incremental = Constants.GYRO_CONVEX_MANIFOLD_INCREMENTAL,
    }

    [CEnum("gyro_step_stage")]
    public enum StepStage : uint
    {
        Forces = Constants.GYRO_STAGE_FORCES,
        Broadphase = Constants.GYRO_STAGE_BROADPHASE,
        Narrowphase = Constants.GYRO_STAGE_NARROWPHASE,
        Islands = Constants.GYRO_STAGE_ISLANDS,
        Solver = Constants.GYRO_STAGE_SOLVER,
        Particles = Constants.GYRO_STAGE_PARTICLES,
        Total = Constants.GYRO_STAGE_TOTAL,
        SoftBodies = Constants.GYRO_STAGE_SOFT_BODIES,
    }

    [CEnum("gyro_soft_model")]
    public enum SoftModel : uint
    {
        Xpbd = Constants.GYRO_SOFT_MODEL_XPBD,
        Springs = Constants.GYRO_SOFT_MODEL_SPRINGS,
    }

    [CEnum("gyro_spring_family")]
    public enum SpringFamily : uint
    {
        Structural = Constants.GYRO_SPRING_STRUCTURAL,
        Shear = Constants.GYRO_SPRING_SHEAR,
        Bend = Constants.GYRO_SPRING_BEND,
        Radial = Constants.GYRO_SPRING_RADIAL,
        Joint = Constants.GYRO_SPRING_JOINT,
    }

    [CEnum("gyro_collision_response")]
    public enum CollisionResponse : uint
    {
        Projection = Constants.GYRO_COLLISION_PROJECTION,
        Penalty = Constants.GYRO_COLLISION_PENALTY,
    }

    [CEnum("gyro_convex_type")]
    public enum ConvexType : uint
    {
        Sphere = Constants.GYRO_CONVEX_SPHERE,
        Box = Constants.GYRO_CONVEX_BOX,
        Capsule = Constants.GYRO_CONVEX_CAPSULE,
        Cylinder = Constants.GYRO_CONVEX_CYLINDER,
        Triangle = Constants.GYRO_CONVEX_TRIANGLE,
        Hull = Constants.GYRO_CONVEX_HULL,
    }

    [CEnum("gyro_convex_status")]
    public enum ConvexStatus : uint
    {
        Separated = Constants.GYRO_CONVEX_SEPARATED,
        Touching = Constants.GYRO_CONVEX_TOUCHING,
        Intersecting = Constants.GYRO_CONVEX_INTERSECTING,
        IterationLimit = Constants.GYRO_CONVEX_ITERATION_LIMIT,
        InvalidInput = Constants.GYRO_CONVEX_INVALID_INPUT,
    }

    // ------------------------------------------------------------------ value types

    [CStruct("gyro_vec3"), StructLayout(LayoutKind.Sequential)]
    public struct Vec3 : IEquatable<Vec3>
    {
        public float X, Y, Z;
        public Vec3(float x, float y, float z) { X = x; Y = y; Z = z; }
        public static readonly Vec3 Zero = new Vec3(0, 0, 0);
        public static Vec3 operator +(Vec3 a, Vec3 b) { return new Vec3(a.X + b.X, a.Y + b.Y, a.Z + b.Z); }
        public static Vec3 operator -(Vec3 a, Vec3 b) { return new Vec3(a.X - b.X, a.Y - b.Y, a.Z - b.Z); }
        public static Vec3 operator *(Vec3 a, float s) { return new Vec3(a.X * s, a.Y * s, a.Z * s); }
        public float Length => (float)Math.Sqrt((double)X * X + (double)Y * Y + (double)Z * Z);
        public bool Equals(Vec3 o) { return X.Equals(o.X) && Y.Equals(o.Y) && Z.Equals(o.Z); }
        public override bool Equals(object o) { return o is Vec3 v && Equals(v); }
        public override int GetHashCode() { return X.GetHashCode() ^ (Y.GetHashCode() * 397) ^ (Z.GetHashCode() * 7919); }
        public override string ToString() { return "(" + X.ToString("R") + ", " + Y.ToString("R") + ", " + Z.ToString("R") + ")"; }
    }

    /// <summary>A rotation (x, y, z, w); w is the scalar part.</summary>
    [CStruct("gyro_quat"), StructLayout(LayoutKind.Sequential)]
    public struct Quat : IEquatable<Quat>
    {
        public float X, Y, Z, W;
        public Quat(float x, float y, float z, float w) { X = x; Y = y; Z = z; W = w; }
        public static readonly Quat Identity = new Quat(0, 0, 0, 1);
        /// <summary>A rotation of angle radians about a unit axis (System.Math's sin/cos: for
        /// setting things up, not for state that must be bit-identical across platforms).</summary>
        public static Quat FromAxisAngle(Vec3 axis, float angle)
        {
            double s = Math.Sin(angle * 0.5), c = Math.Cos(angle * 0.5);
            return new Quat((float)(axis.X * s), (float)(axis.Y * s), (float)(axis.Z * s), (float)c);
        }
        public bool Equals(Quat o) { return X.Equals(o.X) && Y.Equals(o.Y) && Z.Equals(o.Z) && W.Equals(o.W); }
        public override bool Equals(object o) { return o is Quat q && Equals(q); }
        public override int GetHashCode() { return X.GetHashCode() ^ (Y.GetHashCode() * 397) ^ (Z.GetHashCode() * 7919) ^ (W.GetHashCode() * 104729); }
        public override string ToString() { return "(" + X.ToString("R") + ", " + Y.ToString("R") + ", " + Z.ToString("R") + ", " + W.ToString("R") + ")"; }
    }

    /// <summary>A body's id; all-zero is null. Ordered by index, then generation.</summary>
    [CStruct("gyro_body_id"), StructLayout(LayoutKind.Sequential)]
    public struct BodyId : IEquatable<BodyId>, IComparable<BodyId>
    {
        public uint Index, Generation;
        public BodyId(uint index, uint generation) { Index = index; Generation = generation; }
        public bool IsNull => Index == 0 && Generation == 0;
        public bool Equals(BodyId o) { return Index == o.Index && Generation == o.Generation; }
        public override bool Equals(object o) { return o is BodyId b && Equals(b); }
        public override int GetHashCode() { return (int)(Index * 31 + Generation); }
        public int CompareTo(BodyId o) { return Index != o.Index ? Index.CompareTo(o.Index) : Generation.CompareTo(o.Generation); }
        public static bool operator ==(BodyId a, BodyId b) { return a.Equals(b); }
        public static bool operator !=(BodyId a, BodyId b) { return !a.Equals(b); }
        public override string ToString() { return "body " + Index + "#" + Generation; }
    }

    /// <summary>A scene model's id; all-zero is null.</summary>
    [CStruct("gyro_model_id"), StructLayout(LayoutKind.Sequential)]
    public struct ModelId : IEquatable<ModelId>
    {
        public uint Index, Generation;
        public ModelId(uint index, uint generation) { Index = index; Generation = generation; }
        public bool IsNull => Index == 0 && Generation == 0;
        public bool Equals(ModelId o) { return Index == o.Index && Generation == o.Generation; }
        public override bool Equals(object o) { return o is ModelId b && Equals(b); }
        public override int GetHashCode() { return (int)(Index * 31 + Generation); }
        public static bool operator ==(ModelId a, ModelId b) { return a.Equals(b); }
        public static bool operator !=(ModelId a, ModelId b) { return !a.Equals(b); }
        public override string ToString() { return "model " + Index + "#" + Generation; }
    }

    /// <summary>A soft body's id; all-zero is null.</summary>
    [CStruct("gyro_soft_body_id"), StructLayout(LayoutKind.Sequential)]
    public struct SoftBodyId : IEquatable<SoftBodyId>
    {
        public uint Index, Generation;
        public SoftBodyId(uint index, uint generation) { Index = index; Generation = generation; }
        public bool IsNull => Index == 0 && Generation == 0;
        public bool Equals(SoftBodyId o) { return Index == o.Index && Generation == o.Generation; }
        public override bool Equals(object o) { return o is SoftBodyId b && Equals(b); }
        public override int GetHashCode() { return (int)(Index * 31 + Generation); }
        public static bool operator ==(SoftBodyId a, SoftBodyId b) { return a.Equals(b); }
        public static bool operator !=(SoftBodyId a, SoftBodyId b) { return !a.Equals(b); }
        public override string ToString() { return "soft body " + Index + "#" + Generation; }
    }

    // ------------------------------------------------------------------ shape arrays, rays, hits

    [CStruct("gyro_ray_soa"), StructLayout(LayoutKind.Sequential)]
    public unsafe struct RaySoa
    {
        public float* Ox, Oy, Oz, Dx, Dy, Dz;
        /// <summary>May be null: 0.</summary>
        public float* Tmin;
        /// <summary>May be null: +infinity.</summary>
        public float* Tmax;
    }

    [CStruct("gyro_sphere_soa"), StructLayout(LayoutKind.Sequential)]
    public unsafe struct SphereSoa
    {
        public float* Cx, Cy, Cz, R;
    }

    [CStruct("gyro_aabb_soa"), StructLayout(LayoutKind.Sequential)]
    public unsafe struct AabbSoa
    {
        public float* Cx, Cy, Cz, Ex, Ey, Ez;
    }

    [CStruct("gyro_obb_soa"), StructLayout(LayoutKind.Sequential)]
    public unsafe struct ObbSoa
    {
        public float* Cx, Cy, Cz, Ex, Ey, Ez;
        public float* U0x, U0y, U0z, U1x, U1y, U1z, U2x, U2y, U2z;
    }

    [CStruct("gyro_plane_soa"), StructLayout(LayoutKind.Sequential)]
    public unsafe struct PlaneSoa
    {
        public float* Nx, Ny, Nz, D;
    }

    [CStruct("gyro_triangle_soa"), StructLayout(LayoutKind.Sequential)]
    public unsafe struct TriangleSoa
    {
        public float* Ax, Ay, Az, Bx, By, Bz, Cx, Cy, Cz;
    }

    /// <summary>gyro_shape_soa's anonymous union `as`.</summary>
    [CUnion("gyro_shape_soa", "as"), StructLayout(LayoutKind.Explicit)]
    public struct ShapeSoaUnion
    {
        [FieldOffset(0)] public SphereSoa Sphere;
        [FieldOffset(0)] public AabbSoa Aabb;
        [FieldOffset(0)] public ObbSoa Obb;
        [FieldOffset(0)] public PlaneSoa Plane;
        [FieldOffset(0)] public TriangleSoa Triangle;
    }

    /// <summary>An array of one type of shape: set Type and the matching member of As.</summary>
    [CStruct("gyro_shape_soa"), StructLayout(LayoutKind.Sequential)]
    public struct ShapeSoa
    {
        public ShapeType Type;
        public uint Reserved;
        public ShapeSoaUnion As;
    }

    [CStruct("gyro_hit_soa"), StructLayout(LayoutKind.Sequential)]
    public unsafe struct HitSoa
    {
        public float* T;
        public int* Primitive;
        public float* Nx, Ny, Nz;
        public float* U, V;
    }

    // ------------------------------------------------------------------ meshes, camera, scenes

    [CStruct("gyro_mesh_def"), StructLayout(LayoutKind.Sequential)]
    public unsafe struct MeshDef
    {
        public uint StructSize;
        public int VertexCount;
        public float* X, Y, Z;
        public uint* Indices;
        public int TriangleCount;
        public uint Reserved;
    }

    [CStruct("gyro_mesh_info"), StructLayout(LayoutKind.Sequential)]
    public unsafe struct MeshInfo
    {
        public int TriangleCount, BvhNodes, BvhLeaves, BvhDepth;
        public ulong Bytes;
        public fixed float BoundsMin[3];
        public fixed float BoundsMax[3];
    }

    [CStruct("gyro_camera"), StructLayout(LayoutKind.Sequential)]
    public unsafe struct Camera
    {
        public fixed float Position[3];
        /// <summary>Row-major 3x3: right, up, forward.</summary>
        public fixed float Orientation[9];
        public Projection Mode;
        public float FovY, Aspect, Width, Height, ZNear, ZFar;
    }

    /// <summary>Six planes (left, right, bottom, top, near, far) nx, ny, nz, d: planes[6][4].</summary>
    [CStruct("gyro_frustum"), StructLayout(LayoutKind.Sequential)]
    public unsafe struct Frustum
    {
        public fixed float Planes[24];
    }

    /// <summary>Scale, then rotate (x, y, z, w), then translate.</summary>
    [CStruct("gyro_transform"), StructLayout(LayoutKind.Sequential)]
    public unsafe struct Transform
    {
        public fixed float Position[3];
        public fixed float Rotation[4];
        public float Scale;

        public static Transform At(Vec3 p)
        {
            Transform t = default(Transform);
            t.Position[0] = p.X; t.Position[1] = p.Y; t.Position[2] = p.Z;
            t.Rotation[3] = 1;
            t.Scale = 1;
            return t;
        }
    }

    [CStruct("gyro_model_def"), StructLayout(LayoutKind.Sequential)]
    public unsafe struct ModelDef
    {
        public uint StructSize;
        public ModelShape Shape;
        public float Radius;
        public fixed float HalfExtents[3];
        public fixed float Plane[4];
        /// <summary>A gyro_mesh*: set by Scene.AddMesh from a Gyro.Mesh.</summary>
        public IntPtr Mesh;
        public Transform Transform;
        public ModelId Parent;
    }

    [CStruct("gyro_scene_hit_soa"), StructLayout(LayoutKind.Sequential)]
    public unsafe struct SceneHitSoa
    {
        public float* T;
        public ModelId* Model;
        public int* Primitive;
        public float* Nx, Ny, Nz;
        public float* U, V;
    }

    [CStruct("gyro_scene_hit"), StructLayout(LayoutKind.Sequential)]
    public unsafe struct SceneHit
    {
        public uint Hit;
        public float T;
        public fixed float Point[3];
        public fixed float Normal[3];
        public ModelId Model;
        public int Primitive;
        public float U, V;
    }

    // ------------------------------------------------------------------ dynamics world

    [CStruct("gyro_world_def"), StructLayout(LayoutKind.Sequential)]
    public struct WorldDef
    {
        public uint StructSize;
        public ContactModel ContactModel;
        public Vec3 Gravity;
        public uint Substeps, VelocityIterations, RelaxIterations, PositionIterations;
        public float LinearSlop, Baumgarte, ContactHertz, ContactDampingRatio, MaxPushVelocity, RestitutionThreshold;
        public uint EnableWarmStarting, EnableSleep;
        public float SleepTime, SleepLinearVelocity, SleepAngularVelocity;
        public uint EnableContinuous, Threads;
        public ConvexManifold ConvexManifold;
    }

    [CStruct("gyro_body_def"), StructLayout(LayoutKind.Sequential)]
    public struct BodyDef
    {
        public uint StructSize;
        public BodyType Type;
        public BodyShape Shape;
        public float Radius;
        public Vec3 HalfExtents;
        public Vec3 Position;
        public Quat Orientation;
        public Vec3 LinearVelocity;
        public Vec3 AngularVelocity;
        public float Density, Mass, Friction, Restitution, LinearDamping, AngularDamping, GravityScale;
        public uint Category, Mask, AllowSleep, Awake, Reserved;
        public ulong UserData;
        /// <summary>A const gyro_mesh*: set by World.CreateBody(def, Mesh).</summary>
        public IntPtr Mesh;
        public float HalfHeight;
        public uint Reserved2;
        /// <summary>A const gyro_convex_hull*: set by World.CreateBody(def, ConvexHull).</summary>
        public IntPtr Hull;
    }

    [CStruct("gyro_body_view"), StructLayout(LayoutKind.Sequential)]
    public unsafe struct BodyView
    {
        public int Count;
        public uint Reserved;
        public BodyId* Ids;
        public float* Px, Py, Pz;
        public float* Qx, Qy, Qz, Qw;
        public float* Vx, Vy, Vz;
        public float* Wx, Wy, Wz;
    }

    [CStruct("gyro_step_timings"), StructLayout(LayoutKind.Sequential)]
    public struct StepTimings
    {
        public double Forces, Broadphase, Narrowphase, Islands, Solver, Particles, Total;
    }

    [CStruct("gyro_step_stats"), StructLayout(LayoutKind.Sequential)]
    public struct StepStats
    {
        public uint Bodies, AwakeBodies, Pairs, Manifolds, Contacts, Colors, Islands, Reserved;
    }

    [CStruct("gyro_contact_event"), StructLayout(LayoutKind.Sequential)]
    public struct ContactEvent
    {
        public BodyId A, B;
        public override string ToString() { return A + " - " + B; }
    }

    [CStruct("gyro_contact_events"), StructLayout(LayoutKind.Sequential)]
    public unsafe struct ContactEvents
    {
        public ContactEvent* Begin;
        public ContactEvent* End;
        public int BeginCount, EndCount;
    }

    // ------------------------------------------------------------------ soft bodies

    [CStruct("gyro_spring_constants"), StructLayout(LayoutKind.Sequential)]
    public struct SpringConstants
    {
        public float Stiffness, Damping;
        public SpringConstants(float stiffness, float damping) { Stiffness = stiffness; Damping = damping; }
    }

    [CStruct("gyro_soft_settings"), StructLayout(LayoutKind.Sequential)]
    public struct SoftSettings
    {
        public uint StructSize;
        public SoftModel Model;
        public uint Substeps, Iterations;
        public Vec3 Gravity;
        public float Damping, Thickness, Friction;
        public CollisionResponse Response;
        public float PenaltyStiffness;
    }

    [CStruct("gyro_cloth_def"), StructLayout(LayoutKind.Sequential)]
    public struct ClothDef
    {
        public uint StructSize;
        public int Nx, Nz;
        public float SizeX, SizeZ;
        public Vec3 Center;
        public float ParticleMass;
        public uint BothDiagonals, Bend;
        public SpringConstants Structural, Shear, BendConstants;
    }

    [CStruct("gyro_soft_cube_def"), StructLayout(LayoutKind.Sequential)]
    public struct SoftCubeDef
    {
        public uint StructSize;
        public Vec3 Center;
        public float HalfExtent, ParticleMass;
        public SpringConstants Structural, Shear, Bend;
    }

    [CStruct("gyro_soft_mesh_def"), StructLayout(LayoutKind.Sequential)]
    public unsafe struct SoftMeshDef
    {
        public uint StructSize;
        public int VertexCount;
        public float* X, Y, Z;
        public uint* Indices;
        public int TriangleCount;
        public float ParticleMass;
        public SpringConstants Structural, Bend, Radial;
    }

    [CStruct("gyro_soft_body_view"), StructLayout(LayoutKind.Sequential)]
    public unsafe struct SoftBodyView
    {
        public int Count, TriangleCount;
        public float* Px, Py, Pz;
        public float* Vx, Vy, Vz;
        public float* InverseMass;
        public uint* Triangles;
    }

    [CStruct("gyro_soft_body_stats"), StructLayout(LayoutKind.Sequential)]
    public struct SoftBodyStats
    {
        public int Particles, Springs, Colors;
        public uint Reserved;
        public double MaxStrain, MeanStrain, KineticEnergy, PotentialEnergy, ElasticEnergy, MinY;
    }

    // ------------------------------------------------------------------ convex shapes

    [CStruct("gyro_convex_hull_info"), StructLayout(LayoutKind.Sequential)]
    public struct ConvexHullInfo
    {
        public int VertexCount, FaceCount, EdgeCount, FaceVertexCount;
    }

    [CStruct("gyro_convex_plane"), StructLayout(LayoutKind.Sequential)]
    public struct ConvexPlane
    {
        public Vec3 Normal;
        public float D;
    }

    [CStruct("gyro_convex_edge"), StructLayout(LayoutKind.Sequential)]
    public struct ConvexEdge
    {
        public uint A, B;
    }

    [CStruct("gyro_convex_mass"), StructLayout(LayoutKind.Sequential)]
    public struct ConvexMass
    {
        public float Volume;
        public Vec3 Centroid;
        public Vec3 Inertia0, Inertia1, Inertia2;
        public Vec3 PrincipalMoments;
        public Vec3 PrincipalAxes0, PrincipalAxes1, PrincipalAxes2;
    }

    [CStruct("gyro_convex_shape"), StructLayout(LayoutKind.Sequential)]
    public struct ConvexShape
    {
        public ConvexType Type;
        public float Radius, HalfHeight;
        public Vec3 HalfExtents;
        public Vec3 Triangle0, Triangle1, Triangle2;
        public uint Reserved;
        /// <summary>A const gyro_convex_hull*, not copied: it must stay alive during the call.</summary>
        public IntPtr Hull;

        public static ConvexShape Sphere(float radius) { ConvexShape s = default(ConvexShape); s.Type = ConvexType.Sphere; s.Radius = radius; return s; }
        public static ConvexShape Box(Vec3 halfExtents) { ConvexShape s = default(ConvexShape); s.Type = ConvexType.Box; s.HalfExtents = halfExtents; return s; }
        public static ConvexShape Capsule(float radius, float halfHeight) { ConvexShape s = default(ConvexShape); s.Type = ConvexType.Capsule; s.Radius = radius; s.HalfHeight = halfHeight; return s; }
        public static ConvexShape Cylinder(float radius, float halfHeight) { ConvexShape s = default(ConvexShape); s.Type = ConvexType.Cylinder; s.Radius = radius; s.HalfHeight = halfHeight; return s; }
    }

    /// <summary>world = local * rotation + position (rows: the local axes in the world).</summary>
    [CStruct("gyro_convex_pose"), StructLayout(LayoutKind.Sequential)]
    public struct ConvexPose
    {
        public Vec3 Position;
        public Vec3 Rotation0, Rotation1, Rotation2;

        public static ConvexPose At(Vec3 position)
        {
            ConvexPose p;
            p.Position = position;
            p.Rotation0 = new Vec3(1, 0, 0); p.Rotation1 = new Vec3(0, 1, 0); p.Rotation2 = new Vec3(0, 0, 1);
            return p;
        }
    }

    [CStruct("gyro_convex_result"), StructLayout(LayoutKind.Sequential)]
    public struct ConvexResult
    {
        public ConvexStatus Status;
        public float Distance;
        public Vec3 Normal, PointA, PointB;
        public uint Iterations;
    }

    // ------------------------------------------------------------------ replay

    [CStruct("gyro_replay_report"), StructLayout(LayoutKind.Sequential)]
    public struct ReplayReport
    {
        public uint StructSize, Diverged;
        public long Steps, Calls, FirstDivergentStep;
        public ulong ExpectedHash, ActualHash, FinalHash;
    }

    // ------------------------------------------------------------------ handles

    /// <summary>Owns a gyro_world*; releasing it calls gyro_world_destroy.</summary>
    [COpaque("gyro_world")]
    public sealed class WorldHandle : SafeHandleZeroOrMinusOneIsInvalid
    {
        public WorldHandle() : base(true) { }
        protected override bool ReleaseHandle() { NativeMethods.gyro_world_destroy(handle); return true; }
    }

    /// <summary>Owns a reference to a gyro_mesh*; releasing it calls gyro_mesh_destroy.</summary>
    [COpaque("gyro_mesh")]
    public sealed class MeshHandle : SafeHandleZeroOrMinusOneIsInvalid
    {
        public MeshHandle() : base(true) { }
        protected override bool ReleaseHandle() { NativeMethods.gyro_mesh_destroy(handle); return true; }
    }

    /// <summary>Owns a gyro_scene*; releasing it calls gyro_scene_destroy.</summary>
    [COpaque("gyro_scene")]
    public sealed class SceneHandle : SafeHandleZeroOrMinusOneIsInvalid
    {
        public SceneHandle() : base(true) { }
        protected override bool ReleaseHandle() { NativeMethods.gyro_scene_destroy(handle); return true; }
    }

    /// <summary>Owns a gyro_convex_hull*; releasing it calls gyro_convex_hull_destroy.</summary>
    [COpaque("gyro_convex_hull")]
    public sealed class ConvexHullHandle : SafeHandleZeroOrMinusOneIsInvalid
    {
        public ConvexHullHandle() : base(true) { }
        protected override bool ReleaseHandle() { NativeMethods.gyro_convex_hull_destroy(handle); return true; }
    }

    // ------------------------------------------------------------------ entry points

    /// <summary>One P/Invoke per C function, under its C name. Strings come back as IntPtr to
    /// a NUL-terminated UTF-8 string owned by the library (NativeMethods.Utf8 reads one);
    /// paths go in as NUL-terminated UTF-8 bytes (NativeMethods.ToUtf8z).</summary>
    public static unsafe class NativeMethods
    {
        public const string Library = "gyro";
        const CallingConvention Cdecl = CallingConvention.Cdecl;

        /// <summary>A NUL-terminated UTF-8 string owned by the library ("" for NULL).</summary>
        public static string Utf8(IntPtr s)
        {
            if (s == IntPtr.Zero) return "";
            byte* p = (byte*)s;
            int n = 0;
            while (p[n] != 0) ++n;
            return System.Text.Encoding.UTF8.GetString(p, n);
        }

        /// <summary>A string as NUL-terminated UTF-8.</summary>
        public static byte[] ToUtf8z(string s)
        {
            if (s == null) return null;
            byte[] b = new byte[System.Text.Encoding.UTF8.GetByteCount(s) + 1];
            System.Text.Encoding.UTF8.GetBytes(s, 0, s.Length, b, 0);
            return b;
        }

        // version, features, errors, execution settings
        [DllImport(Library, CallingConvention = Cdecl)] public static extern uint gyro_abi_version();
        [DllImport(Library, CallingConvention = Cdecl)] public static extern IntPtr gyro_version_string();
        [DllImport(Library, CallingConvention = Cdecl)] public static extern Features gyro_features();
        [DllImport(Library, CallingConvention = Cdecl)] public static extern IntPtr gyro_last_error();
        [DllImport(Library, CallingConvention = Cdecl)] public static extern IntPtr gyro_status_name(Status status);
        [DllImport(Library, CallingConvention = Cdecl)] public static extern Status gyro_set_simd_level(SimdLevel level);
        [DllImport(Library, CallingConvention = Cdecl)] public static extern SimdLevel gyro_get_simd_level();
        [DllImport(Library, CallingConvention = Cdecl)] public static extern uint gyro_simd_level_available(SimdLevel level);
        [DllImport(Library, CallingConvention = Cdecl)] public static extern IntPtr gyro_simd_level_name(SimdLevel level);
        [DllImport(Library, CallingConvention = Cdecl)] public static extern Status gyro_set_thread_count(uint threads);
        [DllImport(Library, CallingConvention = Cdecl)] public static extern uint gyro_get_thread_count();

        // brute-force batch raycasts and overlaps
        [DllImport(Library, CallingConvention = Cdecl)] public static extern Status gyro_raycast_closest(RaySoa* rays, int ray_count, ShapeSoa* prims, int prim_count, HitSoa* hits);
        [DllImport(Library, CallingConvention = Cdecl)] public static extern Status gyro_raycast_any(RaySoa* rays, int ray_count, ShapeSoa* prims, int prim_count, HitSoa* hits);
        [DllImport(Library, CallingConvention = Cdecl)] public static extern Status gyro_raycast_spheres_closest(RaySoa* rays, int ray_count, SphereSoa* spheres, int sphere_count, HitSoa* hits);
        [DllImport(Library, CallingConvention = Cdecl)] public static extern Status gyro_overlap_pairwise(ShapeSoa* a, ShapeSoa* b, int count, OverlapResult* @out, BatchFlags flags);
        [DllImport(Library, CallingConvention = Cdecl)] public static extern Status gyro_overlap_one_against_many(ShapeSoa* one, ShapeSoa* many, int count, OverlapResult* @out, BatchFlags flags);
        [DllImport(Library, CallingConvention = Cdecl)] public static extern Status gyro_obb_separation_pairwise(ObbSoa* a, ObbSoa* b, int count, float* @out);

        // meshes
        [DllImport(Library, CallingConvention = Cdecl)] public static extern MeshDef gyro_mesh_def_default();
        [DllImport(Library, CallingConvention = Cdecl)] public static extern Status gyro_mesh_create(MeshDef* def, out MeshHandle @out);
        [DllImport(Library, CallingConvention = Cdecl)] public static extern Status gyro_mesh_load_obj(byte* path, out MeshHandle @out);
        [DllImport(Library, CallingConvention = Cdecl)] public static extern void gyro_mesh_destroy(IntPtr mesh);
        [DllImport(Library, CallingConvention = Cdecl)] public static extern Status gyro_mesh_get_info(MeshHandle mesh, MeshInfo* @out);
        [DllImport(Library, CallingConvention = Cdecl)] public static extern Status gyro_mesh_raycast_closest(MeshHandle mesh, RaySoa* rays, int ray_count, HitSoa* hits);
        [DllImport(Library, CallingConvention = Cdecl)] public static extern Status gyro_mesh_raycast_any(MeshHandle mesh, RaySoa* rays, int ray_count, HitSoa* hits);

        // camera and frustum
        [DllImport(Library, CallingConvention = Cdecl)] public static extern Camera gyro_camera_perspective(float fov_y, float aspect, float z_near, float z_far);
        [DllImport(Library, CallingConvention = Cdecl)] public static extern Status gyro_camera_look_at(Camera* camera, float* eye, float* target, float* up);
        [DllImport(Library, CallingConvention = Cdecl)] public static extern Status gyro_camera_view_projection(Camera* camera, float* @out);
        [DllImport(Library, CallingConvention = Cdecl)] public static extern Status gyro_camera_picking_ray(Camera* camera, float screen_x, float screen_y, float viewport_width, float viewport_height, float* origin, float* direction);
        [DllImport(Library, CallingConvention = Cdecl)] public static extern Status gyro_frustum_from_matrix(float* view_projection, Frustum* @out);
        [DllImport(Library, CallingConvention = Cdecl)] public static extern Status gyro_camera_frustum(Camera* camera, Frustum* @out);
        [DllImport(Library, CallingConvention = Cdecl)] public static extern Status gyro_frustum_cull(Frustum* frustum, ShapeSoa* shapes, int count, uint* visible);

        // scenes
        [DllImport(Library, CallingConvention = Cdecl)] public static extern ModelDef gyro_model_def_default();
        [DllImport(Library, CallingConvention = Cdecl)] public static extern Status gyro_scene_create(SceneAccel accel, out SceneHandle @out);
        [DllImport(Library, CallingConvention = Cdecl)] public static extern void gyro_scene_destroy(IntPtr scene);
        [DllImport(Library, CallingConvention = Cdecl)] public static extern Status gyro_scene_set_ray_prefetch(SceneHandle scene, RayPrefetch mode);
        [DllImport(Library, CallingConvention = Cdecl)] public static extern Status gyro_scene_set_refit(SceneHandle scene, uint enabled);
        [DllImport(Library, CallingConvention = Cdecl)] public static extern Status gyro_scene_add_model(SceneHandle scene, ModelDef* def, ModelId* @out);
        [DllImport(Library, CallingConvention = Cdecl)] public static extern Status gyro_scene_remove_model(SceneHandle scene, ModelId id);
        [DllImport(Library, CallingConvention = Cdecl)] public static extern Status gyro_scene_set_transform(SceneHandle scene, ModelId id, Transform* local);
        [DllImport(Library, CallingConvention = Cdecl)] public static extern Status gyro_scene_set_parent(SceneHandle scene, ModelId id, ModelId parent);
        [DllImport(Library, CallingConvention = Cdecl)] public static extern Status gyro_scene_set_layers(SceneHandle scene, ModelId id, uint layers);
        [DllImport(Library, CallingConvention = Cdecl)] public static extern int gyro_scene_model_count(SceneHandle scene);
        [DllImport(Library, CallingConvention = Cdecl)] public static extern Status gyro_scene_raycast_closest(SceneHandle scene, RaySoa* rays, int ray_count, SceneHitSoa* hits);
        [DllImport(Library, CallingConvention = Cdecl)] public static extern Status gyro_scene_raycast_any(SceneHandle scene, RaySoa* rays, int ray_count, SceneHitSoa* hits);
        [DllImport(Library, CallingConvention = Cdecl)] public static extern Status gyro_scene_raycast_closest_masked(SceneHandle scene, RaySoa* rays, uint* masks, int ray_count, SceneHitSoa* hits);
        [DllImport(Library, CallingConvention = Cdecl)] public static extern Status gyro_scene_raycast_any_masked(SceneHandle scene, RaySoa* rays, uint* masks, int ray_count, SceneHitSoa* hits);
        [DllImport(Library, CallingConvention = Cdecl)] public static extern Status gyro_scene_query(SceneHandle scene, ShapeSoa* shape, ModelId* @out, int capacity, int* count);
        [DllImport(Library, CallingConvention = Cdecl)] public static extern Status gyro_scene_query_frustum(SceneHandle scene, Frustum* frustum, ModelId* @out, int capacity, int* count);
        [DllImport(Library, CallingConvention = Cdecl)] public static extern Status gyro_scene_pick(SceneHandle scene, Camera* camera, float screen_x, float screen_y, float viewport_width, float viewport_height, SceneHit* @out);
        [DllImport(Library, CallingConvention = Cdecl)] public static extern Status gyro_scene_query_masked(SceneHandle scene, ShapeSoa* shape, uint mask, ModelId* @out, int capacity, int* count);
        [DllImport(Library, CallingConvention = Cdecl)] public static extern Status gyro_scene_query_frustum_masked(SceneHandle scene, Frustum* frustum, uint mask, ModelId* @out, int capacity, int* count);
        [DllImport(Library, CallingConvention = Cdecl)] public static extern Status gyro_scene_pick_masked(SceneHandle scene, Camera* camera, float screen_x, float screen_y, float viewport_width, float viewport_height, uint mask, SceneHit* @out);

        // world and rigid bodies
        [DllImport(Library, CallingConvention = Cdecl)] public static extern WorldDef gyro_world_def_default();
        [DllImport(Library, CallingConvention = Cdecl)] public static extern Status gyro_world_create(WorldDef* def, out WorldHandle @out);
        [DllImport(Library, CallingConvention = Cdecl)] public static extern void gyro_world_destroy(IntPtr world);
        [DllImport(Library, CallingConvention = Cdecl)] public static extern Status gyro_world_step(WorldHandle world, float dt);
        [DllImport(Library, CallingConvention = Cdecl)] public static extern Status gyro_world_hash(WorldHandle world, ulong* @out);
        [DllImport(Library, CallingConvention = Cdecl)] public static extern Status gyro_world_body_count(WorldHandle world, int* @out);
        [DllImport(Library, CallingConvention = Cdecl)] public static extern BodyDef gyro_body_def_default();
        [DllImport(Library, CallingConvention = Cdecl)] public static extern Status gyro_body_create(WorldHandle world, BodyDef* def, BodyId* @out);
        [DllImport(Library, CallingConvention = Cdecl)] public static extern Status gyro_body_destroy(WorldHandle world, BodyId id);
        [DllImport(Library, CallingConvention = Cdecl)] public static extern uint gyro_body_is_valid(WorldHandle world, BodyId id);
        [DllImport(Library, CallingConvention = Cdecl)] public static extern Status gyro_body_get_transform(WorldHandle world, BodyId id, Vec3* position, Quat* orientation);
        [DllImport(Library, CallingConvention = Cdecl)] public static extern Status gyro_body_get_shape_frame(WorldHandle world, BodyId id, Vec3* offset, Quat* rotation);
        [DllImport(Library, CallingConvention = Cdecl)] public static extern Status gyro_body_set_transform(WorldHandle world, BodyId id, Vec3 position, Quat orientation);
        [DllImport(Library, CallingConvention = Cdecl)] public static extern Status gyro_body_get_velocity(WorldHandle world, BodyId id, Vec3* linear, Vec3* angular);
        [DllImport(Library, CallingConvention = Cdecl)] public static extern Status gyro_body_set_velocity(WorldHandle world, BodyId id, Vec3 linear, Vec3 angular);
        [DllImport(Library, CallingConvention = Cdecl)] public static extern Status gyro_body_get_mass(WorldHandle world, BodyId id, float* @out);
        [DllImport(Library, CallingConvention = Cdecl)] public static extern Status gyro_body_get_type(WorldHandle world, BodyId id, BodyType* @out);
        [DllImport(Library, CallingConvention = Cdecl)] public static extern Status gyro_body_get_user_data(WorldHandle world, BodyId id, ulong* @out);
        [DllImport(Library, CallingConvention = Cdecl)] public static extern Status gyro_body_apply_force(WorldHandle world, BodyId id, Vec3 force, Vec3 world_point);
        [DllImport(Library, CallingConvention = Cdecl)] public static extern Status gyro_body_apply_force_at_center(WorldHandle world, BodyId id, Vec3 force);
        [DllImport(Library, CallingConvention = Cdecl)] public static extern Status gyro_body_apply_torque(WorldHandle world, BodyId id, Vec3 torque);
        [DllImport(Library, CallingConvention = Cdecl)] public static extern Status gyro_body_apply_linear_impulse(WorldHandle world, BodyId id, Vec3 impulse, Vec3 world_point);
        [DllImport(Library, CallingConvention = Cdecl)] public static extern Status gyro_body_apply_angular_impulse(WorldHandle world, BodyId id, Vec3 impulse);
        [DllImport(Library, CallingConvention = Cdecl)] public static extern Status gyro_body_set_awake(WorldHandle world, BodyId id, uint awake);
        [DllImport(Library, CallingConvention = Cdecl)] public static extern Status gyro_body_is_awake(WorldHandle world, BodyId id, uint* @out);
        [DllImport(Library, CallingConvention = Cdecl)] public static extern Status gyro_world_get_body_view(WorldHandle world, BodyView* @out);
        [DllImport(Library, CallingConvention = Cdecl)] public static extern Status gyro_world_get_timings(WorldHandle world, StepTimings* @out);
        [DllImport(Library, CallingConvention = Cdecl)] public static extern Status gyro_world_get_stats(WorldHandle world, StepStats* @out);
        [DllImport(Library, CallingConvention = Cdecl)] public static extern Status gyro_world_get_stage_time(WorldHandle world, StepStage stage, double* out_ms);
        [DllImport(Library, CallingConvention = Cdecl)] public static extern Status gyro_world_get_contact_events(WorldHandle world, ContactEvents* @out);

        // springs, cloth and soft bodies
        [DllImport(Library, CallingConvention = Cdecl)] public static extern SoftSettings gyro_soft_settings_default();
        [DllImport(Library, CallingConvention = Cdecl)] public static extern ClothDef gyro_cloth_def_default();
        [DllImport(Library, CallingConvention = Cdecl)] public static extern SoftCubeDef gyro_soft_cube_def_default();
        [DllImport(Library, CallingConvention = Cdecl)] public static extern SoftMeshDef gyro_soft_mesh_def_default();
        [DllImport(Library, CallingConvention = Cdecl)] public static extern Status gyro_world_create_cloth(WorldHandle world, ClothDef* def, SoftBodyId* @out);
        [DllImport(Library, CallingConvention = Cdecl)] public static extern Status gyro_world_create_soft_cube(WorldHandle world, SoftCubeDef* def, SoftBodyId* @out);
        [DllImport(Library, CallingConvention = Cdecl)] public static extern Status gyro_world_create_soft_mesh(WorldHandle world, SoftMeshDef* def, SoftBodyId* @out);
        [DllImport(Library, CallingConvention = Cdecl)] public static extern Status gyro_world_destroy_soft_body(WorldHandle world, SoftBodyId id);
        [DllImport(Library, CallingConvention = Cdecl)] public static extern uint gyro_soft_body_is_valid(WorldHandle world, SoftBodyId id);
        [DllImport(Library, CallingConvention = Cdecl)] public static extern Status gyro_world_soft_body_count(WorldHandle world, int* @out);
        [DllImport(Library, CallingConvention = Cdecl)] public static extern Status gyro_soft_body_set_settings(WorldHandle world, SoftBodyId id, SoftSettings* settings);
        [DllImport(Library, CallingConvention = Cdecl)] public static extern Status gyro_soft_body_get_settings(WorldHandle world, SoftBodyId id, SoftSettings* @out);
        [DllImport(Library, CallingConvention = Cdecl)] public static extern Status gyro_soft_body_set_family(WorldHandle world, SoftBodyId id, SpringFamily family, SpringConstants* constants);
        [DllImport(Library, CallingConvention = Cdecl)] public static extern Status gyro_soft_body_get_family(WorldHandle world, SoftBodyId id, SpringFamily family, SpringConstants* @out);
        [DllImport(Library, CallingConvention = Cdecl)] public static extern Status gyro_soft_body_set_mass(WorldHandle world, SoftBodyId id, float mass);
        [DllImport(Library, CallingConvention = Cdecl)] public static extern Status gyro_soft_body_set_particle_mass(WorldHandle world, SoftBodyId id, uint particle, float mass);
        [DllImport(Library, CallingConvention = Cdecl)] public static extern Status gyro_soft_body_pin(WorldHandle world, SoftBodyId id, uint particle);
        [DllImport(Library, CallingConvention = Cdecl)] public static extern Status gyro_soft_body_unpin(WorldHandle world, SoftBodyId id, uint particle);
        [DllImport(Library, CallingConvention = Cdecl)] public static extern Status gyro_soft_body_is_pinned(WorldHandle world, SoftBodyId id, uint particle, uint* @out);
        [DllImport(Library, CallingConvention = Cdecl)] public static extern Status gyro_soft_body_get_position(WorldHandle world, SoftBodyId id, uint particle, Vec3* @out);
        [DllImport(Library, CallingConvention = Cdecl)] public static extern Status gyro_soft_body_set_position(WorldHandle world, SoftBodyId id, uint particle, Vec3 position);
        [DllImport(Library, CallingConvention = Cdecl)] public static extern Status gyro_soft_body_get_velocity(WorldHandle world, SoftBodyId id, uint particle, Vec3* @out);
        [DllImport(Library, CallingConvention = Cdecl)] public static extern Status gyro_soft_body_set_velocity(WorldHandle world, SoftBodyId id, uint particle, Vec3 velocity);
        [DllImport(Library, CallingConvention = Cdecl)] public static extern Status gyro_soft_body_cloth_index(WorldHandle world, SoftBodyId id, uint ix, uint iz, uint* @out);
        [DllImport(Library, CallingConvention = Cdecl)] public static extern Status gyro_soft_body_add_distance_joint(WorldHandle world, SoftBodyId id, uint a, uint b, float rest_length, uint* out_joint);
        [DllImport(Library, CallingConvention = Cdecl)] public static extern Status gyro_soft_body_add_ball_joint(WorldHandle world, SoftBodyId id, uint a, uint b);
        [DllImport(Library, CallingConvention = Cdecl)] public static extern Status gyro_soft_body_add_hinge_joint(WorldHandle world, SoftBodyId id, uint a0, uint b0, uint a1, uint b1);
        [DllImport(Library, CallingConvention = Cdecl)] public static extern Status gyro_soft_body_get_view(WorldHandle world, SoftBodyId id, SoftBodyView* @out);
        [DllImport(Library, CallingConvention = Cdecl)] public static extern Status gyro_soft_body_get_stats(WorldHandle world, SoftBodyId id, SoftBodyStats* @out);
        [DllImport(Library, CallingConvention = Cdecl)] public static extern Status gyro_soft_body_hash(WorldHandle world, SoftBodyId id, ulong* @out);

        // convex hulls and pair queries
        [DllImport(Library, CallingConvention = Cdecl)] public static extern Status gyro_convex_hull_create(Vec3* points, int count, out ConvexHullHandle @out);
        [DllImport(Library, CallingConvention = Cdecl)] public static extern void gyro_convex_hull_destroy(IntPtr hull);
        [DllImport(Library, CallingConvention = Cdecl)] public static extern Status gyro_convex_hull_get_info(ConvexHullHandle hull, ConvexHullInfo* @out);
        [DllImport(Library, CallingConvention = Cdecl)] public static extern Status gyro_convex_hull_get_vertices(ConvexHullHandle hull, Vec3* @out, int capacity, int* count);
        [DllImport(Library, CallingConvention = Cdecl)] public static extern Status gyro_convex_hull_get_planes(ConvexHullHandle hull, ConvexPlane* @out, int capacity, int* count);
        [DllImport(Library, CallingConvention = Cdecl)] public static extern Status gyro_convex_hull_get_face_starts(ConvexHullHandle hull, uint* @out, int capacity, int* count);
        [DllImport(Library, CallingConvention = Cdecl)] public static extern Status gyro_convex_hull_get_face_vertices(ConvexHullHandle hull, uint* @out, int capacity, int* count);
        [DllImport(Library, CallingConvention = Cdecl)] public static extern Status gyro_convex_hull_get_edges(ConvexHullHandle hull, ConvexEdge* @out, int capacity, int* count);
        [DllImport(Library, CallingConvention = Cdecl)] public static extern Status gyro_convex_hull_mass(ConvexHullHandle hull, ConvexMass* @out);
        [DllImport(Library, CallingConvention = Cdecl)] public static extern Status gyro_convex_pose_from_quat(Vec3 position, Quat orientation, ConvexPose* @out);
        [DllImport(Library, CallingConvention = Cdecl)] public static extern Status gyro_convex_intersect_pairs(ConvexShape* a, ConvexPose* pa, ConvexShape* b, ConvexPose* pb, int count, ConvexResult* @out);
        [DllImport(Library, CallingConvention = Cdecl)] public static extern Status gyro_convex_distance_pairs(ConvexShape* a, ConvexPose* pa, ConvexShape* b, ConvexPose* pb, int count, ConvexResult* @out);
        [DllImport(Library, CallingConvention = Cdecl)] public static extern Status gyro_convex_penetration_pairs(ConvexShape* a, ConvexPose* pa, ConvexShape* b, ConvexPose* pb, int count, ConvexResult* @out);
        [DllImport(Library, CallingConvention = Cdecl)] public static extern Status gyro_convex_contact_pairs(ConvexShape* a, ConvexPose* pa, ConvexShape* b, ConvexPose* pb, int count, ConvexResult* @out);

        // snapshot and restore
        [DllImport(Library, CallingConvention = Cdecl)] public static extern Status gyro_world_snapshot_size(WorldHandle world, ulong* @out);
        [DllImport(Library, CallingConvention = Cdecl)] public static extern Status gyro_world_snapshot(WorldHandle world, void* buffer, ulong capacity, ulong* out_size);
        [DllImport(Library, CallingConvention = Cdecl)] public static extern Status gyro_world_restore(WorldHandle world, void* buffer, ulong size);
        [DllImport(Library, CallingConvention = Cdecl)] public static extern Status gyro_world_create_from_snapshot(void* buffer, ulong size, out WorldHandle @out);

        // record and replay
        [DllImport(Library, CallingConvention = Cdecl)] public static extern Status gyro_world_record_begin(WorldHandle world);
        [DllImport(Library, CallingConvention = Cdecl)] public static extern Status gyro_world_record_size(WorldHandle world, ulong* @out);
        [DllImport(Library, CallingConvention = Cdecl)] public static extern Status gyro_world_record_copy(WorldHandle world, void* buffer, ulong capacity, ulong* out_size);
        [DllImport(Library, CallingConvention = Cdecl)] public static extern Status gyro_world_record_save(WorldHandle world, byte* path);
        [DllImport(Library, CallingConvention = Cdecl)] public static extern Status gyro_world_record_end(WorldHandle world);
        [DllImport(Library, CallingConvention = Cdecl)] public static extern Status gyro_replay(void* data, ulong size, ReplayReport* @out);
        [DllImport(Library, CallingConvention = Cdecl)] public static extern Status gyro_replay_file(byte* path, ReplayReport* @out);
    }
}
