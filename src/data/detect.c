/* detect.c: the text scanning the readers' detect functions share
 * (reader.h): lines and the first lines that hold content, over
 * the first bytes of a file. */
#include <string.h>

#include "data/reader.h"

int bf__detect_line(const char *text, size_t n, size_t *pos,
                    const char **line, size_t *len)
{
    size_t start = *pos;
    size_t end = start;
    if (start >= n) {
        return 0;
    }
    while (end < n && text[end] != '\n') {
        end++;
    }
    *pos = end + 1;
    *line = text + start;
    *len = end;
    while (*len > start && (text[*len - 1] == '\r' || text[*len - 1] == ' ' ||
                            text[*len - 1] == '\t')) {
        (*len)--;
    }
    *len -= start;
    return 1;
}

int bf__detect_content_line(const char *text, size_t n, size_t *pos,
                            const char **line, size_t *len)
{
    if (*pos == 0 && n >= 3 && memcmp(text, "\xEF\xBB\xBF", 3) == 0) {
        *pos = 3; /* a UTF-8 byte order mark (lineio.c) */
    }
    while (bf__detect_line(text, n, pos, line, len)) {
        while (*len > 0 && (**line == ' ' || **line == '\t')) {
            (*line)++;
            (*len)--;
        }
        if (*len > 0 && (*line)[0] != '#') {
            return 1;
        }
    }
    return 0;
}
