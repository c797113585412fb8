/* Record and replay through the C ABI (ABI 1.5).
 *
 * A short session is recorded: boxes stacked on a ground plane, a ball thrown at them, a
 * push, 3 seconds of steps. The recording (the world's snapshot when recording began, every
 * call since, and the world hash after every step) is saved to a file, then replayed: the
 * replay rebuilds the world, makes the calls again and compares the hash after every step.
 *
 *   record_replay [FILE]    default FILE: record_replay.gyrorec
 *
 * Exit status 0 when the replay reproduced every step bit for bit. */
#include "gyro.h"

#include <stdio.h>

static gyro_vec3 vec3(float x, float y, float z) {
  gyro_vec3 v;
  v.x = x, v.y = y, v.z = z;
  return v;
}

static int fail(const char* what, gyro_status s) {
  fprintf(stderr, "%s: %s (%s)\n", what, gyro_status_name(s), gyro_last_error());
  return 1;
}

int main(int argc, char** argv) {
  const char* path = argc > 1 ? argv[1] : "record_replay.gyrorec";
  const float dt = 1.0f / 60.0f;
  gyro_world_def wd = gyro_world_def_default();
  gyro_body_def d;
  gyro_world* world = NULL;
  gyro_body_id ball, top;
  gyro_replay_report report;
  uint64_t size = 0, live = 0;
  gyro_status s;
  int i;

  if (!(gyro_features() & GYRO_FEATURE_REPLAY)) {
    fprintf(stderr, "this gyro build has no record and replay\n");
    return 1;
  }
  if ((s = gyro_world_create(&wd, &world)) != GYRO_OK) return fail("gyro_world_create", s);

  /* The scene before recording: the recording starts from its snapshot. */
  d = gyro_body_def_default(), d.type = GYRO_BODY_STATIC, d.shape = GYRO_BODY_SHAPE_PLANE;
  gyro_body_create(world, &d, &top);
  d = gyro_body_def_default();
  for (i = 0; i < 4; ++i) {
    d.position = vec3(0.0f, 0.5f + (float)i, 0.0f);
    gyro_body_create(world, &d, &top);
  }

  if ((s = gyro_world_record_begin(world)) != GYRO_OK) return fail("gyro_world_record_begin", s);
  d = gyro_body_def_default(), d.shape = GYRO_BODY_SHAPE_SPHERE, d.radius = 0.3f, d.density = 50.0f;
  d.position = vec3(-6.0f, 2.0f, 0.0f), d.linear_velocity = vec3(9.0f, 2.5f, 0.0f);
  if ((s = gyro_body_create(world, &d, &ball)) != GYRO_OK) return fail("gyro_body_create", s);
  for (i = 0; i < 180; ++i) {
    if (i == 90) gyro_body_apply_linear_impulse(world, top, vec3(0.0f, 0.0f, 3.0f), vec3(0.0f, 3.8f, 0.2f));
    if ((s = gyro_world_step(world, dt)) != GYRO_OK) return fail("gyro_world_step", s);
  }
  gyro_world_hash(world, &live);
  gyro_world_record_size(world, &size);
  if ((s = gyro_world_record_save(world, path)) != GYRO_OK) return fail("gyro_world_record_save", s);
  gyro_world_record_end(world);
  gyro_world_destroy(world);
  printf("recorded %llu bytes to %s\n", (unsigned long long)size, path);

  report.struct_size = sizeof report;
  if ((s = gyro_replay_file(path, &report)) != GYRO_OK) return fail("gyro_replay_file", s);
  printf("replayed %lld calls, %lld steps: %s\n", (long long)report.calls, (long long)report.steps,
         report.diverged ? "DIVERGED" : "bit-identical");
  if (report.diverged)
    printf("  first divergent step %lld: recorded hash %016llx, replayed %016llx\n",
           (long long)report.first_divergent_step, (unsigned long long)report.expected_hash,
           (unsigned long long)report.actual_hash);
  printf("final hash %016llx (live world %016llx)\n", (unsigned long long)report.final_hash, (unsigned long long)live);
  return report.diverged || report.final_hash != live ? 1 : 0;
}
