// The C# binding's test: mono GyroTest.exe <gyro_api.json>
//
// 1. The binding against gyro_api.json (ApiCheck.cs): every mapped struct's Marshal.SizeOf and
//    Marshal.OffsetOf of every field, field and parameter types, constant values, entry points.
// 2. The binding against the library, with numbers: a box dropped on a plane rests at its
//    half-height, identical runs (and SIMD levels) give identical hashes, bad input throws
//    GyroException with the right status and changes nothing, batch raycasts hit a sphere at
//    the analytic t, snapshot/restore reproduces the hashes, and more.
// Prints one line per check; exits 1 if any failed.
using System;
using System.Diagnostics;
using System.IO;
using Gyro;
using Gyro.Native;

namespace Gyro.Tests
{
    public static class GyroTest
    {
        static int passed, failed;

        static void Ok(bool cond, string what)
        {
            if (cond) { ++passed; Console.WriteLine("  ok    " + what); }
            else { ++failed; Console.WriteLine("  FAIL  " + what); }
        }

        static void Near(double have, double want, double tol, string what)
        {
            bool ok = Math.Abs(have - want) <= tol;
            Ok(ok, what + ": " + have.ToString("R") + " (want " + want.ToString("R") + " +- " + tol.ToString("R") + ")");
        }

        /// <summary>Runs f and checks it throws GyroException with the status.</summary>
        static GyroException Throws(Status status, Action f, string what)
        {
            try
            {
                f();
            }
            catch (GyroException e)
            {
                Ok(e.Status == status, what + ": GyroException " + e.Status + " (want " + status + "): " + e.Message);
                return e;
            }
            catch (Exception e)
            {
                Ok(false, what + ": threw " + e.GetType().Name + " (want GyroException " + status + "): " + e.Message);
                return null;
            }
            Ok(false, what + ": did not throw (want GyroException " + status + ")");
            return null;
        }

        static void Section(string name) { Console.WriteLine(name); }

        public static int Main(string[] args)
        {
            Stopwatch clock = Stopwatch.StartNew();
            if (args.Length != 1)
            {
                Console.Error.WriteLine("usage: mono GyroTest.exe <build>/capi/api/gyro_api.json");
                return 2;
            }
            try
            {
                ApiDescription(args[0]);
                Library();
                DropBox();
                Determinism();
                BadInput();
                StaleIds();
                SceneRaycast();
                MeshAndSpheres();
                CameraFrustum();
                ConvexHulls();
                Cloth();
                Snapshots();
                Handles();
            }
            catch (Exception e)
            {
                ++failed;
                Console.WriteLine("  FAIL  unexpected " + e);
            }
            Console.WriteLine("capi.csharp: " + passed + " passed, " + failed + " failed, " + clock.ElapsedMilliseconds + " ms");
            return failed == 0 ? 0 : 1;
        }

        // ------------------------------------------------------------------ gyro_api.json

        static void ApiDescription(string path)
        {
            Section("binding vs " + path);
            if (!File.Exists(path))
            {
                Ok(false, "gyro_api.json exists (build the gyro_api_json target)");
                return;
            }
            ApiCheck check = new ApiCheck(typeof(World).Assembly, File.ReadAllText(path));
            check.Run();
            foreach (string f in check.Failures) Console.WriteLine("  FAIL  " + f);
            failed += check.Failures.Count;
            Ok(check.Structs > 40 && check.Functions > 120 && check.Constants > 80,
               "checked " + check.Structs + " structs (" + check.Fields + " fields: size, offset, type), " + check.Constants +
               " constants, " + check.EnumMembers + " enum members, " + check.Functions + " P/Invokes (" + check.Params +
               " parameters: count and type), " + check.Failures.Count + " mismatches");
        }

        // ------------------------------------------------------------------ library

        static void Library()
        {
            Section("library");
            uint abi = GyroLibrary.AbiVersion;
            Ok(abi >> 16 == GyroLibrary.BindingAbiMajor && (abi & 0xffff) >= GyroLibrary.BindingAbiMinor,
               "ABI " + (abi >> 16) + "." + (abi & 0xffff) + " serves the binding's " + GyroLibrary.BindingAbiMajor + "." + GyroLibrary.BindingAbiMinor +
               ", version \"" + GyroLibrary.Version + "\"");
            Ok(GyroLibrary.Has(Features.Dynamics | Features.Spatial | Features.Geometry), "features " + GyroLibrary.Features);

            // The version rule on made-up library versions.
            Action<uint, bool> rule = (v, accept) =>
            {
                string name = (v >> 16) + "." + (v & 0xffff);
                try
                {
                    GyroLibrary.CheckAbi(v);
                    Ok(accept, "CheckAbi accepts library ABI " + name);
                }
                catch (GyroVersionException e)
                {
                    Ok(!accept && e.LibraryAbi == v, "CheckAbi refuses library ABI " + name + ": " + e.Message);
                }
            };
            uint b = GyroLibrary.BindingAbi;
            rule(b, true);
            rule(b + 3, true);
            rule(b - 1, false);
            rule(b + (1u << 16), false);
            rule(b - (1u << 16), false);

            SimdLevel level = GyroLibrary.SimdLevel;
            Ok(level != SimdLevel.Auto && GyroLibrary.IsSimdLevelAvailable(SimdLevel.Scalar),
               "SIMD level " + GyroLibrary.SimdLevelName(level) + ", scalar available");
            Throws(Status.InvalidArgument, () => GyroLibrary.SimdLevel = (SimdLevel)99, "gyro_set_simd_level(99)");
            Ok(GyroLibrary.StatusName(Status.StaleId) == "stale_id", "gyro_status_name(STALE_ID) = \"" + GyroLibrary.StatusName(Status.StaleId) + "\"");
            uint threads = GyroLibrary.ThreadCount;
            GyroLibrary.ThreadCount = 1;
            Ok(GyroLibrary.ThreadCount == 1, "thread count set to 1 (was " + threads + ")");
            GyroLibrary.ThreadCount = 0;
        }

        // ------------------------------------------------------------------ rigid bodies

        static void DropBox()
        {
            Section("box dropped on a plane");
            const float dt = 1.0f / 60.0f, h = 0.5f, y0 = 3.0f;
            WorldDef wd = Defaults.World();
            Ok(wd.Gravity.Equals(new Vec3(0, -9.81f, 0)) && wd.Substeps >= 1, "gyro_world_def_default: gravity " + wd.Gravity + ", " + wd.Substeps + " sub-steps, slop " + wd.LinearSlop);
            using (World w = new World(wd))
            {
                BodyId ground = w.CreateGround();
                BodyDef bd = Defaults.Body();
                Ok(bd.Type == BodyType.Dynamic && bd.Shape == BodyShape.Box && bd.HalfExtents.Equals(new Vec3(h, h, h)) &&
                   bd.Orientation.Equals(Quat.Identity) && bd.StructSize == 160,
                   "gyro_body_def_default: dynamic unit box, identity, struct_size " + bd.StructSize);
                bd.Position = new Vec3(0, y0, 0);
                bd.UserData = 0xfeedface12345678UL;
                BodyId box = w.CreateBody(bd);
                Ok(w.BodyCount == 2 && w.IsValid(box) && w.IsValid(ground), "2 bodies, both ids valid: " + ground + ", " + box);
                Ok(w.GetUserData(box) == 0xfeedface12345678UL, "user data round-trips");
                Near(w.GetMass(box), 1.0, 1e-6, "mass of a unit box at density 1");
                Ok(w.GetBodyType(ground) == BodyType.Static && w.GetMass(ground) == 0, "the plane is static with mass 0");

                // Free fall for 0.25 s: v = g t (no damping by default).
                for (int i = 0; i < 15; ++i) w.Step(dt);
                Near(w.GetLinearVelocity(box).Y, -9.81 * 15 * dt, 1e-3, "free-fall velocity after 15 steps (m/s)");
                Ok(w.GetPosition(box).Y < y0 - 0.25f, "the box fell: y = " + w.GetPosition(box).Y);
                Ok(w.Stats.Bodies == 2, "stats: " + w.Stats.Bodies + " bodies");

                bool began = false;
                for (int i = 0; i < 225; ++i)
                {
                    w.Step(dt);
                    ContactEventsView ev = w.ContactEvents;
                    foreach (ContactEvent e in ev.Begin) if ((e.A == box && e.B == ground) || (e.A == ground && e.B == box)) began = true;
                }
                Ok(began, "a contact-begin event between box and plane");
                Vec3 p; Quat q;
                w.GetTransform(box, out p, out q);
                Near(p.Y, h, 0.01, "resting height = half-height 0.5 m (tolerance 1 cm, twice the 5 mm linear slop)");
                Near(Math.Sqrt(p.X * p.X + p.Z * p.Z), 0, 0.005, "sideways drift of a straight drop (m, tolerance 5 mm)");
                Near(w.GetLinearVelocity(box).Length, 0, 0.01, "at rest |v| (m/s)");
                Near(Math.Abs(q.W), 1, 1e-4, "still upright |q.w|");
                Ok(!w.IsAwake(box), "asleep after 4 s at rest");
                Ok(w.Timings.Total >= 0 && w.StageTime(StepStage.Total) >= 0, "timings readable: total " + w.Timings.Total.ToString("F4") + " ms");

                BodyStateView view = w.GetBodyView();
                int slot = view.Ids.IndexOf(box);
                Ok(view.Count == 2 && slot >= 0 && view.Position(slot).Equals(p) && view.Py[slot] == p.Y,
                   "body view: 2 slots, the box's slot holds its position");

                // Impulse and velocity calls (structs passed by value: Vec3, Quat, BodyId).
                w.ApplyLinearImpulse(box, new Vec3(0, 4, 0), p);
                Ok(w.IsAwake(box), "an impulse wakes the box");
                Near(w.GetLinearVelocity(box).Y, 4.0, 1e-5, "impulse 4 N s on 1 kg: vy (m/s)");
                Quat turned = Quat.FromAxisAngle(new Vec3(0, 1, 0), 0.5f);
                w.SetTransform(box, new Vec3(1, 2, 3), turned);
                w.GetTransform(box, out p, out q);
                Ok(p.Equals(new Vec3(1, 2, 3)) && Math.Abs(q.Y - turned.Y) < 1e-6 && Math.Abs(q.W - turned.W) < 1e-6, "set_transform round-trips " + p + " " + q);
                w.SetVelocity(box, new Vec3(1, 0, 0), new Vec3(0, 2, 0));
                Vec3 lin, ang;
                w.GetVelocity(box, out lin, out ang);
                Ok(lin.Equals(new Vec3(1, 0, 0)) && ang.Equals(new Vec3(0, 2, 0)), "set_velocity round-trips " + lin + " " + ang);
                w.ApplyForceAtCenter(box, new Vec3(0, 9.81f, 0));
                w.ApplyTorque(box, Vec3.Zero);
                w.ApplyForce(box, Vec3.Zero, p);
                w.ApplyAngularImpulse(box, Vec3.Zero);
                w.SetAwake(box, false);
                Ok(!w.IsAwake(box), "set_awake(0)");
            }
        }

        /// <summary>A pile of boxes and spheres; returns the hash after steps.</summary>
        static ulong Pile(int steps, out ulong[] trace)
        {
            using (World w = new World())
            {
                w.CreateGround();
                for (int i = 0; i < 12; ++i)
                {
                    Vec3 at = new Vec3(0.3f * (i % 3) - 0.3f, 0.6f + 1.1f * i, 0.2f * (i % 2));
                    if (i % 3 == 2) w.CreateSphere(at, 0.45f);
                    else w.CreateBox(at, new Vec3(0.5f, 0.5f, 0.5f));
                }
                trace = new ulong[steps];
                for (int s = 0; s < steps; ++s)
                {
                    w.Step(1.0f / 60.0f);
                    trace[s] = w.Hash;
                }
                return w.Hash;
            }
        }

        static void Determinism()
        {
            Section("determinism");
            ulong[] t1, t2, t3;
            ulong h1 = Pile(120, out t1);
            ulong h2 = Pile(120, out t2);
            bool same = true;
            for (int i = 0; i < t1.Length; ++i) same &= t1[i] == t2[i];
            Ok(same && h1 == h2, "two identical runs: the same hash after each of 120 steps (" + h1.ToString("x16") + ")");
            bool moved = false;
            for (int i = 1; i < t1.Length; ++i) moved |= t1[i] != t1[0];
            Ok(moved, "the hash changes as the pile moves");
            SimdLevel level = GyroLibrary.SimdLevel;
            GyroLibrary.SimdLevel = SimdLevel.Scalar;
            ulong h3 = Pile(120, out t3);
            GyroLibrary.SimdLevel = SimdLevel.Auto;
            Ok(h3 == h1, "scalar level gives the same hash as " + GyroLibrary.SimdLevelName(level) + " (" + h3.ToString("x16") + ")");
        }

        static void BadInput()
        {
            Section("bad input throws and changes nothing");
            using (World w = new World())
            {
                w.CreateGround();
                BodyId box = w.CreateBox(new Vec3(0, 2, 0), new Vec3(0.5f, 0.5f, 0.5f));
                w.Step(1.0f / 60.0f);
                ulong before = w.Hash;
                GyroException e = Throws(Status.NonFinite, () => w.Step(float.NaN), "step(NaN)");
                Ok(e != null && e.Function == "gyro_world_step" && e.Detail.Length > 0, "the exception names the call and carries gyro_last_error: \"" + (e == null ? "" : e.Detail) + "\"");
                Ok(w.Hash == before, "hash unchanged after step(NaN)");
                Throws(Status.NonFinite, () => w.Step(float.PositiveInfinity), "step(+inf)");
                Throws(Status.InvalidArgument, () => w.Step(-0.01f), "step(-0.01)");
                Throws(Status.InvalidArgument, () => w.Step(0), "step(0)");
                Throws(Status.NonFinite, () => w.SetTransform(box, new Vec3(float.NaN, 0, 0), Quat.Identity), "set_transform(NaN)");
                Throws(Status.InvalidArgument, () => w.SetTransform(box, Vec3.Zero, new Quat(0, 0, 0, 0)), "set_transform(zero quaternion)");
                BodyDef bd = Defaults.Body();
                bd.Mass = -1;
                Throws(Status.InvalidArgument, () => w.CreateBody(bd), "body with mass -1");
                bd = Defaults.Body();
                bd.StructSize = 12;
                Throws(Status.InvalidArgument, () => w.CreateBody(bd), "body with struct_size 12");
                bd = Defaults.Body();
                bd.HalfExtents = new Vec3(0, 1, 1);
                Throws(Status.InvalidArgument, () => w.CreateBody(bd), "box with a zero half extent");
                Ok(w.Hash == before && w.BodyCount == 2, "hash and body count unchanged after every refused call");
                WorldDef wd = Defaults.World();
                wd.Substeps = 0;
                Throws(Status.InvalidArgument, () => new World(wd), "world with 0 sub-steps");
            }
        }

        static void StaleIds()
        {
            Section("stale ids");
            using (World w = new World())
            {
                BodyId a = w.CreateSphere(new Vec3(0, 1, 0), 0.5f);
                w.DestroyBody(a);
                Ok(!w.IsValid(a), "destroyed id is not valid");
                ulong before = w.Hash;
                Throws(Status.StaleId, () => w.GetPosition(a), "get_transform(stale id)");
                Throws(Status.StaleId, () => w.DestroyBody(a), "destroy(stale id)");
                Throws(Status.StaleId, () => w.ApplyLinearImpulse(a, new Vec3(1, 0, 0), Vec3.Zero), "apply_linear_impulse(stale id)");
                Throws(Status.StaleId, () => w.GetMass(default(BodyId)), "get_mass(null id)");
                BodyId b = w.CreateSphere(new Vec3(0, 1, 0), 0.5f);
                Ok(b != a && w.IsValid(b) && !w.IsValid(a), "a new body does not revive the stale id (" + a + " -> " + b + ")");
                Throws(Status.StaleId, () => w.SetVelocity(a, Vec3.Zero, Vec3.Zero), "set_velocity(old id after slot reuse)");
                Ok(w.Hash != before, "the hash covers the new body");
            }
        }

        // ------------------------------------------------------------------ spatial

        static void SceneRaycast()
        {
            Section("scene batch raycast");
            foreach (SceneAccel accel in new[] { SceneAccel.Bvh, SceneAccel.Octree })
            using (Scene s = new Scene(accel))
            {
                ModelId sphere = s.AddSphere(new Vec3(0, 0, 5), 1.0f);
                ModelId box = s.AddBox(new Vec3(10, 0, 0), new Vec3(1, 1, 1));
                Ok(s.ModelCount == 2, accel + ": 2 models");
                RayBatch rays = new RayBatch(5);
                rays.Set(0, Vec3.Zero, new Vec3(0, 0, 1));                         // centre: t = 4
                rays.Set(1, new Vec3(0.6f, 0, 0), new Vec3(0, 0, 1));              // off-centre: t = 5 - 0.8
                rays.Set(2, new Vec3(0, 3, 0), new Vec3(0, 0, 1));                 // miss
                rays.Set(3, Vec3.Zero, new Vec3(0, 0, 2));                         // |d| = 2: t = 2
                rays.Set(4, new Vec3(0, 0, 0), new Vec3(1, 0, 0));                 // the box: t = 9
                SceneHitBatch hits = new SceneHitBatch(5);
                s.RaycastClosest(rays, hits);
                Near(hits.T[0], 4.0, 1e-5, accel + ": centre ray t");
                Ok(hits.Model[0] == sphere && hits.Normal(0).Equals(new Vec3(0, 0, -1)), accel + ": centre ray hits the sphere, normal " + hits.Normal(0));
                Near(hits.T[1], 5.0 - Math.Sqrt(1.0 - 0.36), 1e-5, accel + ": off-centre ray t = 5 - sqrt(1 - 0.6^2)");
                Near(hits.Nx[1], 0.6, 1e-5, accel + ": off-centre normal x");
                Near(hits.Nz[1], -0.8, 1e-5, accel + ": off-centre normal z");
                Ok(float.IsPositiveInfinity(hits.T[2]) && hits.Model[2].IsNull && hits.Primitive[2] == -1, accel + ": miss: t = +inf, null model, primitive -1");
                Near(hits.T[3], 2.0, 1e-5, accel + ": t in units of |d| = 2");
                Ok(hits.Model[4] == box && Math.Abs(hits.T[4] - 9.0f) < 1e-5, accel + ": the box at t = " + hits.T[4]);
                float[] before = (float[])hits.T.Clone();
                foreach (RayPrefetch mode in new[] { RayPrefetch.Always, RayPrefetch.Never, RayPrefetch.Auto })
                {
                    s.SetRayPrefetch(mode);
                    s.RaycastClosest(rays, hits);
                    for (int k = 0; k < 5; ++k)
                        Ok(hits.T[k] == before[k], accel + ": prefetch " + mode + " changes no t");
                }
                foreach (bool on in new[] { false, true })
                {
                    s.SetRefit(on);
                    s.SetTransform(box, Transform.At(new Vec3(10, 0, 0)));
                    s.RaycastClosest(rays, hits);
                    for (int k = 0; k < 5; ++k)
                        Ok(hits.T[k] == before[k], accel + ": refit " + on + " after a move changes no t");
                }

                // Layers: the sphere in layer 2 only; ray 0 sees layer 1 (passes through it),
                // ray 4 layer 1 (still sees the box, in every layer).
                s.SetLayers(sphere, 2u);
                uint[] masks = { 1u, 2u, ~0u, 0u, 1u };
                s.RaycastClosest(rays, hits, masks);
                Ok(hits.Model[0].IsNull && float.IsPositiveInfinity(hits.T[0]), accel + ": a ray of layer 1 passes through a sphere of layer 2");
                Ok(hits.Model[1] == sphere && hits.T[1] == before[1], accel + ": a ray of layer 2 hits it, the same t");
                Ok(hits.Model[3].IsNull, accel + ": a ray of no layer hits nothing");
                Ok(hits.Model[4] == box && hits.T[4] == before[4], accel + ": a ray of layer 1 still hits the box");
                s.RaycastAny(rays, hits, masks);
                Ok(hits.Model[0].IsNull && hits.Model[1] == sphere, accel + ": any-hit honours the masks");
                Ok(s.QuerySphere(new Vec3(0, 0, 3.5f), 1.0f, 1u).Length == 0 && s.QuerySphere(new Vec3(0, 0, 3.5f), 1.0f, 2u).Length == 1, accel + ": queries see the sphere in layer 2 only");
                Ok(s.QueryAabb(new Vec3(5, 0, 0), new Vec3(6, 2, 6), 1u).Length == 1, accel + ": a box query of layer 1 finds the box alone");
                s.SetLayers(sphere, ~0u);
                s.RaycastClosest(rays, hits);
                Ok(hits.Model[0] == sphere && hits.T[0] == before[0], accel + ": the sphere back in every layer");
                try
                {
                    s.RaycastClosest(rays, hits, new uint[2]);
                    Ok(false, accel + ": fewer masks than rays are refused");
                }
                catch (ArgumentException) { Ok(true, accel + ": fewer masks than rays are refused (ArgumentException)"); }

                SceneHitBatch any = new SceneHitBatch(5, normals: false);
                s.RaycastAny(rays, any);
                Ok(!any.Model[0].IsNull && any.Model[2].IsNull && any.Nx == null, accel + ": any-hit: hit, miss");
                ModelId[] near = s.QuerySphere(new Vec3(0, 0, 3.5f), 1.0f);
                Ok(near.Length == 1 && near[0] == sphere, accel + ": sphere query finds the sphere only");
                Ok(s.QueryAabb(new Vec3(5, 0, 0), new Vec3(6, 2, 6)).Length == 2, accel + ": box query finds both");
                // A thin box along the line from the sphere to the box reaches both; the axis-aligned
                // box of the same extents, around the same centre, neither.
                Vec3 mid = new Vec3(5, 0, 2.5f), thin = new Vec3(6, 0.5f, 0.5f);
                Vec3 along = new Vec3(0.8944272f, 0, -0.4472136f), up = new Vec3(0, 1, 0), across = new Vec3(0.4472136f, 0, 0.8944272f);
                Ok(s.QueryObb(mid, thin, along, up, across).Length == 2, accel + ": an oriented box query finds both");
                Ok(s.QueryObb(mid, thin, along, up, across, 0u).Length == 0, accel + ": an oriented box query of no layer finds none");
                Ok(s.QueryAabb(mid, thin).Length == 0, accel + ": the axis-aligned box of the same extents finds neither");

                rays.Count = 2;
                Ok(rays.Count == 2, accel + ": a batch can use fewer rays than its capacity");
                s.RemoveModel(sphere);
                Throws(Status.StaleId, () => s.RemoveModel(sphere), accel + ": remove(stale model)");
                try
                {
                    s.RaycastClosest(new RayBatch(8), new SceneHitBatch(4));
                    Ok(false, accel + ": a hit batch smaller than the rays is refused");
                }
                catch (ArgumentException) { Ok(true, accel + ": a hit batch smaller than the rays is refused (ArgumentException)"); }
            }
        }

        static void MeshAndSpheres()
        {
            Section("mesh and sphere batches");
            // A 2 x 2 quad at y = 1, two triangles.
            float[] x = { -1, 1, 1, -1 }, y = { 1, 1, 1, 1 }, z = { -1, -1, 1, 1 };
            uint[] idx = { 0, 1, 2, 0, 2, 3 };
            using (Mesh m = Mesh.Create(x, y, z, idx))
            {
                MeshInfo info = m.Info;
                Ok(info.TriangleCount == 2, "mesh: 2 triangles, " + info.BvhNodes + " BVH nodes, " + info.Bytes + " bytes");
                unsafe { Ok(info.BoundsMin[0] == -1 && info.BoundsMax[2] == 1 && info.BoundsMin[1] == 1, "mesh bounds from the fixed buffers"); }
                RayBatch rays = new RayBatch(3);
                rays.Set(0, new Vec3(0.5f, 5, 0.25f), new Vec3(0, -1, 0));
                rays.Set(1, new Vec3(3, 5, 0), new Vec3(0, -1, 0));
                rays.Set(2, new Vec3(0, 5, 0), new Vec3(0, 0, 0)); // zero direction: cannot be answered
                HitBatch hits = new HitBatch(3, normals: true, barycentrics: true);
                m.RaycastClosest(rays, hits);
                Near(hits.T[0], 4.0, 1e-5, "mesh: t down to the quad");
                Ok(hits.Primitive[0] >= 0 && hits.Primitive[1] == -1 && hits.Primitive[2] == Constants.GYRO_RAY_INVALID,
                   "mesh: hit, miss (-1), invalid ray (GYRO_RAY_INVALID): " + hits.Primitive[0] + ", " + hits.Primitive[1] + ", " + hits.Primitive[2]);
                using (Scene s = new Scene())
                {
                    ModelId inst = s.AddMesh(m, Transform.At(new Vec3(0, 2, 0)));
                    SceneHitBatch sh = new SceneHitBatch(1);
                    rays.Count = 1;
                    s.RaycastClosest(rays, sh);
                    Ok(sh.Model[0] == inst && Math.Abs(sh.T[0] - 2.0f) < 1e-5, "mesh instance in a scene, moved up 2: t = " + sh.T[0]);
                }
            }

            SphereBatch spheres = new SphereBatch(2);
            spheres.Set(0, new Vec3(0, 0, 10), 2);
            spheres.Set(1, new Vec3(0, 0, 6), 1);
            RayBatch r2 = new RayBatch(1);
            r2.Set(0, Vec3.Zero, new Vec3(0, 0, 1), 0, 5.5f);
            HitBatch h2 = new HitBatch(1);
            Geometry.RaycastSpheresClosest(r2, spheres, h2);
            Near(h2.T[0], 5.0, 1e-6, "brute-force spheres: the nearer sphere at t = 5 (tmax 5.5)");
            Ok(h2.Primitive[0] == 1, "brute-force spheres: primitive 1");
            r2.Tmax[0] = 4.5f;
            Geometry.RaycastSpheresClosest(r2, spheres, h2);
            Ok(h2.Primitive[0] == -1, "brute-force spheres: nothing before tmax 4.5");
        }

        static void CameraFrustum()
        {
            Section("camera and frustum");
            Camera cam = Cameras.Perspective(1.0f, 16.0f / 9.0f, 0.1f, 100.0f);
            Ok(cam.Mode == Projection.Perspective && cam.FovY == 1.0f && cam.ZFar == 100.0f, "perspective camera fields");
            Cameras.LookAt(ref cam, new Vec3(0, 0, -10), Vec3.Zero, new Vec3(0, 1, 0));
            Vec3 o, d;
            Cameras.PickingRay(cam, 640, 360, 1280, 720, out o, out d);
            Near(d.Z, 1.0, 1e-5, "picking ray through the screen centre looks down +z");
            Near(o.Z, -10 + 0.1, 1e-4, "it starts on the near plane");
            Frustum f = Cameras.Frustum(cam);
            Frustum g = Cameras.FrustumFromMatrix(Cameras.ViewProjection(cam));
            bool same = true;
            unsafe { for (int i = 0; i < 24; ++i) same &= Math.Abs(f.Planes[i] - g.Planes[i]) <= 1e-4 * Math.Max(1.0, Math.Abs(f.Planes[i])); }
            Ok(same, "camera frustum = frustum of its view-projection matrix (relative 1e-4)");
            SphereBatch s = new SphereBatch(3);
            s.Set(0, Vec3.Zero, 1);
            s.Set(1, new Vec3(0, 0, -20), 1);  // behind the eye
            s.Set(2, new Vec3(0, 0, 200), 1);  // past the far plane
            uint[] vis = new uint[3];
            Geometry.CullSpheres(f, s, vis);
            Ok(vis[0] == 1 && vis[1] == 0 && vis[2] == 0, "cull: in front visible, behind and too far culled (" + vis[0] + vis[1] + vis[2] + ")");
            using (Scene sc = new Scene())
            {
                ModelId ball = sc.AddSphere(Vec3.Zero, 1);
                sc.AddSphere(new Vec3(0, 0, -20), 1);
                SceneHit hit = sc.Pick(cam, 640, 360, 1280, 720);
                Ok(hit.Hit == 1 && hit.Model == ball && Math.Abs(hit.T - 8.9f) < 1e-3, "pick at the screen centre: the ball at t = " + hit.T);
                ModelId[] inView = sc.QueryFrustum(f);
                Ok(inView.Length == 1 && inView[0] == ball, "frustum query: only the ball");
            }
        }

        static void ConvexHulls()
        {
            Section("convex hulls and pair queries");
            Vec3[] pts = new Vec3[9];
            for (int i = 0; i < 8; ++i) pts[i] = new Vec3((i & 1) != 0 ? 1 : -1, (i & 2) != 0 ? 1 : -1, (i & 4) != 0 ? 1 : -1);
            pts[8] = Vec3.Zero; // inside: dropped
            using (ConvexHull hull = new ConvexHull(pts))
            {
                ConvexHullInfo info = hull.Info;
                Ok(info.VertexCount == 8 && info.FaceCount == 6 && info.EdgeCount == 12 && info.FaceVertexCount == 24,
                   "cube hull: 8 vertices, 6 faces, 12 edges, 24 face vertices");
                Ok(hull.Vertices().Length == 8 && hull.Planes().Length == 6 && hull.FaceStarts().Length == 7 &&
                   hull.FaceVertices().Length == 24 && hull.Edges().Length == 12, "copy-out getters agree with the info");
                ConvexMass m = hull.Mass();
                Near(m.Volume, 8.0, 1e-5, "cube volume (side 2)");
                Near(m.Inertia0.X, 8.0 * 8.0 / 12.0, 1e-4, "inertia xx = V (b^2 + c^2) / 12");
                Near(m.Centroid.Length, 0, 1e-6, "centroid at the origin");

                ConvexShape[] a = { ConvexShape.Sphere(1), hull.AsShape(), ConvexShape.Box(new Vec3(1, 1, 1)) };
                ConvexShape[] b = { ConvexShape.Sphere(1), ConvexShape.Sphere(0.5f), ConvexShape.Box(new Vec3(1, 1, 1)) };
                ConvexPose[] pa = { ConvexPose.At(Vec3.Zero), ConvexPose.At(Vec3.Zero), ConvexPose.At(Vec3.Zero) };
                ConvexPose[] pb = { ConvexPose.At(new Vec3(5, 0, 0)), ConvexPose.At(new Vec3(0, 3, 0)), ConvexPose.At(new Vec3(1.5f, 0, 0)) };
                ConvexResult[] r = new ConvexResult[3];
                Convex.DistancePairs(a, pa, b, pb, r);
                Near(r[0].Distance, 3.0, 1e-5, "sphere-sphere distance 5 - 1 - 1");
                Near(r[0].Normal.X, 1.0, 1e-5, "normal from A towards B");
                Near(r[1].Distance, 1.5, 1e-5, "hull (cube) to sphere distance 3 - 1 - 0.5");
                Convex.PenetrationPairs(a, pa, b, pb, r);
                Ok(r[2].Status == ConvexStatus.Intersecting, "boxes 1.5 apart intersect: " + r[2].Status);
                Near(r[2].Distance, -0.5, 1e-4, "penetration depth 0.5 (distance = -depth)");
                ConvexResult[] pen = (ConvexResult[])r.Clone();
                Convex.ContactPairs(a, pa, b, pb, r);
                Ok(r[0].Status == ConvexStatus.Separated && r[1].Status == ConvexStatus.Separated, "contact: separated pairs stay separated");
                Ok(r[2].Equals(pen[2]), "contact: an overlapping pair gets the penetration answer bit for bit");
                Convex.IntersectPairs(a, pa, b, pb, r);
                Ok(r[0].Status == ConvexStatus.Separated && r[2].Status != ConvexStatus.Separated, "intersect verdicts");
                ConvexPose turned = Convex.PoseFromQuat(new Vec3(1, 2, 3), Quat.Identity);
                Ok(turned.Position.Equals(new Vec3(1, 2, 3)) && turned.Rotation0.Equals(new Vec3(1, 0, 0)), "pose from the identity quaternion");

                using (World w = new World())
                {
                    w.CreateGround();
                    BodyDef bd = Defaults.Body();
                    bd.Position = new Vec3(0, 3, 0);
                    BodyId hb = w.CreateBody(bd, hull);
                    for (int i = 0; i < 240; ++i) w.Step(1.0f / 60.0f);
                    Near(w.GetPosition(hb).Y, 1.0, 0.01, "a cube hull body (half-size 1) rests at y = 1 (1 cm)");
                }
            }
            Throws(Status.InvalidArgument, () => new ConvexHull(new[] { Vec3.Zero, new Vec3(1, 0, 0), new Vec3(0, 1, 0), new Vec3(1, 1, 0) }), "hull of coplanar points");
        }

        static void Cloth()
        {
            Section("cloth");
            using (World w = new World())
            {
                ClothDef cd = Defaults.Cloth();
                cd.Nx = 8; cd.Nz = 8; cd.SizeX = 2; cd.SizeZ = 2; cd.Center = new Vec3(0, 2, 0);
                SoftBodyId c = w.CreateCloth(cd);
                Ok(w.IsValid(c) && w.SoftBodyCount == 1, "cloth created");
                uint corner0 = w.ClothIndex(c, 0, 0), corner1 = w.ClothIndex(c, 7, 0), middle = w.ClothIndex(c, 4, 4);
                w.Pin(c, corner0);
                w.Pin(c, corner1);
                Vec3 pin0 = w.GetParticlePosition(c, corner0);
                Near(pin0.Y, 2.0, 1e-6, "corner starts at the cloth's height");
                ulong before = w.SoftBodyHash(c);
                for (int i = 0; i < 60; ++i) w.Step(1.0f / 60.0f);
                Ok(w.GetParticlePosition(c, corner0).Equals(pin0) && w.IsPinned(c, corner0), "a pinned corner stays put");
                Ok(w.GetParticlePosition(c, middle).Y < 1.5f, "the free middle fell: y = " + w.GetParticlePosition(c, middle).Y);
                SoftBodyStateView v = w.GetSoftBodyView(c);
                Ok(v.Count == 64 && v.InverseMass[(int)corner0] == 0 && v.Py[(int)middle] == w.GetParticlePosition(c, middle).Y,
                   "view: 64 particles, pinned inverse mass 0, " + v.TriangleCount + " triangles");
                SoftBodyStats st = w.GetSoftBodyStats(c);
                Ok(st.Particles == 64 && st.Springs > 0 && st.MaxStrain < 0.5, "stats: " + st.Springs + " springs, max strain " + st.MaxStrain.ToString("F4"));
                Ok(w.SoftBodyHash(c) != before, "the soft body hash moved");
                Throws(Status.InvalidArgument, () => w.GetParticlePosition(c, 64), "particle index 64 of 64");
                SoftSettings ss = w.GetSoftSettings(c);
                Ok(ss.Model == SoftModel.Xpbd && ss.Substeps == 16, "default soft settings: XPBD, 16 sub-steps");
                w.DestroySoftBody(c);
                Throws(Status.StaleId, () => w.GetParticlePosition(c, 0), "destroyed cloth id");
            }
        }

        static void Snapshots()
        {
            Section("snapshot and restore");
            using (World w = new World())
            {
                w.CreateGround();
                for (int i = 0; i < 6; ++i) w.CreateBox(new Vec3(0.1f * i, 0.6f + 1.2f * i, 0), new Vec3(0.5f, 0.5f, 0.5f));
                for (int i = 0; i < 30; ++i) w.Step(1.0f / 60.0f);
                long size;
                try
                {
                    size = w.SnapshotSize;
                }
                catch (GyroException e) when (e.Status == Status.Unsupported)
                {
                    Console.WriteLine("  SKIP  snapshot checks: gyro_world_snapshot_size returned UNSUPPORTED (5): " + e.Detail);
                    return;
                }
                ulong atSnapshot = w.Hash;
                byte[] snap = w.Snapshot();
                Ok(snap.Length == size && size > 0, "snapshot of " + size + " bytes");
                for (int i = 0; i < 30; ++i) w.Step(1.0f / 60.0f);
                ulong after = w.Hash;
                w.Restore(snap);
                Ok(w.Hash == atSnapshot, "restore gives back the hash at the snapshot (" + atSnapshot.ToString("x16") + ")");
                for (int i = 0; i < 30; ++i) w.Step(1.0f / 60.0f);
                Ok(w.Hash == after, "snapshot -> step -> restore -> step: identical hashes (" + after.ToString("x16") + ")");
                using (World copy = World.FromSnapshot(snap))
                {
                    for (int i = 0; i < 30; ++i) copy.Step(1.0f / 60.0f);
                    Ok(copy.Hash == after, "a world created from the snapshot steps to the same hash");
                }
                byte[] bad = (byte[])snap.Clone();
                bad[bad.Length / 2] ^= 0x5a;
                ulong now = w.Hash;
                Throws(Status.CorruptData, () => w.Restore(bad), "restore(corrupted snapshot)");
                Throws(Status.CorruptData, () => w.Restore(new ReadOnlySpan<byte>(snap, 0, snap.Length / 2)), "restore(truncated snapshot)");
                Ok(w.Hash == now, "the world is unchanged after refused restores");
                Throws(Status.InvalidCount, () => w.Snapshot(new byte[4]), "snapshot into 4 bytes");
            }
        }

        static void Handles()
        {
            Section("handles");
            World w = new World();
            WorldHandle h = w.Handle;
            w.Dispose();
            Ok(h.IsClosed, "Dispose closes the world's SafeHandle");
            try
            {
                w.Step(1.0f / 60.0f);
                Ok(false, "a disposed world refuses calls");
            }
            catch (ObjectDisposedException) { Ok(true, "a disposed world refuses calls (ObjectDisposedException)"); }
            w.Dispose();
            Ok(true, "a second Dispose is harmless");

            // Meshes are reference counted: a scene keeps its mesh after the handle is gone.
            Scene s = new Scene();
            Mesh m = Mesh.Create(new float[] { 0, 1, 0 }, new float[] { 0, 0, 1 }, new float[] { 0, 0, 0 }, new uint[] { 0, 1, 2 });
            s.AddMesh(m, Transform.At(Vec3.Zero));
            m.Dispose();
            RayBatch r = new RayBatch(1);
            r.Set(0, new Vec3(0.2f, 0.2f, -1), new Vec3(0, 0, 1));
            SceneHitBatch hits = new SceneHitBatch(1);
            s.RaycastClosest(r, hits);
            Ok(Math.Abs(hits.T[0] - 1) < 1e-6, "the scene still hits its mesh after Mesh.Dispose: t = " + hits.T[0]);
            s.Dispose();
        }
    }
}
