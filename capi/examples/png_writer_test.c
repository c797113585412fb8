/* Checks png_writer: the CRC-32 and Adler-32 check values, then writes images (one small,
 * one whose data spans several stored deflate blocks) and decodes them again here: the
 * signature, every chunk's CRC, the IHDR fields, the zlib header, the stored blocks and
 * their LEN/NLEN, the Adler-32, the filter bytes and every pixel. Usage: png_writer_test DIR */
#include "png_writer.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static int failures = 0;
#define EXPECT(cond)                                                  \
  do {                                                                \
    if (!(cond)) {                                                    \
      fprintf(stderr, "%s:%d: FAILED: %s\n", __FILE__, __LINE__, #cond); \
      ++failures;                                                     \
      return;                                                         \
    }                                                                 \
  } while (0)

static uint32_t be32(const unsigned char* p) {
  return (uint32_t)p[0] << 24 | (uint32_t)p[1] << 16 | (uint32_t)p[2] << 8 | p[3];
}

static void check_image(const char* dir, uint32_t w, uint32_t h) {
  static const unsigned char signature[8] = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1A, '\n'};
  const size_t row = 1 + 3 * (size_t)w;
  unsigned char *rgb = malloc(3 * (size_t)w * h), *file = NULL, *z = NULL, *raw = malloc(row * h);
  char path[1024];
  size_t size = 0, zsize = 0, rsize = 0, pos, i;
  FILE* f;
  int seen_ihdr = 0, seen_iend = 0;
  EXPECT(rgb && raw);
  for (i = 0; i < 3 * (size_t)w * h; ++i) rgb[i] = (unsigned char)(i * 7 + i / 5);
  snprintf(path, sizeof path, "%s/png_writer_test_%ux%u.png", dir, (unsigned)w, (unsigned)h);
  EXPECT(png_write_rgb(path, w, h, rgb) == 0);
  EXPECT((f = fopen(path, "rb")) != NULL);
  fseek(f, 0, SEEK_END);
  size = (size_t)ftell(f);
  fseek(f, 0, SEEK_SET);
  file = malloc(size), z = malloc(size);
  EXPECT(file && z && fread(file, 1, size, f) == size);
  fclose(f);

  EXPECT(size > 8 && memcmp(file, signature, 8) == 0);
  for (pos = 8; pos + 12 <= size && !seen_iend;) {
    const uint32_t len = be32(file + pos);
    const unsigned char* type = file + pos + 4;
    EXPECT(pos + 12 + len <= size);
    EXPECT(be32(file + pos + 8 + len) == png_crc32(0, type, 4 + (size_t)len));
    if (memcmp(type, "IHDR", 4) == 0) {
      EXPECT(len == 13 && be32(type + 4) == w && be32(type + 8) == h);
      EXPECT(type[12] == 8 && type[13] == 2 && type[14] == 0 && type[15] == 0 && type[16] == 0);
      seen_ihdr = 1;
    } else if (memcmp(type, "IDAT", 4) == 0) {
      memcpy(z + zsize, type + 4, len), zsize += len;
    } else if (memcmp(type, "IEND", 4) == 0) {
      EXPECT(len == 0);
      seen_iend = 1;
    }
    pos += 12 + len;
  }
  EXPECT(seen_ihdr && seen_iend && pos == size);

  /* zlib: CMF/FLG, stored blocks, Adler-32 */
  EXPECT(zsize >= 6 && z[0] == 0x78 && (z[0] * 256u + z[1]) % 31 == 0 && !(z[1] & 0x20));
  for (pos = 2;;) {
    unsigned len, nlen, final;
    EXPECT(pos + 5 <= zsize);
    final = z[pos] & 1u;
    EXPECT((z[pos] >> 1 & 3u) == 0); /* BTYPE 00: stored */
    len = z[pos + 1] | (unsigned)z[pos + 2] << 8, nlen = z[pos + 3] | (unsigned)z[pos + 4] << 8;
    EXPECT((len ^ 0xFFFFu) == nlen && pos + 5 + len <= zsize && rsize + len <= row * h);
    memcpy(raw + rsize, z + pos + 5, len), rsize += len, pos += 5 + len;
    if (final) break;
  }
  EXPECT(rsize == row * h && pos + 4 == zsize && be32(z + pos) == png_adler32(1, raw, rsize));
  for (i = 0; i < h; ++i) {
    EXPECT(raw[i * row] == 0);
    EXPECT(memcmp(raw + i * row + 1, rgb + i * (row - 1), row - 1) == 0);
  }
  printf("ok: %s (%lu bytes)\n", path, (unsigned long)size);
  free(rgb), free(raw), free(file), free(z);
}

int main(int argc, char** argv) {
  const char* dir = argc > 1 ? argv[1] : ".";
  const unsigned char digits[] = "123456789", wiki[] = "Wikipedia";
  unsigned char big[70000];
  uint32_t whole, parts;
  size_t i;
  /* The catalogued check values of CRC-32/ISO-HDLC and of Adler-32. */
  if (png_crc32(0, digits, 9) != 0xCBF43926u) ++failures, fprintf(stderr, "crc32 check value\n");
  if (png_adler32(1, wiki, 9) != 0x11E60398u) ++failures, fprintf(stderr, "adler32 check value\n");
  /* Both continue across calls; Adler-32's modulo is taken often enough for long inputs. */
  for (i = 0; i < sizeof big; ++i) big[i] = 0xFF;
  whole = png_adler32(1, big, sizeof big), parts = png_adler32(png_adler32(1, big, 1000), big + 1000, sizeof big - 1000);
  if (whole != parts) ++failures, fprintf(stderr, "adler32 in parts\n");
  {
    /* the reference: the definition, summed modulo 65521 at every byte */
    uint32_t a = 1, b = 0;
    for (i = 0; i < sizeof big; ++i) a = (a + big[i]) % 65521u, b = (b + a) % 65521u;
    if (whole != (b << 16 | a)) ++failures, fprintf(stderr, "adler32 on 70,000 bytes of 0xFF\n");
  }
  if (png_crc32(png_crc32(0, digits, 4), digits + 4, 5) != 0xCBF43926u) ++failures, fprintf(stderr, "crc32 in parts\n");
  if (png_write_rgb(NULL, 1, 1, big) == 0 || png_write_rgb("x.png", 0, 1, big) == 0) ++failures;
  check_image(dir, 3, 2);
  check_image(dir, 200, 150); /* 90,150 bytes of data: two stored blocks */
  check_image(dir, 1, 1);
  if (failures) fprintf(stderr, "%d failure(s)\n", failures);
  return failures ? 1 : 0;
}
