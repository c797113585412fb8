/* gyro hello world: a sphere dropped onto the ground, through the C ABI.
 *
 *   cc hello_world.c $(pkg-config --cflags --libs gyro) -o hello_world
 *
 * Creates a world, adds a static ground box and a dynamic sphere 5 m above it, steps two
 * seconds at 60 Hz, and prints the sphere's height as it falls and settles, then the world
 * hash: the 64-bit witness of the whole state, the same bits on every machine, SIMD level
 * and thread count for the same calls. Exits 1 if a call fails or the sphere does not come
 * to rest on the ground. */
#include "gyro.h"

#include <math.h>
#include <stdio.h>

#define STEPS 120

/* Prints the failed call and its detail, and returns 1 from main. */
#define CHECK(call)                                                                                        \
  do {                                                                                                     \
    gyro_status status_ = (call);                                                                          \
    if (status_ != GYRO_OK) {                                                                              \
      fprintf(stderr, "%s failed: %s (%s)\n", #call, gyro_status_name(status_), gyro_last_error());       \
      return 1;                                                                                            \
    }                                                                                                      \
  } while (0)

int main(void) {
  gyro_world_def world_def = gyro_world_def_default();
  gyro_body_def ground_def = gyro_body_def_default(), ball_def = gyro_body_def_default();
  gyro_world* world = NULL;
  gyro_body_id ground, ball;
  gyro_vec3 position;
  uint64_t hash;
  int step;

  /* The library must speak the header's ABI: same major version, same or newer minor. */
  if (gyro_abi_version() >> 16 != GYRO_ABI_VERSION >> 16 || gyro_abi_version() < GYRO_ABI_VERSION) {
    fprintf(stderr, "gyro library ABI %#x does not match the header's %#x\n", (unsigned)gyro_abi_version(),
            (unsigned)GYRO_ABI_VERSION);
    return 1;
  }
  if (!(gyro_features() & GYRO_FEATURE_DYNAMICS)) {
    printf("this gyro build has no dynamics module\n");
    return 0;
  }
  printf("gyro %s, ABI %u.%u, SIMD %s\n", gyro_version_string(), (unsigned)(gyro_abi_version() >> 16),
         (unsigned)(gyro_abi_version() & 0xFFFFu), gyro_simd_level_name(gyro_get_simd_level()));

  CHECK(gyro_world_create(&world_def, &world));

  /* A static 20 x 1 x 20 m box whose top face is y = 0. */
  ground_def.type = GYRO_BODY_STATIC;
  ground_def.half_extents.x = 10.0f, ground_def.half_extents.y = 0.5f, ground_def.half_extents.z = 10.0f;
  ground_def.position.y = -0.5f;
  CHECK(gyro_body_create(world, &ground_def, &ground));

  /* A 0.5 m sphere (density 1000 kg/m^3: about 524 kg) 5 m up. */
  ball_def.shape = GYRO_BODY_SHAPE_SPHERE;
  ball_def.radius = 0.5f;
  ball_def.density = 1000.0f;
  ball_def.position.y = 5.0f;
  CHECK(gyro_body_create(world, &ball_def, &ball));

  for (step = 1; step <= STEPS; ++step) {
    CHECK(gyro_world_step(world, 1.0f / 60.0f));
    if (step % 20 == 0) {
      CHECK(gyro_body_get_transform(world, ball, &position, NULL));
      printf("t = %.2f s  sphere at (%.3f, %.3f, %.3f)\n", step / 60.0, position.x, position.y, position.z);
    }
  }
  CHECK(gyro_world_hash(world, &hash));
  printf("world hash after %d steps: 0x%016llx\n", STEPS, (unsigned long long)hash);
  gyro_world_destroy(world);

  /* At rest on the ground: its centre one radius above y = 0 (within a centimetre). */
  if (fabsf(position.y - ball_def.radius) > 0.01f || fabsf(position.x) > 1e-3f || fabsf(position.z) > 1e-3f) {
    fprintf(stderr, "the sphere is not resting on the ground\n");
    return 1;
  }
  return 0;
}
