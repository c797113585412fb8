/* A minimal PNG writer for the examples (C99, no dependencies): 8-bit RGB, no interlace,
 * filter 0 on every row, and a zlib stream of stored (uncompressed) deflate blocks. The
 * CRC-32 of the chunks and the Adler-32 of the zlib stream are computed here. The files are
 * larger than a compressing encoder's (width * height * 3 bytes and a little) but any PNG
 * reader opens them. */
#ifndef GYRO_EXAMPLES_PNG_WRITER_H
#define GYRO_EXAMPLES_PNG_WRITER_H

#include <stddef.h>
#include <stdint.h>

#ifdef __cplusplus
extern "C" {
#endif

/** Writes rgb (height rows of width pixels, 3 bytes each: red, green, blue, top row first)
 *  to path as a PNG file. Returns 0 on success, -1 on bad arguments or an I/O error. */
int png_write_rgb(const char* path, uint32_t width, uint32_t height, const unsigned char* rgb);

/** CRC-32 (ISO-HDLC, as PNG's chunks use it) of n bytes, continuing from crc (start at 0). */
uint32_t png_crc32(uint32_t crc, const unsigned char* data, size_t n);

/** Adler-32 (as zlib streams end with it) of n bytes, continuing from adler (start at 1). */
uint32_t png_adler32(uint32_t adler, const unsigned char* data, size_t n);

#ifdef __cplusplus
}
#endif

#endif
