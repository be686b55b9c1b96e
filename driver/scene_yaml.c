/*
 * scene_yaml.c -- the scene loader's view of the raw YAML: path lookups in
 * the tree (scene_yaml_read.c builds it), the error list, and the
 * translation of libcyaml's log into "FILE:LINE: FIELD: what, expected
 * ..." messages.
 */
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "scene_internal.h"

/* ---- Paths --------------------------------------------------------------- */

/* Walk `path`; *last_line receives the line of the deepest existing step. */
static const cti_ynode *walk(const cti_ynode *root, const char *path, int *last_line, int *complete)
{
    const cti_ynode *n = root;
    *last_line = root ? root->line : 0;
    *complete = 0;
    const char *p = path;
    while (n && *p) {
        if (*p == '.')
            p++;
        if (*p == '[') {
            char *end;
            long i = strtol(p + 1, &end, 10);
            if (*end != ']' || n->kind != CTI_Y_SEQ || i < 0 || i >= n->n)
                return NULL;
            n = n->child[i];
            *last_line = n->line;
            p = end + 1;
        } else {
            size_t len = strcspn(p, ".[");
            if (n->kind != CTI_Y_MAP)
                return NULL;
            int found = -1;
            for (int i = 0; i < n->n; i++)
                if (n->key[i] && strlen(n->key[i]) == len && strncmp(n->key[i], p, len) == 0)
                    found = i;
            if (found < 0)
                return NULL;
            *last_line = n->key_line[found];
            n = n->child[found];
            p += len;
        }
    }
    *complete = 1;
    return n;
}

const cti_ynode *cti_ynode_at(const cti_ynode *root, const char *path)
{
    int line, complete;
    const cti_ynode *n = walk(root, path, &line, &complete);
    return complete ? n : NULL;
}

int cti_path_line(const cti_ynode *root, const char *path)
{
    int line, complete;
    walk(root, path, &line, &complete);
    return line;
}

void cti_quote_value(const char *s, char *buf, size_t len)
{
    size_t n = strlen(s), cut = n > 60 ? 60 : n;
    /* When the first byte left out continues a UTF-8 sequence (10xxxxxx),
     * leave out the whole sequence: back to its lead byte. */
    if (cut < n) {
        size_t k = cut;
        while (k > 0 && ((unsigned char)s[k] & 0xC0) == 0x80)
            k--;
        cut = k;
    }
    snprintf(buf, len, "'%.*s%s'", (int)cut, s, cut < n ? "..." : "");
}

void cti_ynode_describe(const cti_ynode *n, char *buf, size_t len)
{
    if (!n)
        snprintf(buf, len, "nothing");
    else if (n->kind == CTI_Y_SEQ)
        snprintf(buf, len, "a list");
    else if (n->kind == CTI_Y_MAP)
        snprintf(buf, len, "a mapping");
    else if (!n->value[0])
        snprintf(buf, len, "an empty value");
    else
        cti_quote_value(n->value, buf, len);
}

/* ---- Errors -------------------------------------------------------------- */

int cti_err(cti_errs *e, int code, int line, const char *field, const char *fmt, ...)
{
    if (e->count == 0)
        e->code = code;
    int l = e->root && field && field[0] ? cti_path_line(e->root, field) : 0;
    if (l <= 0)
        l = line;
    if (e->out && e->count < CTD_SCENE_MAXERR) {
        ctd_scene_msg *m = &e->out->msg[e->count];
        char what[512];
        va_list ap;
        va_start(ap, fmt);
        vsnprintf(what, sizeof what, fmt, ap);
        va_end(ap);
        m->line = l;
        snprintf(m->field, sizeof m->field, "%s", field ? field : "");
        if (l <= 0)
            snprintf(m->text, sizeof m->text, "%s: %s", e->file, what);
        else if (field && field[0])
            snprintf(m->text, sizeof m->text, "%s:%d: %s: %s", e->file, l, field, what);
        else
            snprintf(m->text, sizeof m->text, "%s:%d: %s", e->file, l, what);
    }
    e->count++;
    if (e->out) {
        e->out->count = e->count;
        e->out->code = e->code;
    }
    return code;
}

/* One backtrace step of libcyaml's log: "  in mapping field 'K' (line: L,
 * column: C)", "  in sequence entry 'N' (line ...)", "  in mapping (...)". */
typedef struct bt_step {
    int kind; /* 0 field, 1 entry, 2 mapping */
    char key[64];
    int index, line;
} bt_step;

static int parse_step(const char *s, bt_step *st)
{
    const char *l = strstr(s, "(line: ");
    st->line = l ? atoi(l + 7) : 0;
    st->key[0] = '\0';
    const char *q = strchr(s, '\'');
    const char *q2 = q ? strchr(q + 1, '\'') : NULL;
    if (strstr(s, "in mapping field") && q && q2) {
        st->kind = 0;
        snprintf(st->key, sizeof st->key, "%.*s", (int)(q2 - q - 1), q + 1);
        return 0;
    }
    if (strstr(s, "in sequence entry") && q) {
        st->kind = 1;
        st->index = atoi(q + 1) - 1; /* libcyaml counts entries from 1 */
        return 0;
    }
    if (strstr(s, "in mapping")) {
        st->kind = 2;
        return 0;
    }
    return -1;
}

void cti_cyaml_error(cti_errs *e, cyaml_err_t rc, const char *log)
{
    /* The first "Load: " line is the message; the steps follow. */
    char first[256] = "";
    bt_step steps[32];
    int ns = 0;
    const char *p = log;
    while (p && *p) {
        const char *nl = strchr(p, '\n');
        size_t len = nl ? (size_t)(nl - p) : strlen(p);
        char line[512];
        snprintf(line, sizeof line, "%.*s", (int)(len < 511 ? len : 511), p);
        if (strncmp(line, "Load: ", 6) == 0 && strncmp(line, "Load: Backtrace", 15) != 0) {
            if (!first[0])
                snprintf(first, sizeof first, "%.250s", line + 6);
        } else if (ns < 32 && parse_step(line, &steps[ns]) == 0) {
            ns++;
        }
        p = nl ? nl + 1 : NULL;
    }
    const char *missing = strstr(first, "Missing required mapping field: ");
    const char *unknown = strstr(first, "Unexpected key: ");
    const char *twice = strstr(first, "Mapping field already seen: ");
    /* For a missing field the innermost step is the last field read of the
     * mapping, not part of the path. */
    int skip = (missing && ns > 0 && steps[0].kind == 0) ? 1 : 0;
    char path[256] = "";
    size_t off = 0;
    for (int i = ns - 1; i >= skip; i--) {
        if (steps[i].kind == 0)
            off += (size_t)snprintf(path + off, sizeof path - off, "%s%s", off ? "." : "",
                                    steps[i].key);
        else if (steps[i].kind == 1)
            off += (size_t)snprintf(path + off, sizeof path - off, "[%d]", steps[i].index);
        if (off >= sizeof path)
            off = sizeof path - 1;
    }
    int line = ns > 0 ? steps[0].line : 0;
    char expect[512], got[96];
    if (missing || unknown) {
        const char *key = missing ? missing + 32 : unknown + 16;
        char parent[256];
        snprintf(parent, sizeof parent, "%s", path);
        off += (size_t)snprintf(path + off, sizeof path - off, "%s%s", off ? "." : "", key);
        if (missing) {
            cti_schema_expect(path, 0, expect, sizeof expect);
            cti_err(e, CT_ERR_ARG, line, path, "required field missing (expected %s)",
                    expect[0] ? expect : "a value");
        } else {
            cti_schema_expect(parent, 1, expect, sizeof expect);
            cti_err(e, CT_ERR_ARG, line, path, "unknown field, expected one of %s",
                    expect[0] ? expect : "the documented keys");
        }
        return;
    }
    if (twice) {
        cti_err(e, CT_ERR_ARG, line, path, "field given twice");
        return;
    }
    cti_schema_expect(path, 0, expect, sizeof expect);
    cti_ynode_describe(e->root ? cti_ynode_at(e->root, path) : NULL, got, sizeof got);
    if (expect[0])
        cti_err(e, CT_ERR_ARG, line, path, "expected %s, got %s", expect, got);
    else
        cti_err(e, CT_ERR_ARG, line, path, "%s (%s)", first[0] ? first : "invalid",
                cyaml_strerror(rc));
}
