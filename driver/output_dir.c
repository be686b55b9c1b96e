/*
 * output_dir.c -- the output directory: opened (created when missing,
 * proved writable, checked for free space) at the start of a run, or only
 * checked, creating nothing, by `contact check`; and the output's paths and
 * messages.
 */
#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <sys/statvfs.h>
#include <unistd.h>

#include "output_internal.h"

char *cti_out_path(const char *dir, const char *name)
{
    size_t n = strlen(dir) + strlen(name) + 2;
    char *p = malloc(n);
    if (p)
        snprintf(p, n, "%s/%s", dir, name);
    return p;
}

int cti_out_fail(char *err, size_t len, const char *what, const char *path, int errnum)
{
    if (err && len)
        snprintf(err, len, "%s '%s': %s", what, path, strerror(errnum));
    return CT_ERR_ARG;
}

int cti_out_nomem(char *err, size_t len)
{
    if (err && len)
        snprintf(err, len, "out of memory");
    return CT_ERR_NOMEM;
}

/* ---- Directory ----------------------------------------------------------- */

/* Create dir and its missing parents (as mkdir -p). Returns 0 or the
 * errno of the first level that could not be made. */
static int make_dirs(const char *dir)
{
    char *p = strdup(dir);
    if (!p)
        return ENOMEM;
    int e = 0;
    for (char *c = p + 1; !e; c++) {
        const int end = *c == '\0';
        if (!end && *c != '/')
            continue;
        *c = '\0';
        if (mkdir(p, 0777) != 0) {
            e = errno;
            struct stat st;
            if (e == EEXIST) /* there already: fine if a directory */
                e = stat(p, &st) != 0 ? errno : (S_ISDIR(st.st_mode) ? 0 : ENOTDIR);
        }
        if (end)
            break;
        *c = '/';
    }
    free(p);
    return e;
}

int ctd_output_open(ctd_output **out, const ctd_output_opts *opts, char *err, size_t errlen)
{
    if (err && errlen)
        err[0] = '\0';
    if (!out || !opts || !opts->dir || !opts->dir[0]) {
        if (err && errlen)
            snprintf(err, errlen, "no output directory given");
        return CT_ERR_ARG;
    }
    *out = NULL;
    if (opts->vtu_format != CTD_VTU_ASCII && opts->vtu_format != CTD_VTU_RAW) {
        if (err && errlen)
            snprintf(err, errlen, "unknown VTU format %d (expected ascii 0 or raw 1)",
                     opts->vtu_format);
        return CT_ERR_ARG;
    }
    const char *dir = opts->dir;
    struct stat st;
    if (stat(dir, &st) != 0) {
        if (errno != ENOENT)
            return cti_out_fail(err, errlen, "cannot use output directory", dir, errno);
        int e = make_dirs(dir);
        if (e)
            return e == ENOMEM ? cti_out_nomem(err, errlen)
                               : cti_out_fail(err, errlen, "cannot create output directory",
                                              dir, e);
    } else if (!S_ISDIR(st.st_mode)) {
        return cti_out_fail(err, errlen, "output path is not a directory", dir, ENOTDIR);
    }
    /* Prove it writable: a probe file written, flushed and removed. */
    char *probe = cti_out_path(dir, ".contact-probe");
    if (!probe)
        return cti_out_nomem(err, errlen);
    errno = 0;
    FILE *f = fopen(probe, "wb");
    int e = 0;
    if (!f) {
        e = errno ? errno : EIO;
    } else {
        static const char zeros[4096];
        if (fwrite(zeros, 1, sizeof zeros, f) != sizeof zeros || fflush(f) != 0)
            e = errno ? errno : EIO;
        if (fclose(f) != 0 && !e)
            e = errno ? errno : EIO;
        remove(probe);
    }
    free(probe);
    if (e)
        return cti_out_fail(err, errlen, "cannot write to output directory", dir, e);
    struct statvfs vfs;
    if (statvfs(dir, &vfs) == 0 && (double)vfs.f_bavail * (double)vfs.f_frsize < 1048576.0)
        return cti_out_fail(err, errlen, "output directory is on a full disk", dir, ENOSPC);
    ctd_output *o = calloc(1, sizeof *o);
    if (!o)
        return cti_out_nomem(err, errlen);
    o->dir = strdup(dir);
    o->base = strdup(opts->base ? opts->base : "state");
    o->vtu = opts->vtu;
    o->csv = opts->csv;
    o->vtu_format = opts->vtu_format;
    if (!o->dir || !o->base) {
        ctd_output_close(o);
        return cti_out_nomem(err, errlen);
    }
    *out = o;
    return CT_OK;
}

/* The directory that holds dir: "." for a bare name, "/" for "/x"; the
 * result is cut in place (dir's own buffer). */
static void cut_to_parent(char *dir)
{
    size_t n = strlen(dir);
    while (n > 1 && dir[n - 1] == '/') /* "out/" is "out" */
        n--;
    while (n > 0 && dir[n - 1] != '/')
        n--;
    while (n > 1 && dir[n - 1] == '/')
        n--;
    if (n == 0)
        strcpy(dir, ".");
    else
        dir[n] = '\0';
}

int ctd_output_check_dir(const char *dir, char *err, size_t errlen)
{
    if (err && errlen)
        err[0] = '\0';
    if (!dir || !dir[0]) {
        if (err && errlen)
            snprintf(err, errlen, "no output directory given");
        return CT_ERR_ARG;
    }
    struct stat st;
    char *anc = NULL; /* the nearest existing ancestor of a missing dir */
    int rc = CT_OK;
    if (stat(dir, &st) != 0) {
        if (errno != ENOENT)
            return cti_out_fail(err, errlen, "cannot use output directory", dir, errno);
        /* Missing: ctd_output_open creates it and its missing parents in
         * the nearest existing ancestor, which must be a writable
         * directory. */
        if (!(anc = malloc(strlen(dir) + 2)))
            return cti_out_nomem(err, errlen);
        strcpy(anc, dir);
        int e;
        do {
            cut_to_parent(anc);
            e = stat(anc, &st) != 0 ? errno : 0;
        } while (e == ENOENT && strcmp(anc, ".") && strcmp(anc, "/"));
        if (!e && !S_ISDIR(st.st_mode))
            e = ENOTDIR;
        else if (!e && access(anc, W_OK | X_OK) != 0)
            e = errno;
        if (e)
            rc = cti_out_fail(err, errlen, "cannot create output directory", dir, e);
    } else if (!S_ISDIR(st.st_mode)) {
        return cti_out_fail(err, errlen, "output path is not a directory", dir, ENOTDIR);
    } else if (access(dir, W_OK | X_OK) != 0) {
        return cti_out_fail(err, errlen, "cannot write to output directory", dir, errno);
    }
    /* A filesystem with no blocks at all (proc, sysfs) stores no files,
     * whatever access() tells root; the run's probe would fail there. */
    struct statvfs vfs;
    if (rc == CT_OK && statvfs(anc ? anc : dir, &vfs) == 0 &&
        (double)vfs.f_bavail * (double)vfs.f_frsize < 1048576.0)
        rc = cti_out_fail(err, errlen,
                          vfs.f_blocks == 0
                              ? "output directory is on a filesystem that stores no files"
                              : "output directory is on a full disk",
                          dir, ENOSPC);
    free(anc);
    return rc;
}

void ctd_output_close(ctd_output *o)
{
    if (!o)
        return;
    if (o->csvf)
        fclose(o->csvf);
    free(o->dir);
    free(o->base);
    free(o->step_time);
    free(o);
}

const char *ctd_output_error(const ctd_output *o) { return o ? o->err : "no output"; }
const char *ctd_output_dir(const ctd_output *o) { return o ? o->dir : ""; }
