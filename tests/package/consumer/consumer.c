/* A program that embeds gyro from its installed package: it checks that the library it
 * linked speaks the header's ABI and has the dynamics module, drops a sphere onto a box for
 * 60 steps, and prints one line: "<kind> abi <version> hash <world hash>". The
 * install-and-consume test builds it with CMake (gyro::gyro, gyro::gyro_static) and with
 * pkg-config (shared and --static), and compares the four hashes. */
#include <gyro.h>

#include <stdio.h>

#ifndef CONSUMER_KIND
#define CONSUMER_KIND "consumer"
#endif

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
  gyro_body_def box = gyro_body_def_default(), ball = gyro_body_def_default();
  gyro_world* world = NULL;
  gyro_body_id id;
  uint64_t hash = 0;
  int step;
  if (gyro_abi_version() != GYRO_ABI_VERSION) {
    fprintf(stderr, CONSUMER_KIND ": linked ABI %#x, header ABI %#x\n", (unsigned)gyro_abi_version(),
            (unsigned)GYRO_ABI_VERSION);
    return 1;
  }
  if (!(gyro_features() & GYRO_FEATURE_DYNAMICS)) {
    fprintf(stderr, CONSUMER_KIND ": the installed gyro has no dynamics module\n");
    return 1;
  }
  CHECK(gyro_world_create(&world_def, &world));
  box.type = GYRO_BODY_STATIC;
  box.half_extents.x = 5.0f, box.half_extents.y = 0.5f, box.half_extents.z = 5.0f;
  box.position.y = -0.5f;
  CHECK(gyro_body_create(world, &box, &id));
  ball.shape = GYRO_BODY_SHAPE_SPHERE, ball.radius = 0.25f, ball.position.y = 2.0f, ball.position.x = 0.1f;
  CHECK(gyro_body_create(world, &ball, &id));
  for (step = 0; step < 60; ++step) CHECK(gyro_world_step(world, 1.0f / 60.0f));
  CHECK(gyro_world_hash(world, &hash));
  gyro_world_destroy(world);
  printf(CONSUMER_KIND " abi %u.%u version %s hash 0x%016llx\n", (unsigned)(gyro_abi_version() >> 16),
         (unsigned)(gyro_abi_version() & 0xFFFFu), gyro_version_string(), (unsigned long long)hash);
  return 0;
}
