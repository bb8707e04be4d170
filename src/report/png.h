/* png.h: writes an RGB image as a small PNG -- 8-bit palette colour
 * (exact when the image has at most 256 colours; otherwise each colour
 * mapped to the nearest of a palette of blends of the figure's colours
 * with white, as anti-aliasing makes them), deflated with zlib, with no
 * text or time chunk. Private to src/report (plot.c draws PNG figures
 * into memory and writes them with it). */
#ifndef BF_REPORT_PNG_H
#define BF_REPORT_PNG_H

#include <stddef.h>

/* Writes the w x h image rgb (3 bytes a pixel, rows top to bottom) to
 * path. base lists the n_base colours the image was drawn with (RGB);
 * when the image has more than 256 colours, the palette is white and
 * BF__PNG_LEVELS blends of each base colour with white. Returns BF_OK,
 * BF_EIO (cannot write), BF_ENOMEM or BF_EINVAL. */
#define BF__PNG_LEVELS 12
int bf__png_write(const char *path, unsigned w, unsigned h,
                  const unsigned char *rgb, const unsigned char (*base)[3],
                  size_t n_base);

#endif
