//! The safe crate against the built libgyro (ctest capi.rust): a box comes to rest on a
//! plane, identical runs hash the same, bad input maps to the right Err, mesh and scene
//! raycasts through slices give the analytic hits, convex pair queries and hulls, cloth,
//! snapshots.
use gyro::sys;
use gyro::*;

const DT: f32 = 1.0 / 60.0;

fn close(a: f32, b: f32, tol: f32) -> bool {
    (a - b).abs() <= tol
}

/// A static plane (y = 0) and a dynamic unit box whose bottom starts 1.5 m above it.
fn box_on_plane() -> (World, BodyId, BodyId) {
    let mut world = World::with_defaults().unwrap();
    let mut ground = body_def();
    ground.r#type = sys::GYRO_BODY_STATIC;
    ground.shape = sys::GYRO_BODY_SHAPE_PLANE;
    let plane = world.create_body(&ground).unwrap();
    let mut bd = body_def();
    bd.position = vec3(0.0, 2.0, 0.0);
    bd.user_data = 42;
    let boxed = world.create_body(&bd).unwrap();
    (world, plane, boxed)
}

#[test]
fn the_library_matches_the_bindings() {
    assert!(abi_compatible(), "library ABI {:#x}, bindings {:#x}", abi_version(), sys::GYRO_ABI_VERSION);
    assert!(!version().is_empty());
    assert_ne!(features() & sys::GYRO_FEATURE_DYNAMICS, 0);
}

#[test]
fn a_box_dropped_on_a_plane_comes_to_rest_on_it() {
    let (mut world, plane, boxed) = box_on_plane();
    assert_eq!(world.body_count().unwrap(), 2);
    assert_eq!(world.mass(boxed).unwrap(), 1.0);
    assert_eq!(world.mass(plane).unwrap(), 0.0);
    assert_eq!(world.user_data(boxed).unwrap(), 42);
    assert_eq!(world.body_type(plane).unwrap(), sys::GYRO_BODY_STATIC);
    for _ in 0..60 {
        world.step(DT).unwrap();
    }
    let (p, q) = world.transform(boxed).unwrap();
    let (v, w) = world.velocity(boxed).unwrap();
    assert!(close(p.y, 0.5, 0.01), "box centre at y = {} (expected 0.5, half its height)", p.y);
    assert!(close(p.x, 0.0, 1e-3) && close(p.z, 0.0, 1e-3), "drifted to {p:?}");
    assert!(close(q.w.abs(), 1.0, 1e-3), "tipped over: {q:?}");
    assert!(v.y.abs() < 0.05 && w.x.abs() < 0.05 && w.z.abs() < 0.05, "still moving: {v:?} {w:?}");

    // the zero-copy view agrees with the getters
    let view = world.body_view().unwrap();
    assert_eq!(view.len(), 2);
    let slot = view.ids().iter().position(|id| id.index == boxed.index && id.generation == boxed.generation);
    let slot = slot.expect("the box is in the view");
    assert_eq!(view.py()[slot], p.y);
    assert_eq!(view.qw()[slot], q.w);
    let stats = world.stats().unwrap();
    assert_eq!(stats.bodies, 2);
}

#[test]
fn forces_impulses_and_teleports_act() {
    let (mut world, _plane, boxed) = box_on_plane();
    world.apply_linear_impulse(boxed, vec3(2.0, 0.0, 0.0), vec3(0.0, 2.0, 0.0)).unwrap();
    let (v, _) = world.velocity(boxed).unwrap();
    assert!(close(v.x, 2.0, 1e-6), "1 kg box after a 2 N s impulse: {v:?}");
    world.set_velocity(boxed, vec3(0.0, 0.0, 0.0), vec3(0.0, 0.0, 0.0)).unwrap();
    world.set_transform(boxed, vec3(1.0, 5.0, 0.0), QUAT_IDENTITY).unwrap();
    assert_eq!(world.position(boxed).unwrap().y, 5.0);
    world.apply_force_at_center(boxed, vec3(0.0, 9.81 * 2.0, 0.0)).unwrap(); // gravity reversed, once
    world.step(DT).unwrap();
    let (v, _) = world.velocity(boxed).unwrap();
    assert!(v.y > 0.0, "an upward force of twice the weight lifts the box: {v:?}");
    assert!(world.is_awake(boxed).unwrap());
}

fn scripted_run() -> u64 {
    let (mut world, _plane, boxed) = box_on_plane();
    let mut bd = body_def();
    bd.shape = sys::GYRO_BODY_SHAPE_SPHERE;
    bd.radius = 0.3;
    bd.position = vec3(0.2, 4.0, -0.1);
    let ball = world.create_body(&bd).unwrap();
    for i in 0..90 {
        if i == 30 {
            world.apply_angular_impulse(boxed, vec3(0.0, 0.5, 0.1)).unwrap();
        }
        if i == 45 {
            world.apply_force(ball, vec3(3.0, 0.0, 1.0), vec3(0.2, 1.0, 0.0)).unwrap();
        }
        world.step(DT).unwrap();
    }
    world.hash().unwrap()
}

#[test]
fn identical_runs_hash_the_same() {
    let a = scripted_run();
    let b = scripted_run();
    assert_eq!(a, b);
    let (mut world, _, _) = box_on_plane();
    world.step(DT).unwrap();
    assert_ne!(world.hash().unwrap(), a, "a different history hashes differently");
}

#[test]
fn errors_carry_the_status_and_the_library_text() {
    let (mut world, _plane, boxed) = box_on_plane();
    let before = world.hash().unwrap();

    let e = world.step(f32::NAN).unwrap_err();
    assert_eq!(e.status(), Status::NonFinite);
    assert_eq!(e.status().code(), sys::GYRO_STATUS_NON_FINITE);
    assert!(!e.message().is_empty());
    assert!(e.to_string().starts_with("non_finite"), "{e}");
    assert_eq!(world.step(0.0).unwrap_err().status(), Status::InvalidArgument);
    assert_eq!(world.step(f32::INFINITY).unwrap_err().status(), Status::NonFinite);
    assert_eq!(world.hash().unwrap(), before, "a failed call changes nothing");

    world.destroy_body(boxed).unwrap();
    assert!(!world.is_valid(boxed));
    let e = world.transform(boxed).unwrap_err();
    assert_eq!(e.status(), Status::StaleId);
    assert_eq!(world.destroy_body(boxed).unwrap_err().status(), Status::StaleId);
    assert_eq!(world.apply_torque(boxed, vec3(1.0, 0.0, 0.0)).unwrap_err().status(), Status::StaleId);

    let mut bad = body_def();
    bad.mass = -1.0;
    assert_eq!(world.create_body(&bad).unwrap_err().status(), Status::InvalidArgument);
    bad = body_def();
    bad.position.x = f32::NAN;
    assert_eq!(world.create_body(&bad).unwrap_err().status(), Status::NonFinite);

    let mut wd = world_def();
    wd.substeps = 0;
    assert_eq!(World::new(&wd).err().unwrap().status(), Status::InvalidArgument);
    wd = world_def();
    wd.struct_size = 3;
    assert_eq!(World::new(&wd).err().unwrap().status(), Status::InvalidArgument);
}

fn quad() -> Mesh {
    let v = [[-1.0, 0.0, -1.0], [1.0, 0.0, -1.0], [1.0, 0.0, 1.0], [-1.0, 0.0, 1.0]];
    Mesh::new(&v, &[[0, 1, 2], [0, 2, 3]]).unwrap()
}

#[test]
fn mesh_raycasts_through_slices_give_the_analytic_hits() {
    let mesh = quad();
    let info = mesh.info().unwrap();
    assert_eq!(info.triangle_count, 2);
    assert_eq!((info.bounds_min, info.bounds_max), ([-1.0, 0.0, -1.0], [1.0, 0.0, 1.0]));

    // down onto triangle 0 (z <= x) with |d| = 2, onto triangle 1, beside the quad, a NaN ray
    let ox = [0.25, -0.5, 5.0, f32::NAN];
    let oy = [5.0, 3.0, 1.0, 1.0];
    let oz = [-0.5, 0.5, 0.0, 0.0];
    let dx = [0.0; 4];
    let dy = [-2.0, -1.0, -1.0, -1.0];
    let dz = [0.0; 4];
    let rays = Rays::new([&ox, &oy, &oz], [&dx, &dy, &dz]);
    let (mut t, mut prim) = ([0.0f32; 4], [0i32; 4]);
    let (mut nx, mut ny, mut nz, mut u, mut v) = ([0.0f32; 4], [0.0f32; 4], [0.0f32; 4], [0.0f32; 4], [0.0f32; 4]);
    let mut hits = Hits { t: &mut t, primitive: &mut prim, normal: Some([&mut nx, &mut ny, &mut nz]), uv: Some([&mut u, &mut v]) };
    mesh.raycast_closest(&rays, &mut hits).unwrap();
    assert_eq!(prim, [0, 1, -1, sys::GYRO_RAY_INVALID]);
    assert_eq!(t[0], 2.5, "t in units of |d| = 2");
    assert_eq!(t[1], 3.0);
    assert!(t[2].is_infinite() && t[3].is_infinite());
    assert_eq!((nx[0], ny[0], nz[0]), (0.0, 1.0, 0.0), "the normal faces the ray");
    // point = a + u (b - a) + v (c - a) for triangle 0 = (v0, v1, v2)
    let (px, pz) = (-1.0 + u[0] * 2.0 + v[0] * 2.0, -1.0 + v[0] * 2.0);
    assert!(close(px, 0.25, 1e-6) && close(pz, -0.5, 1e-6), "barycentrics {} {} give ({px}, {pz})", u[0], v[0]);

    let (mut t2, mut prim2) = ([0.0f32; 4], [0i32; 4]);
    mesh.raycast_any(&rays, &mut Hits::new(&mut t2, &mut prim2)).unwrap();
    assert_eq!(prim2[2], -1);
    assert!(prim2[0] >= 0 && prim2[1] >= 0);

    // slices of different lengths are refused before the call
    let short = [0.0f32; 3];
    let bad = Rays::new([&ox, &oy, &short], [&dx, &dy, &dz]);
    let e = mesh.raycast_closest(&bad, &mut Hits::new(&mut t2, &mut prim2)).unwrap_err();
    assert_eq!(e.status(), Status::InvalidCount);

    // an index out of range
    let e = Mesh::new(&[[0.0; 3]; 3], &[[0, 1, 3]]).err().unwrap();
    assert_eq!(e.status(), Status::InvalidArgument);
}

#[test]
fn brute_force_sphere_raycasts() {
    let (cx, cy, cz, r) = ([0.0f32, 0.0], [0.0f32, 0.0], [5.0f32, 10.0], [1.0f32, 2.0]);
    let (o, d) = ([0.0f32], [1.0f32]);
    let rays = Rays::new([&o, &o, &o], [&o, &o, &d]);
    let (mut t, mut prim) = ([0.0f32], [0i32]);
    raycast_spheres_closest(&rays, &Spheres { center: [&cx, &cy, &cz], radius: &r }, &mut Hits::new(&mut t, &mut prim)).unwrap();
    assert_eq!((t[0], prim[0]), (4.0, 0));
}

#[test]
fn scene_raycasts_name_the_model_hit() {
    let mesh = quad();
    let mut scene = Scene::new(SceneAccel::Bvh).unwrap();
    let mut sphere = Scene::model_def();
    sphere.transform.position = [0.0, 0.0, 5.0];
    let sphere_id = scene.add_model(&sphere, None).unwrap();
    let mut cube = Scene::model_def();
    cube.shape = sys::GYRO_MODEL_BOX;
    cube.half_extents = [1.0, 1.0, 1.0];
    cube.transform.position = [3.0, 0.0, 5.0];
    let cube_id = scene.add_model(&cube, None).unwrap();
    let mut floor = Scene::model_def();
    floor.shape = sys::GYRO_MODEL_MESH;
    floor.transform.position = [0.0, -2.0, 20.0];
    floor.transform.scale = 2.0;
    let floor_id = scene.add_model(&floor, Some(&mesh)).unwrap();
    drop(mesh); // the scene keeps its own reference
    assert_eq!(scene.model_count(), 3);

    let ox = [0.0, 3.0, 0.2, 100.0];
    let oy = [0.0, 0.5, 5.0, 100.0];
    let oz = [0.0, 0.0, 20.3, 100.0];
    let dx = [0.0; 4];
    let dy = [0.0, 0.0, -1.0, 1.0];
    let dz = [1.0, 1.0, 0.0, 0.0];
    let rays = Rays::new([&ox, &oy, &oz], [&dx, &dy, &dz]);
    let mut t = [0.0f32; 4];
    let mut model = [ModelId { index: 0, generation: 0 }; 4];
    let mut prim = [0i32; 4];
    let (mut nx, mut ny, mut nz) = ([0.0f32; 4], [0.0f32; 4], [0.0f32; 4]);
    let mut hits = SceneHits { t: &mut t, model: &mut model, primitive: Some(&mut prim), normal: Some([&mut nx, &mut ny, &mut nz]), uv: None };
    scene.raycast_closest(&rays, &mut hits).unwrap();
    let same = |a: ModelId, b: ModelId| a.index == b.index && a.generation == b.generation;
    assert!(same(model[0], sphere_id) && close(t[0], 4.0, 1e-6) && close(nz[0], -1.0, 1e-6));
    assert!(same(model[1], cube_id) && close(t[1], 4.0, 1e-6) && close(nz[1], -1.0, 1e-6));
    assert!(same(model[2], floor_id) && close(t[2], 7.0, 1e-5) && prim[2] >= 0 && close(ny[2], 1.0, 1e-6));
    assert_eq!((model[3].index, model[3].generation, prim[3]), (0, 0, -1));
    assert!(t[3].is_infinite());
    // Layers: the sphere in layer 2 only. Ray 0 (layer 1) passes through it to nothing,
    // ray 1 (layer 2) still hits the cube, which is in every layer; a mask of 0 sees nothing.
    scene.set_layers(sphere_id, 2).unwrap();
    {
        let mut t2 = [0.0f32; 4];
        let mut model2 = [ModelId { index: 0, generation: 0 }; 4];
        let mut hits2 = SceneHits { t: &mut t2, model: &mut model2, primitive: None, normal: None, uv: None };
        scene.raycast_closest_masked(&rays, &[1, 2, 0, u32::MAX], &mut hits2).unwrap();
        assert!(hits2.t[0].is_infinite() && hits2.model[0].generation == 0);
        assert!(same(hits2.model[1], cube_id) && hits2.t[1].to_bits() == t[1].to_bits());
        assert!(hits2.t[2].is_infinite());
        scene.raycast_any_masked(&rays, &[2, 2, 2, 2], &mut hits2).unwrap();
        assert!(same(hits2.model[0], sphere_id));
        let short = scene.raycast_closest_masked(&rays, &[1], &mut hits2).unwrap_err();
        assert_eq!(short.status(), Status::InvalidCount);
    }
    let c = Vec3 { x: 0.0, y: 0.0, z: 5.0 };
    assert!(scene.query_sphere_masked(c, 0.5, 1).unwrap().is_empty());
    let in2 = scene.query_sphere_masked(c, 0.5, 2).unwrap();
    assert!(in2.len() == 1 && same(in2[0], sphere_id));
    scene.set_layers(sphere_id, u32::MAX).unwrap();
    // Prefetching changes speed only.
    let before = t;
    for mode in [RayPrefetch::Always, RayPrefetch::Never, RayPrefetch::Auto] {
        scene.set_ray_prefetch(mode).unwrap();
        let mut t2 = [0.0f32; 4];
        let mut model2 = [ModelId { index: 0, generation: 0 }; 4];
        let mut hits2 = SceneHits { t: &mut t2, model: &mut model2, primitive: None, normal: None, uv: None };
        scene.raycast_closest(&rays, &mut hits2).unwrap();
        assert_eq!(t2.map(f32::to_bits), before.map(f32::to_bits));
    }
    // Refit or rebuild after a move, the same hits.
    for on in [false, true] {
        scene.set_refit(on).unwrap();
        scene.set_transform(cube_id, &cube.transform).unwrap();
        let mut t2 = [0.0f32; 4];
        let mut model2 = [ModelId { index: 0, generation: 0 }; 4];
        let mut hits2 = SceneHits { t: &mut t2, model: &mut model2, primitive: None, normal: None, uv: None };
        scene.raycast_closest(&rays, &mut hits2).unwrap();
        assert_eq!(t2.map(f32::to_bits), before.map(f32::to_bits));
    }

    let near = scene.query_sphere(vec3(0.0, 0.0, 6.5), 1.0).unwrap();
    assert_eq!(near.len(), 1);
    assert!(same(near[0], sphere_id));

    scene.remove_model(sphere_id).unwrap();
    assert_eq!(scene.remove_model(sphere_id).unwrap_err().status(), Status::StaleId);
}

#[test]
fn scene_queries_frustums_and_picks() {
    let mut scene = Scene::new(SceneAccel::Bvh).unwrap();
    let add = |scene: &mut Scene, shape: u32, at: [f32; 3], layers: u32| {
        let mut d = Scene::model_def();
        d.shape = shape;
        d.transform.position = at;
        let id = scene.add_model(&d, None).unwrap();
        scene.set_layers(id, layers).unwrap();
        id
    };
    let ahead = add(&mut scene, sys::GYRO_MODEL_SPHERE, [0.0, 0.0, 10.0], 1);
    let right = add(&mut scene, sys::GYRO_MODEL_SPHERE, [5.0, 0.0, 10.0], 2);
    let behind = add(&mut scene, sys::GYRO_MODEL_SPHERE, [0.0, 0.0, -10.0], 1);
    let above = add(&mut scene, sys::GYRO_MODEL_BOX, [0.0, 5.0, 10.0], 4);
    let ids = |v: Vec<ModelId>| v.iter().map(|m| (m.index, m.generation)).collect::<Vec<_>>();
    let id = |m: ModelId| (m.index, m.generation);

    // A 60-degree camera at the origin looking down +z: half its view at z = 10 is 5.77.
    let mut camera = Camera::perspective(core::f32::consts::FRAC_PI_3, 1.0, 0.1, 100.0);
    let (o, y, z) = (vec3(0.0, 0.0, 0.0), vec3(0.0, 1.0, 0.0), vec3(0.0, 0.0, 10.0));
    camera.look_at(o, z, y).unwrap();
    let vp = camera.view_projection().unwrap();
    let frustum = camera.frustum().unwrap();
    let from_matrix = Frustum::from_matrix(&vp).unwrap();
    for (a, b) in frustum.0.planes.iter().flatten().zip(from_matrix.0.planes.iter().flatten()) {
        assert!(close(*a, *b, 1e-4), "{:?} against {:?}", frustum.0.planes, from_matrix.0.planes);
    }
    assert_eq!(ids(scene.query_frustum(&frustum).unwrap()), vec![id(ahead), id(right), id(above)]);
    assert_eq!(ids(scene.query_frustum_masked(&frustum, 2).unwrap()), vec![id(right)]);
    let (cx, cy, cz, r) = ([0.0, 5.0, 0.0, 0.0], [0.0, 0.0, 0.0, 5.0], [10.0, 10.0, -10.0, 10.0], [1.0; 4]);
    let mut visible = [false; 4];
    frustum.cull_spheres(&Spheres { center: [&cx, &cy, &cz], radius: &r }, &mut visible).unwrap();
    assert_eq!(visible, [true, true, false, true]);
    assert_eq!(frustum.cull_spheres(&Spheres { center: [&cx, &cy, &cz], radius: &r }, &mut visible[..2]).unwrap_err().status(), Status::InvalidCount);

    // The picking ray through the viewport's centre runs down +z from the near plane.
    let (origin, dir) = camera.picking_ray((50.0, 50.0), (100.0, 100.0)).unwrap();
    assert!(close(origin.z, 0.1, 1e-5) && close(dir.z, 1.0, 1e-6) && close(dir.x, 0.0, 1e-6));
    let hit = scene.pick(&camera, (50.0, 50.0), (100.0, 100.0)).unwrap().expect("the sphere ahead");
    assert_eq!(id(hit.model), id(ahead));
    assert!(close(hit.point[2], 9.0, 1e-4) && close(hit.normal[2], -1.0, 1e-4) && close(hit.t, 8.9, 1e-4));
    assert!(scene.pick_masked(&camera, (50.0, 50.0), (100.0, 100.0), 2).unwrap().is_none());
    assert!(scene.pick(&camera, (50.0, 50.0), (0.0, 0.0)).is_err());

    // Boxes: an AABB around the sphere ahead; an OBB spanning both spheres at z = 10, then
    // the same turned a quarter about z (it then runs along y between them: nothing).
    assert_eq!(ids(scene.query_aabb(z, vec3(1.5, 1.5, 1.5)).unwrap()), vec![id(ahead)]);
    assert!(scene.query_aabb_masked(z, vec3(1.5, 1.5, 1.5), 2).unwrap().is_empty());
    let (c, h) = (vec3(2.5, 0.0, 10.0), vec3(3.0, 0.5, 0.5));
    let straight = [vec3(1.0, 0.0, 0.0), vec3(0.0, 1.0, 0.0), vec3(0.0, 0.0, 1.0)];
    let turned = [vec3(0.0, 1.0, 0.0), vec3(-1.0, 0.0, 0.0), vec3(0.0, 0.0, 1.0)];
    assert_eq!(ids(scene.query_obb(c, h, straight).unwrap()), vec![id(ahead), id(right)]);
    assert_eq!(ids(scene.query_obb_masked(c, h, straight, 2).unwrap()), vec![id(right)]);
    assert!(scene.query_obb(c, h, turned).unwrap().is_empty());
    assert!(scene.query_aabb(vec3(f32::NAN, 0.0, 0.0), h).is_err());

    // An orthographic camera 4 m wide sees only the sphere straight ahead.
    let mut ortho = Camera::orthographic(4.0, 4.0, 0.1, 100.0);
    ortho.look_at(o, z, y).unwrap();
    assert_eq!(ids(scene.query_frustum(&ortho.frustum().unwrap()).unwrap()), vec![id(ahead)]);
    // A failed look_at leaves the camera as it was.
    let before = ortho.0.orientation;
    assert!(ortho.look_at(o, o, y).is_err());
    assert_eq!(ortho.0.orientation, before);
    let _ = behind;
}

#[test]
fn convex_pair_queries_over_slices() {
    let a = [ConvexShape::sphere(1.0), ConvexShape::cuboid(vec3(1.0, 1.0, 1.0)), ConvexShape::sphere(0.5)];
    let b = [ConvexShape::sphere(1.0), ConvexShape::cuboid(vec3(1.0, 1.0, 1.0)), ConvexShape::cuboid(vec3(1.0, 1.0, 1.0))];
    let pa = [convex_pose_at(vec3(0.0, 0.0, 0.0)); 3];
    let pb = [convex_pose_at(vec3(3.0, 0.0, 0.0)), convex_pose_at(vec3(1.5, 0.0, 0.0)), convex_pose_at(vec3(2.0, 0.0, 0.0))];
    let mut out: [ConvexResult; 3] = unsafe { core::mem::zeroed() };
    convex_penetration_pairs(&a, &pa, &b, &pb, &mut out).unwrap();
    assert_eq!(out[0].status, sys::GYRO_CONVEX_SEPARATED);
    assert!(close(out[0].distance, 1.0, 1e-5) && close(out[0].normal.x, 1.0, 1e-5));
    assert_eq!(out[1].status, sys::GYRO_CONVEX_INTERSECTING);
    assert!(close(out[1].distance, -0.5, 1e-5) && close(out[1].normal.x, 1.0, 1e-5), "{:?}", out[1].normal);
    assert!(close(out[2].distance, 0.5, 1e-5));

    // contact (ABI 1.6): the overlapping pair's penetration bits, the separated pairs separated
    let mut contact: [ConvexResult; 3] = unsafe { core::mem::zeroed() };
    convex_contact_pairs(&a, &pa, &b, &pb, &mut contact).unwrap();
    assert_eq!(contact[0].status, sys::GYRO_CONVEX_SEPARATED);
    assert_eq!(contact[2].status, sys::GYRO_CONVEX_SEPARATED);
    assert_eq!(contact[1].distance.to_bits(), out[1].distance.to_bits());
    assert_eq!(contact[1].normal.x.to_bits(), out[1].normal.x.to_bits());
    assert!(contact[0].distance >= out[0].distance && contact[2].distance >= out[2].distance);

    let mut hits: [ConvexResult; 3] = unsafe { core::mem::zeroed() };
    convex_intersect_pairs(&a, &pa, &b, &pb, &mut hits).unwrap();
    assert_eq!(hits[0].status, sys::GYRO_CONVEX_SEPARATED);
    assert_eq!(hits[1].status, sys::GYRO_CONVEX_INTERSECTING);

    // a bad pair is flagged, the others answered
    let bad = [ConvexShape::sphere(-1.0), ConvexShape::sphere(1.0), ConvexShape::sphere(1.0)];
    convex_distance_pairs(&bad, &pa, &b, &pb, &mut out).unwrap();
    assert_eq!(out[0].status, sys::GYRO_CONVEX_INVALID_INPUT);
    assert!(close(out[2].distance, 0.0, 1e-6) || out[2].distance > 0.0);
    // different lengths are refused
    assert_eq!(convex_distance_pairs(&bad[..2], &pa, &b, &pb, &mut out).unwrap_err().status(), Status::InvalidCount);
    let pose = convex_pose(vec3(0.0, 0.0, 0.0), Quat { x: 0.0, y: 0.0, z: 0.0, w: 2.0 }).unwrap();
    assert_eq!(pose.rotation[0].x, 1.0);
    assert_eq!(convex_pose(vec3(0.0, 0.0, 0.0), Quat { x: 0.0, y: 0.0, z: 0.0, w: 0.0 }).unwrap_err().status(), Status::InvalidArgument);
}

#[test]
fn hulls_and_hull_bodies() {
    let mut pts = vec![];
    for i in 0..8 {
        let s = |b: i32| if i & b != 0 { 1.0 } else { -1.0 };
        pts.push(vec3(s(1), s(2), s(4)));
    }
    pts.push(vec3(0.1, 0.2, 0.3)); // inside
    let hull = ConvexHull::new(&pts).unwrap();
    let info = hull.info().unwrap();
    assert_eq!((info.vertex_count, info.face_count, info.edge_count), (8, 6, 12));
    assert_eq!(hull.vertices().unwrap().len(), 8);
    assert_eq!(hull.planes().unwrap().len(), 6);
    assert_eq!(hull.face_starts().unwrap().len(), 7);
    assert_eq!(hull.face_vertices().unwrap().len(), info.face_vertex_count as usize);
    assert!(hull.edges().unwrap().iter().all(|e| e.a < e.b));
    assert!(close(hull.mass().unwrap().volume, 8.0, 1e-4));
    assert_eq!(ConvexHull::new(&pts[..3]).err().unwrap().status(), Status::InvalidCount);

    let a = [ConvexShape::hull(&hull)];
    let b = [ConvexShape::sphere(1.0)];
    let mut out: [ConvexResult; 1] = unsafe { core::mem::zeroed() };
    convex_distance_pairs(&a, &[convex_pose_at(vec3(0.0, 0.0, 0.0))], &b, &[convex_pose_at(vec3(0.0, 3.0, 0.0))], &mut out).unwrap();
    assert!(close(out[0].distance, 1.0, 1e-5));

    let (mut world, _plane, _box) = box_on_plane();
    let mut bd = body_def();
    bd.position = vec3(5.0, 3.0, 0.0);
    let id = world.create_hull_body(&bd, &hull).unwrap();
    drop(hull); // the world copied it
    for _ in 0..90 {
        world.step(DT).unwrap();
    }
    assert!(close(world.position(id).unwrap().y, 1.0, 0.02), "hull cube rests at {:?}", world.position(id).unwrap());
}

fn hanging_cloth() -> (World, SoftBodyId, [u32; 2]) {
    let mut world = World::with_defaults().unwrap();
    let mut cd = cloth_def();
    cd.nx = 8;
    cd.nz = 8;
    cd.size_x = 2.0;
    cd.size_z = 2.0;
    cd.center = vec3(0.0, 2.0, 0.0);
    let cloth = world.create_cloth(&cd).unwrap();
    let corners = [world.cloth_index(cloth, 0, 0).unwrap(), world.cloth_index(cloth, 7, 0).unwrap()];
    for c in corners {
        world.pin(cloth, c).unwrap();
    }
    (world, cloth, corners)
}

#[test]
fn a_cloth_pinned_at_two_corners_hangs() {
    let (mut world, cloth, corners) = hanging_cloth();
    let pinned_at = world.particle_position(cloth, corners[0]).unwrap();
    for _ in 0..30 {
        world.step(DT).unwrap();
    }
    assert_eq!(world.soft_body_count().unwrap(), 1);
    assert!(world.is_pinned(cloth, corners[0]).unwrap());
    let p = world.particle_position(cloth, corners[0]).unwrap();
    assert_eq!((p.x, p.y, p.z), (pinned_at.x, pinned_at.y, pinned_at.z), "a pinned particle stays");
    let view = world.soft_view(cloth).unwrap();
    assert_eq!(view.len(), 64);
    assert_eq!(view.triangles().len(), 7 * 7 * 2 * 3);
    assert_eq!(view.inverse_mass()[corners[1] as usize], 0.0);
    let stats = world.soft_stats(cloth).unwrap();
    assert!(stats.min_y < 1.5 && stats.min_y.is_finite(), "the free edge falls: min_y {}", stats.min_y);
    assert!(view.py().iter().all(|y| y.is_finite()));

    let (mut again, cloth2, _) = hanging_cloth();
    for _ in 0..30 {
        again.step(DT).unwrap();
    }
    assert_eq!(world.soft_hash(cloth).unwrap(), again.soft_hash(cloth2).unwrap());

    assert_eq!(world.pin(cloth, 64).unwrap_err().status(), Status::InvalidArgument);
    world.destroy_soft_body(cloth).unwrap();
    assert_eq!(world.soft_hash(cloth).unwrap_err().status(), Status::StaleId);

    let mut cube = soft_cube_def();
    cube.center = vec3(0.0, 3.0, 0.0);
    let c = world.create_soft_cube(&cube).unwrap();
    assert_eq!(world.soft_view(c).unwrap().len(), 8);
}

#[test]
fn a_restored_snapshot_steps_on_bit_identically() {
    let (mut world, _plane, boxed) = box_on_plane();
    for _ in 0..20 {
        world.step(DT).unwrap();
    }
    let snap = world.snapshot().unwrap();
    assert!(!snap.is_empty());
    for _ in 0..10 {
        world.step(DT).unwrap();
    }
    let after = world.hash().unwrap();

    world.restore(&snap).unwrap();
    for _ in 0..10 {
        world.step(DT).unwrap();
    }
    assert_eq!(world.hash().unwrap(), after);
    assert!(world.is_valid(boxed));

    let mut copy = World::from_snapshot(&snap).unwrap();
    for _ in 0..10 {
        copy.step(DT).unwrap();
    }
    assert_eq!(copy.hash().unwrap(), after);

    let before = world.hash().unwrap();
    let mut corrupt = snap.clone();
    let mid = corrupt.len() / 2;
    corrupt[mid] ^= 0x40;
    assert_eq!(world.restore(&corrupt).unwrap_err().status(), Status::CorruptData);
    assert_eq!(world.restore(&snap[..snap.len() - 1]).unwrap_err().status(), Status::CorruptData);
    assert_eq!(World::from_snapshot(&[]).err().unwrap().status(), Status::CorruptData);
    assert_eq!(world.hash().unwrap(), before, "a refused snapshot changes nothing");
}

#[test]
fn a_recording_replays_to_the_same_hashes() {
    let (mut world, _plane, boxed) = box_on_plane();
    world.record_begin().unwrap();
    assert_eq!(world.record_begin().unwrap_err().status(), Status::InvalidArgument, "already recording");
    for i in 0..30 {
        if i == 10 {
            world.apply_linear_impulse(boxed, vec3(0.5, 1.0, 0.0), vec3(0.0, 2.0, 0.1)).unwrap();
        }
        world.step(DT).unwrap();
    }
    let rec = world.recording().unwrap();
    world.record_end().unwrap();
    let report = replay(&rec).unwrap();
    assert_eq!(report.diverged, 0);
    assert_eq!(report.steps, 30);
    assert_eq!(report.first_divergent_step, -1);
    assert_eq!(report.final_hash, world.hash().unwrap());
    let mut bad = rec.clone();
    bad.truncate(rec.len() / 2);
    assert_eq!(replay(&bad).unwrap_err().status(), Status::CorruptData);
}
