/* outfile.c: the report's output folder and its atomic output files
 * (rep.h): written to a temporary name, renamed into place on commit. */
#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "rep.h"

int bf_rep_check_outdir(const char *dir)
{
    struct stat st;
    char parent[4096];
    char *slash;
    if (dir[0] == '\0') {
        bf_rep_err("--out: empty folder name");
        return BF_REPORT_CANTCREAT;
    }
    if (stat(dir, &st) == 0) {
        if (!S_ISDIR(st.st_mode)) {
            bf_rep_err("%s: output path exists and is not a folder", dir);
            return BF_REPORT_CANTCREAT;
        }
        /* access() also reports EROFS, which root is not exempt from. */
        if (access(dir, W_OK | X_OK) != 0) {
            bf_rep_err("%s: output folder is not writable: %s", dir,
                       strerror(errno));
            return BF_REPORT_CANTCREAT;
        }
        return BF_REPORT_OK;
    }
    if (errno != ENOENT) {
        bf_rep_err("%s: cannot use as output folder: %s", dir,
                   strerror(errno));
        return BF_REPORT_CANTCREAT;
    }
    /* dir is missing: bf_rep_make_outdir creates one level, so its parent
     * must be a writable folder. */
    snprintf(parent, sizeof parent, "%s", dir);
    slash = strrchr(parent, '/');
    while (slash != NULL && slash > parent && slash[1] == '\0') {
        *slash = '\0'; /* "out/" names the folder out */
        slash = strrchr(parent, '/');
    }
    if (slash == NULL) {
        snprintf(parent, sizeof parent, ".");
    } else if (slash == parent) {
        parent[1] = '\0'; /* "/out": the parent is the root */
    } else {
        *slash = '\0';
    }
    if (stat(parent, &st) != 0 || !S_ISDIR(st.st_mode)) {
        bf_rep_err("%s: cannot create output folder: parent folder %s does "
                   "not exist",
                   dir, parent);
        return BF_REPORT_CANTCREAT;
    }
    /* Permission bits do not stop root, and some folders refuse new
     * entries whatever the user (/proc): try it, and take it back. */
    if (mkdir(dir, 0777) != 0) {
        bf_rep_err("%s: cannot create output folder: %s", dir,
                   strerror(errno));
        return BF_REPORT_CANTCREAT;
    }
    (void)rmdir(dir);
    return BF_REPORT_OK;
}

int bf_rep_make_outdir(const char *dir)
{
    struct stat st;
    if (stat(dir, &st) == 0) {
        if (!S_ISDIR(st.st_mode)) {
            bf_rep_err("%s: output path exists and is not a folder", dir);
            return BF_REPORT_CANTCREAT;
        }
    } else if (mkdir(dir, 0777) != 0) {
        bf_rep_err("%s: cannot create output folder: %s", dir,
                   strerror(errno));
        return BF_REPORT_CANTCREAT;
    }
    if (access(dir, W_OK) != 0) {
        bf_rep_err("%s: output folder is not writable: %s", dir,
                   strerror(errno));
        return BF_REPORT_CANTCREAT;
    }
    return BF_REPORT_OK;
}

int bf_out_open(bf_out *o, const char *dir, const char *name)
{
    int fd;
    memset(o, 0, sizeof *o);
    snprintf(o->path, sizeof o->path, "%s/%s", dir, name);
    snprintf(o->tmp, sizeof o->tmp, "%s/.%s.XXXXXX", dir, name);
    fd = mkstemp(o->tmp);
    if (fd < 0) {
        bf_rep_err("%s: cannot create: %s", o->path, strerror(errno));
        o->tmp[0] = '\0';
        return BF_REPORT_CANTCREAT;
    }
    (void)fchmod(fd, 0644);
    o->fp = fdopen(fd, "w");
    if (o->fp == NULL) { /* fdopen fails only for want of memory */
        int e = errno;
        bf_rep_err("%s: cannot open: %s", o->path, strerror(e));
        close(fd);
        unlink(o->tmp);
        o->tmp[0] = '\0';
        return e == ENOMEM ? BF_REPORT_SOFTWARE : BF_REPORT_CANTCREAT;
    }
    return BF_REPORT_OK;
}

int bf_out_commit(bf_out *o)
{
    int bad = ferror(o->fp);
    if (fflush(o->fp) != 0) {
        bad = 1;
    }
    if (fsync(fileno(o->fp)) != 0 && errno != EINVAL) {
        bad = 1;
    }
    if (fclose(o->fp) != 0) {
        bad = 1;
    }
    o->fp = NULL;
    if (bad) {
        bf_rep_err("%s: write failed: %s", o->path, strerror(errno));
        unlink(o->tmp);
        return BF_REPORT_IOERR;
    }
    if (rename(o->tmp, o->path) != 0) {
        bf_rep_err("%s: cannot rename into place: %s", o->path,
                   strerror(errno));
        unlink(o->tmp);
        return BF_REPORT_IOERR;
    }
    return BF_REPORT_OK;
}

void bf_out_abort(bf_out *o)
{
    if (o->fp != NULL) {
        fclose(o->fp);
        o->fp = NULL;
    }
    if (o->tmp[0] != '\0') {
        unlink(o->tmp);
        o->tmp[0] = '\0';
    }
}
