/* A minimal PNG writer: see png_writer.h. Layout of the file (PNG specification, 2nd ed.):
 *   signature, IHDR, one IDAT holding the whole zlib stream, IEND
 * and of the zlib stream (RFC 1950 / 1951):
 *   CMF 0x78 (deflate, 32 KiB window), FLG 0x01 (no dictionary, fastest; CMF*256+FLG is a
 *   multiple of 31), stored blocks of at most 65,535 bytes (header byte BFINAL|BTYPE=00,
 *   then LEN and its one's complement NLEN, little-endian), then the Adler-32 of the raw
 *   data, big-endian.
 * The raw data is the image's rows, each preceded by its filter type byte (0: none). */
#include "png_writer.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define STORED_MAX 65535u

uint32_t png_crc32(uint32_t crc, const unsigned char* data, size_t n) {
  static uint32_t table[256];
  static int ready = 0;
  size_t i;
  if (!ready) { /* reflected polynomial 0xEDB88320, one entry per byte value */
    uint32_t k, c;
    int b;
    for (k = 0; k < 256; ++k) {
      c = k;
      for (b = 0; b < 8; ++b) c = (c & 1u) ? 0xEDB88320u ^ (c >> 1) : c >> 1;
      table[k] = c;
    }
    ready = 1;
  }
  crc = ~crc;
  for (i = 0; i < n; ++i) crc = table[(crc ^ data[i]) & 0xFFu] ^ (crc >> 8);
  return ~crc;
}

uint32_t png_adler32(uint32_t adler, const unsigned char* data, size_t n) {
  uint32_t a = adler & 0xFFFFu, b = adler >> 16;
  while (n > 0) {
    /* 5552 bytes is the most that can be summed before b may overflow 32 bits */
    size_t chunk = n < 5552 ? n : 5552, i;
    for (i = 0; i < chunk; ++i) {
      a += data[i];
      b += a;
    }
    a %= 65521u, b %= 65521u;
    data += chunk, n -= chunk;
  }
  return (b << 16) | a;
}

/* An open chunk: bytes go to the file and into its CRC. */
typedef struct chunk_writer {
  FILE* file;
  uint32_t crc;
  int failed;
} chunk_writer;

static void put_be32(unsigned char* p, uint32_t v) {
  p[0] = (unsigned char)(v >> 24), p[1] = (unsigned char)(v >> 16), p[2] = (unsigned char)(v >> 8);
  p[3] = (unsigned char)v;
}

static void chunk_put(chunk_writer* w, const unsigned char* data, size_t n) {
  if (n == 0) return;
  if (fwrite(data, 1, n, w->file) != n) w->failed = 1;
  w->crc = png_crc32(w->crc, data, n);
}

static void chunk_begin(chunk_writer* w, const char type[4], uint32_t length) {
  unsigned char len[4];
  put_be32(len, length);
  if (fwrite(len, 1, 4, w->file) != 4) w->failed = 1;
  w->crc = 0; /* the CRC covers the type and the data, not the length */
  chunk_put(w, (const unsigned char*)type, 4);
}

static void chunk_end(chunk_writer* w) {
  unsigned char crc[4];
  put_be32(crc, w->crc);
  if (fwrite(crc, 1, 4, w->file) != 4) w->failed = 1;
}

int png_write_rgb(const char* path, uint32_t width, uint32_t height, const unsigned char* rgb) {
  static const unsigned char signature[8] = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1A, '\n'};
  const uint64_t row_bytes = 1 + 3 * (uint64_t)width;
  const uint64_t raw_size = row_bytes * height;
  const uint64_t blocks = raw_size == 0 ? 1 : (raw_size + STORED_MAX - 1) / STORED_MAX;
  const uint64_t zlib_size = 2 + 5 * blocks + raw_size + 4;
  unsigned char *raw, header[13], zhead[2] = {0x78, 0x01}, trailer[4];
  chunk_writer w;
  uint64_t offset, y;
  if (!path || !rgb || width == 0 || height == 0 || width > 0x7FFFFFFFu || height > 0x7FFFFFFFu ||
      zlib_size > 0x7FFFFFFFu) /* a chunk holds at most 2^31 - 1 bytes */
    return -1;
  raw = (unsigned char*)malloc((size_t)raw_size);
  if (!raw) return -1;
  for (y = 0; y < height; ++y) {
    raw[y * row_bytes] = 0; /* filter: none */
    memcpy(raw + y * row_bytes + 1, rgb + y * (row_bytes - 1), (size_t)(row_bytes - 1));
  }
  w.file = fopen(path, "wb"), w.crc = 0, w.failed = 0;
  if (!w.file) {
    free(raw);
    return -1;
  }
  if (fwrite(signature, 1, sizeof signature, w.file) != sizeof signature) w.failed = 1;

  put_be32(header, width), put_be32(header + 4, height);
  header[8] = 8;  /* bits per sample */
  header[9] = 2;  /* colour type: RGB */
  header[10] = 0; /* compression: deflate */
  header[11] = 0; /* filter method 0 */
  header[12] = 0; /* no interlace */
  chunk_begin(&w, "IHDR", sizeof header);
  chunk_put(&w, header, sizeof header);
  chunk_end(&w);

  chunk_begin(&w, "IDAT", (uint32_t)zlib_size);
  chunk_put(&w, zhead, sizeof zhead);
  for (offset = 0; offset < raw_size; offset += STORED_MAX) {
    const uint32_t len = (uint32_t)(raw_size - offset < STORED_MAX ? raw_size - offset : STORED_MAX);
    unsigned char block[5];
    block[0] = offset + len >= raw_size ? 1 : 0; /* BFINAL on the last block, BTYPE 00: stored */
    block[1] = (unsigned char)len, block[2] = (unsigned char)(len >> 8);
    block[3] = (unsigned char)~len, block[4] = (unsigned char)(~len >> 8);
    chunk_put(&w, block, sizeof block);
    chunk_put(&w, raw + offset, len);
  }
  put_be32(trailer, png_adler32(1, raw, (size_t)raw_size));
  chunk_put(&w, trailer, sizeof trailer);
  chunk_end(&w);

  chunk_begin(&w, "IEND", 0);
  chunk_end(&w);
  free(raw);
  if (fclose(w.file) != 0) w.failed = 1;
  return w.failed ? -1 : 0;
}
